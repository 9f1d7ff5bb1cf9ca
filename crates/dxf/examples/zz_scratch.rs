use std::time::Instant;
fn count_pairs(data: &[u8]) -> usize {
    let mut lines = data.split(|&b| b == b'\n');
    let mut pairs = 0;
    while let Some(code) = lines.next() {
        let code = code.trim_ascii();
        if code.is_empty() && lines.size_hint().1 == Some(0) {
            break;
        }
        let Some(value) = lines.next() else { break };
        let value = value.strip_suffix(b"\r").unwrap_or(value);
        let n = code
            .iter()
            .fold(0i64, |n, d| n * 10 + i64::from(d.wrapping_sub(b'0')));
        std::hint::black_box((n, value));
        pairs += 1;
    }
    pairs
}
fn main() {
    let files: Vec<Vec<u8>> = std::env::args_os()
        .skip(1)
        .map(|f| std::fs::read(f).unwrap())
        .collect();
    for round in 0..200 {
        let t = Instant::now();
        let mut n = 0;
        for f in &files {
            n += count_pairs(f);
        }
        let a = t.elapsed();
        let t = Instant::now();
        let mut m = 0;
        for f in &files {
            m += millpath_dxf::read_dxf(f)
                .map(|d| d.entities.len())
                .unwrap_or(0);
        }
        let b = t.elapsed();
        if round % 50 == 0 {
            eprintln!(
                "round {round}: tokenize {:?} ({n}) read_dxf {:?} ({m}) ratio {:.2}",
                a,
                b,
                b.as_secs_f64() / a.as_secs_f64()
            );
        }
    }
}
