//! Any input gives a report, never a panic, within bounded time and memory: random bytes,
//! mutated programs, absurd geometry, and the limits.

use millpath_verify::{verify, Dialect, FindingKind, Limit, Limits, Options, Severity, StockSkip};

mod common;

use common::{mutate, Rng};

const GOOD: &str = "%\n(millpath)\nF150\nG17 G21 G40 G49 G54 G80 G90 G94\nT1\n(MILLPATH-STOCK T=2.000 O=2.000 BOTTOM=-0.300)\n\
G00 Z5.000\nG00 X0.000 Y0.000\nG00 X10.000 Y-0.050\nG00 Z4.000\n\
G02 F150.000 I0 J0.050 X10.000 Y0.050 Z1.400\nG02 F150.000 I0 J-0.050 X10.000 Y-0.050 Z-0.300\n\
G00 X10.000 Y0.000\nG00 Z5.000\nG00 X20.000 Y0.000\nG00 Z2.000(=2.000+0.794*[#51-2.000])\nG01 Z0.800\n\
G01 F150.000 X30.000 Y5.000 Z0.800\nG03 F150.000 I-5.000 J0.000 X20.000 Y5.000 Z0.800\n\
G38.3 Z0 F50.000\nG04 P4\nG00 Z5.000\n; G00 X1 Y1\nM30\n%\n";

const ALPHABET: &[u8] = b"GMXYZIJKRFPNST0123456789.-+ ()[];%#=eE\n\n\n\t/\xc3\xa4\x00";

fn all_dialects() -> [Options; 3] {
    [Dialect::Reference, Dialect::LinuxCnc, Dialect::Grbl].map(|dialect| Options {
        dialect,
        top: Some(2.0),
        tool: Some(2.0),
        ..Default::default()
    })
}

#[test]
fn the_good_program_is_clean() {
    let r = verify(GOOD, &Options::default());
    assert!(r.findings.is_empty(), "{:#?}", r.findings);
    assert!(r.stock.is_some());
    assert!(r.removed_volume_mm3 > 0.0);
}

#[test]
fn random_bytes_never_panic() {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    for round in 0..1500 {
        let len = rng.below(600);
        let bytes: Vec<u8> = (0..len)
            .map(|_| {
                if rng.below(8) == 0 {
                    rng.next() as u8
                } else {
                    ALPHABET[rng.below(ALPHABET.len())]
                }
            })
            .collect();
        let text = String::from_utf8_lossy(&bytes);
        let o = &all_dialects()[round % 3];
        let r = verify(&text, o);
        for f in &r.findings {
            assert!(f.line.is_none_or(|l| l >= 1 && l <= r.lines + 1), "{f:?}");
            assert!(!f.message(millpath_verify::Lang::De).is_empty());
        }
        assert!(r.removed_volume_mm3.is_finite());
    }
}

#[test]
fn mutated_programs_never_panic() {
    let mut rng = Rng(42);
    let lines: Vec<&str> = GOOD.lines().collect();
    for round in 0..1500 {
        let mut prog: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
        for _ in 0..1 + rng.below(6) {
            mutate(&mut prog, &mut rng, ALPHABET);
        }
        let text = prog.join(if round % 2 == 0 { "\n" } else { "\r\n" });
        let r = verify(&text, &all_dialects()[round % 3]);
        assert!(r.removed_volume_mm3.is_finite() && r.removed_volume_mm3 >= 0.0);
    }
}

#[test]
fn a_huge_area_for_a_thin_tool_skips_the_stock_checks() {
    let p = "G21 G90 G94 F100\nG00 X-900000 Y-900000 Z1\nG01 Z-1\nG01 X900000 Y900000\nM30\n";
    let o = Options {
        top: Some(0.0),
        tool: Some(0.1),
        ..Default::default()
    };
    let r = verify(p, &o);
    let kinds: Vec<_> = r.findings.iter().map(|f| &f.kind).collect();
    assert!(
        matches!(
            kinds[..],
            [FindingKind::StockSkipped(StockSkip::AreaTooLarge { .. })]
        ),
        "{kinds:?}"
    );
    assert_eq!(r.findings[0].severity, Severity::Warning);
}

#[test]
fn huge_arcs_and_long_diagonals_stay_within_the_work_limit() {
    let mut p = String::from("G21 G90 G94 F100\nG00 X0 Y0 Z1\nG01 Z-1\n");
    for k in 0..200 {
        // out along an axis, back on a half circle
        if k % 2 == 0 {
            p += "G01 X0 Y1000\nG02 X0 Y0 I0 J-500\n";
        } else {
            p += "G01 X1000 Y0\nG03 X0 Y0 I-500 J0\n";
        }
    }
    p += "M30\n";
    let o = Options {
        top: Some(0.0),
        tool: Some(5.0),
        limits: Limits {
            max_work: 5_000_000,
            ..Default::default()
        },
        ..Default::default()
    };
    let r = verify(&p, &o);
    assert!(
        r.findings.iter().any(|f| matches!(
            f.kind,
            FindingKind::StockSkipped(StockSkip::WorkLimit { .. })
        )),
        "{:#?}",
        r.findings
    );
    assert!(!r.has_errors());
}

#[test]
fn line_and_finding_limits() {
    let limits = Limits {
        max_lines: 100,
        max_findings: 10,
        ..Default::default()
    };
    let o = Options {
        limits,
        ..Default::default()
    };
    let p = "G00 X1\n".repeat(1000);
    let r = verify(&p, &o);
    assert!(r.lines <= 100);
    assert!(r
        .findings
        .iter()
        .any(|f| f.kind == FindingKind::Limit(Limit::Lines(100))));
    let garbage = "#\n".repeat(50);
    let r = verify(&garbage, &o);
    assert_eq!(r.findings.len(), 11);
    assert_eq!(
        r.findings.last().unwrap().kind,
        FindingKind::Limit(Limit::Findings(10))
    );
    let long = format!("G00 X{}\nM30\n", "1".repeat(5000));
    let r = verify(&long, &Options::default());
    assert!(r
        .findings
        .iter()
        .any(|f| f.line == Some(1) && f.kind.code() == "syntax"));
}

/// The worst cases at the default limits, timed: `cargo test --release -p millpath-verify
/// -- --ignored --nocapture`.
#[test]
#[ignore]
fn worst_case_timing() {
    let o = Options {
        top: Some(0.0),
        tool: Some(2.0),
        ..Default::default()
    };
    let mut cases: Vec<(&str, String)> = Vec::new();
    // a million lines of diagonals across a grid at its cell limit
    let mut p = String::from("G21 G90 G94 F100\nG00 X0 Y0 Z1\nG01 Z-1\n");
    for k in 0..1_000_000 {
        p += if k % 2 == 0 { "X450 Y450\n" } else { "X0 Y0\n" };
    }
    cases.push(("diagonals", p));
    let mut p = String::from("G21 G90 G94 F100\nG00 X0 Y0 Z1\nG01 Z-1\n");
    for _ in 0..1_000_000 {
        p += "G02 X0 Y0 I225 J225\n";
    }
    cases.push(("full circles", p));
    cases.push(("rapids", {
        let mut p = String::from("G21 G90 G94 F100\nG00 X0 Y0 Z1\nG01 Z-1\n");
        for k in 0..1_000_000 {
            p += if k % 2 == 0 {
                "G00 X450 Y450\n"
            } else {
                "G00 X0 Y0\n"
            };
        }
        p
    }));
    cases.push(("garbage", "#?@\n".repeat(2_000_000)));
    cases.push((
        "long lines",
        format!("G00 X{}\n", "1".repeat(4000)).repeat(100_000),
    ));
    for (name, p) in &cases {
        let t = std::time::Instant::now();
        let r = verify(p, &o);
        eprintln!(
            "{name}: {} bytes, {:?}, {} findings, stock {:?}",
            p.len(),
            t.elapsed(),
            r.findings.len(),
            r.stock.map(|s| (s.nx, s.ny, s.cell))
        );
    }
}
