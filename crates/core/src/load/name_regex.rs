//! The regular expressions of path and file names (`/n`, `/p`), built for short haystacks.
//!
//! Same syntax and matches as the `regex` crate (both are `regex_automata`'s meta engine), but
//! built without literal prefilters and lazy/full DFAs: those speed up searches in long texts
//! and cost most of the build, while names are a few characters long. The six patterns of a
//! run were built on every `check`'s critical path (each worker needs them before its first
//! file): 3.7 M instructions before, under 1 M now. Matching stays linear (PikeVM, or the
//! bounded backtracker / one-pass DFA where they apply).
//!
//! `NameRegex`: the `regex` crate's meta engine built without prefilters and DFAs (names are short;
//! a fifth of the build cost), same matches; a case-insensitive pattern's ASCII part serves every
//! name without ſ or K (the whole pattern is built on the first that has one).

use regex_automata::meta::{self, Regex};
use regex_automata::util::captures::Captures;
use regex_syntax::hir::{Class, ClassUnicode, ClassUnicodeRange, Hir, HirKind};
use std::sync::{Arc, OnceLock};

/// A compiled name pattern.
///
/// Case-insensitive letters are the one costly part of most name patterns: Unicode folds `k`
/// with the Kelvin sign and `s` with the long s, and one non-ASCII character in a class makes
/// the compiler build UTF-8 automata (with a 320 KB table, written in full, on every
/// `check`'s critical path). When those two are the only non-ASCII characters a pattern can
/// match, it matches exactly what its ASCII part matches in every name without them (the
/// same steps, minus transitions no such name can take). So such a pattern is built in two
/// forms: its ASCII part at once, and the whole pattern on the first name with ſ or K.
#[derive(Debug, Clone)]
pub struct NameRegex {
    /// The whole pattern, or its ASCII part when `full` is there.
    re: Regex,
    /// The whole pattern, built when first needed (a name with one of [`FOLDS_OF_ASCII`]);
    /// `None` when `re` is the whole pattern.
    full: Option<Arc<LazyFull>>,
}

#[derive(Debug)]
struct LazyFull {
    hir: Hir,
    size_limit: usize,
    re: OnceLock<Option<Regex>>,
}

/// The NFA size limit (the meta engine's default, as the `regex` crate's).
const NFA_SIZE_LIMIT: usize = 10 << 20;

/// The largest ASCII part whose whole pattern is built later is the size limit over this.
/// The whole pattern differs only by two characters per class (at most 5 more NFA states for
/// the 2 of the ASCII part; 3.2 times the memory for `(?i)[a-z]{2000}`), so from an ASCII
/// part this small it cannot reach the limit: no error of the whole pattern waits for the
/// first name with ſ or K. Larger ones are built whole at once.
const DEFER_MARGIN: usize = 16;

/// The only non-ASCII characters that Unicode's simple case folding puts with ASCII letters:
/// ſ (with s) and the Kelvin sign (with k).
const FOLDS_OF_ASCII: [char; 2] = ['\u{17F}', '\u{212A}'];

impl NameRegex {
    /// Compiles `pattern`; the error message is the `regex` crate's.
    pub fn new(pattern: &str) -> Result<NameRegex, String> {
        NameRegex::with_size_limit(pattern, NFA_SIZE_LIMIT)
    }

    fn with_size_limit(pattern: &str, size_limit: usize) -> Result<NameRegex, String> {
        let hir = regex_automata::util::syntax::parse(pattern).map_err(|e| e.to_string())?;
        if let Some(ascii_hir) = ascii_part(&hir).filter(|a| *a != hir) {
            if let Ok(ascii) = build(&ascii_hir, size_limit) {
                if ascii.memory_usage() <= size_limit / DEFER_MARGIN
                    && ascii
                        .group_info()
                        .pattern_names(regex_automata::PatternID::ZERO)
                        .eq(group_names(&hir))
                {
                    let full = LazyFull {
                        hir,
                        size_limit,
                        re: OnceLock::new(),
                    };
                    return Ok(NameRegex {
                        re: ascii,
                        full: Some(Arc::new(full)),
                    });
                }
            }
        }
        // whole at once: its errors show now
        Ok(NameRegex {
            re: build(&hir, size_limit)?,
            full: None,
        })
    }

    /// The form that matches `haystack` as the whole pattern does.
    fn engine(&self, haystack: &str) -> &Regex {
        match &self.full {
            Some(full) if haystack.contains(FOLDS_OF_ASCII) => full
                .re
                .get_or_init(|| {
                    let re = build(&full.hir, full.size_limit).ok();
                    // DEFER_MARGIN rules this out; the ASCII part is the fallback all the same
                    debug_assert!(re.is_some(), "the whole name pattern failed to build");
                    re
                })
                .as_ref()
                .unwrap_or(&self.re),
            _ => &self.re,
        }
    }

    pub fn is_match(&self, haystack: &str) -> bool {
        self.engine(haystack).is_match(haystack)
    }

    /// The leftmost-first match.
    pub fn find<'h>(&self, haystack: &'h str) -> Option<&'h str> {
        self.engine(haystack)
            .find(haystack)
            .map(|m| &haystack[m.range()])
    }

    /// Every non-overlapping match, left to right.
    pub fn find_iter<'r, 'h>(&'r self, haystack: &'h str) -> impl Iterator<Item = &'h str> + 'r
    where
        'h: 'r,
    {
        self.engine(haystack)
            .find_iter(haystack)
            .map(move |m| &haystack[m.range()])
    }

    /// The groups of the leftmost-first match (group 0 is the whole match).
    pub fn captures<'h>(&self, haystack: &'h str) -> Option<Groups<'h>> {
        let re = self.engine(haystack);
        let mut caps = re.create_captures();
        re.captures(haystack, &mut caps);
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
        self.engine(haystack)
            .captures_iter(haystack)
            .map(move |caps| Groups { haystack, caps })
    }

    /// Number of groups, group 0 included.
    pub fn captures_len(&self) -> usize {
        self.re.captures_len()
    }
}

/// Built for short haystacks: without literal prefilters and lazy/full DFAs, which speed up
/// searches in long texts and cost most of the build. Errors read as the `regex` crate's.
fn build(hir: &Hir, size_limit: usize) -> Result<Regex, String> {
    let config = meta::Config::new()
        .auto_prefilter(false)
        .hybrid(false)
        .dfa(false)
        .nfa_size_limit(Some(size_limit));
    meta::Builder::new()
        .configure(config)
        .build_from_hir(hir)
        .map_err(|e| match e.size_limit() {
            Some(limit) => format!("Compiled regex exceeds size limit of {limit} bytes."),
            None => e.to_string(),
        })
}

/// The group names of `hir` in order, as a built regex lists them (`None` for group 0 and
/// unnamed groups): the ASCII part must keep every group of the whole.
fn group_names(hir: &Hir) -> Vec<Option<&str>> {
    fn walk<'a>(h: &'a Hir, out: &mut Vec<Option<&'a str>>) {
        match h.kind() {
            HirKind::Capture(c) => {
                out.push(c.name.as_deref());
                walk(&c.sub, out);
            }
            HirKind::Repetition(r) => walk(&r.sub, out),
            HirKind::Concat(v) | HirKind::Alternation(v) => v.iter().for_each(|h| walk(h, out)),
            _ => {}
        }
    }
    let mut out = vec![None];
    walk(hir, &mut out);
    out
}

/// What `hir` matches in ASCII haystacks, when it differs from the whole only by the
/// [`FOLDS_OF_ASCII`] in its classes; `None` when any other non-ASCII character appears
/// (then the whole pattern is built at once).
fn ascii_part(hir: &Hir) -> Option<Hir> {
    let ascii = ClassUnicode::new([ClassUnicodeRange::new('\0', '\x7F')]);
    Some(match hir.kind() {
        HirKind::Literal(lit) if !lit.0.is_ascii() => return None,
        HirKind::Class(Class::Unicode(class)) => {
            for r in class.ranges().iter().filter(|r| !r.end().is_ascii()) {
                let start = r.start().max('\u{80}');
                if start != r.end() || !FOLDS_OF_ASCII.contains(&start) {
                    return None;
                }
            }
            let mut class = class.clone();
            class.intersect(&ascii);
            Hir::class(Class::Unicode(class))
        }
        HirKind::Class(Class::Bytes(class)) if !class.is_ascii() => return None,
        HirKind::Repetition(r) => Hir::repetition(regex_syntax::hir::Repetition {
            sub: Box::new(ascii_part(&r.sub)?),
            ..r.clone()
        }),
        HirKind::Capture(c) => Hir::capture(regex_syntax::hir::Capture {
            sub: Box::new(ascii_part(&c.sub)?),
            ..c.clone()
        }),
        HirKind::Concat(v) => Hir::concat(v.iter().map(ascii_part).collect::<Option<_>>()?),
        HirKind::Alternation(v) => {
            Hir::alternation(v.iter().map(ascii_part).collect::<Option<_>>()?)
        }
        _ => hir.clone(),
    })
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
            "(?i)k+s",
            "(?i)(?<letter>[a-z])(x)?|(?<kelvin>\u{212A})",
            "(?i)[^a-z]+",
            r"(?i)\bs\w*",
            ".+",
            "(?-i:K)(?i:k)",
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
            "8998.2\u{212A}",
            "8998.2\u{17F}",
            "\u{17F}\u{212A} Ks kſ",
            "x\u{212A}y",
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

    /// Every name of up to four characters from letters that fold (or not) with ASCII ones:
    /// the same answers as the `regex` crate, whichever form answers.
    #[test]
    fn short_names_match_as_the_regex_crate_does() {
        let alphabet = [
            '1', '.', 'k', 'K', 's', 'S', 'ü', '\u{17F}', '\u{212A}', '-',
        ];
        let patterns = [
            "(?i)([0-9]{4})[.]([0-9]+)([A-Z])",
            "(?i)^[k-s]+$",
            "(?i)(s|k)\\.?(1)",
            "(?i)[^k]s",
            r"(?i)\bk",
        ];
        let mut names = vec![String::new()];
        for _ in 0..4 {
            let longer: Vec<String> = names
                .iter()
                .filter(|n| n.chars().count() == names.last().map_or(0, |l| l.chars().count()))
                .flat_map(|n| alphabet.iter().map(move |c| format!("{n}{c}")))
                .collect();
            names.extend(longer);
        }
        for p in patterns {
            let ours = NameRegex::new(p).unwrap();
            let theirs = regex::Regex::new(p).unwrap();
            for n in &names {
                assert_eq!(ours.is_match(n), theirs.is_match(n), "{p} {n}");
                let a = ours
                    .captures(n)
                    .map(|g| (0..g.len()).map(|i| g.get(i)).collect::<Vec<_>>());
                let b = theirs.captures(n).map(|c| {
                    (0..c.len())
                        .map(|i| c.get(i).map(|m| m.as_str()))
                        .collect::<Vec<_>>()
                });
                assert_eq!(a, b, "{p} {n}");
            }
        }
    }

    /// Whether the whole form of `re` is built (`None`: there is no other form).
    fn whole_built(re: &NameRegex) -> Option<bool> {
        re.full.as_ref().map(|f| f.re.get().is_some())
    }

    #[test]
    fn case_folded_letters_build_the_whole_pattern_on_the_first_other_name() {
        let re = NameRegex::new("(?i)([0-9]{4})[.]([0-9]+)([A-Z])").unwrap();
        assert_eq!(whole_built(&re), Some(false));
        assert!(re.is_match("8998.2p"));
        assert!(!re.is_match("8998.2-"));
        assert!(re.is_match("Schlüssel 8998.2ü 8998.3Ü 8998.4x"));
        assert!(!re.is_match("8998.2ü"));
        assert_eq!(
            whole_built(&re),
            Some(false),
            "names without ſ or K need the ASCII part"
        );
        // the Kelvin sign folds with k: the whole pattern matches it, as the regex crate does
        assert!(re.is_match("8998.2\u{212A}"));
        assert_eq!(whole_built(&re), Some(true));
        let groups = re.captures("x8998.2\u{17F}").unwrap();
        assert_eq!(groups.get(3), Some("\u{17F}"));
        // a clone shares the whole form
        assert_eq!(whole_built(&re.clone()), Some(true));
    }

    #[test]
    fn other_non_ascii_characters_build_the_whole_pattern_at_once() {
        for p in [
            "(?i)ü",
            ".",
            r"\w",
            "[^a]",
            r"(?i)\x{212A}\x{FF}",
            "(?i)k|é",
        ] {
            assert_eq!(whole_built(&NameRegex::new(p).unwrap()), None, "{p}");
        }
        // no non-ASCII character at all: one form
        for p in ["[0-9]+", "(?i:[0-9]{4})", "(?-u:[a-z])"] {
            assert_eq!(whole_built(&NameRegex::new(p).unwrap()), None, "{p}");
        }
    }

    /// A whole pattern over the size limit is an error when compiled, as with the `regex`
    /// crate, not on the first non-ASCII name.
    #[test]
    fn size_errors_show_at_once() {
        // a small limit (64 KiB): quick in a debug build
        let limit = 64 << 10;
        let (mut seen, mut deferred) = ((false, false), false);
        for n in [10, 50, 200, 400, 1_000, 3_000] {
            let p = format!("(?i)[a-z]{{{n}}}");
            let ours = NameRegex::with_size_limit(&p, limit);
            let theirs = regex::RegexBuilder::new(&p).size_limit(limit).build();
            assert_eq!(ours.is_ok(), theirs.is_ok(), "{p}");
            match ours {
                Ok(re) => {
                    seen.0 = true;
                    deferred |= whole_built(&re) == Some(false);
                    let name = "\u{212A}".repeat(n);
                    assert!(re.is_match(&name), "{p}");
                    assert_ne!(whole_built(&re), Some(false));
                    assert!(re
                        .full
                        .as_ref()
                        .is_none_or(|f| f.re.get().unwrap().is_some()));
                }
                Err(e) => {
                    seen.1 = true;
                    assert!(e.contains("size limit"), "{e}");
                }
            }
        }
        assert_eq!(seen, (true, true), "both outcomes tried");
        assert!(deferred, "a whole pattern built on its first name with K");
    }

    #[test]
    fn invalid_and_oversized_patterns_are_errors() {
        assert!(NameRegex::new("(").is_err());
        assert!(NameRegex::new("[").is_err());
        assert!(NameRegex::new(r"\w{1000}{1000}").is_err());
        // the messages are the regex crate's
        for p in ["(", r"\w{1000}{1000}", r"\p{Nope}"] {
            let ours = NameRegex::new(p).unwrap_err();
            assert_eq!(ours, regex::Regex::new(p).unwrap_err().to_string(), "{p}");
        }
    }
}
