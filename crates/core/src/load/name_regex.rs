//! The regular expressions of path and file names (`/n`, `/p`), built for short haystacks.
//!
//! Same syntax and matches as the `regex` crate (both are `regex_automata`'s meta engine), but
//! built without literal prefilters and lazy/full DFAs: those speed up searches in long texts
//! and cost most of the build, while names are a few characters long. The six patterns of a
//! run were built on every `check`'s critical path (each worker needs them before its first
//! file): 3.7 M instructions before, under 1 M now. Matching stays linear (PikeVM, or the
//! bounded backtracker / one-pass DFA where they apply).

use regex_automata::meta::{self, Regex};
use regex_automata::util::captures::Captures;

/// A compiled name pattern.
#[derive(Debug, Clone)]
pub struct NameRegex {
    re: Regex,
}

impl NameRegex {
    /// Compiles `pattern`; the error message is the `regex` crate's.
    pub fn new(pattern: &str) -> Result<NameRegex, String> {
        let config = meta::Config::new()
            .auto_prefilter(false)
            .hybrid(false)
            .dfa(false);
        meta::Builder::new()
            .configure(config)
            .build(pattern)
            .map(|re| NameRegex { re })
            .map_err(|e| e.to_string())
    }

    pub fn is_match(&self, haystack: &str) -> bool {
        self.re.is_match(haystack)
    }

    /// The leftmost-first match.
    pub fn find<'h>(&self, haystack: &'h str) -> Option<&'h str> {
        self.re.find(haystack).map(|m| &haystack[m.range()])
    }

    /// Every non-overlapping match, left to right.
    pub fn find_iter<'r, 'h>(&'r self, haystack: &'h str) -> impl Iterator<Item = &'h str> + 'r
    where
        'h: 'r,
    {
        self.re
            .find_iter(haystack)
            .map(move |m| &haystack[m.range()])
    }

    /// The groups of the leftmost-first match (group 0 is the whole match).
    pub fn captures<'h>(&self, haystack: &'h str) -> Option<Groups<'h>> {
        let mut caps = self.re.create_captures();
        self.re.captures(haystack, &mut caps);
        caps.is_match().then_some(Groups { haystack, caps })
    }

    /// The groups of every non-overlapping match, left to right.
    pub fn captures_iter<'r, 'h>(
        &'r self,
        haystack: &'h str,
    ) -> impl Iterator<Item = Groups<'h>> + 'r
    where
        'h: 'r,
    {
        self.re
            .captures_iter(haystack)
            .map(move |caps| Groups { haystack, caps })
    }

    /// Number of groups, group 0 included.
    pub fn captures_len(&self) -> usize {
        self.re.captures_len()
    }
}

/// The groups of one match.
pub struct Groups<'h> {
    haystack: &'h str,
    caps: Captures,
}

impl<'h> Groups<'h> {
    /// Group `i`, `None` when it took no part in the match.
    pub fn get(&self, i: usize) -> Option<&'h str> {
        self.caps.get_group(i).map(|s| &self.haystack[s.range()])
    }

    /// Number of groups, group 0 included.
    pub fn len(&self) -> usize {
        self.caps.group_len()
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The same matches and groups as the `regex` crate, on names and hostile haystacks.
    #[test]
    fn matches_as_the_regex_crate_does() {
        let patterns = [
            "^(?i:([0-9]{4})[.]([0-9]+)([A-Z]))$",
            "([0-9]{4})[.]([0-9]+)([A-Z])",
            "(?i)([0-9]{4})[.]([0-9]+)([A-Z])",
            "(?i)(([0-9]{4})(?:[.]([0-9]+))?)-(([0-9]{4})(?:[.]([0-9]+))?)",
            r"(?i)\d+ü",
            "a|ab|(b)?",
            "",
        ];
        let long = "1234.5P".repeat(2000);
        let haystacks = [
            "8998.2P",
            "8998.2p",
            "x8998.31-8998.34P y",
            "2051 Pv Schlüssel ٣٤٥Ü",
            "ab",
            "",
            "1234.5-1234.10",
            &long,
        ];
        for p in patterns {
            let ours = NameRegex::new(p).unwrap();
            let theirs = regex::Regex::new(p).unwrap();
            assert_eq!(ours.captures_len(), theirs.captures_len());
            for h in haystacks {
                assert_eq!(ours.is_match(h), theirs.is_match(h), "{p} {h}");
                assert_eq!(ours.find(h), theirs.find(h).map(|m| m.as_str()), "{p} {h}");
                let a: Vec<&str> = ours.find_iter(h).collect();
                let b: Vec<&str> = theirs.find_iter(h).map(|m| m.as_str()).collect();
                assert_eq!(a, b, "{p} {h}");
                fn groups<'h>(g: &Groups<'h>) -> Vec<Option<&'h str>> {
                    (0..g.len()).map(|i| g.get(i)).collect()
                }
                fn rgroups<'h>(c: &regex::Captures<'h>) -> Vec<Option<&'h str>> {
                    (0..c.len()).map(|i| c.get(i).map(|m| m.as_str())).collect()
                }
                assert_eq!(
                    ours.captures(h).as_ref().map(groups),
                    theirs.captures(h).as_ref().map(rgroups),
                    "{p} {h}"
                );
                let a: Vec<_> = ours.captures_iter(h).map(|g| groups(&g)).collect();
                let b: Vec<_> = theirs.captures_iter(h).map(|c| rgroups(&c)).collect();
                assert_eq!(a, b, "{p} {h}");
            }
        }
    }

    #[test]
    fn invalid_and_oversized_patterns_are_errors() {
        assert!(NameRegex::new("(").is_err());
        assert!(NameRegex::new("[").is_err());
        assert!(NameRegex::new(r"\w{1000}{1000}").is_err());
    }
}
