//! The invariants every generated drawing must keep, as panics (a fuzzer's crash):
//! - the formatter's text of the drawing parses and converts to DXF (no syntax error);
//! - compiling it never panics, and every number of every written file is finite and sane;
//! - the DXF and the text compile to the same files, byte for byte (the file-name comment and
//!   the probing set's digest over it aside), or are refused with the same error codes;
//! - the independent checker (`millpath-verify`, with the options of the compiler's second
//!   opinion) finds no error in a written program.

use crate::gen::Case;
use millpath_core::diag::FileRef;
use millpath_core::load::names::{Patterns, DEFAULT_FILE_PATTERN, DEFAULT_PATH_PATTERN};
use millpath_core::stock::stock_of;
use millpath_core::{compile_file, Diagnostic, Dialect, MemFileSystem, Msg, Session, Severity};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// What one front-end made of a case.
struct Run {
    /// Written files: name and content, the file name masked.
    outputs: Vec<(String, String)>,
    /// Error codes, as a set (the two front-ends locate and word them differently).
    errors: BTreeSet<String>,
    diags: Vec<Diagnostic>,
}

/// Checks every invariant on one case.
pub fn check(case: &Case) {
    let texts: Vec<(String, String)> = case
        .files
        .iter()
        .map(|(stem, tree)| (stem.clone(), millpath_syntax::format(tree, "")))
        .collect();
    // compiled once per process, as the sessions do
    let patterns = Patterns::shared(DEFAULT_PATH_PATTERN, DEFAULT_FILE_PATTERN).expect("defaults");
    let mut text_fs = MemFileSystem::default();
    let mut dxf_fs = MemFileSystem::default();
    for (stem, text) in &texts {
        let name = format!("{stem}.mpath");
        let file = FileRef::new(PathBuf::from(&name));
        text_fs.add(&name, text.as_bytes().to_vec());
        match millpath_core::convert::text_to_dxf(text, &file, &patterns) {
            Ok(dxf) => dxf_fs.add(format!("{stem}.dxf"), dxf.into_bytes()),
            Err(refusal) => {
                // text2dxf refuses a text with errors (a letter given twice): compile must
                // refuse it for the same reasons
                let run = compile(&text_fs, &name, case);
                for d in &refusal {
                    assert!(
                        run.errors.contains(&d.msg.code()),
                        "text2dxf refuses with {d:?}, compile does not: {:?}\n{text}",
                        run.diags
                    );
                }
                return;
            }
        };
    }
    let top = &texts[0].0;
    let from_text = compile(&text_fs, &format!("{top}.mpath"), case);
    let from_dxf = compile(&dxf_fs, &format!("{top}.dxf"), case);
    let show = || {
        texts
            .iter()
            .map(|(s, t)| format!("# {s}\n{t}"))
            .collect::<String>()
    };
    assert_eq!(
        from_text.errors,
        from_dxf.errors,
        "the front-ends disagree on the errors\ntext: {:?}\ndxf: {:?}\n{}",
        from_text.diags,
        from_dxf.diags,
        show()
    );
    assert_eq!(
        from_text.outputs.len(),
        from_dxf.outputs.len(),
        "the front-ends write different files\ntext: {:?}\ndxf: {:?}\n{}",
        from_text.diags,
        from_dxf.diags,
        show()
    );
    for (t, d) in from_text.outputs.iter().zip(&from_dxf.outputs) {
        assert_eq!(t.0, d.0, "{}", show());
        if t.1 != d.1 {
            panic!(
                "{} differs between the front-ends\n{}\n--- text ---\n{}\n--- dxf ---\n{}",
                t.0,
                show(),
                t.1,
                d.1
            );
        }
    }
    for run in [&from_text, &from_dxf] {
        for (name, content) in &run.outputs {
            assert_sane(name, content);
        }
    }
    second_opinion(&text_fs, &format!("{top}.mpath"), case, &from_text, &show);
}

fn compile(fs: &MemFileSystem, input: &str, case: &Case) -> Run {
    let mut session = Session::new(case.settings.clone(), fs).expect("sane settings");
    let outcome = compile_file(&mut session, Path::new(input), "fuzz");
    let ext = if input.ends_with(".dxf") {
        ".dxf"
    } else {
        ".mpath"
    };
    let outputs = outcome
        .outputs
        .iter()
        .map(|o| (o.path.display().to_string(), mask(&o.content, ext)))
        .collect();
    let errors = session
        .diags
        .list
        .iter()
        .filter(|d| d.severity == Severity::Error)
        .map(|d| match d.msg {
            // "DXF file … contains no error-free path layer" is the text file's "File …"
            Msg::NoErrorFreePathInFile => Msg::NoErrorFreePath.code(),
            m => m.code(),
        })
        .collect();
    Run {
        outputs,
        errors,
        diags: session.diags.list,
    }
}

/// The file name is the one difference allowed: `X.mpath` against `X.dxf` in the comment, and
/// with it the probing set's digest, which covers that comment.
fn mask(content: &str, ext: &str) -> String {
    let s = content.replace(ext, ".input");
    match s.find(" set=") {
        Some(at) => {
            let end = s[at + 5..]
                .find(|c: char| !c.is_ascii_hexdigit())
                .map_or(s.len(), |e| at + 5 + e);
            format!("{}{}", &s[..at + 5], &s[end..])
        }
        None => s,
    }
}

/// Every number outside comments is finite and within ±1e7 (inputs are bounded by ±1e6, and
/// a height is a sum of a few of them: T + S).
fn assert_sane(name: &str, content: &str) {
    for line in content.lines() {
        let code = strip_comments(line);
        for word in code.split(|c: char| c.is_whitespace() || "[]=+*/<>,;".contains(c)) {
            let number = match word.chars().next() {
                Some(c) if c.is_ascii_alphabetic() => &word[1..],
                Some(_) => word,
                None => continue,
            };
            if let Ok(v) = number.parse::<f64>() {
                assert!(
                    v.is_finite() && v.abs() <= 1e7,
                    "{name}: number out of range in {line:?}"
                );
            }
        }
        let lower = code.to_ascii_lowercase();
        assert!(
            !lower.contains("nan") && !lower.contains("inf"),
            "{name}: {line:?}"
        );
    }
}

/// A G-code line without its `( … )` comments and what follows `;`.
fn strip_comments(line: &str) -> String {
    let mut out = String::new();
    let mut depth = 0usize;
    for c in line.chars() {
        match c {
            '(' => depth += 1,
            ')' => depth = depth.saturating_sub(1),
            ';' if depth == 0 => break,
            _ if depth == 0 => out.push(c),
            _ => {}
        }
    }
    out
}

/// The compiler reviews every program it writes with the independent checker: in `linuxcnc`
/// and `grbl` an error there refuses the write (so none may come); in the reference dialect
/// findings are warnings, so each is checked again here with the checker's own severity.
fn second_opinion(
    fs: &MemFileSystem,
    input: &str,
    case: &Case,
    run: &Run,
    show: &dyn Fn() -> String,
) {
    let opinions: Vec<&Diagnostic> = run
        .diags
        .iter()
        .filter(|d| d.msg == Msg::SecondOpinion)
        .collect();
    if opinions.is_empty() {
        return;
    }
    if case.settings.dialect != Dialect::Reference {
        let errors: Vec<_> = opinions
            .iter()
            .filter(|d| d.severity == Severity::Error)
            .collect();
        assert!(
            errors.is_empty(),
            "verify finds errors: {errors:?}\n{}",
            show()
        );
        return;
    }
    // the program compile wrote (the clean one of a probing set)
    let Some((_, program)) = run
        .outputs
        .iter()
        .find(|(n, _)| n.ends_with("_Milling.gcode") || n.ends_with("_Clean.gcode"))
    else {
        return;
    };
    let mut session = Session::new(case.settings.clone(), fs).expect("sane settings");
    session.load_file(Path::new(input));
    let Ok(Some(model)) = session.build_top("1000.1P") else {
        return;
    };
    let (top, tool, bottom) = stock_of(&model);
    let report = millpath_verify::verify(
        &program.replace(".input", ".mpath"),
        &millpath_verify::Options {
            dialect: millpath_verify::Dialect::Reference,
            top: Some(top),
            tool: Some(tool),
            bottom,
            ..millpath_verify::Options::default()
        },
    );
    let errors: Vec<_> = report
        .findings
        .iter()
        .filter(|f| f.severity == millpath_verify::Severity::Error)
        .collect();
    assert!(
        errors.is_empty(),
        "verify finds errors: {errors:?}\n{}",
        show()
    );
}

/// The files the text front-end writes for a case and its error codes (the generator's
/// reach, for tests).
pub fn reach(case: &Case) -> (usize, BTreeSet<String>) {
    let mut fs = MemFileSystem::default();
    for (stem, tree) in &case.files {
        fs.add(
            format!("{stem}.mpath"),
            millpath_syntax::format(tree, "").into_bytes(),
        );
    }
    let run = compile(&fs, &format!("{}.mpath", case.files[0].0), case);
    (run.outputs.len(), run.errors)
}

/// The text front-end's diagnostics of a case and its files (for tuning the generator).
pub fn explain(case: &Case) -> String {
    let mut fs = MemFileSystem::default();
    let mut out = String::new();
    for (stem, tree) in &case.files {
        let text = millpath_syntax::format(tree, "");
        out.push_str(&format!("# {stem}\n{text}"));
        fs.add(format!("{stem}.mpath"), text.into_bytes());
    }
    let run = compile(&fs, &format!("{}.mpath", case.files[0].0), case);
    for d in &run.diags {
        out.push_str(&format!(
            "{} {}: {:?}\n",
            d.msg.code(),
            d.msg.name(),
            d.args
        ));
    }
    out
}
