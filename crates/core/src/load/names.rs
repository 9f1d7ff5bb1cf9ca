//! Path-name and file-name patterns: which file may contain which path (reference-input.md §3).
//!
//! Path/file-name patterns, "does this file contain that path" (reference-input.md §3.1–3.2;
//! answers remembered per patterns).

use crate::load::name_regex::{Groups, NameRegex};
use crate::load::regex_cache::Memo;
use std::cmp::Ordering;
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

pub const DEFAULT_PATH_PATTERN: &str = "([0-9]{4})[.]([0-9]+)([A-Z])";
pub const DEFAULT_FILE_PATTERN: &str = "([0-9]{4})(?:[.]([0-9]+))?";

/// The compiled forms of the user's `/n` and `/p` patterns.
#[derive(Debug)]
pub struct Patterns {
    pub path_text: String,
    /// `^(?i:N)$`: layer test and path side of file comparisons.
    pub path_full: NameRegex,
    /// `N`, case-sensitive, unanchored: `@` references.
    pub path_cs: NameRegex,
    /// `^(?:N)$`, case-sensitive: names that match only when case is ignored get a warning.
    pub path_exact: NameRegex,
    /// `(?i)N`, unanchored: subpath targets in `>` values.
    pub path_ci: NameRegex,
    /// `^(?i:F)$`.
    file_full: NameRegex,
    /// `(?i)F`, unanchored.
    file_any: NameRegex,
    /// `(?i)(F)-(F)` and the group index of the second part.
    file_range: NameRegex,
    range_second: usize,
    /// [`Patterns::file_contains`] answers by file stem and path name: every session of a
    /// `check` run asks the same questions about the same folder.
    contains: Mutex<(usize, ContainsTable)>,
}

/// File stem → path name → whether the file may contain the path.
type ContainsTable = HashMap<String, HashMap<String, bool>>;

/// Answers remembered at most (then the table starts again).
const CONTAINS_CAPACITY: usize = 100_000;

impl Patterns {
    /// Both patterns compiled, shared by every file and analysis of the process;
    /// `Err((which option, pattern, message))` for invalid ones.
    pub fn shared(path: &str, file: &str) -> Result<Arc<Patterns>, (char, String, String)> {
        type Compiled = Result<Arc<Patterns>, (char, String, String)>;
        static MEMO: OnceLock<Memo<(String, String), Compiled>> = OnceLock::new();
        MEMO.get_or_init(Memo::new)
            .get_or(&(path.to_string(), file.to_string()), || {
                Patterns::new(path, file).map(Arc::new)
            })
    }

    /// Compiles both patterns; `Err((which option, pattern, message))` for invalid ones.
    pub fn new(path: &str, file: &str) -> Result<Patterns, (char, String, String)> {
        fn bad(c: char, p: &str) -> impl Fn(String) -> (char, String, String) + '_ {
            move |e| (c, p.to_string(), e)
        }
        let path_full = NameRegex::new(&format!("^(?i:{path})$")).map_err(bad('n', path))?;
        let path_cs = NameRegex::new(path).map_err(bad('n', path))?;
        let path_exact = NameRegex::new(&format!("^(?:{path})$")).map_err(bad('n', path))?;
        let path_ci = NameRegex::new(&format!("(?i){path}")).map_err(bad('n', path))?;
        let file_full = NameRegex::new(&format!("^(?i:{file})$")).map_err(bad('p', file))?;
        let file_any = NameRegex::new(&format!("(?i){file}")).map_err(bad('p', file))?;
        let file_range =
            NameRegex::new(&format!("(?i)({file})-({file})")).map_err(bad('p', file))?;
        let range_second = 2 + file_any.captures_len() - 1;
        Ok(Patterns {
            path_text: path.to_string(),
            path_full,
            path_cs,
            path_exact,
            path_ci,
            file_full,
            file_any,
            file_range,
            range_second,
            contains: Mutex::default(),
        })
    }

    /// Compare(fileToken, pathName) of §3.2; `None` when either does not match its pattern.
    pub fn compare(&self, file_token: &str, path_name: &str) -> Option<i64> {
        let f = self.file_full.captures(file_token)?;
        let p = self.path_full.captures(path_name)?;
        let (mut gf, mut gp) = (0i64, 0i64);
        let n = f.len().min(p.len());
        for i in 1..n {
            let a = group(&f, i);
            let b = group(&p, i);
            if !a.is_empty() {
                gf += 1;
            }
            if !b.is_empty() {
                gp += 1;
            }
            if a.is_empty() || b.is_empty() {
                break;
            }
            let c = match (a.parse::<i32>(), b.parse::<i32>()) {
                (Ok(x), Ok(y)) => (x as i64) - (y as i64),
                _ => match a.to_lowercase().cmp(&b.to_lowercase()) {
                    Ordering::Less => -1,
                    Ordering::Equal => 0,
                    Ordering::Greater => 1,
                },
            };
            if c != 0 {
                return Some(c);
            }
        }
        Some(if gp >= gf { 0 } else { gf - gp })
    }

    /// The spelling a path name that matches the pattern only when case is ignored (a layer
    /// `1000_1a`) was likely meant to have: its upper-case form, if that matches exactly.
    /// `None` for names that match as they are (reference-input.md §1.3 takes both).
    pub fn meant_case(&self, name: &str) -> Option<String> {
        if self.path_exact.is_match(name) || !self.path_full.is_match(name) {
            return None;
        }
        let upper = name.to_uppercase();
        self.path_exact.is_match(&upper).then_some(upper)
    }

    /// Whether a file (name without directory and extension) may contain the path.
    pub fn file_contains(&self, file_stem: &str, path_name: &str) -> bool {
        let table = || self.contains.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(&known) = table().1.get(file_stem).and_then(|m| m.get(path_name)) {
            return known;
        }
        let answer = self.file_contains_uncached(file_stem, path_name);
        let (len, map) = &mut *table();
        if *len >= CONTAINS_CAPACITY {
            (*len, *map) = (0, HashMap::new());
        }
        let by_name = map.entry(file_stem.to_string()).or_default();
        if by_name.insert(path_name.to_string(), answer).is_none() {
            *len += 1;
        }
        answer
    }

    fn file_contains_uncached(&self, file_stem: &str, path_name: &str) -> bool {
        for c in self.file_range.captures_iter(file_stem) {
            let (Some(a), Some(b)) = (c.get(1), c.get(self.range_second)) else {
                continue;
            };
            if self.compare(a, path_name).is_some_and(|x| x <= 0)
                && self.compare(b, path_name).is_some_and(|x| x >= 0)
            {
                return true;
            }
        }
        self.file_any
            .find_iter(file_stem)
            .any(|m| self.compare(m, path_name) == Some(0))
    }
}

fn group<'a>(c: &Groups<'a>, i: usize) -> &'a str {
    c.get(i).unwrap_or("")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_patterns() {
        let p = Patterns::new(DEFAULT_PATH_PATTERN, DEFAULT_FILE_PATTERN).unwrap();
        // the second round answers from the table
        for _ in 0..2 {
            default_answers(&p);
        }
    }

    fn default_answers(p: &Patterns) {
        assert!(p.file_contains("8998", "8998.2P"));
        assert!(p.file_contains("8998", "8998.31T"));
        assert!(p.file_contains("8999.01P", "8999.1P"));
        assert!(p.file_contains("8998.31-8998.34P", "8998.31T"));
        assert!(p.file_contains("8998.31-8998.34P", "8998.34P"));
        assert!(p.file_contains("8998.31-8998.34P", "8998.33X"));
        assert!(!p.file_contains("8998.31-8998.34P", "8998.2P"));
        assert!(p.file_contains("2051 Pv Schlüssel", "2051.2P"));
        assert!(p.file_contains("8999.23 Pv", "8999.23P"));
        assert!(!p.file_contains("8999.24 Pv", "8999.23P"));
        assert!(p.file_contains("1234-1236", "1235.99B"));
        assert!(p.file_contains("1234.5-1234.10", "1234.8A"));
        assert!(!p.file_contains("1234.5-1234.10", "1234.40A"));
    }

    #[test]
    fn names_in_the_wrong_case_get_their_meant_spelling() {
        let p = Patterns::new(DEFAULT_PATH_PATTERN, DEFAULT_FILE_PATTERN).unwrap();
        assert_eq!(p.meant_case("1000.1a").as_deref(), Some("1000.1A"));
        assert_eq!(p.meant_case("1000.1A"), None);
        assert_eq!(p.meant_case("1000-1A"), None);
        // a pattern that takes lower case: nothing to say
        let lower = Patterns::new("([0-9]{4})[.]([0-9]+)([a-z])", DEFAULT_FILE_PATTERN).unwrap();
        assert_eq!(lower.meant_case("1000.1a"), None);
    }

    #[test]
    fn unit_test_patterns_of_the_reference() {
        let p = Patterns::new("([0-9]+)[.]([0-9A-Z]+)", "([0-9]+)(?:[.]([0-9A-Z]+))?").unwrap();
        assert_eq!(p.compare("8002", "8002.0"), Some(0));
        assert_eq!(p.compare("8002", "8002.A"), Some(0));
        assert!(p.file_contains("FILE 8000.4-8001,8000.1-8001.3", "8000.2"));
        assert!(!p.file_contains("FILE 8000.4-8001,8000.1-8000.2", "8000.3"));
        assert!(!p.file_contains("FILE 8000.0-8000.3,8000.5,8001", "8000.4"));
        assert!(p.file_contains("FILE 8000-8002", "8002.99"));
        assert!(!p.file_contains("FILE 8001-8003", "8000.99"));
    }

    #[test]
    fn invalid_patterns_are_reported() {
        assert_eq!(Patterns::new("(", DEFAULT_FILE_PATTERN).unwrap_err().0, 'n');
        assert_eq!(Patterns::new(DEFAULT_PATH_PATTERN, "[").unwrap_err().0, 'p');
    }
}
