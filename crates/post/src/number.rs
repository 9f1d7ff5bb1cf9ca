//! Number formats: decimals (a fixed count or the shortest exact text), decimal separator,
//! trailing zeros, leading zero and plus sign. A fixed count of 3 with the other defaults is
//! Rust's `{:.3}`, as the dialects wrote before the posts.

use std::fmt::Write;

/// The most decimals a post may ask for (beyond them a double has no more digits).
pub const MAX_DECIMALS: u32 = 9;

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Decimals {
    /// Exactly this many (rounded), trailing zeros as [`NumberFormat::trailing_zeros`] says.
    Fixed(u8),
    /// The shortest text that reads back as the same number (Rust's `{}`).
    Shortest,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NumberFormat {
    pub decimals: Decimals,
    pub separator: char,
    pub trailing_zeros: bool,
    pub leading_zero: bool,
    pub plus_sign: bool,
}

impl Default for NumberFormat {
    fn default() -> Self {
        NumberFormat {
            decimals: Decimals::Fixed(3),
            separator: '.',
            trailing_zeros: true,
            leading_zero: true,
            plus_sign: false,
        }
    }
}

impl NumberFormat {
    /// Writes `v` into `out`. Non-finite values are written as Rust writes them (the emitter
    /// refuses them before they reach a post; the checker finds them if one did).
    pub fn write(&self, v: f64, out: &mut String) {
        let start = out.len();
        match self.decimals {
            Decimals::Fixed(d) => {
                let _ = write!(out, "{:.*}", d as usize, v);
            }
            Decimals::Shortest => {
                let _ = write!(out, "{v}");
                if &out[start..] == "-0" {
                    out.truncate(start);
                    out.push('0');
                }
            }
        }
        if *self == NumberFormat::default() || !v.is_finite() {
            return;
        }
        let mut text = out.split_off(start);
        if !self.trailing_zeros && text.contains('.') {
            while text.ends_with('0') {
                text.pop();
            }
            if text.ends_with('.') {
                text.pop();
            }
            if text == "-0" {
                text = "0".into();
            }
        }
        if !self.leading_zero {
            if let Some(rest) = text.strip_prefix("0.") {
                text = format!(".{rest}");
            } else if let Some(rest) = text.strip_prefix("-0.") {
                text = format!("-.{rest}");
            }
        }
        if self.plus_sign && !text.starts_with('-') {
            text.insert(0, '+');
        }
        if self.separator != '.' {
            text = text.replace('.', &self.separator.to_string());
        }
        out.push_str(&text);
    }

    pub fn text(&self, v: f64) -> String {
        let mut s = String::new();
        self.write(v, &mut s);
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_is_three_fixed_decimals() {
        let f = NumberFormat::default();
        for v in [0.0, -0.0004, 1.0005, 12.3456, -7.0, 1e14, 123456.789] {
            assert_eq!(f.text(v), format!("{v:.3}"));
        }
    }

    #[test]
    fn options_apply() {
        let f = NumberFormat {
            decimals: Decimals::Fixed(4),
            separator: ',',
            trailing_zeros: false,
            leading_zero: false,
            plus_sign: true,
        };
        assert_eq!(f.text(0.5), "+,5");
        assert_eq!(f.text(-0.25), "-,25");
        assert_eq!(f.text(2.0), "+2");
        assert_eq!(f.text(-0.00001), "+0");
        let s = NumberFormat {
            decimals: Decimals::Shortest,
            ..NumberFormat::default()
        };
        assert_eq!(s.text(9000.5), "9000.5");
        assert_eq!(s.text(12000.0), "12000");
        assert_eq!(s.text(-0.0), "0");
    }
}
