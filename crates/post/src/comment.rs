//! Comment text made safe by a post's `[comments]` rules. Every post: `(` → `[`, `)` → `]`,
//! `\` → `/`, control characters → blanks, the text trimmed. Then, as the post says:
//! `reserved` characters → `_` (GRBL's real-time commands `!~?`); `ascii`: German letters
//! transliterated (`ä` → `ae`, …), other non-ASCII characters → `_` (GRBL reads bytes from
//! 0x80 as real-time commands); `active_words`: a comment starting with one of them (followed
//! by `,`, a blank or nothing; LinuxCNC's `MSG`, `PROBEOPEN`, …) gets a `_` in front;
//! `line_break`: what a line break inside the text becomes (else a blank).

/// The text of a comment (without its delimiters) under `rules`.
pub fn safe_text(rules: &CommentRules, text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.trim().chars() {
        match c {
            ')' => out.push(']'),
            '(' => out.push('['),
            '\\' => out.push('/'),
            '\n' if !rules.line_break.is_empty() => out.push_str(&rules.line_break),
            c if c.is_control() => out.push(' '),
            c if rules.reserved.contains(c) => out.push('_'),
            c if rules.ascii && !c.is_ascii() => transliterate(c, &mut out),
            c => out.push(c),
        }
    }
    if active(rules, &out) {
        out.insert(0, '_');
    }
    out
}

fn transliterate(c: char, out: &mut String) {
    out.push_str(match c {
        'ä' => "ae",
        'ö' => "oe",
        'ü' => "ue",
        'Ä' => "Ae",
        'Ö' => "Oe",
        'Ü' => "Ue",
        'ß' => "ss",
        _ => "_",
    })
}

/// Does the controller read this comment text as a command?
fn active(rules: &CommentRules, text: &str) -> bool {
    if rules.active_words.is_empty() {
        return false;
    }
    let t = text.trim_start();
    let word_end = t
        .find(|c: char| !c.is_ascii_alphabetic())
        .unwrap_or(t.len());
    let word = &t[..word_end];
    let next = t[word_end..].chars().next();
    rules
        .active_words
        .iter()
        .any(|w| w.eq_ignore_ascii_case(word))
        && matches!(next, None | Some(',' | ' ' | '\t'))
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CommentStyle {
    Parens,
    Semicolon,
}

#[derive(Debug, Clone, PartialEq)]
pub struct CommentRules {
    pub style: CommentStyle,
    /// Characters replaced by `_`.
    pub reserved: String,
    /// Only ASCII (German letters transliterated, others `_`).
    pub ascii: bool,
    /// Comment words the controller executes.
    pub active_words: Vec<String>,
    /// What a line break inside a comment becomes (xCAM's `_C_N_L_`); empty: a blank.
    pub line_break: String,
}
