//! Reading `_Z.txt`: one measured value per probe, `(comment/T=<t>) #<n>=<value>`.

use super::bounds::{line_origin, LIMIT, MAX_LINE};
use crate::args;
use crate::diag::{Diags, Msg};
use crate::params::{parse_number_checked, NumberError};

/// A number of `_Z.txt`: `Err(message)` unless finite and within ±[`LIMIT`].
fn sane_number(text: &str) -> Result<f64, Msg> {
    match parse_number_checked(text) {
        Ok(v) if v.abs() <= LIMIT => Ok(v),
        Ok(_) | Err(NumberError::OutOfRange) => Err(Msg::ZOutOfRange),
        Err(_) => Err(Msg::ZNotNumber),
    }
}

/// One measured line of `_Z.txt`: `(comment/T=<t>) #<n>=<value>`.
#[derive(Debug, Clone, PartialEq)]
pub struct ZLine {
    /// 1-based line number.
    pub line: usize,
    /// `#51`.
    pub name: String,
    pub t: f64,
    pub t_text: String,
    pub value: f64,
    pub value_text: String,
}

/// Splits a `_Z.txt` line into T text, name and value text (empty when not filled in yet);
/// `None` if it is not of the form `(…/T=t) #digits=value` (blanks allowed around `#`, the
/// digits and `=`).
pub(super) fn split_z_line(line: &str) -> Option<(&str, &str, &str)> {
    let line = line.trim();
    let rest = line.strip_prefix('(')?;
    // the comment cannot contain `)`: AsComment writes it as `]`
    let close = rest.find(')')?;
    let comment = &rest[..close];
    let t_text = comment[comment.rfind("/T=")? + 3..].trim();
    let rest = rest[close + 1..]
        .trim_start()
        .strip_prefix('#')?
        .trim_start();
    let digits = rest.len() - rest.trim_start_matches(|c: char| c.is_ascii_digit()).len();
    if digits == 0 {
        return None;
    }
    let (name, rest) = rest.split_at(digits);
    let value = rest.trim_start().strip_prefix('=')?.trim();
    Some((t_text, name, value))
}

/// Reads the measured values of a `_Z.txt` file. Every line must be blank or of the form
/// `(comment/T=t) #n=value` with finite numbers within ±[`LIMIT`]; errors name file and line.
pub fn parse_z_file(text: &str, file: &str, diags: &mut Diags) -> Vec<ZLine> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut out: Vec<ZLine> = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let origin = line_origin(file, i + 1);
        if line.len() > MAX_LINE {
            diags.error(Msg::LineTooLong, origin, args![MAX_LINE]);
            continue;
        }
        if line.trim().is_empty() {
            continue;
        }
        let Some((t_text, digits, value_text)) = split_z_line(line) else {
            diags.error(Msg::ZLineFormat, origin, vec![]);
            continue;
        };
        let name = format!("#{digits}");
        if value_text.is_empty() {
            // the line as compile wrote it: one message that says what is missing
            diags.error(Msg::ZNoValue, origin, args![name, t_text]);
            continue;
        }
        let (t, value) = match (sane_number(t_text), sane_number(value_text)) {
            (Ok(t), Ok(v)) => (t, v),
            (Err(msg), _) => {
                diags.error(msg, origin, args![t_text, name]);
                continue;
            }
            (_, Err(msg)) => {
                diags.error(msg, origin, args![value_text, name]);
                continue;
            }
        };
        if out.iter().any(|z| z.name == name) {
            diags.error(Msg::ZDuplicate, origin, args![name]);
            continue;
        }
        out.push(ZLine {
            line: i + 1,
            name,
            t,
            t_text: t_text.to_string(),
            value,
            value_text: value_text.to_string(),
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    const Z: &str = "([57.358 242.020]/T=2.000) #51=2,1\n\n([1.000 2.000]/L:a/T=2.000) #52=2.2\n";

    #[test]
    fn z_lines_must_have_the_form() {
        for line in [
            "2.1=9",
            "([0 0]/T=2.000) #51",
            "([0 0]/T=2.000) 51=2.1",
            "([0 0]/T=2.000) #=2.1",
            "([0 0]/T=2.000) #5a=2.1",
            "([0 0]) #51=2.1",
            "[0 0]/T=2.000 #51=2.1",
            "#51=2.1",
            "([0 0]/T=2.000 #51=2.1",
        ] {
            let z = format!("{}\n{line}\n", Z.lines().next().unwrap());
            let mut d = Diags::default();
            parse_z_file(&z, "z", &mut d);
            assert_eq!(
                d.list.iter().map(|x| x.msg).collect::<Vec<_>>(),
                [Msg::ZLineFormat],
                "{line}"
            );
            assert_eq!(d.list[0].origin.context(), "z:2", "{line}");
        }
        // a second `=` is not a number
        let mut d = Diags::default();
        parse_z_file("([0 0]/T=2.000) #51=2.1=9\n", "z", &mut d);
        assert_eq!(d.list[0].msg, Msg::ZNotNumber);
        assert_eq!(d.list[0].args, args!["2.1=9", "#51"]);
        // blanks, a label with `#` and `=`, CR LF and a byte-order mark are fine
        let mut d = Diags::default();
        let v = parse_z_file(
            "\u{feff}([1 2]/L:a#b=c/T=2.000)  # 51 = 2,1 \r\n \r\n",
            "z",
            &mut d,
        );
        assert!(d.list.is_empty(), "{:?}", d.list);
        assert_eq!((v[0].name.as_str(), v[0].t, v[0].value), ("#51", 2.0, 2.1));
        // too long
        let mut d = Diags::default();
        parse_z_file(&"x".repeat(MAX_LINE + 1), "z", &mut d);
        assert_eq!(d.list[0].msg, Msg::LineTooLong);
    }

    #[test]
    fn duplicates_and_missing_values() {
        let mut d = Diags::default();
        parse_z_file(
            "([57.358 242.020]/T=2.000) #51=\n([0 0]/T=2.000) #52=x\n([0 0]/T=2.000) #53=2\n([0 0]/T=2.000) #53=2\n",
            "z",
            &mut d,
        );
        let msgs: Vec<Msg> = d.list.iter().map(|x| x.msg).collect();
        assert_eq!(msgs, vec![Msg::ZNoValue, Msg::ZNotNumber, Msg::ZDuplicate]);
        assert_eq!(d.list[0].origin.context(), "z:1");
        assert_eq!(
            d.list[0].message(crate::Lang::En),
            "No measured value for probe #51 (nominal height 2.000): type the height the probing program measured after '='"
        );
        assert_eq!(
            d.list[0].message(crate::Lang::De),
            "Kein Messwert für Messpunkt #51 (Soll-Höhe 2.000): die vom Antastprogramm gemessene Höhe nach '=' eintragen"
        );
    }

    #[test]
    fn an_unfilled_file_gets_one_message_per_probe() {
        let mut d = Diags::default();
        let unfilled = "([10.000 5.000]/T=3.000) #51=\n([50.000 5.000]/L:1/T=3.000) #52= \r\n";
        assert!(parse_z_file(unfilled, "2020_Z.txt", &mut d).is_empty());
        let got: Vec<(Msg, String)> = d.list.iter().map(|x| (x.msg, x.origin.context())).collect();
        assert_eq!(
            got,
            [
                (Msg::ZNoValue, "2020_Z.txt:1".to_string()),
                (Msg::ZNoValue, "2020_Z.txt:2".to_string())
            ]
        );
    }
}
