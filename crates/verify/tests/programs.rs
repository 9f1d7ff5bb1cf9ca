//! Hand-made programs, each with the exact findings (kind and line) it must give.

use millpath_verify::{
    parse_stock_comment, stock_comment, verify, ArcProblem, Dialect, Finding, FindingKind, Lang,
    NoFeedReason, NumberProblem, Options, Severity, StockCommentProblem, StockParams, StockSkip,
    SyntaxError,
};

mod common;

use common::{opts, program};

/// Errors and warnings (notes left out).
fn problems(text: &str, o: &Options) -> Vec<Finding> {
    verify(text, o)
        .findings
        .into_iter()
        .filter(|f| f.severity != Severity::Note)
        .collect()
}

fn only(text: &str, o: &Options) -> Finding {
    let p = problems(text, o);
    assert_eq!(p.len(), 1, "{p:#?}");
    p.into_iter().next().unwrap()
}

// a slot along X at depth −0.5 (T = 2, O = 2), from x 0 to 10
const SLOT: &str = "G00 Z2.000\nG01 Z-0.500\nG01 F150 X10.000 Y0.000 Z-0.500\n";

#[test]
fn a_clean_program_has_no_findings_and_the_slot_volume() {
    let r = verify(&program(SLOT), &opts(2.0, 2.0));
    assert!(r.findings.is_empty(), "{:#?}", r.findings);
    // (10 × 2 + π·1²) × 2.5
    let want = (20.0 + std::f64::consts::PI) * 2.5;
    assert!(
        (r.removed_volume_mm3 - want).abs() / want < 0.03,
        "{} vs {want}",
        r.removed_volume_mm3
    );
    let s = r.stock.unwrap();
    assert_eq!(s.cell, 0.25);
    assert_eq!(r.lines, 11);
    assert_eq!(r.moves, 5);
}

#[test]
fn a_rapid_across_uncut_material_is_found() {
    // line 10: sideways out of the slot at depth
    let f = only(
        &program(&format!("{SLOT}G00 X10.000 Y10.000\nG00 Z5.000\n")),
        &opts(2.0, 2.0),
    );
    assert_eq!(f.line, Some(10));
    assert_eq!(f.text, "G00 X10.000 Y10.000");
    assert_eq!(f.severity, Severity::Error);
    match f.kind {
        FindingKind::RapidIntoMaterial { depth, .. } => assert!((depth - 2.5).abs() < 1e-9),
        k => panic!("{k:?}"),
    }
    assert!(f
        .message(Lang::En)
        .starts_with("rapid move (G00) into material"));
    assert!(f
        .message(Lang::De)
        .starts_with("Eilgang (G00) ins Material"));
}

#[test]
fn a_rapid_along_the_slot_just_cut_is_fine() {
    let p = program(&format!(
        "{SLOT}G00 X0.000 Y0.000\nG00 X7.000\nG00 Z5.000\n"
    ));
    assert!(problems(&p, &opts(2.0, 2.0)).is_empty());
}

#[test]
fn a_rapid_above_the_material_is_fine_and_a_rapid_plunge_is_not() {
    let p = program(&format!(
        "{SLOT}G00 Z5.000\nG00 X20.000 Y20.000\nG00 Z1.000\nG00 Z5.000\n"
    ));
    let f = only(&p, &opts(2.0, 2.0));
    assert_eq!(f.line, Some(12));
    assert!(
        matches!(f.kind, FindingKind::RapidIntoMaterial { depth, .. } if (depth - 1.0).abs() < 1e-9)
    );
    // straight down into the slot's own hole is fine; onto the top too
    let p = program(&format!(
        "{SLOT}G00 Z5.000\nG00 X5.000 Y0.000\nG00 Z-0.500\nG00 Z5.000\nG00 X20.000\nG00 Z2.000\n"
    ));
    assert!(problems(&p, &opts(2.0, 2.0)).is_empty());
}

/// The reference's helix (§9.2): T = 2, O = 2, drawn radius 1.05, B = −0.1; the tool goes
/// back to the centre inside its own hole.
fn helix(r_mill: f64, back_to_centre: &str) -> String {
    let (lo, hi) = (-r_mill, r_mill);
    let mut body = format!("G00 X10.000 Y0.000\nG00 Z4.000\nG00 X10.000 Y{lo:.3}\n");
    for (z1, z2) in [(1.4, 0.8), (0.2, -0.1), (-0.1, -0.1)] {
        body += &format!("G02 F150.000 I0 J{hi:.3} X10.000 Y{hi:.3} Z{z1:.3}\n");
        body += &format!("G02 F150.000 I0 J{lo:.3} X10.000 Y{lo:.3} Z{z2:.3}\n");
    }
    body += back_to_centre;
    body += "G00 Z5.000\n";
    program(&body)
}

#[test]
fn a_helix_returning_to_its_centre_is_fine() {
    for r_mill in [0.05, 0.5, 1.0] {
        let p = helix(r_mill, "G00 X10.000 Y0.000\n");
        let r = verify(&p, &opts(2.0, 2.0));
        assert!(!r.has_errors(), "{r_mill}: {:#?}", r.findings);
        let want = std::f64::consts::PI * (r_mill + 1.0).powi(2) * 2.1;
        assert!(
            (r.removed_volume_mm3 - want).abs() / want < 0.05,
            "{r_mill}"
        );
    }
}

#[test]
fn a_helix_leaving_a_core_is_hit_by_a_rapid_to_its_centre() {
    // milling radius 2 with O = 2: a core of radius 1 stays; the line after the helix
    // (7 + 3 + 6 = line 16) rapids into it
    let f = only(&helix(2.0, "G00 X10.000 Y0.000\n"), &opts(2.0, 2.0));
    assert_eq!(f.line, Some(16));
    assert!(
        matches!(f.kind, FindingKind::RapidIntoMaterial { depth, .. } if (depth - 2.1).abs() < 1e-9)
    );
}

#[test]
fn f0_is_a_finding_and_the_move_after_it_is_not_reported_again() {
    let p = program("G00 Z2.000\nG01 F0 Z1.000\nG01 X5.000\n");
    let f = only(&p, &Options::default());
    assert_eq!(f.line, Some(8));
    assert_eq!(f.kind, FindingKind::FeedNotPositive { value: 0.0 });
    let p = program("F-10\nG00 Z2.000\n");
    let f = only(&p, &Options::default());
    assert_eq!(f.line, Some(7));
    assert_eq!(f.kind, FindingKind::FeedNotPositive { value: -10.0 });
}

#[test]
fn feed_before_g94_fails_in_linuxcnc_only() {
    let p = program("G00 Z2.000\nG01 Z-0.100\nG01 F150.000 X5.000 Y0.000 Z-0.100\n");
    for dialect in [Dialect::Reference, Dialect::Grbl] {
        let o = Options {
            dialect,
            ..Default::default()
        };
        // grbl has no `%` lines
        let p = if dialect == Dialect::Grbl {
            p.replace("%\n", "")
        } else {
            p.clone()
        };
        assert!(problems(&p, &o).is_empty(), "{dialect:?}");
    }
    let o = Options {
        dialect: Dialect::LinuxCnc,
        ..Default::default()
    };
    let f = only(&p, &o);
    assert_eq!(f.line, Some(8));
    assert_eq!(
        f.kind,
        FindingKind::NoFeed {
            motion: "G01".into(),
            reason: NoFeedReason::ResetBy {
                code: "G94".into(),
                line: 3,
                dialect: Dialect::LinuxCnc
            }
        }
    );
    assert!(f
        .message(Lang::En)
        .contains("G94 on line 3 resets the feed rate in LinuxCNC"));
    // F after G94 on the same line is fine: the feed mode is set first
    let fixed = p.replace(
        "F150\nG17 G21 G40 G49 G54 G80 G90 G94",
        "G17 G21 G40 G49 G54 G80 G90 G94 F150",
    );
    assert!(problems(&fixed, &o).is_empty());
}

#[test]
fn no_feed_at_all_is_found_once_in_every_dialect() {
    let p = "G21 G90 G94\nG00 X0 Y0 Z1\nG01 X1\nG01 X2\nM30\n";
    for dialect in [Dialect::Reference, Dialect::LinuxCnc, Dialect::Grbl] {
        let o = Options {
            dialect,
            ..Default::default()
        };
        let f = only(p, &o);
        assert_eq!(f.line, Some(3));
        assert!(matches!(
            f.kind,
            FindingKind::NoFeed {
                reason: NoFeedReason::NeverSet,
                ..
            }
        ));
    }
}

#[test]
fn inverse_time_needs_f_on_every_cutting_line() {
    let p = "G21 G90 G93\nG00 X0 Y0 Z1\nG01 X1 F10\nG01 X2\nM30\n";
    let o = Options {
        dialect: Dialect::Grbl,
        ..Default::default()
    };
    let f = only(p, &o);
    assert_eq!(f.line, Some(4));
    assert!(matches!(
        f.kind,
        FindingKind::NoFeed {
            reason: NoFeedReason::InverseTime,
            ..
        }
    ));
}

#[test]
fn an_arc_whose_end_is_off_its_circle_is_found() {
    // start (0, 0), centre (5, 0): radius 5 at the start, 5.01 at the end
    let p = program("G00 Z1.000\nG02 F150 I5.000 J0.000 X10.010 Y0.000\n");
    let f = only(&p, &Options::default());
    assert_eq!(f.line, Some(8));
    match f.kind {
        FindingKind::ArcRadiusMismatch { start, end } => {
            assert!((start - 5.0).abs() < 1e-9 && (end - 5.01).abs() < 1e-9)
        }
        k => panic!("{k:?}"),
    }
    // rounding to 3 decimals is well inside the tolerance
    let p = program("G00 Z1.000\nG02 F150 I0.000 J14.000 X-6.712 Y1.714\n");
    assert!(problems(&p, &Options::default()).is_empty());
}

#[test]
fn arcs_without_centre_of_radius_zero_or_in_other_planes() {
    let f = only(&program("G00 Z1\nG02 F150 X1 Y1\n"), &Options::default());
    assert_eq!(
        (f.line, f.kind),
        (Some(8), FindingKind::ArcInvalid(ArcProblem::NoCentre))
    );
    let f = only(
        &program("G00 Z1\nG02 F150 X1 Y1 I0 J0\n"),
        &Options::default(),
    );
    assert_eq!(
        (f.line, f.kind),
        (Some(8), FindingKind::ArcInvalid(ArcProblem::ZeroRadius))
    );
    let f = only(
        &program("G00 Z1\nG03 F150 X10 Y0 R4\n"),
        &Options::default(),
    );
    assert_eq!(f.kind, FindingKind::ArcInvalid(ArcProblem::RadiusTooSmall));
    let f = only(
        &program("G18\nG00 Z1\nG02 F150 X1 Z0 I0.5 K0\n"),
        &Options::default(),
    );
    assert_eq!(f.line, Some(9));
    assert_eq!(f.severity, Severity::Warning);
    assert_eq!(
        f.kind,
        FindingKind::ArcPlane {
            plane: "G18".into()
        }
    );
    // R form: a half circle of radius 5 cuts its stock
    let p = program("G00 X0 Y0\nG00 Z2\nG01 Z1\nG03 F150 X10 Y0 R5\nG00 Z5\n");
    let r = verify(&p, &opts(2.0, 2.0));
    assert!(!r.has_errors(), "{:#?}", r.findings);
    // half annulus 4..6 plus the end discs, 1 deep: π/2·(36−16) + π ≈ 34.6
    assert!(
        (r.removed_volume_mm3 - 34.6).abs() < 1.5,
        "{}",
        r.removed_volume_mm3
    );
}

#[test]
fn non_finite_and_absurd_numbers() {
    let f = only(&program("G00 ZNaN\n"), &Options::default());
    assert_eq!(f.line, Some(7));
    assert_eq!(f.text, "G00 ZNaN");
    assert_eq!(
        f.kind,
        FindingKind::BadNumber {
            letter: 'Z',
            text: "NaN".into(),
            problem: NumberProblem::NonFinite
        }
    );
    let f = only(&program("G00 Z1e9\n"), &Options::default());
    assert_eq!(
        f.kind,
        FindingKind::BadNumber {
            letter: 'Z',
            text: "1e9".into(),
            problem: NumberProblem::Absurd
        }
    );
    let f = only(&program("G01 F150 X-2000000 Y0\n"), &Options::default());
    assert!(matches!(
        f.kind,
        FindingKind::BadNumber {
            problem: NumberProblem::Absurd,
            ..
        }
    ));
    let f = only(&program("G00 X-inf\n"), &Options::default());
    assert!(matches!(
        f.kind,
        FindingKind::BadNumber {
            problem: NumberProblem::NonFinite,
            ..
        }
    ));
}

#[test]
fn a_truncated_program_has_no_end() {
    let full = program(SLOT);
    let cut = &full[..full.find("G01 F150").unwrap() + 12];
    let f = only(cut, &Options::default());
    assert_eq!(f.kind, FindingKind::MissingProgramEnd);
    assert_eq!(f.line, Some(9));
    assert_eq!(f.text, "G01 F150 X10");
    // an empty file too
    let f = only("", &Options::default());
    assert_eq!((f.line, f.kind), (None, FindingKind::MissingProgramEnd));
    // code after M30 is ignored by the controller
    let f = only(&format!("{full}G00 X1\nG00 X2\n"), &Options::default());
    assert_eq!((f.line, f.severity), (Some(12), Severity::Warning));
    assert_eq!(f.kind, FindingKind::AfterProgramEnd);
}

#[test]
fn a_cut_below_the_bottom() {
    let o = Options {
        bottom: Some(-0.5),
        ..opts(2.0, 2.0)
    };
    assert!(problems(&program(SLOT), &o).is_empty());
    let o = Options {
        bottom: Some(-0.4995),
        ..opts(2.0, 2.0)
    };
    assert!(problems(&program(SLOT), &o).is_empty(), "within 0.001");
    let o = Options {
        bottom: Some(-0.2),
        ..opts(2.0, 2.0)
    };
    // more than the tolerance above: the drill (line 8) and the line (line 9)
    let p = problems(&program(SLOT.replace("-0.500", "-0.300").as_str()), &o);
    let lines: Vec<_> = p.iter().map(|f| (f.line, f.kind.code())).collect();
    assert_eq!(
        lines,
        [(Some(8), "below-bottom"), (Some(9), "below-bottom")]
    );
}

#[test]
fn the_stock_comment_gives_the_values_and_options_override_it() {
    let body = format!(
        "{}\n{SLOT}G00 X10.000 Y10.000\n",
        stock_comment(2.0, 2.0, Some(-0.3))
    );
    let p = program(&body);
    assert!(p.contains("(MILLPATH-STOCK T=2.000 O=2.000 BOTTOM=-0.300)"));
    let kinds: Vec<_> = problems(&p, &Options::default())
        .iter()
        .map(|f| (f.line, f.kind.code()))
        .collect();
    assert_eq!(
        kinds,
        [
            (Some(9), "below-bottom"),
            (Some(10), "below-bottom"),
            (Some(11), "rapid-into-material")
        ]
    );
    // a lower top and bottom from the options: the slot is an air cut, the rapid is above
    let o = Options {
        top: Some(-1.0),
        bottom: Some(-1.0),
        ..Default::default()
    };
    assert!(problems(&p, &o).is_empty());
    assert_eq!(
        parse_stock_comment("MILLPATH-STOCK T=2 O=3"),
        Some(Ok(StockParams {
            top: Some(2.0),
            tool: Some(3.0),
            bottom: None
        }))
    );
    assert_eq!(parse_stock_comment("Model 1234"), None);
    assert_eq!(
        parse_stock_comment("MILLPATH-STOCK T=NaN O=2"),
        Some(Err(StockCommentProblem::BadValue {
            key: "T".into(),
            text: "NaN".into()
        }))
    );
    let f = only(&program("(MILLPATH-STOCK T=2 O=0)\n"), &Options::default());
    assert_eq!(f.kind.code(), "stock-comment");
}

#[test]
fn without_top_and_tool_the_stock_checks_are_skipped_with_one_note() {
    let r = verify(
        &program(&format!("{SLOT}G00 X10.000 Y10.000\n")),
        &Options::default(),
    );
    assert_eq!(r.findings.len(), 1);
    assert_eq!(r.findings[0].line, None);
    assert_eq!(r.findings[0].severity, Severity::Note);
    assert_eq!(
        r.findings[0].kind,
        FindingKind::StockSkipped(StockSkip::MissingParams {
            top: true,
            tool: true
        })
    );
    assert!(!r.has_errors());
    assert_eq!(r.removed_volume_mm3, 0.0);
}

#[test]
fn clean_files_probe_expressions_and_probing_files() {
    let clean = "%\nF150\nG17 G21 G40 G49 G54 G80 G90 G94\nT1\nG00 Z5.000\nG00 X0.000 Y0.000\n\
        G00 Z2.000(=2.000+0.794*[#51-2.000]+0.206*[#52-2.000])\n\
        G01 Z0.800(=0.800+0.794*[#51-2.000]+0.206*[#52-2.000])\n\
        G01 F150.000 X5.000 Y0.000 Z0.800(=0.800+1.000*[#51-2.000])\nG00 Z5.000\nM30\n%\n";
    let r = verify(clean, &opts(2.0, 2.0));
    assert!(r.findings.is_empty(), "{:#?}", r.findings);
    let probing = "%\nF150\nG17 G21 G40 G49 G54 G80 G90 G94\nT1\nG00 Z5.000\nG00 X0.000 Y0.000\n\
        G00 X8.429 Y9.528\nG00 Z4.000\nG38.3 Z0 F50.000\nG04 P4\nG00 Z5.000\nG00 X0.000 Y0.000\nM30\n%\n";
    let r = verify(probing, &opts(2.0, 2.0));
    assert!(r.findings.is_empty(), "{:#?}", r.findings);
    // in LinuxCNC too: the probe line has its own F
    let o = Options {
        dialect: Dialect::LinuxCnc,
        ..opts(2.0, 2.0)
    };
    assert!(verify(probing, &o).findings.is_empty());
}

#[test]
fn syntax_findings_name_their_line() {
    let cases: [(&str, FindingKind); 6] = [
        (
            "G00 X1 (open",
            FindingKind::Syntax(SyntaxError::UnclosedComment),
        ),
        (
            "G00 G01 X1",
            FindingKind::Syntax(SyntaxError::SameModalGroup("G00".into(), "G01".into())),
        ),
        (
            "G07.5",
            FindingKind::Syntax(SyntaxError::UnknownCode("G7.5".into())),
        ),
        (
            "G00 #1=2",
            FindingKind::Syntax(SyntaxError::UnexpectedChar('#')),
        ),
        ("G04", FindingKind::Syntax(SyntaxError::BadDwell)),
        ("X", FindingKind::Syntax(SyntaxError::MissingNumber('X'))),
    ];
    for (line, kind) in cases {
        let f = only(&program(&format!("{line}\n")), &Options::default());
        assert_eq!((f.line, &f.kind), (Some(7), &kind), "{line}");
        assert_eq!(f.text, line);
    }
    // axis words with G80 in effect
    let f = only("G80\nX1\nM30\n", &Options::default());
    assert_eq!(
        (f.line, f.kind),
        (Some(2), FindingKind::Syntax(SyntaxError::AxesWithoutMotion))
    );
    // a nested comment: an error for LinuxCNC, a warning elsewhere
    let p = program("(part (copy].dxf)\n");
    assert_eq!(only(&p, &Options::default()).severity, Severity::Warning);
    let o = Options {
        dialect: Dialect::LinuxCnc,
        ..Default::default()
    };
    assert_eq!(only(&p, &o).severity, Severity::Error);
}

#[test]
fn a_cut_from_an_unknown_position_is_a_warning() {
    let f = only("G21 G90 G94 F100\nG01 X1 Y1\nM30\n", &Options::default());
    assert_eq!(f.line, Some(2));
    assert_eq!(f.severity, Severity::Warning);
    assert_eq!(
        f.kind,
        FindingKind::UnknownPosition {
            motion: "G01".into()
        }
    );
}

#[test]
fn inches_relative_moves_and_unsupported_codes() {
    // 1 inch deep slot from a G91 move: the rapid back sideways hits the material
    let p = "G20 G90 G94 F10\nG00 X0 Y0 Z1\nG01 Z-0.04\nG91 G01 X0.4\nG90 G00 Y0.4\nM30\n";
    let r = verify(p, &opts(0.0, 2.0));
    let f: Vec<_> = r.findings.iter().map(|f| (f.line, f.kind.code())).collect();
    assert_eq!(f, [(Some(5), "rapid-into-material")]);
    match r.findings[0].kind {
        FindingKind::RapidIntoMaterial { depth, .. } => assert!((depth - 1.016).abs() < 1e-9),
        _ => unreachable!(),
    }
    let f = only("G21 G90 G94 F10\nG41\nM30\n", &Options::default());
    assert_eq!(f.severity, Severity::Warning);
    assert_eq!(f.kind.code(), "unsupported");
}

#[test]
fn german_messages_differ_from_english_ones() {
    let p = program("G00 Z1\nG02 F150 I5.000 J0.000 X10.010 Y0.000\nG01 F0 X1\n");
    let r = verify(&p, &opts(0.5, 2.0));
    assert_eq!(r.findings.len(), 2, "{:#?}", r.findings);
    for f in &r.findings {
        assert_ne!(f.message(Lang::En), f.message(Lang::De));
    }
    assert!(r.findings[1].message(Lang::De).contains("Vorschub F0.000"));
}
