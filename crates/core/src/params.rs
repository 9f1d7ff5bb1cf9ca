//! Parameter texts (`T2 O2 B-0,3 :B-0.5~3.0 >8998.2P`): tokens, variables, interpolation and
//! numeric views (reference-input.md §2, §6).

use crate::args;
use crate::diag::{Diagnostic, Msg, Origin};
use std::collections::BTreeSet;

/// One parameter text as written at an element, split into parameters and variable tokens.
#[derive(Debug, Clone, PartialEq)]
pub struct ParamText {
    /// The text as used for parameters (after MTEXT decoding and `%%` replacement).
    pub text: String,
    /// `key → raw value`, in text order. Keys are unique (checked on construction).
    pub params: Vec<(char, String)>,
    /// Variable tokens `:<name><rest>`, in text order.
    pub vars: Vec<(char, String)>,
    /// All tokens in text order (what the text language writes).
    pub tokens: Vec<String>,
    /// Where the text is.
    pub origin: Origin,
}

/// Splits a text into tokens: `~` + line break joins lines, then split at LF and space.
pub fn tokenize(text: &str) -> Vec<String> {
    let joined = join_continuations(text);
    joined
        .split(['\n', ' '])
        .map(str::trim)
        .filter(|t| !t.is_empty())
        .map(str::to_string)
        .collect()
}

/// Deletes every `~` that is directly followed by one or more (CR or LF, then whitespace).
fn join_continuations(text: &str) -> String {
    let chars: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    while i < chars.len() {
        if chars[i] == '~' && i + 1 < chars.len() && matches!(chars[i + 1], '\r' | '\n') {
            let mut j = i + 1;
            while j < chars.len() && matches!(chars[j], '\r' | '\n') {
                j += 1;
                while j < chars.len()
                    && chars[j].is_whitespace()
                    && !matches!(chars[j], '\r' | '\n')
                {
                    j += 1;
                }
            }
            i = j;
            continue;
        }
        out.push(chars[i]);
        i += 1;
    }
    out
}

impl ParamText {
    /// Parses a text. The checks that abort the whole file upstream (duplicate keys, variables
    /// in N, O, @, a variable defined twice) are returned as an error.
    pub fn parse(text: &str, origin: Origin) -> Result<ParamText, Diagnostic> {
        let mut params: Vec<(char, String)> = Vec::new();
        let mut vars: Vec<(char, String)> = Vec::new();
        let mut dup = String::new();
        let tokens = tokenize(text);
        for tok in &tokens {
            let mut cs = tok.chars();
            let key = cs.next().unwrap_or(' ');
            let value: String = cs.collect();
            if key == ':' {
                let mut vc = value.chars();
                if let Some(name) = vc.next() {
                    if vars.iter().any(|(n, _)| *n == name) {
                        return Err(Diagnostic::error(
                            Msg::DuplicateVariable,
                            origin,
                            args![name, text],
                        ));
                    }
                    vars.push((name, vc.collect()));
                }
                continue;
            }
            if params.iter().any(|(k, _)| *k == key) {
                if !dup.contains(key) {
                    dup.push(key);
                }
                continue;
            }
            params.push((key, value));
        }
        if !dup.is_empty() {
            return Err(Diagnostic::error(
                Msg::DuplicateParameter,
                origin,
                args![text, dup],
            ));
        }
        for (k, v) in &params {
            let msg = match k {
                'N' => Msg::NCannotUseVariable,
                'O' => Msg::OCannotUseVariable,
                '@' => Msg::AtCannotUseVariable,
                _ => continue,
            };
            if v.contains('=') {
                return Err(Diagnostic::error(msg, origin, args![v]));
            }
        }
        Ok(ParamText {
            text: text.to_string(),
            params,
            vars,
            tokens,
            origin,
        })
    }

    pub fn raw(&self, key: char) -> Option<&str> {
        self.params
            .iter()
            .find(|(k, _)| *k == key)
            .map(|(_, v)| v.as_str())
    }
    pub fn has(&self, key: char) -> bool {
        self.raw(key).is_some()
    }
    pub fn has_keys(&self) -> bool {
        !self.params.is_empty()
    }
    /// `N` as integer from the raw value; anything else counts as "no N".
    pub fn order(&self) -> Option<i64> {
        self.raw('N').and_then(|v| v.trim().parse::<i64>().ok())
    }
}

/// The largest magnitude of any number a drawing, a text or a setting may hold (mm, mm/min):
/// one kilometre. Beyond it a value is a typing error, and nothing downstream (pass counts,
/// bar pieces, the traversal grid, G-code text) has to cope with absurd magnitudes.
pub const MAX_MAGNITUDE: f64 = 1e6;

/// Why a value is not a usable number.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NumberError {
    /// Not numeric at all (a word, a variable reference left over).
    NotANumber,
    /// `NaN`, `Infinity`, or a literal too large for a float (`1e999`).
    NotFinite,
    /// Finite but beyond ±[`MAX_MAGNITUDE`].
    OutOfRange,
}

/// Parses a number the way the reference does (`,` → `.`, trimmed, invariant), but accepts
/// only finite values within ±[`MAX_MAGNITUDE`]: a `NaN` passes every range check (all
/// comparisons are false) and would reach the G-code.
pub fn parse_number_checked(value: &str) -> Result<f64, NumberError> {
    let s = value.replace(',', ".");
    let s = s.trim();
    let lower = s.to_ascii_lowercase();
    let word = lower.trim_start_matches(['+', '-']);
    if matches!(word, "nan" | "inf" | "infinity") {
        return Err(NumberError::NotFinite);
    }
    let numeric = !s.is_empty()
        && s.chars()
            .all(|c| c.is_ascii_digit() || matches!(c, '.' | '-' | '+' | 'e' | 'E'));
    let v: f64 = match numeric.then(|| s.parse().ok()).flatten() {
        Some(v) => v,
        None => return Err(NumberError::NotANumber),
    };
    if !v.is_finite() {
        Err(NumberError::NotFinite)
    } else if v.abs() > MAX_MAGNITUDE {
        Err(NumberError::OutOfRange)
    } else {
        Ok(v)
    }
}

/// [`parse_number_checked`] for callers that only need the value.
pub fn parse_number(value: &str) -> Option<f64> {
    parse_number_checked(value).ok()
}

/// An assignment of variable values (for one build of a path).
#[derive(Debug, Clone, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Vars(pub Vec<(char, String)>);

/// More rounds than this means a value refers to itself (the reference loops forever).
const MAX_ROUNDS: usize = 32;

impl Vars {
    /// Replaces `=<name>` by the variable's value, repeatedly while anything changes.
    /// `Err(name)` when a value keeps referring to itself.
    pub fn interpolate(&self, value: &str) -> Result<String, char> {
        if self.0.is_empty() || !value.contains('=') {
            return Ok(value.to_string());
        }
        let mut s = value.to_string();
        for _ in 0..MAX_ROUNDS {
            let mut changed = None;
            for (name, val) in &self.0 {
                let pat = format!("={name}");
                if s.contains(&pat) {
                    s = s.replace(&pat, val);
                    changed = Some(*name);
                }
            }
            if changed.is_none() {
                return Ok(s);
            }
            if s.len() > 10_000 {
                return Err(changed.unwrap_or('?'));
            }
        }
        let culprit = self
            .0
            .iter()
            .find(|(n, v)| v.contains(&format!("={n}")))
            .map(|(n, _)| *n);
        Err(culprit
            .or_else(|| self.0.first().map(|(n, _)| *n))
            .unwrap_or('?'))
    }

    pub fn names(&self) -> BTreeSet<char> {
        self.0.iter().map(|(n, _)| *n).collect()
    }
    pub fn get(&self, name: char) -> Option<&str> {
        self.0
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, v)| v.as_str())
    }
}

/// A variable definition at a path start (§6.1).
#[derive(Debug, Clone, PartialEq)]
pub enum VarDef {
    List(Vec<String>),
    Range(f64, f64),
}

/// Interprets a definition; `Err((msg, args))` for a malformed one.
pub fn parse_definition(name: char, def: &str) -> Result<VarDef, (Msg, Vec<String>)> {
    let d = def.trim();
    if d.contains(',') {
        let cleaned = d.replace('?', "");
        return Ok(VarDef::List(
            cleaned.split(',').map(|s| s.trim().to_string()).collect(),
        ));
    }
    if let Some(rest) = d.strip_prefix('?') {
        if rest.is_empty() {
            return Err((Msg::EmptyCharList, args![name]));
        }
        return Ok(VarDef::List(rest.chars().map(|c| c.to_string()).collect()));
    }
    if d.contains('~') {
        let parts: Vec<&str> = d.split('~').collect();
        if parts.len() != 2 {
            return Err((Msg::RangeFormat, args![name, d]));
        }
        let from = parse_number(parts[0]);
        let to = parse_number(parts[1]);
        return match (from, to) {
            (Some(a), Some(b)) => Ok(VarDef::Range(a, b)),
            _ => Err((Msg::RangeNumber, args![name, d])),
        };
    }
    Err((Msg::DefinitionFormat, args![name, d]))
}

impl VarDef {
    pub fn accepts(&self, value: &str) -> bool {
        match self {
            VarDef::List(items) => items.iter().any(|i| i == value),
            VarDef::Range(a, b) => parse_number(value).is_some_and(|v| *a <= v && v <= *b),
        }
    }
}

/// Formats a number like .NET's invariant `ToString()`: shortest round-trip form.
pub fn fmt_num(v: f64) -> String {
    if v.is_nan() {
        return "NaN".into();
    }
    if v.is_infinite() {
        return if v > 0.0 { "∞".into() } else { "-∞".into() };
    }
    let s = format!("{v}");
    if s == "-0" {
        "0".into()
    } else {
        s
    }
}

/// Check values for `/c` (§6.2): a shared counter over the definitions in order.
pub fn check_values(defs: &[(char, String)]) -> Result<Vars, (Msg, Vec<String>)> {
    let mut out = Vec::new();
    for (k, (name, def)) in defs.iter().enumerate() {
        let v = match parse_definition(*name, def)? {
            VarDef::List(items) => items[k % items.len()].clone(),
            VarDef::Range(a, b) => fmt_num(if k % 2 == 0 { a } else { b }),
        };
        out.push((*name, v));
    }
    Ok(Vars(out))
}

/// The slowest feed (mm/min) a drawing or the settings may give: below it no machine moves
/// usefully (1 mm/min is 6 cm an hour), and a value such as `F0,0001` would be written as
/// `F0.000`, a feed of nothing. A typo, not a wish: an error, not a warning.
pub const MIN_FEED: f64 = 1.0;

/// The error of a feed above 0 but below [`MIN_FEED`] (`what` names it: `F`, `Z`, `feed`).
pub fn feed_too_small(what: &str, v: f64, origin: &Origin) -> Option<Diagnostic> {
    (v > 0.0 && v < MIN_FEED).then(|| {
        Diagnostic::error(
            Msg::FeedTooSmall,
            origin.clone(),
            args![what, fmt_num(v), fmt_num(MIN_FEED), format!("{v:.3}")],
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pt(s: &str) -> Result<ParamText, Diagnostic> {
        ParamText::parse(s, Origin::Options)
    }

    #[test]
    fn tokens_and_continuations() {
        assert_eq!(
            tokenize("M2x20\r\nO2\r\nT2 I1,2"),
            vec!["M2x20", "O2", "T2", "I1,2"]
        );
        assert_eq!(tokenize(":Y?~\r\n   VD  B1"), vec![":Y?VD", "B1"]);
        assert_eq!(tokenize(":B-0.5~3.0"), vec![":B-0.5~3.0"]);
        assert_eq!(tokenize("a\tb c"), vec!["a\tb", "c"]);
        let p = pt("T2 O2 >8998.2P :B1 B=B").unwrap();
        assert_eq!(p.raw('>'), Some("8998.2P"));
        assert_eq!(p.raw('B'), Some("=B"));
        assert_eq!(p.vars, vec![('B', "1".to_string())]);
    }

    #[test]
    fn construction_errors() {
        let e = pt("B1 T2 B3 T4").unwrap_err();
        assert_eq!(e.msg, Msg::DuplicateParameter);
        assert_eq!(e.args[1], "BT");
        assert_eq!(pt("N=A").unwrap_err().msg, Msg::NCannotUseVariable);
        assert_eq!(pt("O=A").unwrap_err().msg, Msg::OCannotUseVariable);
        assert_eq!(pt("@=A").unwrap_err().msg, Msg::AtCannotUseVariable);
        assert_eq!(pt(":A1 :A2").unwrap_err().msg, Msg::DuplicateVariable);
        assert_eq!(pt("N1.5").unwrap().order(), None);
        assert_eq!(pt("N-3").unwrap().order(), Some(-3));
    }

    #[test]
    fn numbers() {
        assert_eq!(parse_number("-0,3"), Some(-0.3));
        assert_eq!(parse_number(" 1e2 "), Some(100.0));
        assert_eq!(parse_number("=B"), None);
        assert_eq!(parse_number("2x20"), None);
        assert_eq!(parse_number(""), None);
        for bad in [
            "NaN",
            "nan",
            "-NaN",
            "inf",
            "-Infinity",
            "+Infinity",
            "1e999",
            "-1e400",
        ] {
            assert_eq!(
                parse_number_checked(bad),
                Err(NumberError::NotFinite),
                "{bad}"
            );
        }
        for bad in ["1e300", "-99999999999999999999", "1000000,001"] {
            assert_eq!(
                parse_number_checked(bad),
                Err(NumberError::OutOfRange),
                "{bad}"
            );
        }
        assert_eq!(parse_number_checked("-1000000"), Ok(-1e6));
        assert_eq!(parse_number_checked("x"), Err(NumberError::NotANumber));
    }

    #[test]
    fn interpolation() {
        let v = Vars(vec![('X', "D".into()), ('B', "1".into())]);
        assert_eq!(v.interpolate(">8998.34=X").unwrap(), ">8998.34D");
        assert_eq!(v.interpolate("=B").unwrap(), "1");
        assert_eq!(v.interpolate("=XB").unwrap(), "DB");
        assert_eq!(v.interpolate("=Q").unwrap(), "=Q");
        let chain = Vars(vec![('A', "=B".into()), ('B', "7".into())]);
        assert_eq!(chain.interpolate("=A").unwrap(), "7");
        let selfref = Vars(vec![('A', "=A1".into())]);
        assert_eq!(selfref.interpolate("=A"), Err('A'));
    }

    #[test]
    fn definitions_and_check_values() {
        assert_eq!(
            parse_definition('A', "P1,P2,P3").unwrap(),
            VarDef::List(vec!["P1".into(), "P2".into(), "P3".into()])
        );
        assert_eq!(
            parse_definition('A', "?PQ").unwrap(),
            VarDef::List(vec!["P".into(), "Q".into()])
        );
        assert_eq!(
            parse_definition('B', "-0.5~3.0").unwrap(),
            VarDef::Range(-0.5, 3.0)
        );
        assert_eq!(
            parse_definition('B', "0,5~2").unwrap(),
            VarDef::List(vec!["0".into(), "5~2".into()])
        );
        assert_eq!(
            parse_definition('B', "1~2~3").unwrap_err().0,
            Msg::RangeFormat
        );
        assert_eq!(
            parse_definition('B', "a~2").unwrap_err().0,
            Msg::RangeNumber
        );
        assert_eq!(
            parse_definition('B', "7").unwrap_err().0,
            Msg::DefinitionFormat
        );
        assert_eq!(
            parse_definition('B', "?").unwrap_err().0,
            Msg::EmptyCharList
        );
        assert!(VarDef::Range(-0.5, 3.0).accepts("1"));
        assert!(!VarDef::Range(-0.5, 3.0).accepts("4"));
        let cv = check_values(&[
            ('B', "-0.5~3.0".into()),
            ('Q', "?PQR".into()),
            ('X', "D,V".into()),
        ])
        .unwrap();
        assert_eq!(
            cv.0,
            vec![('B', "-0.5".into()), ('Q', "Q".into()), ('X', "D".into())]
        );
    }
}
