//! Line-type names of other CAD programs, for the extended input mode: names are compared
//! without regard to case and common ISO and vendor names are mapped to the names the
//! reference knows (`CONTINUOUS`, `DASHED`, `DASHDOT`, `BORDER`, `DIVIDE`, `PHANTOM`,
//! `HIDDEN`, `DOT`). The table is documented in the manual (docs/src/cad-input.md).

/// ISO 128 line types as AutoCAD names them (`ACAD_ISO02W100`; the `W…` part is the pen
/// width): the number → the reference name with the same pattern. Numbers without a
/// reference counterpart (08 long-dash short-dash, 13–15) are left unmapped.
const ISO: &[(u32, &str)] = &[
    (1, "CONTINUOUS"), // some exporters number the solid line 01
    (2, "DASHED"),     // dashed
    (3, "DASHED"),     // dashed, long gaps
    (4, "DASHDOT"),    // long-dash dot
    (5, "DIVIDE"),     // long-dash double-dot
    (7, "DOT"),        // dotted
    (9, "PHANTOM"),    // long-dash double-short-dash
    (10, "DASHDOT"),   // dash dot
    (11, "BORDER"),    // double-dash dot
    (12, "DIVIDE"),    // dash double-dot
];

/// Vendor spellings (upper case) → reference names.
const NAMES: &[(&str, &str)] = &[
    ("SOLID", "CONTINUOUS"),
    ("CONTINUOUS_LINE", "CONTINUOUS"),
    ("DASH", "DASHED"),
    ("DASHES", "DASHED"),
    ("DOTTED", "DOT"),
    ("DOTS", "DOT"),
    ("DASH_DOT", "DASHDOT"),
    ("DASH-DOT", "DASHDOT"),
    ("DASHDOTTED", "DASHDOT"),
    ("DASH_DOT_DOT", "DIVIDE"),
    ("DASH-DOT-DOT", "DIVIDE"),
    ("DASHDOTDOT", "DIVIDE"),
    ("DASH_DASH_DOT", "BORDER"),
    ("DASH-DASH-DOT", "BORDER"),
    ("HIDDEN_LINE", "HIDDEN"),
];

/// The name the compiler compares for a line type of the extended mode: upper case, then
/// the alias table; scale suffixes stay (`dashed2` → `DASHED2`, which works by prefix).
pub fn canonical(name: &str) -> String {
    let up = name.trim().to_uppercase();
    if let Some(num) = up
        .strip_prefix("ACAD_ISO")
        .or_else(|| up.strip_prefix("ISO"))
        .and_then(|rest| rest.get(..2))
        .and_then(|d| d.parse::<u32>().ok())
    {
        if let Some((_, to)) = ISO.iter().find(|(n, _)| *n == num) {
            return (*to).to_string();
        }
    }
    match NAMES.iter().find(|(from, _)| *from == up) {
        Some((_, to)) => (*to).to_string(),
        None => up,
    }
}

/// The whole table as (name, reference name) rows, for the manual's test.
pub fn table() -> Vec<(String, &'static str)> {
    let iso = ISO
        .iter()
        .map(|(n, to)| (format!("ACAD_ISO{n:02}W100"), *to));
    let names = NAMES.iter().map(|(from, to)| (from.to_string(), *to));
    iso.chain(names).collect()
}

#[cfg(test)]
mod tests {
    use super::canonical;

    #[test]
    fn case_aliases_and_scale_variants() {
        assert_eq!(canonical("Continuous"), "CONTINUOUS");
        assert_eq!(canonical("ACAD_ISO02W100"), "DASHED");
        assert_eq!(canonical("acad_iso10w050"), "DASHDOT");
        assert_eq!(canonical("ISO11"), "BORDER");
        assert_eq!(canonical("dashed2"), "DASHED2");
        assert_eq!(canonical("Phantom"), "PHANTOM");
        assert_eq!(canonical("Dotted"), "DOT");
        // no counterpart: stays (and is then unsupported, as CENTER is in the reference)
        assert_eq!(canonical("ACAD_ISO08W100"), "ACAD_ISO08W100");
        assert_eq!(canonical("Center"), "CENTER");
        assert_eq!(canonical("ByBlock"), "BYBLOCK");
    }

    #[test]
    fn the_manual_lists_every_alias() {
        let doc = include_str!("../../../../docs/src/cad-input.md");
        for (name, to) in super::table() {
            let row = doc
                .lines()
                .find(|l| l.starts_with('|') && l.contains(&format!("`{name}`")))
                .unwrap_or_else(|| panic!("{name} is not in docs/src/cad-input.md"));
            assert!(row.contains(&format!("| `{to}` |")), "{name} → {to}: {row}");
            assert_eq!(super::canonical(&name), to);
        }
    }
}
