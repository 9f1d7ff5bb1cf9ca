//! What GRBL 1.1 accepts, from its sources (`protocol.c`: comments and whitespace are
//! dropped before a line is stored, at most 80 characters stay; `gcode.c`: the word letters,
//! G/M numbers and modal groups of `gc_execute_line`) and its wiki page "Grbl v1.1 Commands".

/// (G number, modal group): group 0 is non-modal.
const G: &[(&str, u8)] = &[
    ("4", 0),
    ("10", 0),
    ("28", 0),
    ("30", 0),
    ("53", 0),
    ("92", 0),
    ("0", 1),
    ("1", 1),
    ("2", 1),
    ("3", 1),
    ("38.2", 1),
    ("38.3", 1),
    ("38.4", 1),
    ("38.5", 1),
    ("80", 1),
    ("17", 2),
    ("18", 2),
    ("19", 2),
    ("90", 3),
    ("91", 3),
    ("91.1", 4),
    ("93", 5),
    ("94", 5),
    ("20", 6),
    ("21", 6),
    ("40", 7),
    ("43.1", 8),
    ("49", 8),
    ("54", 12),
    ("55", 12),
    ("56", 12),
    ("57", 12),
    ("58", 12),
    ("59", 12),
    ("61", 13),
];
/// (M number, modal group).
const M: &[(&str, u8)] = &[
    ("0", 4),
    ("1", 4),
    ("2", 4),
    ("30", 4),
    ("3", 7),
    ("4", 7),
    ("5", 7),
    ("7", 8),
    ("8", 8),
    ("9", 8),
    ("56", 9),
];
/// The other word letters.
const LETTERS: &str = "FIJKLNPRSTXYZ";
/// GRBL's line buffer (LINE_BUFFER_SIZE 80, one byte for the terminator).
const MAX_CODE: usize = 79;

/// The characters GRBL keeps of a line: comments and whitespace dropped, upper case.
pub fn code(line: &str) -> Result<String, String> {
    let mut out = String::new();
    let mut in_paren = false;
    for c in line.chars() {
        if in_paren {
            in_paren = c != ')';
        } else if c == '(' {
            in_paren = true;
        } else if c == ';' {
            break;
        } else if !c.is_whitespace() {
            out.push(c.to_ascii_uppercase());
        }
    }
    if in_paren {
        return Err("unclosed comment".into());
    }
    Ok(out)
}

/// Canonical number text of a G/M value: `01` → `1`, `38.30` → `38.3`.
fn canon(v: &str) -> String {
    let (i, f) = v.split_once('.').unwrap_or((v, ""));
    let i = i.trim_start_matches('0');
    let i = if i.is_empty() { "0" } else { i };
    let f = f.trim_end_matches('0');
    if f.is_empty() {
        i.to_string()
    } else {
        format!("{i}.{f}")
    }
}

pub fn check_line(line: &str) -> Result<(), String> {
    let code = code(line)?;
    if code.len() > MAX_CODE {
        return Err(format!(
            "{} characters: longer than GRBL's line buffer",
            code.len()
        ));
    }
    let b = code.as_bytes();
    let mut i = 0;
    let mut seen_letters = String::new();
    let mut groups: Vec<(char, u8)> = Vec::new();
    let mut g10 = false;
    let mut l = None;
    while i < b.len() {
        let letter = b[i] as char;
        i += 1;
        let start = i;
        if i < b.len() && (b[i] == b'-' || b[i] == b'+') {
            i += 1;
        }
        let digits = i;
        while i < b.len() && (b[i].is_ascii_digit() || b[i] == b'.') {
            i += 1;
        }
        let value = &code[start..i];
        let ok_number = i > digits && value.matches('.').count() <= 1 && value != ".";
        if !letter.is_ascii_uppercase() {
            return Err(format!("'{letter}' is not a word letter (error:1)"));
        }
        if !ok_number {
            return Err(format!("{letter} without a plain number (error:2)"));
        }
        match letter {
            'G' | 'M' => {
                let table = if letter == 'G' { G } else { M };
                let v = canon(value);
                let Some(&(_, group)) = table.iter().find(|(n, _)| *n == v) else {
                    return Err(format!("{letter}{value} is not supported (error:20)"));
                };
                if group != 0 && groups.contains(&(letter, group)) {
                    return Err(format!("two {letter} words of one modal group (error:21)"));
                }
                if group != 0 {
                    groups.push((letter, group));
                }
                g10 |= letter == 'G' && v == "10";
            }
            _ if LETTERS.contains(letter) => {
                if seen_letters.contains(letter) {
                    return Err(format!("{letter} twice (error:25)"));
                }
                seen_letters.push(letter);
                if letter == 'L' {
                    l = Some(canon(value));
                }
            }
            _ => return Err(format!("word {letter} is not supported (error:20)")),
        }
    }
    if g10 && !matches!(l.as_deref(), Some("2") | Some("20")) {
        return Err("G10 needs L2 or L20".into());
    }
    Ok(())
}

pub fn check_program(g: &str) -> Result<(), String> {
    for (n, line) in g.lines().enumerate() {
        check_line(line).map_err(|e| format!("line {}: {line}: {e}", n + 1))?;
    }
    Ok(())
}
