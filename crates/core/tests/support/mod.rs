//! Builds small path drawings as DXF text and compiles them in memory.
#![allow(clippy::too_many_arguments)]
#![allow(dead_code)]

use millpath_core::diag::{Diagnostic, Lang, Msg, Severity};
use millpath_core::{compile_file, MemFileSystem, OutputFile, Session, Settings};
use millpath_dxf::writer::DxfWriter;
use std::path::{Path, PathBuf};

pub mod gcode;
pub mod grbl;

pub type Pt = (f64, f64);

/// A drawing with one or more path layers.
pub struct Drawing {
    pub w: DxfWriter,
}

impl Default for Drawing {
    fn default() -> Self {
        Drawing {
            w: DxfWriter::new(),
        }
    }
}

fn mid(a: Pt, b: Pt) -> Pt {
    ((a.0 + b.0) / 2.0, (a.1 + b.1) / 2.0)
}

impl Drawing {
    pub fn new() -> Self {
        Self::default()
    }
    /// Start marker with its parameter text (tokens separated by spaces, one MTEXT line each).
    pub fn start(&mut self, layer: &str, at: Pt, text: &str) -> &mut Self {
        self.w.circle(layer, Some("PHANTOM"), at, 0.5);
        if !text.is_empty() {
            let lines: Vec<&str> = text.split(' ').collect();
            self.w.mtext(layer, at, 0.5, &lines);
        }
        self
    }
    pub fn end(&mut self, layer: &str, at: Pt) -> &mut Self {
        self.w.circle(layer, Some("PHANTOM"), at, 1.0);
        self
    }
    /// A line of the given line type with an optional text on its middle.
    pub fn line(&mut self, layer: &str, lt: &str, a: Pt, b: Pt, text: &str) -> &mut Self {
        self.w.line(layer, Some(lt), a, b);
        if !text.is_empty() {
            self.w.text(layer, mid(a, b), 0.5, text);
        }
        self
    }
    pub fn arc(
        &mut self,
        layer: &str,
        lt: &str,
        c: Pt,
        r: f64,
        a0: f64,
        a1: f64,
        text: &str,
    ) -> &mut Self {
        self.w.arc(layer, Some(lt), c, r, a0, a1);
        if !text.is_empty() {
            let m = ((a0 + a1) / 2.0).to_radians();
            self.w
                .text(layer, (c.0 + r * m.cos(), c.1 + r * m.sin()), 0.5, text);
        }
        self
    }
    pub fn circle(&mut self, layer: &str, lt: &str, c: Pt, r: f64, text: &str) -> &mut Self {
        self.w.circle(layer, Some(lt), c, r);
        if !text.is_empty() {
            self.w.text(layer, (c.0 + r, c.1), 0.5, text);
        }
        self
    }
    pub fn dxf(&self) -> String {
        self.w.finish()
    }
}

pub fn settings() -> Settings {
    Settings {
        feed: 150.0,
        sweep_speed: 500.0,
        sweep_height: 15.0,
        ..Settings::default()
    }
}

pub struct Run {
    pub outputs: Vec<OutputFile>,
    pub diags: Vec<Diagnostic>,
}

impl Run {
    pub fn errors(&self) -> Vec<Msg> {
        self.diags
            .iter()
            .filter(|d| d.severity == Severity::Error)
            .map(|d| d.msg)
            .collect()
    }
    pub fn warnings(&self) -> Vec<Msg> {
        self.diags
            .iter()
            .filter(|d| d.severity == Severity::Warning)
            .map(|d| d.msg)
            .collect()
    }
    pub fn messages(&self) -> Vec<String> {
        self.diags.iter().map(|d| d.message(Lang::En)).collect()
    }
    pub fn output(&self, suffix: &str) -> &str {
        &self
            .outputs
            .iter()
            .find(|o| o.path.to_string_lossy().ends_with(suffix))
            .unwrap_or_else(|| {
                panic!(
                    "no {suffix} among {:?}; diags {:?}",
                    self.outputs.iter().map(|o| &o.path).collect::<Vec<_>>(),
                    self.messages()
                )
            })
            .content
    }
    /// The G-code body between the `Model` comment and the statistics.
    pub fn body(&self) -> Vec<String> {
        let g = self.output("_Milling.gcode");
        let lines: Vec<&str> = g.lines().collect();
        let from = lines
            .iter()
            .position(|l| l.contains("(Model "))
            .expect("model line")
            + 1;
        let to = lines
            .iter()
            .rposition(|l| l.starts_with("G00 Z"))
            .expect("final z")
            + 1;
        lines[from..to].iter().map(|s| s.to_string()).collect()
    }
    /// Only the motion lines of the body (no comments).
    pub fn moves(&self) -> Vec<String> {
        self.body()
            .into_iter()
            .filter(|l| !l.trim_start().starts_with('(') && !l.starts_with(';'))
            .collect()
    }
}

/// Compiles `top` among `files` (name → DXF text) with the given settings.
pub fn compile_with(files: &[(&str, String)], top: &str, settings: Settings) -> Run {
    let mut fs = MemFileSystem::default();
    for (name, text) in files {
        fs.add(*name, text.clone().into_bytes());
    }
    let mut session = Session::new(settings, &fs).expect("settings");
    let outcome = compile_file(&mut session, Path::new(top), "millpath test");
    Run {
        outputs: outcome.outputs,
        diags: session.diags.list,
    }
}

pub fn compile(files: &[(&str, String)], top: &str) -> Run {
    compile_with(files, top, settings())
}

/// Compiles a single drawing.
pub fn compile_one(d: &Drawing) -> Run {
    compile(&[("1000.1P.dxf", d.dxf())], "1000.1P.dxf")
}

pub const L: &str = "1000_1P";

/// The repository's root.
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The files of `dir` with one of the extensions `ext` (any case), sorted; none when the
/// folder is not there.
pub fn files_in(dir: &Path, ext: &[&str]) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|r| r.map(|e| e.unwrap().path()).collect())
        .unwrap_or_default();
    v.retain(|p| {
        p.extension()
            .is_some_and(|e| ext.iter().any(|x| e.eq_ignore_ascii_case(x)))
    });
    v.sort();
    v
}
