//! Numbers on the command line, read as the drawings read them: a decimal comma is a decimal
//! point (`--max 0,5`, `--feed 300,5`), as in PathDxf2GCode's options, `_Z.txt` and the
//! drawings' texts. Counts are whole numbers, 0 or more.

/// A decimal number; one comma and no point is a decimal comma. What it is beyond that
/// (finite, in range) is the settings' check, located at the option.
pub fn decimal(s: &str) -> Result<f64, String> {
    let t = s.trim();
    let t = if t.matches(',').count() == 1 && !t.contains('.') {
        t.replace(',', ".")
    } else {
        t.to_string()
    };
    t.parse::<f64>()
        .map_err(|_| "not a number (0.5 or 0,5)".to_string())
}

/// A count of warnings: a whole number, 0 or more (`--max-warnings`).
pub fn warning_count(s: &str) -> Result<u32, String> {
    s.trim()
        .parse::<u32>()
        .map_err(|_| "a number of warnings: a whole number, 0 or more".to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_decimal_comma_is_a_point() {
        assert_eq!(decimal("0,5"), Ok(0.5));
        assert_eq!(decimal("300,5"), Ok(300.5));
        assert_eq!(decimal("-1,25"), Ok(-1.25));
        assert_eq!(decimal("2.5"), Ok(2.5));
        assert_eq!(decimal("7"), Ok(7.0));
        // a thousands separator or two commas are no number
        for bad in ["1,000.5", "1,2,3", "", "x", "0,5mm", ","] {
            assert!(decimal(bad).is_err(), "{bad}");
        }
        // NaN and inf are numbers here: the settings' check refuses them at the option
        assert!(decimal("NaN").unwrap().is_nan());
    }

    #[test]
    fn warning_counts_are_whole_and_not_negative() {
        assert_eq!(warning_count("0"), Ok(0));
        assert_eq!(warning_count("12"), Ok(12));
        for bad in ["-1", "NaN", "1.5", "1,5", "", "inf", "99999999999"] {
            assert!(warning_count(bad).is_err(), "{bad}");
        }
    }
}
