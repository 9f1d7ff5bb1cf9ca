//! Programs adjusted to a measured height map, made by hand as adjust-z writes them: the
//! `(MILLPATH-SURFACE …)` record after the stock comment, every point below the safe height
//! on the map at nominal Z + offset, cuts split at the grid lines.

use millpath_verify::{
    program_top, verify, verify_on_surface, FindingKind, HeightMap, Options, Report, Severity,
    SurfaceProblem,
};

const T: f64 = 3.0;
const BOTTOM: f64 = -0.2;

/// A map on x 0..30 (step 10), y −6..6 (step 6) with heights `f`.
fn map(f: impl Fn(f64, f64) -> f64) -> HeightMap {
    let xs = vec![0.0, 10.0, 20.0, 30.0];
    let ys = vec![-6.0, 0.0, 6.0];
    let z = ys
        .iter()
        .flat_map(|&y| xs.iter().map(move |&x| (x, y)))
        .map(|(x, y)| f(x, y))
        .collect();
    HeightMap::new(xs, ys, z, T).unwrap()
}

/// Tilted and twisted: rises 0.3 mm along X, 0.12 along Y, a twist.
fn board() -> HeightMap {
    map(|x, y| T + 0.01 * x + 0.01 * y + 0.0005 * x * y)
}

/// The same program written for the surface `cut_on` with the record of `record`: a slot
/// from (5,0) to (25,0) at −0.2 (split at the grid lines), a half circle of radius 5 around
/// (15,0) at −0.1 in 12 helical pieces, rapids at the safe height 10 leaving the map.
fn program(cut_on: &HeightMap, record: &HeightMap) -> String {
    let z = |nominal: f64, x: f64, y: f64| nominal + cut_on.offset(x, y).unwrap();
    let mut p = vec![
        "%".to_string(),
        "(MILLPATH-STOCK T=3.000 O=2.000 BOTTOM=-0.200)".into(),
    ];
    p.extend(record.comment_lines());
    p.push("G17 G21 G40 G49 G54 G80 G90 G94".into());
    p.push("F300.000".into());
    p.push("G00 Z10.000".into());
    p.push("G00 X5.000 Y0.000".into());
    p.push(format!("G00 Z{:.3}", z(T, 5.0, 0.0)));
    p.push(format!("G01 F150.000 Z{:.3}", z(BOTTOM, 5.0, 0.0)));
    for x in [10.0, 20.0, 25.0] {
        p.push(format!(
            "G01 F300.000 X{x:.3} Y0.000 Z{:.3}",
            z(BOTTOM, x, 0.0)
        ));
    }
    p.push(format!("G00 Z{:.3}", z(T, 25.0, 0.0)));
    p.push("G00 Z10.000".into());
    p.push("G00 X20.000 Y0.000".into());
    p.push(format!("G00 Z{:.3}", z(T, 20.0, 0.0)));
    p.push(format!("G01 F150.000 Z{:.3}", z(-0.1, 20.0, 0.0)));
    for k in 1..=12 {
        let a = std::f64::consts::PI * k as f64 / 12.0;
        let (x, y) = (15.0 + 5.0 * a.cos(), 5.0 * a.sin());
        let (px, py) = {
            let a0 = std::f64::consts::PI * (k - 1) as f64 / 12.0;
            (15.0 + 5.0 * a0.cos(), 5.0 * a0.sin())
        };
        p.push(format!(
            "G03 X{x:.3} Y{y:.3} Z{:.3} I{:.3} J{:.3}",
            z(-0.1, x, y),
            15.0 - px,
            -py
        ));
    }
    p.push(format!("G00 Z{:.3}", z(T, 10.0, 0.0)));
    p.push("G00 Z10.000".into());
    // off the map at the safe height (above the highest point)
    p.push("G00 X40.000 Y0.000".into());
    p.push("M30".into());
    p.push("%".into());
    p.join("\n") + "\n"
}

fn errors(r: &Report) -> Vec<(usize, String)> {
    r.findings
        .iter()
        .filter(|f| f.severity != Severity::Note)
        .map(|f| (f.line.unwrap_or(0), f.code().to_string()))
        .collect()
}

fn options() -> Options {
    Options {
        dialect: millpath_verify::Dialect::LinuxCnc,
        ..Default::default()
    }
}

#[test]
fn a_correct_adjusted_program_is_clean_and_judged_on_its_surface() {
    let b = board();
    let text = program(&b, &b);
    let r = verify(&text, &options());
    assert_eq!(errors(&r), [], "{:#?}", r.findings);
    // the map of its record (heights to 3 decimals)
    let got = r.surface.unwrap();
    assert_eq!(got.xs(), b.xs());
    assert!((got.at(3, 2) - b.at(3, 2)).abs() <= 0.0005);
    // the stock model cut the drawn slot: its volume is that of the flat program
    let flat = map(|_, _| T);
    let nominal = verify(&program(&flat, &flat), &options());
    assert_eq!(errors(&nominal), []);
    let (a, n) = (r.removed_volume_mm3, nominal.removed_volume_mm3);
    assert!((a - n).abs() / n < 0.02, "{a} vs {n}");
    assert_eq!(program_top(&text), Some(T));
    // without its record, the surface given by the caller judges it the same
    let bare: String = text
        .lines()
        .filter(|l| !l.contains("MILLPATH-SURFACE"))
        .map(|l| format!("{l}\n"))
        .collect();
    let r = verify_on_surface(&bare, &options(), Some(&b));
    assert_eq!(errors(&r), [], "{:#?}", r.findings);
    assert!((r.removed_volume_mm3 - n).abs() / n < 0.02);
}

#[test]
fn z_computed_from_another_surface_is_found() {
    // the record says the board rises along X; the Z were computed for one falling along X
    let other = map(|x, _| T + 0.3 - 0.01 * x);
    let r = verify(&program(&other, &board()), &options());
    let e = errors(&r);
    assert!(e.iter().any(|e| e.1 == "below-bottom"), "{e:?}");
    // one finding a line
    let mut lines: Vec<usize> = e.iter().map(|e| e.0).collect();
    lines.dedup();
    assert_eq!(lines.len(), e.len(), "{e:?}");
    // the cut below the drawn depth is where the surfaces part most: the slot's start
    let below = r
        .findings
        .iter()
        .find(|f| f.code() == "below-bottom")
        .unwrap();
    assert!(below.text.starts_with("G01"), "{below:?}");
}

#[test]
fn a_program_cut_from_a_too_low_map_plunges_into_the_board() {
    let b = board();
    let low = map(|x, y| T + 0.01 * x + 0.01 * y + 0.0005 * x * y - 0.05);
    // adjusted to the low map, which is also its record: consistent in itself
    assert_eq!(errors(&verify(&program(&low, &low), &options())), []);
    // on the board as measured on the machine: every plunge rapid ends 0.05 in the material
    let r = verify_on_surface(&program(&low, &low), &options(), Some(&b));
    let e = errors(&r);
    let rapids = e.iter().filter(|e| e.1 == "rapid-into-material").count();
    assert!(rapids >= 1, "{e:?}");
    assert!(e.iter().any(|e| e.1 == "below-bottom"), "{e:?}");
    for f in r.findings.iter().filter(|f| f.code() == "below-bottom") {
        let FindingKind::BelowBottom { z, bottom } = f.kind else {
            unreachable!()
        };
        assert!((z - (bottom - 0.05)).abs() < 0.003, "{f:?}");
    }
    // and the right map given on the command line passes it again
    let r = verify_on_surface(&program(&b, &b), &options(), Some(&b));
    assert_eq!(errors(&r), []);
}

#[test]
fn a_cut_not_split_along_a_curved_surface_is_found_inside() {
    // a ridge along x = 15: the slot written from (5,0) to (25,0) without a split point
    let ridge = map(|x, _| if x == 10.0 || x == 20.0 { T + 0.1 } else { T });
    let whole: String = program(&ridge, &ridge)
        .lines()
        .filter(|l| {
            !(l.starts_with("G01 F300.000 X10.000") || l.starts_with("G01 F300.000 X20.000"))
        })
        .map(|l| format!("{l}\n"))
        .collect();
    let r = verify(&whole, &options());
    let below: Vec<_> = r
        .findings
        .iter()
        .filter(|f| f.code() == "below-bottom")
        .collect();
    assert_eq!(below.len(), 1, "{:#?}", r.findings);
    assert!(below[0].text.starts_with("G01 F300.000 X25.000"));
    let FindingKind::BelowBottom { z, .. } = below[0].kind else {
        unreachable!()
    };
    // 0.05 mm at x = 10 and 20 where the straight Z misses the rise
    assert!(z < BOTTOM - 0.04, "{z}");
    // split, it is clean
    assert_eq!(errors(&verify(&program(&ridge, &ridge), &options())), []);
}

#[test]
fn a_broken_record_is_an_error_at_its_line() {
    let b = board();
    let good = program(&b, &b);
    // a height that is no number, on the first Z row (line 6)
    let nan: String = good
        .lines()
        .enumerate()
        .map(|(i, l)| {
            if i == 5 {
                let mut w: Vec<&str> = l.split(' ').collect();
                w[3] = "NaN";
                w.join(" ") + "\n"
            } else {
                format!("{l}\n")
            }
        })
        .collect();
    assert!(nan
        .lines()
        .nth(5)
        .unwrap()
        .starts_with("(MILLPATH-SURFACE-Z J=0"));
    let r = verify(&nan, &options());
    let f = r
        .findings
        .iter()
        .find(|f| f.code() == "surface-record")
        .unwrap();
    assert_eq!(f.line, Some(6));
    assert_eq!(f.severity, Severity::Error);
    assert!(matches!(
        f.kind,
        FindingKind::Surface(SurfaceProblem::BadNumber { .. })
    ));
    assert!(r.surface.is_none());
    let de = f.message(millpath_verify::Lang::De);
    assert!(
        de.contains("Höhenkarten-Eintrag") && de.contains("NaN"),
        "{de}"
    );
    // a row missing: the record's last line is named
    let missing: String = good
        .lines()
        .filter(|l| !l.starts_with("(MILLPATH-SURFACE-Z J=1"))
        .map(|l| format!("{l}\n"))
        .collect();
    let r = verify(&missing, &options());
    let f = r
        .findings
        .iter()
        .find(|f| f.code() == "surface-record")
        .unwrap();
    assert!(f.text.starts_with("(MILLPATH-SURFACE-Z J=2"), "{f:?}");
    assert!(f
        .message(millpath_verify::Lang::En)
        .contains("values missing"));
}
