//! Three-decimal number text: the standard formatter, the first integer version (u128, one
//! `String` per number) and `F3` / `write_f3` / `f3`.

use criterion::{black_box, criterion_group, criterion_main, Criterion, Throughput};
use millpath_core::geom::{f3, write_f3, F3};
use std::fmt::Write;

/// The first integer version of `f3`, kept here as the baseline.
fn f3_u128(x: f64) -> String {
    if !x.is_finite() || x.abs() >= 1e15 {
        return format!("{x:.3}");
    }
    let bits = x.abs().to_bits();
    let exp_bits = ((bits >> 52) & 0x7ff) as i32;
    let frac = bits & ((1u64 << 52) - 1);
    let (mant, exp) = if exp_bits == 0 {
        (frac, -1074)
    } else {
        (frac | (1u64 << 52), exp_bits - 1075)
    };
    let num = mant as u128 * 1000;
    let q: u128 = if exp >= 0 {
        num << exp
    } else {
        let sh = (-exp) as u32;
        if sh >= 127 {
            0
        } else {
            let q = num >> sh;
            let rem = num - (q << sh);
            let half = 1u128 << (sh - 1);
            if rem > half || (rem == half && q & 1 == 1) {
                q + 1
            } else {
                q
            }
        }
    };
    let sign = if x.is_sign_negative() { "-" } else { "" };
    format!("{sign}{}.{:03}", q / 1000, q % 1000)
}

/// G-code-like numbers: coordinates of a few hundred millimetres, computed (not round).
fn values() -> Vec<f64> {
    let mut seed: u64 = 0x9E37_79B9_7F4A_7C15;
    (0..10_000)
        .map(|i| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            let v = (seed % 1_000_000) as f64 / 1000.0 - 300.0;
            if i % 4 == 0 {
                v.sin() * 120.0
            } else {
                v
            }
        })
        .collect()
}

fn bench(c: &mut Criterion) {
    let xs = values();
    for &x in &xs {
        assert_eq!(f3_u128(x), f3(x));
    }
    let mut g = c.benchmark_group("f3");
    g.throughput(Throughput::Elements(xs.len() as u64));
    g.bench_function("format!(\"{:.3}\")", |b| {
        b.iter(|| {
            for &x in &xs {
                black_box(format!("{:.3}", black_box(x)));
            }
        })
    });
    g.bench_function("old f3 (u128, String)", |b| {
        b.iter(|| {
            for &x in &xs {
                black_box(f3_u128(black_box(x)));
            }
        })
    });
    g.bench_function("f3 (String)", |b| {
        b.iter(|| {
            for &x in &xs {
                black_box(f3(black_box(x)));
            }
        })
    });
    let mut out = String::with_capacity(32);
    g.bench_function("write_f3 (reused String)", |b| {
        b.iter(|| {
            for &x in &xs {
                out.clear();
                write_f3(&mut out, black_box(x));
                black_box(&out);
            }
        })
    });
    let mut line = String::with_capacity(64);
    g.bench_function("write!(\"X{} Y{}\", F3, F3) per pair", |b| {
        b.iter(|| {
            for p in xs.chunks_exact(2) {
                line.clear();
                write!(line, "X{} Y{}", F3(black_box(p[0])), F3(black_box(p[1]))).unwrap();
                black_box(&line);
            }
        })
    });
    g.bench_function("old: format!(\"X{} Y{}\", f3, f3) per pair", |b| {
        b.iter(|| {
            for p in xs.chunks_exact(2) {
                black_box(format!(
                    "X{} Y{}",
                    f3_u128(black_box(p[0])),
                    f3_u128(black_box(p[1]))
                ));
            }
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
