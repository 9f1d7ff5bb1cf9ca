//! The yardstick of `bench/check_vs_tokenizer.sh`: a bare DXF group-code tokenizer. It reads
//! every file given, splits it into (group code, value) pairs — the code parsed as an integer,
//! the value as a byte slice without its line end — and prints how many pairs it saw. No
//! entities, no decoding: the least work any DXF reader has to do.
//!
//! `cargo run --release -p millpath-dxf --example tokenize -- FILE.dxf…`

use std::process::ExitCode;

/// Number of pairs in `data`, or the 1-based line of a group code that is not an integer.
fn count_pairs(data: &[u8]) -> Result<usize, usize> {
    let mut lines = data.split(|&b| b == b'\n');
    let mut pairs = 0;
    let mut line = 0;
    while let Some(code) = lines.next() {
        line += 1;
        let code = code.trim_ascii();
        if code.is_empty() && lines.size_hint().1 == Some(0) {
            break; // the final line end
        }
        let Some(value) = lines.next() else {
            return Err(line);
        };
        line += 1;
        let value = value.strip_suffix(b"\r").unwrap_or(value);
        let (neg, digits) = match code.split_first() {
            Some((b'-', rest)) => (true, rest),
            _ => (false, code),
        };
        if digits.is_empty() || !digits.iter().all(u8::is_ascii_digit) {
            return Err(line - 1);
        }
        let n = digits
            .iter()
            .fold(0i64, |n, d| n * 10 + i64::from(d - b'0'));
        std::hint::black_box((if neg { -n } else { n }, value));
        pairs += 1;
    }
    Ok(pairs)
}

fn main() -> ExitCode {
    let (mut files, mut pairs, mut bad) = (0usize, 0usize, 0usize);
    for f in std::env::args_os().skip(1) {
        match std::fs::read(&f) {
            Ok(data) => match count_pairs(&data) {
                Ok(n) => pairs += n,
                Err(line) => {
                    eprintln!(
                        "{}:{line}: group code is not an integer",
                        f.to_string_lossy()
                    );
                    bad += 1;
                }
            },
            Err(e) => {
                eprintln!("{}: {e}", f.to_string_lossy());
                bad += 1;
            }
        }
        files += 1;
    }
    println!("{pairs} pairs in {files} file(s)");
    ExitCode::from(u8::from(bad > 0))
}
