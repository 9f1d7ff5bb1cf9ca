//! The editor honours `input = "extended"` in millpath.toml: the same analysis as `check`.

use millpath_core::{Msg, Severity};
use millpath_ide::{analyze, Workspace};

fn analysis(toml: &str) -> Vec<millpath_core::Diagnostic> {
    let dir = tempfile::tempdir().unwrap();
    let cad = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../tests/extended/drawings/cad/7001.dxf"
    );
    std::fs::copy(cad, dir.path().join("7001.dxf")).unwrap();
    std::fs::write(dir.path().join("millpath.toml"), toml).unwrap();
    let ws = Workspace {
        roots: vec![dir.path().to_path_buf()],
        ..Workspace::default()
    };
    analyze(&ws, &dir.path().join("7001.dxf")).diagnostics
}

#[test]
fn the_toml_input_setting_decides_how_a_drawing_is_read() {
    let machine = "feed = 150\nsweep_speed = 500\nsweep_height = 15\n";
    let reference = analysis(machine);
    let ignored = reference
        .iter()
        .filter(|d| d.msg == Msg::IgnoredEntity)
        .count();
    assert_eq!(ignored, 5, "{reference:?}");
    assert!(reference.iter().any(|d| d.severity == Severity::Error));
    let extended = analysis(&format!("{machine}input = \"extended\"\n"));
    assert!(
        extended
            .iter()
            .all(|d| d.severity != Severity::Error && d.msg != Msg::IgnoredEntity),
        "{extended:?}"
    );
}
