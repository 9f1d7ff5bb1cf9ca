//! A height map said in the drawing (issue 21): `K<step>` or `K<step>+<margin>` in the path
//! start text, the same token in `.mpath` and DXF. The drawing's K over millpath.toml's
//! `[heightmap]`, the options over both; only the compiled path's K counts; the reference
//! dialect reports K as PathDxf2GCode does (unsupported) with a hint; a bad K is an error at
//! the start text.

mod support;

use millpath_core::diag::Msg;
use millpath_core::probe::heightmap::Heightmap;
use millpath_core::{Dialect, Lang, Origin, Settings};
use support::*;

fn drawing(k: &str) -> String {
    format!(
        "path 1000.1P {{
  start (0, 0)  O2 T3 I1,2 B-0,3 {k}
  end (20, 0)
  mill (0, 0) -> (20, 0)
}}
"
    )
}

fn linuxcnc() -> Settings {
    Settings {
        dialect: Dialect::LinuxCnc,
        ..settings()
    }
}

fn run(text: &str, s: Settings) -> Run {
    compile_with(&[("1000.1P.mpath", text.into())], "1000.1P.mpath", s)
}

/// The `(MILLPATH-HEIGHTMAP …)` line of the probing program.
fn grid_line(r: &Run) -> String {
    assert!(r.errors().is_empty(), "{:?}", r.messages());
    r.output("_Probing.gcode")
        .lines()
        .find(|l| l.starts_with("(MILLPATH-HEIGHTMAP "))
        .expect("a height map's probing program")
        .to_string()
}

#[test]
fn k_in_the_drawing_makes_the_height_map_set() {
    let r = run(&drawing("K10"), linuxcnc());
    assert_eq!(
        grid_line(&r),
        "(MILLPATH-HEIGHTMAP X0=0.000 Y0=0.000 X1=20.000 Y1=0.000 NX=3 NY=1 STEP=10.000)"
    );
    let z = r.output("_Z.txt");
    assert_eq!(z.lines().count(), 3, "{z}");
    assert!(z.starts_with("([0.000 0.000]/T=3.000) #1000=\n"), "{z}");
    // a margin, with a decimal comma
    let r = run(
        &drawing("K2,5+1,5"),
        Settings {
            dialect: Dialect::Grbl,
            ..settings()
        },
    );
    assert_eq!(
        grid_line(&r),
        "(MILLPATH-HEIGHTMAP X0=-1.500 Y0=-1.500 X1=21.500 Y1=1.500 NX=11 NY=3 STEP=2.500)"
    );
    // without K the same drawing has no probing set
    let r = run(&drawing(""), linuxcnc());
    assert!(r.errors().is_empty(), "{:?}", r.messages());
    assert_eq!(r.outputs.len(), 1);
    assert!(r.output("_Milling.gcode").contains("G01"));
}

#[test]
fn the_drawing_over_millpath_toml_and_the_options_over_both() {
    let toml = |step: f64, margin: f64| Settings {
        heightmap: Some(Heightmap {
            margin,
            ..Heightmap::with_step(step)
        }),
        ..linuxcnc()
    };
    // K's step wins over the file's; K without a margin keeps the file's margin
    let r = run(&drawing("K10"), toml(5.0, 2.0));
    assert!(
        grid_line(&r).ends_with("X0=-2.000 Y0=-2.000 X1=22.000 Y1=2.000 NX=4 NY=2 STEP=10.000)")
    );
    // K's margin wins over the file's
    let r = run(&drawing("K10+0"), toml(5.0, 2.0));
    assert!(grid_line(&r).ends_with("X1=20.000 Y1=0.000 NX=3 NY=1 STEP=10.000)"));
    // --heightmap-step and --heightmap-margin win over K
    let options = Settings {
        heightmap_options: (true, true),
        ..toml(4.0, 1.0)
    };
    let r = run(&drawing("K10+0"), options);
    assert!(grid_line(&r).ends_with("X0=-1.000 Y0=-1.000 X1=21.000 Y1=1.000 NX=7 NY=2 STEP=4.000)"));
}

#[test]
fn the_reference_dialect_reports_k_as_the_reference_does() {
    for lang in [Lang::En, Lang::De] {
        let r = run(&drawing("K10"), Settings { lang, ..settings() });
        assert_eq!(r.errors(), [Msg::Unsupported], "{:?}", r.messages());
        assert!(r.outputs.is_empty());
        let hint = &r.diags[0].related[0].note;
        let want = match lang {
            Lang::En => "K (a height map) needs the linuxcnc or grbl dialect",
            Lang::De => "K (eine Höhenkarte) braucht den Dialekt linuxcnc oder grbl",
        };
        assert_eq!(hint, want);
    }
}

#[test]
fn a_bad_k_is_an_error_at_the_start_text() {
    for k in ["K0,2", "Kabc", "K10+-1", "K10+", "K+2", "Knan", "K1e300"] {
        let r = run(&drawing(k), linuxcnc());
        assert!(
            r.errors().contains(&Msg::HeightmapKeyBad),
            "{k}: {:?}",
            r.messages()
        );
        let d = r
            .diags
            .iter()
            .find(|d| d.msg == Msg::HeightmapKeyBad)
            .unwrap();
        assert!(
            matches!(d.origin, Origin::Span { line: 2, .. }),
            "{k}: {:?}",
            d.origin
        );
        assert!(r.outputs.is_empty(), "{k}");
    }
    let r = run(&drawing("K0,2"), linuxcnc());
    assert_eq!(
        r.messages()[0],
        "K0,2 is no height map: write K<step> or K<step>+<margin> in mm (e.g. K10+2), step at least 0.5 mm, margin at least 0"
    );
}

#[test]
fn only_the_compiled_paths_k_counts_and_drawn_probes_are_refused_beside_it() {
    // a part with K, embedded in a project without: the project has no height map
    let part = "path 2001.1P {
  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2 K5
  end (30, 0)
  mill (0, 0) -> (30, 0)
}
"
    .to_string();
    let project = "path 2011.1P {
  start (0, 0)  M10x3 O2 T3
  end (50, 0)
  sweep (0, 0) -> (10, 0)
  sub (10, 0) -> (40, 0)  >2001.1P
  sweep (40, 0) -> (50, 0)
}
"
    .to_string();
    let r = compile_with(
        &[("2001.mpath", part.clone()), ("2011.mpath", project)],
        "2011.mpath",
        linuxcnc(),
    );
    assert!(r.errors().is_empty(), "{:?}", r.messages());
    assert_eq!(r.outputs.len(), 1, "a milling program only");
    // compiled alone, the part has its map
    let r = compile_with(&[("2001.mpath", part)], "2001.mpath", linuxcnc());
    assert!(grid_line(&r).ends_with("STEP=5.000)"));
    // drawn probes and a K: refused as with millpath.toml's [heightmap]
    let probed = drawing("K10").replace("  mill", "  probe (10, 5)\n  mill");
    let r = run(&probed, linuxcnc());
    assert_eq!(
        r.errors(),
        [Msg::HeightmapKWithDrawnProbes],
        "{:?}",
        r.messages()
    );
}
