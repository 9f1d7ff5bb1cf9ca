//! The `xcam` family (xCAM's `.NCC` exchange format): a good file is clean and its moves are
//! rebuilt from its contours; what the checks of every family catch is caught here too
//! (a cut below the bottom, a clamp, an arc whose ends are off its centre, a missing feed);
//! and hostile input (every truncation, random bytes, mutated lines, one contour milled
//! again and again) gives located findings, never a panic.

use millpath_verify::{
    verify, Clamp, Dialect, FindingKind, NccProblem, Options, Severity, RAPID_CLEARANCE,
};

mod common;

use common::{mutate, Rng};

const GOOD: &str = "H DX=20.000 DY=10.000 DZ=2.300 OX=0.000 OY=0.000 OZ=-0.300 T=2.000 FIELD=\"\"\r\n\
COM MSGSTATUS=0 TEXT=\"millpath\"\r\n\
COM MSGSTATUS=0 TEXT=\"MILLPATH-STOCK T=2.000 O=2.000 BOTTOM=-0.300\"\r\n\
G0 X=0.000 Y=0.000 Z=2.000 N=\"P1\" CTYPE=0\r\n\
G1 X=0.000 Y=0.000 Z=-0.300 G1_SPEED=75.000\r\n\
G1 X=10.000 Y=0.000 Z=-0.300 G1_SPEED=150.000\r\n\
G5 X=20.000 Y=0.000 Z=-0.300 I=15.000 J=0.000 DIR=1 G5_SPEED=150.000\r\n\
GIN T=\"2.000\" N=\"P1\" CS=\"0\" CE=\"0\" C=0 IN=0 OUT=0 DFC=1 TI=2.300 GIN_DRIVE_SPEED=150.000\r\n\
B X=5.000 Y=5.000 Z=2.000 DU=2.000 TI=2.300 B_MODE=0 B_WORKSPEED=100.000\r\n\
COM MSGSTATUS=0 TEXT=\"the end_C_N_L_really\"\r\n";

fn xcam() -> Options {
    Options {
        dialect: Dialect::Xcam,
        ..Default::default()
    }
}

fn errors(text: &str, o: &Options) -> Vec<(Option<usize>, String)> {
    verify(text, o)
        .findings
        .into_iter()
        .filter(|f| f.severity == Severity::Error)
        .map(|f| (f.line, f.code().to_string()))
        .collect()
}

#[test]
fn a_good_file_is_clean_and_its_moves_are_rebuilt() {
    let r = verify(GOOD, &xcam());
    assert!(r.findings.is_empty(), "{:#?}", r.findings);
    // the milling: 2 rapids, the plunge of the contour, its 3 elements, a rapid up; the
    // drilling: 3 rapids, its feed down, a rapid up; the set-up line makes none
    assert_eq!(r.moves, 12);
    let stock = r.stock.expect("the stock comment gives T and O");
    assert!(stock.cell > 0.0);
    // the slot (10 mm line, a 5 mm radius half circle) and the hole were cut through 2.3 mm
    assert!(r.removed_volume_mm3 > 60.0, "{}", r.removed_volume_mm3);
    assert_eq!(RAPID_CLEARANCE, 5.0);
}

#[test]
fn the_checks_of_every_family_hold_for_ncc() {
    let o = xcam();
    // deeper than the drawn bottom: located at the element's own line
    let deep = GOOD.replace("X=10.000 Y=0.000 Z=-0.300", "X=10.000 Y=0.000 Z=-2.000");
    assert!(errors(&deep, &o).contains(&(Some(6), "below-bottom".into())));
    // an arc whose end is not on the circle of its start
    let arc = GOOD.replace("I=15.000 J=0.000", "I=14.000 J=0.000");
    assert!(errors(&arc, &o).contains(&(Some(7), "arc-radius-mismatch".into())));
    // no speed anywhere: the first cut has no feed
    let no_feed = GOOD
        .replace(" G1_SPEED=75.000", "")
        .replace(" G1_SPEED=150.000", "")
        .replace(" G5_SPEED=150.000", "")
        .replace(" GIN_DRIVE_SPEED=150.000", "");
    assert!(errors(&no_feed, &o).contains(&(Some(4), "no-feed".into())));
    // a clamp across the slot's line
    let clamped = Options {
        clamps: vec![Clamp {
            name: "vice".into(),
            min: [4.0, -3.0, -5.0],
            max: [6.0, 3.0, 5.0],
        }],
        ..xcam()
    };
    assert!(errors(GOOD, &clamped).contains(&(Some(6), "clamp-hit".into())));
    // a milling of a contour the file does not have, and a G1 outside a contour
    let unknown = GOOD.replace("GIN T=\"2.000\" N=\"P1\"", "GIN T=\"2.000\" N=\"P9\"");
    let found = verify(&unknown, &o).findings;
    assert!(found.iter().any(|f| f.line == Some(8)
        && f.kind == FindingKind::Ncc(NccProblem::UnknownContour("P9".into()))));
    // the contour is not milled now: the file ends with it pending
    assert!(found
        .iter()
        .any(|f| f.kind == FindingKind::Ncc(NccProblem::Incomplete)));
    // what the reader does not model is a warning at its line
    let corrected = GOOD.replace(" C=0 ", " C=1 ");
    let r = verify(&corrected, &o);
    assert!(r.findings.iter().any(|f| f.line == Some(8)
        && f.severity == Severity::Warning
        && f.code() == "unsupported"));
    // German
    let f = &verify(&unknown, &o).findings[0];
    assert!(
        f.message(millpath_verify::Lang::De).contains("Kontur"),
        "{f:?}"
    );
}

#[test]
fn every_truncation_is_found_or_whole() {
    let lines: Vec<&str> = GOOD.split_inclusive("\r\n").collect();
    for cut in 0..GOOD.len() {
        if !GOOD.is_char_boundary(cut) {
            continue;
        }
        let text = &GOOD[..cut];
        let r = verify(text, &xcam());
        // a file cut at the end of a line that leaves nothing pending is a whole file
        let whole_lines = lines
            .iter()
            .scan(0, |n, l| {
                *n += l.len();
                Some(*n)
            })
            .any(|n| n == cut);
        let pending = text.contains("N=\"P1\"") && !text.contains("GIN ");
        // a cut inside a line may leave a line that reads whole (`DZ=2.3` cut to `DZ=2`):
        // only a contour left without its milling, or nothing, is sure to be found
        let _ = whole_lines;
        if pending || cut == 0 {
            assert!(
                r.findings.iter().any(|f| f.severity == Severity::Error),
                "cut at {cut}: {text:?}"
            );
        }
        for f in &r.findings {
            if let Some(l) = f.line {
                assert!(l >= 1 && l <= lines.len(), "{f:?}");
            }
        }
    }
}

#[test]
fn hostile_files_give_findings_never_a_panic() {
    let mut rng = Rng(0x51CA_7E55_D00D_F00D);
    let alphabet: &[u8] = b"HGBINX=YZDJ\"0123456789.-+ _CONTU\r\n\te\xc3\xa4\x00";
    for _ in 0..600 {
        let len = rng.below(400);
        let bytes: Vec<u8> = (0..len)
            .map(|_| alphabet[rng.below(alphabet.len())])
            .collect();
        let text = String::from_utf8_lossy(&bytes);
        let r = verify(&text, &xcam());
        assert!(r
            .findings
            .iter()
            .all(|f| f.line.is_some_and(|l| l >= 1) || f.line.is_none()));
    }
    let good: Vec<String> = GOOD.split("\r\n").map(str::to_string).collect();
    let mut caught = 0;
    for round in 0..600 {
        let mut prog = good.clone();
        for _ in 0..1 + round % 3 {
            mutate(&mut prog, &mut rng, alphabet);
        }
        let text = prog.join("\r\n");
        let r = verify(&text, &xcam());
        if text != GOOD && r.findings.iter().any(|f| f.severity == Severity::Error) {
            caught += 1;
        }
    }
    assert!(caught > 300, "{caught} of 600 mutations caught");
    // one long contour milled again and again: bounded by MAX_REPLAYED
    let mut big = String::from("H DX=1.0 DY=1.0 DZ=1.0\r\nG0 X=0.0 Y=0.0 Z=0.0 N=\"A\"\r\n");
    for k in 0..2000 {
        big.push_str(&format!("G1 X={}.0 Y=0.0 Z=0.0 G1_SPEED=10.0\r\n", k % 2));
    }
    for _ in 0..510 {
        big.push_str("GIN T=\"1\" N=\"A\"\r\n");
    }
    let r = verify(&big, &xcam());
    assert!(
        r.moves <= millpath_verify::MAX_REPLAYED + 20_000,
        "{}",
        r.moves
    );
}
