//! Texts copied into G-code comments (file names, path names, `Q` texts) are safe for each
//! dialect's comment rules, and a changed text is reported (`Msg::CommentTextChanged`), by `check` as by `compile`.

mod common;

use common::millpath;
use millpath_core::diag::Msg;
use std::path::Path;

const MACHINE: [&str; 6] = [
    "--feed",
    "60",
    "--sweep-speed",
    "500",
    "--sweep-height",
    "10",
];

fn plate_as(dir: &Path, name: &str) {
    let example = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/plate/1234.1P.dxf");
    std::fs::copy(example, dir.join(name)).unwrap();
}

/// A parenthesised comment of a line, `None` when the line has none.
fn comments(program: &str) -> Vec<&str> {
    program
        .lines()
        .filter_map(|l| {
            let open = l.find('(')?;
            let close = l[open..].find(')')? + open;
            Some(&l[open + 1..close])
        })
        .collect()
}

#[test]
fn file_name_with_parentheses_compiles_in_every_dialect() {
    let code = Msg::CommentTextChanged.code();
    for dialect in ["reference", "linuxcnc", "grbl"] {
        let dir = tempfile::tempdir().unwrap();
        plate_as(dir.path(), "Halter (v2).dxf");
        let mut args = vec!["compile", "--dialect", dialect];
        args.extend(MACHINE);
        args.push("Halter (v2).dxf");
        let o = millpath(dir.path(), &args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(o.status.success(), "{dialect}: {err}");
        // said once, with what is written instead
        assert_eq!(err.matches(&format!("warning[{code}]")).count(), 1, "{err}");
        assert!(err.contains("'Halter [v2].dxf'"), "{err}");
        let g = std::fs::read_to_string(dir.path().join("Halter (v2)_Milling.gcode")).unwrap();
        assert!(g.contains("\n(Halter [v2].dxf)\n"), "{dialect}: {g}");
        for c in comments(&g) {
            assert!(!c.contains('('), "{dialect}: nested comment ({c})");
        }
        // the independent checker finds nothing to say about the comments
        let v = millpath(
            dir.path(),
            &[
                "verify",
                "--dialect",
                dialect,
                "--top",
                "3",
                "--tool",
                "2",
                "Halter (v2)_Milling.gcode",
            ],
        );
        let out = String::from_utf8_lossy(&v.stdout);
        assert!(v.status.success(), "{dialect}: {out}");
        assert!(!out.contains("inside a comment"), "{dialect}: {out}");

        // check says the same as compile
        let mut args = vec!["check", "--dialect", dialect];
        args.extend(MACHINE);
        args.push("Halter (v2).dxf");
        let c = millpath(dir.path(), &args);
        let all = format!(
            "{}{}",
            String::from_utf8_lossy(&c.stdout),
            String::from_utf8_lossy(&c.stderr)
        );
        assert!(c.status.success(), "{all}");
        assert_eq!(all.matches(&format!("warning[{code}]")).count(), 1, "{all}");
    }
}

#[test]
fn grbl_gets_no_realtime_characters_and_linuxcnc_no_active_comments() {
    let dir = tempfile::tempdir().unwrap();
    plate_as(dir.path(), "Größe!.dxf");
    plate_as(dir.path(), "MSG,Teil.dxf");
    let run = |dialect: &str, file: &str| {
        let mut args = vec!["compile", "--dialect", dialect];
        args.extend(MACHINE);
        args.push(file);
        let o = millpath(dir.path(), &args);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        String::from_utf8_lossy(&o.stderr).into_owned()
    };
    let err = run("grbl", "Größe!.dxf");
    assert!(err.contains("'Groesse_.dxf'"), "{err}");
    let g = std::fs::read_to_string(dir.path().join("Größe!_Milling.gcode")).unwrap();
    assert!(
        g.is_ascii(),
        "GRBL reads bytes from 0x80 as real-time commands"
    );
    assert!(!g.contains(['!', '~', '?']));
    assert!(g.lines().all(|l| l.len() <= 127));

    let err = run("linuxcnc", "MSG,Teil.dxf");
    assert!(err.contains("'_MSG,Teil.dxf'"), "{err}");
    let g = std::fs::read_to_string(dir.path().join("MSG,Teil_Milling.gcode")).unwrap();
    assert!(g.contains("\n(_MSG,Teil.dxf)\n"), "{g}");

    // the reference dialect keeps what the reference writes for these
    let err = run("reference", "Größe!.dxf");
    assert!(!err.contains("warning["), "{err}");
    let g = std::fs::read_to_string(dir.path().join("Größe!_Milling.gcode")).unwrap();
    assert!(g.contains("\n(Größe!.dxf)\n"));
}
