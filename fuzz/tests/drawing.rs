//! The structure-aware target's generator and invariants on a few thousand seeded inputs,
//! without the fuzzer (`cargo test` in `fuzz/`): every input that makes a drawing keeps the
//! invariants, and most drawings compile (the generator reaches the emitters).

use arbitrary::Unstructured;

/// Deterministic bytes (xorshift), so a failure repeats.
fn bytes(seed: u64, len: usize) -> Vec<u8> {
    let mut x = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    (0..len)
        .map(|_| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 24) as u8
        })
        .collect()
}

#[test]
fn generated_drawings_keep_the_invariants() {
    let cases: u64 = std::env::var("MILLPATH_FUZZ_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(2000);
    std::panic::set_hook(Box::new(|_| {}));
    let mut failing = Vec::new();
    for seed in 0..cases {
        let data = bytes(seed, 600);
        if let Err(e) = std::panic::catch_unwind(|| millpath_fuzz::run(&data)) {
            let text = e
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| e.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            std::fs::write(format!("target/failing-{seed}.txt"), &text).unwrap();
            failing.push(seed);
        }
    }
    let _ = std::panic::take_hook();
    assert!(
        failing.is_empty(),
        "{} inputs fail, the messages are in target/failing-SEED.txt: {failing:?}",
        failing.len()
    );
}

#[test]
fn most_drawings_compile() {
    let mut written = 0;
    let n = 400;
    let mut refusals = std::collections::BTreeMap::<String, usize>::new();
    for seed in 0..n {
        let data = bytes(seed + 100_000, 600);
        let case = millpath_fuzz::gen::case(&mut Unstructured::new(&data)).unwrap();
        let (files, errors) = millpath_fuzz::invariants::reach(&case);
        if files > 0 {
            written += 1;
        }
        if let Ok(code) = std::env::var("MILLPATH_FUZZ_SHOW") {
            if errors.contains(&code) {
                eprintln!("{}", millpath_fuzz::invariants::explain(&case));
            }
        }
        for e in errors {
            *refusals.entry(e).or_default() += 1;
        }
    }
    eprintln!("{written} of {n} drawings compile; errors: {refusals:?}");
    assert!(written * 3 >= n, "only {written} of {n} drawings compile");
}
