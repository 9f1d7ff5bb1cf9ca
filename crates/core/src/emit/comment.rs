//! Text in G-code comments made safe for each controller's comment rules (the rules are the
//! post's `[comments]`, applied by `crates/post`). File names, path names and `Q` texts come
//! from the user; a character a controller reads as something else than comment text is
//! replaced, and `comment_changes` names every user text that was changed so that `check`
//! and `compile` can warn about it. The built-in posts' rules:
//!
//! - every dialect: the reference's `)` → `]` and `\` → `/`, and `(` → `[` (LinuxCNC rejects
//!   a `(` inside a comment: "nested comment"); control characters become blanks;
//! - `linuxcnc`: a comment whose text starts with one of LinuxCNC's active comment words
//!   (`MSG,`, `DEBUG,`, `PRINT,`, `LOGOPEN,`, `PROBEOPEN` …) would be executed: it gets a `_`
//!   in front; a line is at most 255 characters (rs274ngc's `LINELEN`);
//! - `grbl`: GRBL 1.1 picks its real-time commands out of the byte stream wherever they are,
//!   comments included: `!` (feed hold), `~` (cycle start), `?` (status), and every byte from
//!   0x80 (a UTF-8 `Ä` holds 0x84, the safety door). Those become `_` (German letters `ae`,
//!   `oe`, `ue`, `ss`), and a line is at most 127 characters, so that it fits GRBL's 128-byte
//!   receive buffer with its line end (senders that count characters need that).
//!
//! Text in comments made safe per dialect (`(` → `[` everywhere; LinuxCNC's active comment words
//! and 255-byte lines; GRBL's real-time characters `!~?` and bytes ≥ 0x80, 127-character lines);
//! `comment_changes`: a warning (`Msg::CommentTextChanged`) for each user text changed (file name,
//! path labels, `Q` texts), the same in `check` and `compile`.

use crate::args;
use crate::diag::{Diagnostic, Msg, Origin};
use crate::machine::Dialect;
use crate::model::{Element, Model};

/// A comment line: `indent` blanks and the text, trimmed and made safe for `dialect` by its
/// post's `[comments]` rules (`crates/post/src/comment.rs`), cut to its longest line.
pub fn comment_line(dialect: Dialect, indent: usize, text: &str) -> String {
    dialect
        .post()
        .comment(indent, text, &millpath_post::Globals::default())
}

/// The text of a comment (without the parentheses) as `dialect` gets it.
pub fn safe_text(dialect: Dialect, text: &str) -> String {
    millpath_post::comment::safe_text(&dialect.post().comments, text)
}

/// What the reference itself writes for a text: its own replacements only.
fn reference_text(text: &str) -> String {
    text.trim().replace(')', "]").replace('\\', "/")
}

/// A user text (file name, path label, `Q` text) as written at `indent` after `prefix`:
/// `Some(written)` when the dialect's rules changed it beyond the reference's own `)`/`\`.
fn changed(dialect: Dialect, indent: usize, prefix: &str, text: &str) -> Option<String> {
    let whole = format!("{prefix}{text}");
    let line = comment_line(dialect, indent, &whole);
    let plain = format!("{}({})", " ".repeat(indent), reference_text(&whole));
    (line != plain).then(|| {
        let inner = &line[indent + 1..line.len() - 1];
        inner.strip_prefix(prefix).unwrap_or(inner).to_string()
    })
}

/// One warning per user text that the comments of `model`'s program change: the file name,
/// the path labels and the `Q` texts (subpaths included), located where the text comes from.
pub fn comment_changes(model: &Model, file_name: &str, dialect: Dialect) -> Vec<Diagnostic> {
    let mut out: Vec<Diagnostic> = Vec::new();
    let mut seen = std::collections::HashSet::new();
    let mut note = |text: &str, written: String, origin: Origin| {
        if seen.insert(text.to_string()) {
            out.push(Diagnostic::warning(
                Msg::CommentTextChanged,
                origin,
                args![text, written, dialect.name()],
            ));
        }
    };
    let start = model.raw.start_origin();
    // the `Model name[file]` comment repeats the file name: one warning is enough
    if let Some(w) = changed(dialect, 0, "", file_name) {
        note(file_name, w, start);
    } else if let Some(w) = changed(dialect, 2, "Model ", &model.label()) {
        note(&model.label(), w, start);
    }
    walk(model, dialect, 0, &mut note);
    out
}

fn walk(model: &Model, dialect: Dialect, depth: usize, note: &mut dyn FnMut(&str, String, Origin)) {
    let q = |q: Option<&str>,
             indent: usize,
             origin: &Origin,
             note: &mut dyn FnMut(&str, String, Origin)| {
        if let Some(q) = q {
            if let Some(w) = changed(dialect, indent, "Q:", q) {
                note(q, w, origin.clone());
            }
        }
    };
    for e in &model.elements {
        match e {
            Element::Chain(c) => c
                .segs
                .iter()
                .for_each(|s| q(s.q.as_deref(), 4, &s.origin, note)),
            Element::Drill(d) => q(d.q.as_deref(), 4, &d.origin, note),
            Element::Helix(h) => q(h.q.as_deref(), 4, &h.origin, note),
            Element::Subpath(emb) => {
                if let (Some(t), true) = (&emb.target, depth < 10) {
                    let label = t.label();
                    if let Some(w) = changed(dialect, 2, "START Subpath ", &label) {
                        note(&label, w, emb.origin.clone());
                    }
                    walk(t, dialect, depth + 1, note);
                }
            }
            _ => {}
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parentheses_become_brackets_in_every_dialect() {
        for d in [Dialect::Reference, Dialect::LinuxCnc, Dialect::Grbl] {
            assert_eq!(
                comment_line(d, 0, "Halter (v2).dxf"),
                "(Halter [v2].dxf)",
                "{d}"
            );
            assert_eq!(comment_line(d, 2, " a)b\\c "), "  (a]b/c)");
            assert_eq!(comment_line(d, 0, "a\nb\rc"), "(a b c)");
        }
    }

    #[test]
    fn linuxcnc_active_comments_are_defused() {
        let d = Dialect::LinuxCnc;
        assert_eq!(comment_line(d, 0, "MSG,hello.dxf"), "(_MSG,hello.dxf)");
        assert_eq!(comment_line(d, 0, "logopen,x.dxf"), "(_logopen,x.dxf)");
        assert_eq!(comment_line(d, 0, "Message.dxf"), "(Message.dxf)");
        assert_eq!(
            comment_line(d, 0, "Model 1.1P[msg,x.dxf]"),
            "(Model 1.1P[msg,x.dxf])"
        );
        assert_eq!(comment_line(Dialect::Reference, 0, "MSG,a"), "(MSG,a)");
        let long = "x".repeat(400);
        let line = comment_line(d, 2, &long);
        assert_eq!(line.len(), 255);
        assert!(line.ends_with("...)"));
    }

    #[test]
    fn grbl_gets_no_realtime_commands_and_short_lines() {
        let d = Dialect::Grbl;
        assert_eq!(comment_line(d, 0, "Teil!~?.dxf"), "(Teil___.dxf)");
        assert_eq!(comment_line(d, 0, "Größe Ä.dxf"), "(Groesse Ae.dxf)");
        assert_eq!(comment_line(d, 0, "Ø 5 à"), "(_ 5 _)");
        let line = comment_line(d, 4, &format!("Q:{}", "ä".repeat(300)));
        assert!(line.len() <= 127 && line.is_ascii(), "{line}");
        // the reference keeps its bytes
        assert_eq!(comment_line(Dialect::Reference, 0, "Größe!"), "(Größe!)");
    }

    #[test]
    fn changes_are_reported_beyond_the_references_own() {
        assert_eq!(changed(Dialect::Reference, 0, "", "a)b.dxf"), None);
        assert_eq!(
            changed(Dialect::Reference, 0, "", "a(b).dxf").as_deref(),
            Some("a[b].dxf")
        );
        assert_eq!(changed(Dialect::Grbl, 4, "Q:", "Ä").as_deref(), Some("Ae"));
        assert_eq!(changed(Dialect::LinuxCnc, 4, "Q:", "Ä"), None);
    }
}
