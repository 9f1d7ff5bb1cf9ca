//! The last step of each line: modal suppression (a word whose value did not change is left
//! out, as the post's `modal` list says), line numbers and the line end.
//!
//! Modal suppression never takes a word that carries an expression comment (`Z1.000(=…)`,
//! which adjust-z evaluates), never leaves a line without words (a line that would become
//! empty is written whole), and forgets what it knew after a probe (`G38`, `G31`: the
//! position is measured) or a non-motion G-code of the motion group (`G80`).

use crate::{LineEnd, Post};
use std::ops::Deref;

/// Writes a program's lines: numbers, modal state and line ends. `P` holds the post: a
/// borrow, or a shared `Arc` where the writer lives as long as its program.
pub struct LineWriter<P: Deref<Target = Post>> {
    post: P,
    next: u64,
    /// Last written value text of each word letter (`A`–`Z`); `motion`: the G0–G3 in force.
    last: [Option<String>; 26],
    motion: Option<u8>,
    plain: bool,
}

impl<P: Deref<Target = Post>> LineWriter<P> {
    pub fn new(post: P) -> LineWriter<P> {
        LineWriter {
            next: post.line_numbers.as_ref().map_or(0, |l| l.start),
            last: Default::default(),
            motion: None,
            plain: post.line_numbers.is_none()
                && post.format.modal.is_empty()
                && post.format.line_end == LineEnd::Lf,
            post,
        }
    }

    /// Does this writer change lines at all? (Without numbers, modal words and CR LF, a line
    /// is written as it is.)
    pub fn is_plain(&self) -> bool {
        self.plain
    }

    /// The line as it is written (without its line end).
    pub fn line(&mut self, line: &str) -> String {
        if self.plain || line.is_empty() {
            return line.to_string();
        }
        let mut text = if self.post.format.modal.is_empty() {
            line.to_string()
        } else {
            self.suppress(line)
        };
        if let Some(n) = &self.post.line_numbers {
            if line != "%" {
                text = format!("{}{:0w$} {text}", n.letter, self.next, w = n.width);
                self.next = self.next.saturating_add(n.step);
            }
        }
        text
    }

    /// The line end.
    pub fn end(&self) -> &'static str {
        self.post.format.line_end.text()
    }

    fn suppress(&mut self, line: &str) -> String {
        let modal = &self.post.format.modal;
        let motion_modal = modal.iter().any(|m| m == "motion");
        let parts: Vec<&str> = line.split(' ').filter(|p| !p.is_empty()).collect();
        let mut keep = vec![true; parts.len()];
        let (mut words, mut dropped) = (0, 0);
        // a probe ends where it touches: nothing of its line is known after it
        let mut unknown_after = false;
        for (k, part) in parts.iter().enumerate() {
            let Some((letter, value, guarded)) = code_word(part) else {
                continue;
            };
            words += 1;
            let drop = if letter == 'G' {
                let v: f64 = value.parse().unwrap_or(-1.0);
                if (0.0..=3.0).contains(&v) && v.fract() == 0.0 {
                    let m = v as u8;
                    let same = self.motion == Some(m);
                    self.motion = Some(m);
                    motion_modal && same && !guarded
                } else {
                    if (38.0..39.0).contains(&v) || v == 31.0 || v == 80.0 {
                        unknown_after = true;
                    }
                    false
                }
            } else {
                let idx = (letter as u8 - b'A') as usize;
                let same = self.last[idx]
                    .as_deref()
                    .is_some_and(|l| numeric_eq(l, value));
                self.last[idx] = Some(value.to_string());
                same && !guarded && modal.iter().any(|m| m.len() == 1 && m.starts_with(letter))
            };
            if drop {
                keep[k] = false;
                dropped += 1;
            }
        }
        if unknown_after {
            self.motion = None;
            self.last = Default::default();
        }
        if dropped == 0 || dropped == words {
            return line.to_string();
        }
        let indent = &line[..line.len() - line.trim_start_matches(' ').len()];
        let kept: Vec<&str> = parts
            .iter()
            .zip(keep)
            .filter_map(|(p, k)| k.then_some(*p))
            .collect();
        format!("{indent}{}", kept.join(" "))
    }
}

/// Values equal as numbers (`G00` = `G0`, `1.000` = `1.0`).
fn numeric_eq(a: &str, b: &str) -> bool {
    match (a.parse::<f64>(), b.parse::<f64>()) {
        (Ok(x), Ok(y)) => x == y,
        _ => a == b,
    }
}

/// A part of a line that is a word: its letter, its number and whether a comment is glued to
/// it (`Z1.000(=…)`: guarded, never taken out).
fn code_word(part: &str) -> Option<(char, &str, bool)> {
    let letter = part.chars().next()?;
    if !letter.is_ascii_uppercase() {
        return None;
    }
    let rest = &part[1..];
    let (number, comment) = match rest.find(['(', ';']) {
        Some(i) => (&rest[..i], &rest[i..]),
        None => (rest, ""),
    };
    let numeric = !number.is_empty()
        && number
            .chars()
            .all(|c| c.is_ascii_digit() || matches!(c, '.' | '-' | '+' | ','));
    numeric.then_some((letter, number, !comment.is_empty()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn post(extra_format: &str, numbers: &str) -> Post {
        let text = crate::builtin::source("linuxcnc")
            .unwrap()
            .replace("modal = []", extra_format)
            .replace("[comments]", &format!("{numbers}\n[comments]"));
        crate::load("t.toml", &text).unwrap()
    }

    #[test]
    fn modal_words_are_not_repeated_but_expressions_stay() {
        let p = post("modal = [\"F\", \"motion\", \"Z\"]", "");
        let p = crate::load(
            "t.toml",
            &p.source.replace("line_end = \"lf\"", "line_end = \"crlf\""),
        )
        .unwrap();
        let mut w = LineWriter::new(&p);
        assert!(!w.is_plain());
        assert_eq!(
            w.line("G01 F300.000 X1.000 Y2.000 Z-1.000"),
            "G01 F300.000 X1.000 Y2.000 Z-1.000"
        );
        assert_eq!(
            w.line("G01 F300.000 X3.000 Y2.000 Z-1.000"),
            "X3.000 Y2.000"
        );
        // a Z with its probe expression is never taken out
        assert_eq!(
            w.line("G01 F300.000 X4.000 Y2.000 Z-1.000(=-1.000+1.000*[#51-0.000])"),
            "X4.000 Y2.000 Z-1.000(=-1.000+1.000*[#51-0.000])"
        );
        // a line that would lose every word is written whole
        assert_eq!(w.line("G01 F300.000 Z-1.000"), "G01 F300.000 Z-1.000");
        // after a probe nothing is known
        assert_eq!(w.line("G38.3 Z0 F50.000"), "G38.3 Z0 F50.000");
        assert_eq!(w.line("G01 F50.000 Z0"), "G01 F50.000 Z0");
        assert_eq!(w.line("  (a comment)"), "  (a comment)");
        assert_eq!(w.end(), "\r\n");
    }

    #[test]
    fn line_numbers_count_every_line_but_percent() {
        let p = post(
            "modal = []",
            "[line_numbers]\nstart = 5\nstep = 5\nwidth = 3\n",
        );
        let mut w = LineWriter::new(&p);
        assert_eq!(w.line("%"), "%");
        assert_eq!(w.line("G00 Z1.000"), "N005 G00 Z1.000");
        assert_eq!(w.line("(c)"), "N010 (c)");
    }

    #[test]
    fn the_built_in_writers_change_nothing() {
        for name in crate::builtin::NAMES {
            let p = crate::builtin::get(name).unwrap();
            let mut w = LineWriter::new(p);
            // only xcam's CR LF line ends make a writer that is not plain
            assert_eq!(w.is_plain(), p.format.line_end == LineEnd::Lf, "{name}");
            assert_eq!(w.line("G01 F1.000 X1.000"), "G01 F1.000 X1.000");
        }
    }
}
