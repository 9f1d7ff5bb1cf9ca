//! A height map as a setting (issue 21): the editor's quick check refuses what compile
//! refuses, and settings errors are located at the millpath.toml that holds `[heightmap]`.

mod support;

use millpath_core::diag::Msg;
use millpath_core::probe::heightmap::Heightmap;
use millpath_core::{Dialect, Origin, Session, Settings};
use support::*;

const PROBED: &str = "path 1000.1P {
  start (0, 0)  O2 T3 I1,2 B-0,3
  end (20, 0)
  mill (0, 0) -> (20, 0)
  probe (10, 5)
}
";

fn with_map(check: bool, quick: bool) -> Settings {
    Settings {
        dialect: Dialect::LinuxCnc,
        heightmap: Some(Heightmap::with_step(5.0)),
        check,
        quick_check: quick,
        ..settings()
    }
}

#[test]
fn drawn_probes_with_a_height_map_are_refused_by_compile_check_and_the_editor() {
    for (check, quick) in [(false, false), (true, false), (true, true)] {
        let run = compile_with(
            &[("1000.1P.mpath", PROBED.into())],
            "1000.1P.mpath",
            with_map(check, quick),
        );
        assert_eq!(
            run.errors(),
            [Msg::HeightmapWithDrawnProbes],
            "check {check} quick {quick}: {:?}",
            run.messages()
        );
        assert!(run.outputs.is_empty());
    }
    // without the probe the same drawing compiles to a grid set: 5 × 1 points along the line
    let plain = PROBED.replace("  probe (10, 5)\n", "");
    let run = compile_with(
        &[("1000.1P.mpath", plain)],
        "1000.1P.mpath",
        with_map(false, false),
    );
    assert!(run.errors().is_empty(), "{:?}", run.messages());
    let z = run.output("_Z.txt");
    assert_eq!(z.lines().count(), 5, "{z}");
    assert!(z.starts_with("([0.000 0.000]/T=3.000) #1000=\n"), "{z}");
    assert!(z.ends_with("([20.000 0.000]/T=3.000) #1004=\n"), "{z}");
}

#[test]
fn settings_errors_are_located_at_the_settings_file() {
    let fs = millpath_core::MemFileSystem::default();
    let toml = std::path::PathBuf::from("shop/millpath.toml");
    let s = Settings {
        heightmap: Some(Heightmap {
            margin: -1.0,
            ..Heightmap::with_step(0.0)
        }),
        heightmap_file: Some(toml.clone()),
        ..with_map(false, false)
    };
    let errors = Session::new(s.clone(), &fs).err().expect("refused");
    let msgs: Vec<Msg> = errors.iter().map(|d| d.msg).collect();
    assert_eq!(msgs, [Msg::HeightmapStepTooSmall, Msg::HeightmapNegative]);
    for d in &errors {
        assert!(
            matches!(&d.origin, Origin::File(f) if f.path == toml),
            "{:?}",
            d.origin
        );
    }
    // a step from the command line is named and located as the option
    let cli = Settings {
        heightmap_options: (true, false),
        ..s.clone()
    };
    let errors = Session::new(cli, &fs).err().expect("refused");
    assert_eq!(errors[0].origin, Origin::Options);
    assert!(errors[0]
        .message(millpath_core::Lang::En)
        .starts_with("--heightmap-step=0 mm"));
    assert!(matches!(&errors[1].origin, Origin::File(_)));
    // the reference dialect refuses a height map, at the file
    let reference = Settings {
        dialect: Dialect::Reference,
        heightmap: Some(Heightmap::with_step(5.0)),
        ..s
    };
    let errors = Session::new(reference, &fs).err().expect("refused");
    assert_eq!(errors[0].msg, Msg::HeightmapReferenceDialect);
    assert!(matches!(&errors[0].origin, Origin::File(_)));
}
