//! A file that cannot be read as DXF: what went wrong and the line where reading stopped, in
//! English and German.

use std::fmt;

/// A file that cannot be read as DXF, with the line where reading stopped.
#[derive(Debug, Clone, PartialEq)]
pub struct DxfError {
    /// 1-based line number (0 when the problem is not tied to a line).
    pub line: usize,
    pub kind: DxfErrorKind,
}

#[derive(Debug, Clone, PartialEq)]
pub enum DxfErrorKind {
    /// The file ends in the middle of a group (code without value).
    Truncated,
    /// A group code line that is not an integer.
    BadGroupCode(String),
    /// A numeric value that does not parse.
    BadNumber { code: i32, value: String },
    /// Binary DXF is not supported.
    Binary,
    /// No `EOF` / missing sections: not a DXF file at all.
    NotDxf,
    /// UTF-16 text (a byte-order mark): a DXF file is ASCII or UTF-8.
    Utf16 { big_endian: bool },
}

impl fmt::Display for DxfError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.kind {
            DxfErrorKind::Truncated => {
                write!(f, "line {}: file ends in the middle of a group", self.line)
            }
            DxfErrorKind::BadGroupCode(s) => {
                write!(
                    f,
                    "line {}: '{}' is not a group code",
                    self.line,
                    excerpt(s)
                )
            }
            DxfErrorKind::BadNumber { code, value } => {
                write!(
                    f,
                    "line {}: value '{}' of group {} is not a number",
                    self.line,
                    excerpt(value),
                    code
                )
            }
            DxfErrorKind::Binary => {
                write!(f, "binary DXF files are not supported; export as ASCII DXF")
            }
            DxfErrorKind::Utf16 { big_endian } => {
                let which = if *big_endian { "BE" } else { "LE" };
                write!(
                    f,
                    "the file is UTF-16 {which} text, a DXF must be ASCII or UTF-8 (PowerShell 5's `>` writes UTF-16: write with -o FILE instead)"
                )
            }
            DxfErrorKind::NotDxf => {
                write!(f, "line {}: not a DXF file (no SECTION found)", self.line)
            }
        }
    }
}

impl std::error::Error for DxfError {}

impl DxfError {
    /// The German wording of [`Display`](fmt::Display)'s text, for German reports.
    pub fn german(&self) -> String {
        let line = self.line;
        match &self.kind {
            DxfErrorKind::Truncated => {
                format!("Zeile {line}: die Datei endet mitten in einer Gruppe")
            }
            DxfErrorKind::BadGroupCode(s) => {
                format!("Zeile {line}: '{}' ist kein Gruppencode", excerpt(s))
            }
            DxfErrorKind::BadNumber { code, value } => format!(
                "Zeile {line}: Wert '{}' der Gruppe {code} ist keine Zahl",
                excerpt(value)
            ),
            DxfErrorKind::Binary => {
                "binäre DXF-Dateien werden nicht unterstützt; als ASCII-DXF exportieren".into()
            }
            DxfErrorKind::Utf16 { big_endian } => {
                let which = if *big_endian { "BE" } else { "LE" };
                format!("die Datei ist UTF-16-{which}-Text, eine DXF muss ASCII oder UTF-8 sein (PowerShell 5 schreibt mit `>` UTF-16: stattdessen mit -o DATEI schreiben)")
            }
            DxfErrorKind::NotDxf => {
                format!("Zeile {line}: keine DXF-Datei (kein SECTION gefunden)")
            }
        }
    }
}

/// At most 40 characters of a line, control characters escaped (`\0`, `\u{7f}`): a binary
/// file given as DXF shows a short readable excerpt, never raw bytes.
fn excerpt(s: &str) -> String {
    const MAX: usize = 40;
    let mut out = String::new();
    for (i, c) in s.chars().enumerate() {
        if i == MAX {
            out.push('…');
            break;
        }
        match c {
            '\0' => out.push_str("\\0"),
            c if c.is_control() => out.extend(c.escape_default()),
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_reading_error_has_its_german_wording() {
        let kinds = [
            DxfErrorKind::Truncated,
            DxfErrorKind::BadGroupCode("layer".into()),
            DxfErrorKind::BadNumber {
                code: 10,
                value: "1,5".into(),
            },
            DxfErrorKind::Binary,
            DxfErrorKind::NotDxf,
            DxfErrorKind::Utf16 { big_endian: false },
        ];
        for kind in kinds {
            let e = DxfError { line: 3, kind };
            let (en, de) = (e.to_string(), e.german());
            assert_ne!(en, de);
            for word in ["line ", " not ", " is ", "file "] {
                assert!(!de.contains(word), "{de}");
            }
        }
    }
}
