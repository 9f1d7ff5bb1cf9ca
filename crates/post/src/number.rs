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

/// A fixed count of three decimals and nothing else changed: the fast path.
const THREE: NumberFormat = NumberFormat {
    decimals: Decimals::Fixed(3),
    separator: '.',
    trailing_zeros: true,
    leading_zero: true,
    plus_sign: false,
};

/// Room for the longest text of [`f3_text`]: sign, 15 digits, point, 3 decimals.
pub const F3_LEN: usize = 20;

/// The text of `{:.3}` (core's `F3`) for finite |x| < 10¹⁵, written at the end of `buf`; `None` otherwise.
///
/// With |x| = m·2⁻ˢ (m < 2⁵³ the significand), x·1000 = m·1000·2⁻ˢ, and m·1000 < 2⁶³ fits a
/// `u64`. |x| < 10¹⁵ < 2⁵⁰ makes s ≥ 3. For s < 64 the shift splits m·1000 exactly into the
/// integer part q and the remainder, compared with the half 2ˢ⁻¹ for the rounding; for
/// s ≥ 64, m·1000 < 2⁶³ ≤ 2ˢ⁻¹ so x·1000 is below one half and rounds to 0.
pub fn f3_text(x: f64, buf: &mut [u8; F3_LEN]) -> Option<&str> {
    if !x.is_finite() || x.abs() >= 1e15 {
        return None;
    }
    let bits = x.to_bits();
    let exp_bits = ((bits >> 52) & 0x7ff) as u32;
    let frac = bits & ((1u64 << 52) - 1);
    let (mant, sh) = if exp_bits == 0 {
        (frac, 1074)
    } else {
        (frac | (1u64 << 52), 1075 - exp_bits)
    };
    debug_assert!(sh >= 3);
    let num = mant * 1000;
    let q = if sh >= 64 {
        0
    } else {
        let q = num >> sh;
        let rem = num & ((1u64 << sh) - 1);
        let half = 1u64 << (sh - 1);
        if rem > half || (rem == half && q & 1 == 1) {
            q + 1
        } else {
            q
        }
    };
    // q < 10¹⁸: at most 15 integer digits
    let (mut int, dec) = (q / 1000, q % 1000);
    let dec = dec as u32;
    buf[F3_LEN - 3] = b'0' + (dec / 100) as u8;
    buf[F3_LEN - 2] = b'0' + (dec / 10 % 10) as u8;
    buf[F3_LEN - 1] = b'0' + (dec % 10) as u8;
    buf[F3_LEN - 4] = b'.';
    let mut i = F3_LEN - 4;
    loop {
        i -= 1;
        buf[i] = b'0' + (int % 10) as u8;
        int /= 10;
        if int == 0 {
            break;
        }
    }
    if x.is_sign_negative() {
        i -= 1;
        buf[i] = b'-';
    }
    std::str::from_utf8(&buf[i..]).ok()
}

impl NumberFormat {
    /// Writes `v` into `out`. Non-finite values are written as Rust writes them (the emitter
    /// refuses them before they reach a post; the checker finds them if one did).
    pub fn write(&self, v: f64, out: &mut String) {
        if *self == THREE {
            // `{:.3}` from integer arithmetic: the hot spot of writing a program
            let mut buf = [0; F3_LEN];
            match f3_text(v, &mut buf) {
                Some(t) => out.push_str(t),
                None => {
                    let _ = write!(out, "{v:.3}");
                }
            }
            return;
        }
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
