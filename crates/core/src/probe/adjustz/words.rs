//! The height-map follower's lines as the post of the adjusted program writes them: its
//! templates for a vertical move (`rapid_z`, `plunge`), a straight one (`linear`; a rapid
//! below the safe height is `rapid_xy` with the post's Z word after it) and an arc
//! (`arc_cw`, `arc_ccw`), its `statistics` line, and its line numbers and modal words over
//! the whole program ([`LineWriter`]). A piece that continues a move repeats no feed: the
//! post's F word is taken out of it. With the `linuxcnc` and `grbl` posts these are the
//! bytes the follower wrote before it used the posts.

use millpath_post::{Event, Globals, LineWriter, Post, Value, Var};

/// Stands for a feed the line does not repeat; the word holding it is taken out.
const NO_FEED: &str = "\u{1}";

/// The words of one post.
pub(super) struct Words<'p> {
    pub post: &'p Post,
}

impl Words<'_> {
    fn render(&self, event: Event, vars: &[(Var, Value)], feed: Option<f64>) -> String {
        let mut all = vars.to_vec();
        all.push((Var::ZProbe, Value::Text("")));
        all.push((
            Var::Feed,
            match feed {
                Some(f) => Value::Num(f),
                None => Value::Text(NO_FEED),
            },
        ));
        let text = self.post.text(event, &all, &Globals::default());
        if !text.contains(NO_FEED) {
            return text;
        }
        text.split('\n')
            .map(|line| {
                line.split(' ')
                    .filter(|w| !w.contains(NO_FEED))
                    .collect::<Vec<_>>()
                    .join(" ")
            })
            .collect::<Vec<_>>()
            .join("\n")
    }

    /// A vertical move to `z`: a rapid, or a feed move at `feed`.
    pub fn vertical(&self, rapid: bool, feed: Option<f64>, z: f64) -> String {
        let event = if rapid { Event::RapidZ } else { Event::Plunge };
        self.render(event, &[(Var::Z, Value::Num(z))], feed)
    }

    /// A straight move to (x, y, z): a rapid, or a feed move at `feed`.
    pub fn straight(&self, rapid: bool, feed: Option<f64>, x: f64, y: f64, z: f64) -> String {
        let xy = [(Var::X, Value::Num(x)), (Var::Y, Value::Num(y))];
        if rapid {
            let mut text = self.render(Event::RapidXy, &xy, None);
            text.push_str(" Z");
            self.post.format.of('Z').write(z, &mut text);
            return text;
        }
        let mut vars = xy.to_vec();
        vars.push((Var::Z, Value::Num(z)));
        self.render(Event::Linear, &vars, feed)
    }

    /// An arc to `end` around the centre `(i, j)` from its start (radius `r`).
    pub fn arc(
        &self,
        ccw: bool,
        feed: Option<f64>,
        ij: (f64, f64),
        end: (f64, f64, f64),
    ) -> String {
        let r = ij.0.hypot(ij.1);
        let vars = [
            (Var::I, Value::Num(ij.0)),
            (Var::J, Value::Num(ij.1)),
            (Var::R, Value::Num(r)),
            (Var::X, Value::Num(end.0)),
            (Var::Y, Value::Num(end.1)),
            (Var::Z, Value::Num(end.2)),
        ];
        let event = if ccw { Event::ArcCcw } else { Event::ArcCw };
        self.render(event, &vars, feed)
    }

    /// A line of the statistics block.
    pub fn statistics(&self, text: &str) -> String {
        let vars = [(Var::Text, Value::Text(text))];
        self.post
            .text(Event::Statistics, &vars, &Globals::default())
    }

    /// A line of the program without its line number (the whole program is numbered again
    /// by [`Words::finish`]).
    pub fn unnumbered<'a>(&self, line: &'a str) -> &'a str {
        let Some(n) = &self.post.line_numbers else {
            return line;
        };
        let Some(rest) = line.strip_prefix(n.letter) else {
            return line;
        };
        let digits = rest.len() - rest.trim_start_matches(|c: char| c.is_ascii_digit()).len();
        match rest[digits..].strip_prefix(' ') {
            Some(after) if digits > 0 => after,
            None if digits > 0 && digits == rest.len() => "",
            _ => line,
        }
    }

    /// The program's lines numbered and with modal words left out as the post says.
    pub fn finish(&self, lines: Vec<String>) -> Vec<String> {
        let mut w = LineWriter::new(self.post);
        if w.is_plain() {
            return lines;
        }
        lines.iter().map(|l| w.line(l)).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn numbered() -> Post {
        let text = millpath_post::builtin::source("linuxcnc").unwrap().replace(
            "[comments]",
            "[line_numbers]\nstart = 10\nstep = 10\n\n[comments]",
        );
        millpath_post::load("n.toml", &text).unwrap()
    }

    #[test]
    fn linuxcnc_writes_the_followers_own_words() {
        let w = Words {
            post: millpath_post::builtin::get("linuxcnc").unwrap(),
        };
        assert_eq!(w.vertical(true, None, 1.5), "G00 Z1.500");
        assert_eq!(w.vertical(false, Some(100.0), 1.5), "G01 F100.000 Z1.500");
        assert_eq!(w.vertical(false, None, -0.25), "G01 Z-0.250");
        assert_eq!(
            w.straight(false, Some(300.0), 10.0, 0.0, 1.6),
            "G01 F300.000 X10.000 Y0.000 Z1.600"
        );
        assert_eq!(
            w.straight(false, None, 20.0, 0.0, 1.7),
            "G01 X20.000 Y0.000 Z1.700"
        );
        assert_eq!(
            w.straight(true, None, 1.0, 2.0, 3.0),
            "G00 X1.000 Y2.000 Z3.000"
        );
        assert_eq!(
            w.arc(true, None, (5.0, 0.0), (15.0, 5.0, 1.0)),
            "G03 I5.000 J0.000 X15.000 Y5.000 Z1.000"
        );
        assert_eq!(
            w.statistics("Split moves:  1 into 2 pieces"),
            "  (Split moves:  1 into 2 pieces)"
        );
        assert_eq!(w.unnumbered("N10 G00 Z1.000"), "N10 G00 Z1.000");
    }

    #[test]
    fn marlin_and_numbered_posts_write_their_way() {
        let marlin = Words {
            post: millpath_post::builtin::get("marlin").unwrap(),
        };
        assert_eq!(
            marlin.straight(false, None, 1.0, 2.0, 3.0),
            "G1 X1.000 Y2.000 Z3.000"
        );
        assert_eq!(marlin.statistics("x"), "  ; x");
        let post = numbered();
        let w = Words { post: &post };
        assert_eq!(w.unnumbered("N10 G00 Z1.000"), "G00 Z1.000");
        assert_eq!(w.unnumbered("N20"), "");
        assert_eq!(w.unnumbered("%"), "%");
        assert_eq!(w.unnumbered("NX"), "NX");
        let lines = vec!["%".to_string(), "(c)".into(), "G00 Z1.000".into()];
        assert_eq!(w.finish(lines), ["%", "N10 (c)", "N20 G00 Z1.000"]);
    }
}
