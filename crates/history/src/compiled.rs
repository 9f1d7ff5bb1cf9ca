//! One version of a drawing compiled as the editor and `render` compile it: its canonical
//! text stands in memory at `DIR/STEM.mpath` beside the real file, so subpaths and
//! `millpath.toml` are found where the drawing is; per path the moves of the written program
//! (each with the element it comes from), the figures of the result, and the effective
//! parameters of elements with their origins.

use crate::version::Version;
use millpath_core::emit::Toolpath;
use millpath_core::Origin;
use millpath_ide::{Analysis, Effective, Workspace};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// A move as the diff compares it: kind, end points, arc centre and feed, rounded to the
/// output precision (3 decimals) as integers.
pub type MoveKey = (&'static str, [i64; 6], Option<(i64, i64, bool)>, i64);

/// The compiled result of one path.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Outcome {
    /// Why the path did not compile (the compiler's messages).
    pub error: Option<String>,
    /// The lowest Z of a cutting move.
    pub lowest_z: f64,
    /// The length of the cutting moves (mm).
    pub milling_length: f64,
    /// The estimated time (s).
    pub seconds: f64,
    /// Moves of the written program.
    pub moves: usize,
    /// The program's move lines (their G-code) in order, hashed: equal ⇔ same G-code moves.
    pub gcode_digest: u64,
    /// Every move in program order with its element's line in the canonical text (0: an
    /// element of another file, or none); the pictures draw them.
    pub sequence: Vec<(MoveKey, usize)>,
    /// Moves by the line of their element in the canonical text (1-based).
    pub by_line: HashMap<usize, Vec<MoveKey>, foldhash::fast::RandomState>,
    /// Moves from elements of other files (embedded subpaths), by their element's label
    /// (`2001.mpath:7`); moves without an element under "".
    pub elsewhere: std::collections::BTreeMap<String, Vec<MoveKey>>,
}

/// The command line's settings over each version's own.
#[derive(Debug, Clone, Default)]
pub struct Options {
    /// As an editor's settings over the version's `millpath.toml`.
    pub config: millpath_core::load::config::FileConfig,
    /// `--heightmap-step` and `--heightmap-margin` over the version's `[heightmap]`.
    pub heightmap: (Option<f64>, Option<f64>),
}

/// One version ready to compile.
pub struct Compiled {
    ws: Workspace,
    /// Where the canonical text stands (in memory).
    pub at: PathBuf,
    analysis: Option<Analysis>,
    /// The version's parsed text, for its analysis.
    tree: Option<std::sync::Arc<millpath_syntax::File>>,
}

impl Compiled {
    /// The version's text in memory at `DIR/STEM.mpath` for a drawing at `file`; `files`:
    /// the other files as the version's revision has them (instead of the disk).
    pub fn new(
        version: &Version,
        file: &Path,
        files: Option<std::sync::Arc<millpath_core::MemFileSystem>>,
    ) -> Compiled {
        let at = file.with_extension("mpath");
        let mut ws = Workspace {
            memory: files,
            // each path's toolpath builds and plans it (the analysis's own would be a second)
            paths_only: true,
            ..Workspace::default()
        };
        ws.overlays.insert(at.clone(), version.text.clone());
        Compiled {
            ws,
            at,
            analysis: None,
            tree: version.tree.clone(),
        }
    }

    /// Settings over the version's own `millpath.toml` (the command line's options, as an
    /// editor's settings): a relative post file is found from `options.config.base_dir`.
    pub fn set_options(&mut self, options: &Options) {
        self.ws.client = options.config.clone();
        self.ws.roots = vec![options.config.base_dir.clone()];
        self.ws.heightmap_options = options.heightmap;
        self.analysis = None;
    }

    /// The version's analysis, made once: the compiles of its paths and the effective
    /// values all read the text it parsed.
    fn analysis(&mut self) -> &Analysis {
        let (ws, at, tree) = (&self.ws, &self.at, &mut self.tree);
        self.analysis.get_or_insert_with(|| match tree.take() {
            // the tree is the version's text, which stands at `at`
            Some(t) => {
                let t = std::sync::Arc::try_unwrap(t).unwrap_or_else(|t| (*t).clone());
                millpath_ide::analyze_parsed(ws, at, t)
            }
            None => millpath_ide::analyze(ws, at),
        })
    }

    /// Compiles one path of the version (its moves and figures).
    pub fn outcome(&mut self, path: &str) -> Outcome {
        self.analysis();
        let a = self.analysis.as_ref().expect("analysed");
        match millpath_ide::toolpath_moves_of(&self.ws, a, path) {
            Ok(tp) => outcome_of(&tp, &self.at),
            Err(e) => Outcome {
                error: Some(e),
                ..Default::default()
            },
        }
    }

    /// The effective parameters of the elements at these offsets of the text.
    pub fn effective(&mut self, offsets: &[usize]) -> Vec<Vec<Effective>> {
        if offsets.is_empty() {
            return Vec::new();
        }
        millpath_ide::effective_values(self.analysis(), offsets)
    }
}

fn r3(v: f64) -> i64 {
    if v.is_finite() {
        (v * 1000.0).round() as i64
    } else {
        i64::MIN
    }
}

/// A coordinate to the output precision, as the toolpath page shows it (the figures are
/// summed from these).
fn shown(v: f64) -> f64 {
    let r = (v * 1000.0).round() / 1000.0;
    if r == 0.0 {
        0.0
    } else {
        r
    }
}

/// Where a move comes from: the element's line in our text (`Ok`, 1-based), or the label
/// of an element of another file (`Err`, `2001.mpath:7`).
fn source_of(o: &Origin, own: &Path) -> Result<usize, String> {
    let (file, line) = match o {
        Origin::Span { file, line, .. } => (Some(&file.path), *line as usize),
        Origin::Entity(e) => (Some(&e.file.path), e.line.max(1)),
        o => (o.file().map(|f| &f.path), 1),
    };
    if file.is_some_and(|f| f == own) {
        return Ok(line);
    }
    // the label only for an element of another file (most moves are the text's own)
    Err(match o {
        Origin::Span { file, line, .. } => format!("{}:{line}", file.name),
        Origin::Entity(e) => format!("{}:{}", e.file.name, e.line),
        o => o.context(),
    })
}

/// The figures and moves of a toolpath.
fn outcome_of(tp: &Toolpath, at: &Path) -> Outcome {
    use std::hash::{BuildHasher, Hash, Hasher};
    let mut out = Outcome {
        lowest_z: f64::INFINITY,
        moves: tp.moves.len(),
        seconds: shown(tp.stats.seconds()),
        ..Default::default()
    };
    // one fixed seed: the digests of both versions compare (a fast hasher: one line a move)
    let mut hasher = foldhash::fast::FixedState::with_seed(0x6d69_6c6c).build_hasher();
    out.sequence.reserve_exact(tp.moves.len());
    for m in &tp.moves {
        let (from, to) = (
            [shown(m.from.x), shown(m.from.y), shown(m.from.z)],
            [shown(m.to.x), shown(m.to.y), shown(m.to.z)],
        );
        let arc = m.arc.map(|(c, ccw)| (shown(c.x), shown(c.y), ccw));
        if m.kind != "rapid" {
            out.lowest_z = out.lowest_z.min(from[2]).min(to[2]);
            out.milling_length += length(from, to, arc);
        }
        m.gcode.hash(&mut hasher);
        let key: MoveKey = (
            m.kind,
            [
                r3(from[0]),
                r3(from[1]),
                r3(from[2]),
                r3(to[0]),
                r3(to[1]),
                r3(to[2]),
            ],
            arc.map(|(x, y, ccw)| (r3(x), r3(y), ccw)),
            r3(shown(m.feed)),
        );
        let source = m.source.as_ref().map(|o| source_of(o, at));
        out.sequence.push((
            key,
            match &source {
                Some(Ok(line)) => *line,
                _ => 0,
            },
        ));
        match source {
            Some(Ok(line)) => out.by_line.entry(line).or_default().push(key),
            Some(Err(label)) => out.elsewhere.entry(label).or_default().push(key),
            None => out.elsewhere.entry(String::new()).or_default().push(key),
        }
    }
    if !out.lowest_z.is_finite() {
        out.lowest_z = 0.0;
    }
    out.gcode_digest = hasher.finish();
    out
}

/// The length of a move: a straight line, or a helical arc around its centre.
fn length(from: [f64; 3], to: [f64; 3], arc: Option<(f64, f64, bool)>) -> f64 {
    let dz = to[2] - from[2];
    match arc {
        None => ((to[0] - from[0]).powi(2) + (to[1] - from[1]).powi(2) + dz * dz).sqrt(),
        Some((cx, cy, ccw)) => {
            let r = (from[0] - cx).hypot(from[1] - cy);
            let a0 = (from[1] - cy).atan2(from[0] - cx);
            let a1 = (to[1] - cy).atan2(to[0] - cx);
            let mut sweep = if ccw { a1 - a0 } else { a0 - a1 };
            if sweep <= 1e-12 {
                sweep += std::f64::consts::TAU;
            }
            (r * sweep).hypot(dz)
        }
    }
}
