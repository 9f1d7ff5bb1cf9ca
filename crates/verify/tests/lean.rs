//! The lean checker (`Verifier::lean`: no moves kept, the clamps, depths and stock model on a
//! second reading) gives the report of the checker that keeps every move (`Verifier::new`),
//! finding for finding, on hand-made programs that reach every check and every limit, and on
//! many mutated ones; a second reading that is not the first program is an error.

use millpath_verify::{
    Clamp, Dialect, FindingKind, Limits, Options, Report, Severity, StockSkip, Verifier,
};

mod common;

use common::{mutate, opts, program, Rng};

/// Both checkers' reports, asserted equal (Debug: every number to its last bit, NaN too).
fn same(program: &str, o: &Options) -> Report {
    let kept = Verifier::new(o.clone()).read_text(program);
    let lean = Verifier::lean(o.clone()).read_text(program);
    assert_eq!(
        format!("{kept:#?}"),
        format!("{lean:#?}"),
        "lean and kept differ on\n{program}\nwith {o:?}"
    );
    kept
}

fn clamp(name: &str, min: [f64; 3], max: [f64; 3]) -> Clamp {
    Clamp {
        name: name.into(),
        min,
        max,
    }
}

// slots along X at depth −0.5 with rapids between them, a helix and an arc
fn slots(n: usize) -> String {
    let mut b = String::new();
    for k in 0..n {
        let y = k as f64 * 3.0;
        b += &format!(
            "G00 Z2.000\nG00 X0.000 Y{y:.3}\nG01 F150 Z-0.500\nG01 X10.000 Y{y:.3} Z-0.500\n\
             G02 X12.000 Y{y:.3} I1.000 J0.000\nG00 Z5.000\n"
        );
    }
    b += "G00 X20.000 Y0.000\nG01 Z0.000\nG03 X20.000 Y0.000 I2.000 J0.000 Z-1.000\nG00 Z5.000\n";
    b
}

#[test]
fn clean_programs_and_their_volumes() {
    let r = same(&program(&slots(5)), &opts(2.0, 2.0));
    assert!(r.findings.is_empty(), "{:#?}", r.findings);
    assert!(r.removed_volume_mm3 > 0.0 && r.stock.is_some());
    assert_eq!(r.moves, 5 * 6 + 4 + 2);
}

#[test]
fn clamp_hits_below_bottom_cuts_and_rapids_into_stock() {
    // the rapid (line 4 of each group) goes sideways at depth into the next slot's stock
    let rapids = program(&slots(4).replace("G00 Z5.000\n", "G00 Z-0.200\n"));
    let o = Options {
        bottom: Some(-0.3),
        clamps: vec![
            clamp("left", [-5.0, -5.0, -10.0], [1.0, 5.0, 0.0]),
            clamp("far", [50.0, 50.0, -10.0], [60.0, 60.0, 0.0]),
            clamp("all", [-100.0, -100.0, -10.0], [100.0, 100.0, 10.0]),
        ],
        ..opts(2.0, 2.0)
    };
    let r = same(&rapids, &o);
    let has = |code: &str| r.findings.iter().any(|f| f.kind.code() == code);
    assert!(has("clamp-hit") && has("below-bottom") && has("rapid-into-material"));
    assert!(r
        .findings
        .iter()
        .all(|f| f.line.is_none() || !f.text.is_empty()));
    // without the tool: the clamps judged at the tool's axis, a warning, no stock model
    let o = Options { tool: None, ..o };
    let r = same(&rapids, &o);
    assert!(r
        .findings
        .iter()
        .any(|f| f.kind == FindingKind::ClampsWithoutTool));
}

#[test]
fn the_stock_comment_gives_tool_and_bottom() {
    let p = program(&format!(
        "(MILLPATH-STOCK T=2.000 O=2.000 BOTTOM=-0.300)\n{}",
        slots(3)
    ));
    let o = Options {
        clamps: vec![clamp("c", [9.0, -1.0, -5.0], [11.0, 1.0, 0.0])],
        ..Default::default()
    };
    let r = same(&p, &o);
    assert_eq!(r.params.bottom, Some(-0.3));
    assert!(r.findings.iter().any(|f| f.kind.code() == "below-bottom"));
    assert!(r.findings.iter().any(|f| f.kind.code() == "clamp-hit"));
    // no values at all: the stock model is skipped with a note
    let r = same(&program(&slots(2)), &Options::default());
    assert!(r.findings.iter().any(|f| matches!(
        f.kind,
        FindingKind::StockSkipped(StockSkip::MissingParams { .. })
    )));
    // only the clamps' quick check
    let o = Options {
        skip_stock: true,
        ..o
    };
    same(&p, &o);
}

#[test]
fn every_limit() {
    let p = program(&slots(40).replace("G00 Z5.000\n", "G00 Z-0.200\n"));
    let every_box = vec![clamp("all", [-100.0, -100.0, -10.0], [100.0, 100.0, 10.0])];
    let base = Options {
        bottom: Some(-0.3),
        clamps: every_box,
        ..opts(2.0, 2.0)
    };
    for limits in [
        // the findings limit: inside the clamps' check, after it, and by the machine's own
        Limits {
            max_findings: 3,
            ..Limits::default()
        },
        Limits {
            max_findings: 60,
            ..Limits::default()
        },
        Limits {
            max_findings: 0,
            ..Limits::default()
        },
        // the stock model's work, the grid, the lines and their length
        Limits {
            max_work: 3_000,
            ..Limits::default()
        },
        Limits {
            max_work: 0,
            ..Limits::default()
        },
        Limits {
            max_cells: 50,
            ..Limits::default()
        },
        Limits {
            max_lines: 77,
            ..Limits::default()
        },
        Limits {
            max_line_len: 12,
            ..Limits::default()
        },
    ] {
        let o = Options {
            limits,
            ..base.clone()
        };
        same(&p, &o);
        let o = Options {
            clamps: Vec::new(),
            ..o
        };
        same(&p, &o);
    }
    // the work limit is reached and said
    let o = Options {
        limits: Limits {
            max_work: 3_000,
            ..Limits::default()
        },
        ..base.clone()
    };
    let r = same(&p, &o);
    assert!(r.findings.iter().any(|f| matches!(
        f.kind,
        FindingKind::StockSkipped(StockSkip::WorkLimit { .. })
    )));
    // many machine findings (no feed on any line: once per feed; unknown words: each line)
    let noisy = "G21 G90\nG00 X0 Y0 Z1\nG01 Z-1 Q1\n".repeat(300);
    for max_findings in [1, 5, 200, 10_000] {
        let o = Options {
            limits: Limits {
                max_findings,
                ..Limits::default()
            },
            ..base.clone()
        };
        let r = same(&noisy, &o);
        assert!(r.findings.len() <= max_findings + 1);
    }
}

#[test]
fn every_dialect_and_line_end() {
    let p = program(&slots(6));
    for dialect in [Dialect::Reference, Dialect::LinuxCnc, Dialect::Grbl] {
        let o = Options {
            dialect,
            bottom: Some(-0.4),
            ..opts(2.0, 2.0)
        };
        same(&p, &o);
        same(&p.replace('\n', "\r\n"), &o);
        // a height map's view keeps every move: lean is the same checker then
        let o = Options {
            view: Some(Default::default()),
            ..o
        };
        same(&p, &o);
    }
}

#[test]
fn mutated_programs_give_the_same_report() {
    // comments the second reading skips, and some it reads: findings on both kinds
    let good = program(&format!(
        "(MILLPATH-STOCK T=2.000 O=2.000 BOTTOM=-0.300)\n{}G38.3 Z0 F50.000\nG04 P4\n\
         (MILLPATH-STOCK T=x)\n  (a (nested) comment)\n(G00 X0 Y0 Z-5)\n(one) G00 Z-0.1 (two)\n",
        slots(3).replace("G00 Z2.000\n", "  (SweepTo [0 0 2])\nG00 Z2.000\n")
    ));
    const ALPHABET: &[u8] = b"GMXYZIJKRF0123456789.- ()%;\n";
    let mut rng = Rng(7);
    let lines: Vec<&str> = good.lines().collect();
    for round in 0..600 {
        let mut prog: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
        for _ in 0..1 + rng.below(5) {
            mutate(&mut prog, &mut rng, ALPHABET);
        }
        let text = prog.join("\n");
        let o = Options {
            dialect: [Dialect::Reference, Dialect::LinuxCnc, Dialect::Grbl][round % 3],
            clamps: vec![clamp("c", [9.0, -1.0, -5.0], [11.0, 8.0, 0.5])],
            limits: Limits {
                max_findings: 1 + rng.below(12),
                max_work: [u64::MAX, 500, 20_000][rng.below(3)],
                ..Limits::default()
            },
            ..Default::default()
        };
        same(&text, &o);
    }
}

#[test]
fn a_second_reading_that_is_not_the_first_is_an_error() {
    let p = program(&slots(3));
    let body = p.strip_suffix('\n').unwrap();
    let first = |v: &mut Verifier| {
        for line in body.split('\n') {
            v.line(line);
        }
    };
    let reread = |r: &Report| {
        r.findings
            .iter()
            .filter(|f| matches!(f.kind, FindingKind::RereadDiffers { .. }))
            .map(|f| (f.severity, f.kind.clone()))
            .collect::<Vec<_>>()
    };
    let lines = body.split('\n').count();
    // nothing given again
    let mut v = Verifier::lean(opts(2.0, 2.0));
    first(&mut v);
    let r = v.finish(|_| {});
    assert_eq!(
        reread(&r),
        [(
            Severity::Error,
            FindingKind::RereadDiffers {
                lines: (0, lines),
                moves: (0, r.moves)
            }
        )]
    );
    assert!(r.stock.is_some(), "the model of what was read");
    // other moves on as many lines
    let mut v = Verifier::lean(opts(2.0, 2.0));
    first(&mut v);
    let r = v.finish(|feed| {
        for line in body.split('\n') {
            feed(if line.starts_with("G02") {
                "G04 P1"
            } else {
                line
            });
        }
    });
    assert_eq!(reread(&r).len(), 1, "{:#?}", r.findings);
    assert!(FindingKind::RereadDiffers {
        lines: (1, 2),
        moves: (3, 4)
    }
    .message(millpath_verify::Lang::De)
    .contains("3 von 4 Bewegungen"));
    // the kept checker needs no second reading of a clean program
    let mut v = Verifier::new(opts(2.0, 2.0));
    first(&mut v);
    let r = v.finish(|_| panic!("not asked"));
    assert!(r.findings.is_empty());
}

#[test]
fn only_whole_comment_lines_are_skipped_on_the_second_reading() {
    use millpath_verify::only_a_comment;
    for l in ["(a)", "  (MillLine s=[0 0] e=[1 1])\r", "()", "(G00 X5)"] {
        assert!(only_a_comment(l), "{l}");
    }
    for l in [
        "",
        "(",
        "(a) G00 X1",
        "G00 X1 (a)",
        "(a (b) c)",
        "(a) (b)",
        "(a",
        ";(a)",
        "%",
        // not an ASCII blank: read as the first reading did
        "\u{a0}(a)",
    ] {
        assert!(!only_a_comment(l), "{l}");
    }
}

#[test]
fn long_lines_show_their_first_200_characters() {
    let long = format!("G00 X1 Q1 ({})", "ä".repeat(300));
    let p = program(&format!("{long}\n(only a comment, {})\n", "x".repeat(300)));
    let r = same(&p, &opts(2.0, 2.0));
    let f = r
        .findings
        .iter()
        .find(|f| f.kind.code() == "unsupported")
        .expect("the word Q");
    assert_eq!(f.text.chars().count(), 200);
    assert!(long.starts_with(&f.text));
}
