//! A compilation session: settings, loading files through a [`FileSystem`], the path caches,
//! subpath search and building models (reference-input.md §3–§6, §7.5).

use crate::args;
use crate::diag::{Diagnostic, Diags, FileRef, Lang, Msg, Origin};
use crate::drawing::{
    RawPath, RawSegment, SegKind, Shape, Style, SweepKind, CHAIN_KEYS, PATH_KEYS, PROBE_KEYS,
};
use crate::dxf_front::{dxf_to_drawing, FrontOptions};
use crate::geom::{absnear, f3, ge, gt, le, near, Geom, Transform, P2};
use crate::model::*;
use crate::names::Patterns;
use crate::params::{check_values, fmt_num, parse_definition, parse_number, ParamText, Vars};
use crate::parse_cache::{self, FileStamp, ParseKey, ParsedFile};
use crate::regex_cache::regex;
use regex::Regex;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// `*.mpath`: the text language.
pub fn is_text_file(p: &Path) -> bool {
    p.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("mpath"))
}

/// File access, so that editors can serve unsaved buffers and tests can use memory.
pub trait FileSystem {
    fn read(&self, path: &Path) -> std::io::Result<Vec<u8>>;
    /// The files of a directory (any order).
    fn list_dir(&self, dir: &Path) -> std::io::Result<Vec<PathBuf>>;
    fn is_dir(&self, dir: &Path) -> bool;
    /// What identifies the current version of a file, so that its parse can be reused;
    /// `None` (the default) parses it again every time.
    fn stamp(&self, _path: &Path) -> Option<FileStamp> {
        None
    }
}

/// The real file system.
pub struct OsFileSystem;

impl FileSystem for OsFileSystem {
    fn read(&self, path: &Path) -> std::io::Result<Vec<u8>> {
        std::fs::read(path)
    }
    fn list_dir(&self, dir: &Path) -> std::io::Result<Vec<PathBuf>> {
        let mut v = Vec::new();
        for e in std::fs::read_dir(dir)? {
            let e = e?;
            if e.file_type().map(|t| t.is_file()).unwrap_or(false) {
                v.push(e.path());
            }
        }
        Ok(v)
    }
    fn is_dir(&self, dir: &Path) -> bool {
        dir.is_dir()
    }
    fn stamp(&self, path: &Path) -> Option<FileStamp> {
        FileStamp::of_disk_file(path)
    }
}

/// Machine settings and options of a run.
#[derive(Debug, Clone)]
pub struct Settings {
    /// `/f`: default feed (mm/min).
    pub feed: f64,
    /// `/v`: sweep speed (mm/min), statistics only.
    pub sweep_speed: f64,
    /// `/s`: sweep height of the top-level path.
    pub sweep_height: f64,
    /// `/z`: probe feed; `None` or ≤ 0 means `/f`.
    pub probe_feed: Option<f64>,
    /// `/c`: check every path, write nothing.
    pub check: bool,
    /// `/d`: further search directories, in order.
    pub search_dirs: Vec<PathBuf>,
    pub path_pattern: String,
    pub file_pattern: String,
    /// `/e parent:child` restrictions, in order.
    pub restrictions: Vec<(String, String)>,
    /// `/x`: debug output of text assignments.
    pub debug_pattern: Option<String>,
    pub lang: Lang,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            feed: 150.0,
            sweep_speed: 500.0,
            sweep_height: 15.0,
            probe_feed: None,
            check: false,
            search_dirs: Vec::new(),
            path_pattern: crate::names::DEFAULT_PATH_PATTERN.into(),
            file_pattern: crate::names::DEFAULT_FILE_PATTERN.into(),
            restrictions: Vec::new(),
            debug_pattern: None,
            lang: Lang::En,
        }
    }
}

impl Settings {
    pub fn probe_feed(&self) -> f64 {
        match self.probe_feed {
            Some(z) if z > 0.0 => z,
            _ => self.feed,
        }
    }
}

/// An error that aborts the current top-level file.
pub type Abort = Diagnostic;

pub struct Session<'a> {
    pub settings: Settings,
    pub patterns: Arc<Patterns>,
    restrictions: Vec<(Arc<Regex>, Arc<Regex>)>,
    debug: Option<Arc<Regex>>,
    fs: &'a dyn FileSystem,
    pub diags: Diags,
    /// Progress lines (`---- Reading …`), in order.
    pub info: Vec<String>,
    raw: HashMap<String, Arc<RawPath>>,
    loaded: HashMap<PathBuf, Vec<String>>,
    models: HashMap<(String, Vars), Option<Arc<Model>>>,
}

struct BuildCtx {
    depth: usize,
    top: bool,
}

impl<'a> Session<'a> {
    /// Creates a session; invalid patterns and restrictions are reported as option errors.
    pub fn new(settings: Settings, fs: &'a dyn FileSystem) -> Result<Session<'a>, Vec<Diagnostic>> {
        let mut errors = Vec::new();
        let patterns = match Patterns::shared(&settings.path_pattern, &settings.file_pattern) {
            Ok(p) => Some(p),
            Err((c, p, e)) => {
                errors.push(Diagnostic::error(
                    Msg::BadRegex,
                    Origin::Options,
                    args![format!("/{c}"), p, e],
                ));
                None
            }
        };
        let mut restrictions = Vec::new();
        for (parent, child) in &settings.restrictions {
            match (regex(parent), regex(child)) {
                (Ok(a), Ok(b)) => restrictions.push((a, b)),
                (Err(e), _) | (_, Err(e)) => errors.push(Diagnostic::error(
                    Msg::EInvalid,
                    Origin::Options,
                    args![format!("{parent}:{child}"), e],
                )),
            }
        }
        let debug = match settings.debug_pattern.as_deref().map(regex) {
            None => None,
            Some(Ok(r)) => Some(r),
            Some(Err(e)) => {
                errors.push(Diagnostic::error(
                    Msg::BadRegex,
                    Origin::Options,
                    args!["/x", settings.debug_pattern.clone().unwrap_or_default(), e],
                ));
                None
            }
        };
        match patterns {
            Some(patterns) if errors.is_empty() => Ok(Session {
                settings,
                patterns,
                restrictions,
                debug,
                fs,
                diags: Diags::default(),
                info: Vec::new(),
                raw: HashMap::new(),
                loaded: HashMap::new(),
                models: HashMap::new(),
            }),
            _ => Err(errors),
        }
    }

    pub fn lang(&self) -> Lang {
        self.settings.lang
    }

    /// Loads a file (once) and registers its paths; returns their names in drawing order.
    pub fn load_file(&mut self, path: &Path) -> Vec<String> {
        if let Some(names) = self.loaded.get(path) {
            return names.clone();
        }
        self.loaded.insert(path.to_path_buf(), Vec::new());
        let parsed = match self.fs.stamp(path) {
            Some(stamp) => {
                let key = ParseKey {
                    path: path.to_path_buf(),
                    stamp,
                    path_pattern: self.settings.path_pattern.clone(),
                    debug_pattern: self.settings.debug_pattern.clone(),
                    lang: self.lang(),
                };
                parse_cache::parsed(key, || self.parse_file(path))
            }
            None => Arc::new(self.parse_file(path)),
        };
        for d in &parsed.diags {
            self.diags.push(d.clone());
        }
        self.info.extend(parsed.info.iter().cloned());
        match &parsed.result {
            Ok(paths) => self.register(path, paths.clone()),
            Err(d) => {
                self.diags.push(d.clone());
                Vec::new()
            }
        }
    }

    /// Registers the paths of a file read elsewhere (an editor's parsed buffer), as if
    /// `load_file` had read it; returns their names in drawing order.
    pub fn add_paths(&mut self, path: &Path, paths: Vec<RawPath>) -> Vec<String> {
        self.register(path, paths.into_iter().map(Arc::new).collect())
    }

    fn register(&mut self, path: &Path, paths: Vec<Arc<RawPath>>) -> Vec<String> {
        let mut names = Vec::new();
        for p in paths {
            names.push(p.name.clone());
            match self.raw.get(&p.name) {
                Some(existing) if existing.file.path != p.file.path => {
                    let d = Diagnostic::error(
                        Msg::AlreadyDefined,
                        p.start_origin(),
                        args![p.name, existing.file.path.display()],
                    )
                    .with_related(existing.start_origin(), "first definition");
                    self.diags.push(d);
                }
                Some(_) => {}
                None => {
                    self.raw.insert(p.name.clone(), p);
                }
            }
        }
        self.loaded.insert(path.to_path_buf(), names.clone());
        names
    }

    /// Reads and parses one file, with its own diagnostics and progress lines.
    fn parse_file(&self, path: &Path) -> ParsedFile {
        let mut diags = Diags::default();
        let mut info = Vec::new();
        let result = match self.fs.read(path) {
            Err(e) => Err(Diagnostic::error(
                Msg::CannotRead,
                Origin::Input,
                args![path.display(), e],
            )),
            Ok(bytes) => {
                let file = FileRef::new(path.to_path_buf());
                self.parse_drawing(&bytes, &file, &mut diags, &mut info)
                    .map(|d| d.paths.into_iter().map(Arc::new).collect())
            }
        };
        ParsedFile {
            result,
            diags: diags.list,
            info,
        }
    }

    fn parse_drawing(
        &self,
        bytes: &[u8],
        file: &Arc<FileRef>,
        diags: &mut Diags,
        info: &mut Vec<String>,
    ) -> Result<crate::drawing::DrawingFile, Diagnostic> {
        let verb = if self.lang() == Lang::De {
            "Einlesen von"
        } else {
            "Reading"
        };
        if is_text_file(&file.path) {
            info.push(format!("---- {verb} {}", file.path.display()));
            let src = String::from_utf8_lossy(bytes);
            let text = crate::text_front::text_objects(&src, file, diags)?;
            let objects = &text.objects;
            let paths = crate::drawing::build_paths(
                objects,
                file,
                &self.patterns.path_cs,
                &self.settings.path_pattern,
                diags,
            )?;
            text.check_declared_kinds(&paths, diags);
            for p in &paths {
                if !self.patterns.path_full.is_match(&p.name) {
                    diags.error(
                        Msg::PathNameNoMatch,
                        p.origin(),
                        args![p.name, self.settings.path_pattern],
                    );
                }
            }
            return Ok(crate::drawing::DrawingFile {
                paths,
                debug: Vec::new(),
                version: String::new(),
            });
        }
        let dxf = millpath_dxf::read_dxf(bytes).map_err(|e| {
            Diagnostic::error(
                Msg::CannotLoadDxf,
                Origin::File(file.clone()),
                args![file.path.display(), e],
            )
        })?;
        info.push(format!(
            "---- {verb} {} (DXF-Version: {})",
            file.path.display(),
            dxf.version
        ));
        let opts = FrontOptions {
            layer_pattern: &self.patterns.path_full,
            path_pattern: &self.patterns.path_cs,
            pattern_text: &self.settings.path_pattern,
            debug: self.debug.as_deref(),
        };
        let drawing = dxf_to_drawing(&dxf, file, &opts, diags)?;
        info.extend(drawing.debug.iter().cloned());
        Ok(drawing)
    }

    pub fn raw_path(&self, name: &str) -> Option<Arc<RawPath>> {
        self.raw.get(name).cloned()
    }

    /// Finds the files that may contain `name` and loads them; returns the matching files.
    fn search(&mut self, name: &str, near_file: &Path) -> Result<Vec<PathBuf>, Abort> {
        let mut dirs = vec![near_file
            .parent()
            .map(Path::to_path_buf)
            .unwrap_or_default()];
        dirs.extend(self.settings.search_dirs.iter().cloned());
        let mut matching = Vec::new();
        for dir in dirs {
            let dir_or_cwd = if dir.as_os_str().is_empty() {
                PathBuf::from(".")
            } else {
                dir.clone()
            };
            if !self.fs.is_dir(&dir_or_cwd) {
                return Err(Diagnostic::error(
                    Msg::SearchDirMissing,
                    Origin::Options,
                    args![dir_or_cwd.display()],
                ));
            }
            let mut files = self.fs.list_dir(&dir_or_cwd).unwrap_or_default();
            files.sort();
            for f in files {
                let is_drawing = f.extension().is_some_and(|e| e.eq_ignore_ascii_case("dxf"))
                    || is_text_file(&f);
                if !is_drawing {
                    continue;
                }
                let stem = f
                    .file_stem()
                    .map(|s| s.to_string_lossy().into_owned())
                    .unwrap_or_default();
                if self.patterns.file_contains(&stem, name) {
                    let f = if dir.as_os_str().is_empty() {
                        PathBuf::from(f.file_name().unwrap_or_default())
                    } else {
                        f
                    };
                    self.load_file(&f);
                    matching.push(f);
                }
            }
        }
        Ok(matching)
    }

    /// The raw path of a name, searching the folder of `near_file` and the search directories
    /// when it is not known yet (editors: hover and go-to-definition of subpath names).
    pub fn lookup(&mut self, name: &str, near_file: &Path) -> Option<Arc<RawPath>> {
        if !self.raw.contains_key(name) {
            let _ = self.search(name, near_file);
        }
        self.raw.get(name).cloned()
    }

    /// Builds (or fetches) the model of a top-level path.
    pub fn build_top(&mut self, name: &str) -> Result<Option<Arc<Model>>, Abort> {
        let vars = if self.settings.check {
            let defs = self
                .raw
                .get(name)
                .and_then(|r| r.start_text.as_ref().map(|t| t.vars.clone()))
                .unwrap_or_default();
            match check_values(&defs) {
                Ok(v) => v,
                Err((msg, a)) => {
                    let origin = self.raw.get(name).map_or(Origin::Input, |r| r.origin());
                    let inner = Diagnostic::error(msg, origin.clone(), a);
                    self.diags.error(
                        Msg::VariableDefinitionError,
                        origin,
                        args![inner.message(self.lang())],
                    );
                    Vars::default()
                }
            }
        } else {
            Vars::default()
        };
        self.build(
            name,
            &vars,
            &BuildCtx {
                depth: 0,
                top: true,
            },
        )
    }

    fn build(
        &mut self,
        name: &str,
        vars: &Vars,
        cx: &BuildCtx,
    ) -> Result<Option<Arc<Model>>, Abort> {
        let key = (name.to_string(), vars.clone());
        if let Some(m) = self.models.get(&key) {
            return Ok(m.clone());
        }
        let Some(raw) = self.raw.get(name).cloned() else {
            return Ok(None);
        };
        let model = self.build_model(raw, vars, cx)?;
        self.models.insert(key, model.clone());
        Ok(model)
    }

    fn build_model(
        &mut self,
        raw: Arc<RawPath>,
        vars: &Vars,
        cx: &BuildCtx,
    ) -> Result<Option<Arc<Model>>, Abort> {
        // 1. markers
        let (Some(start), Some(end)) = (raw.start.clone(), raw.end.clone()) else {
            if raw.start.is_none() {
                self.diags.error(Msg::StartMissing, raw.origin(), vec![]);
            }
            if raw.end.is_none() {
                self.diags.error(Msg::EndMissing, raw.origin(), vec![]);
            }
            return Ok(None);
        };
        // 2. traversal
        let trav = traverse(&raw, start.pos, end.pos, &mut self.diags);
        let ev = Eval { vars };
        self.check_self_references(&raw, vars);
        // 4. path parameters
        let params = self.path_params(&raw, &ev, cx);
        let path_text = raw.start_text.as_ref();
        if let Some(t) = path_text {
            self.check_text(t, PATH_KEYS, &raw.start_origin(), &ev);
        }
        self.validate(&raw.start_origin(), &params, path_text, &ev, true);

        // 3. chains and elements
        let mut elements = Vec::new();
        let mut chain: Option<Chain> = None;
        let mut subpaths = Vec::new();
        for step in &trav {
            let seg = &raw.segments[step.index];
            let geom = match &seg.shape {
                Shape::Path(g) => Some(if step.reversed { g.reversed() } else { *g }),
                Shape::Circle { .. } => None,
            };
            let kind = if step.turn_back {
                turn_back_kind(seg.kind)
            } else {
                seg.kind
            };
            if let (SegKind::Mill(style), Some(g)) = (kind, geom) {
                let first = chain.is_none();
                if first {
                    let (i, w) = self.chain_params(seg, &params, &ev);
                    chain = Some(Chain {
                        segs: Vec::new(),
                        i,
                        w,
                        origin: seg.origin.clone(),
                    });
                }
                let cs = self.chain_seg(seg, style, g, &params, &ev, first)?;
                if let Some(c) = chain.as_mut() {
                    c.segs.push(cs);
                }
                continue;
            }
            if let Some(c) = chain.take() {
                elements.push(Element::Chain(c));
            }
            let text = if step.turn_back {
                None
            } else {
                seg.text.as_ref()
            };
            match (kind, &seg.shape) {
                (SegKind::Drill(style), Shape::Circle { c, .. }) => {
                    if let Some(t) = text {
                        self.check_text(t, kind.allowed_keys(), &seg.origin, &ev);
                    }
                    elements.push(Element::Drill(Drill {
                        c: *c,
                        style,
                        f: ev.num(text, 'F').unwrap_or(params.f),
                        b: ev.num(text, 'B').or(params.b),
                        d: ev.num(text, 'D').or(params.d),
                        q: ev.string(text, 'Q'),
                        origin: seg.origin.clone(),
                    }));
                    self.validate_child(&seg.origin, text, &params, &ev);
                }
                (SegKind::Helix(style), Shape::Circle { c, r }) => {
                    if let Some(t) = text {
                        self.check_text(t, kind.allowed_keys(), &seg.origin, &ev);
                    }
                    if gt(2.0 * r, params.a) {
                        self.diags.error(
                            Msg::HelixTooLarge,
                            seg.origin.clone(),
                            args![f3(2.0 * r), fmt_num(params.a)],
                        );
                    }
                    let b = ev.num(text, 'B').or(params.b);
                    let d = ev.num(text, 'D').or(params.d);
                    let bars = if style == Style::Support {
                        let circle = Geom::Arc {
                            c: *c,
                            r: r - params.o / 2.0,
                            a0: 270.0,
                            a1: 270.0 * (1.0 + 1e-6),
                            ccw: false,
                        };
                        let p = ev.num(text, 'P').or(params.p);
                        let u = ev.num(text, 'U').or(params.u);
                        support_bars(&circle, params.o, p, u, b, d, &seg.origin)?
                    } else {
                        None
                    };
                    elements.push(Element::Helix(Helix {
                        c: *c,
                        r: *r,
                        style,
                        f: ev.num(text, 'F').unwrap_or(params.f),
                        b,
                        d,
                        i: ev.num(text, 'I').or(params.i),
                        q: ev.string(text, 'Q'),
                        bars,
                        origin: seg.origin.clone(),
                    }));
                    self.validate_child(&seg.origin, text, &params, &ev);
                }
                (SegKind::Sweep(sk), _) => {
                    let g = geom.unwrap_or(Geom::Line {
                        a: seg.shape.start(),
                        b: seg.shape.end(),
                    });
                    let text = if sk == SweepKind::Dashed { text } else { None };
                    if let Some(t) = text {
                        self.check_text(t, kind.allowed_keys(), &seg.origin, &ev);
                    }
                    let s = ev.num(text, 'S').unwrap_or(params.s);
                    if text.is_some_and(|t| t.has('S')) && le(s, params.t) {
                        self.diags.error(
                            Msg::SNotAboveT,
                            seg.origin.clone(),
                            args![fmt_num(s), fmt_num(params.t)],
                        );
                    }
                    elements.push(Element::Sweep(Sweep {
                        a: g.start(),
                        b: g.end(),
                        s,
                        bt: !step.turn_back && seg.backtrack(),
                        origin: seg.origin.clone(),
                    }));
                }
                (SegKind::Subpath, _) => {
                    let g = geom.unwrap_or(Geom::Line {
                        a: seg.shape.start(),
                        b: seg.shape.end(),
                    });
                    if let Some(t) = text {
                        self.check_text(t, kind.allowed_keys(), &seg.origin, &ev);
                    }
                    subpaths.push((elements.len(), step.index));
                    elements.push(Element::Subpath(Embedding {
                        a: g.start(),
                        b: g.end(),
                        h: ev.num(text, 'H').unwrap_or(0.0),
                        target: None,
                        origin: seg.origin.clone(),
                    }));
                }
                _ => {}
            }
        }
        if let Some(c) = chain.take() {
            elements.push(Element::Chain(c));
        }

        // probes
        let mut probes = Vec::new();
        for p in &raw.probes {
            let text = p.text.as_ref();
            if let Some(t) = text {
                self.check_text(t, PROBE_KEYS, &p.origin, &ev);
            }
            probes.push(Probe {
                center: p.center,
                t: ev.num(text, 'T').unwrap_or(params.t),
                h: ev.num(text, 'H').unwrap_or(0.0),
                l: ev.string(text, 'L'),
                z: ev.num(text, 'Z').unwrap_or(params.z),
                origin: p.origin.clone(),
            });
        }

        // 5. subpaths
        for (ei, si) in subpaths {
            let seg = &raw.segments[si];
            let target = self.connect(&raw, seg, &params, &ev, cx)?;
            if let Element::Subpath(emb) = &mut elements[ei] {
                if let Some(t) = &target {
                    let size = emb.a.dist(emb.b);
                    let tsize = t.start.dist(t.end);
                    if !absnear(size, tsize, 1e-3) {
                        let d = Diagnostic::error(
                            Msg::SizeMismatch,
                            emb.origin.clone(),
                            args![f3(size), t.label(), f3(tsize)],
                        )
                        .with_related(t.raw.start_origin(), "start of the referenced path");
                        self.diags.push(d);
                    } else if Transform::between(t.start, t.end, emb.a, emb.b).is_none() {
                        self.diags
                            .error(Msg::CannotPlace, emb.origin.clone(), args![t.label()]);
                    }
                }
                emb.target = target;
            }
        }

        Ok(Some(Arc::new(Model {
            raw: raw.clone(),
            vars: vars.clone(),
            start: start.pos,
            end: end.pos,
            params,
            elements,
            probes,
        })))
    }

    fn check_self_references(&mut self, raw: &RawPath, vars: &Vars) {
        for (name, value) in &vars.0 {
            if vars.interpolate(&format!("={name}")).is_err() {
                self.diags
                    .error(Msg::SelfReference, raw.start_origin(), args![name, value]);
            }
        }
    }

    fn path_params(&mut self, raw: &RawPath, ev: &Eval, cx: &BuildCtx) -> PathParams {
        let t_ = raw.start_text.as_ref();
        let missing = |key: &str, diags: &mut Diags| {
            diags.error(Msg::ValueMissing, raw.start_origin(), args![key]);
            f64::NAN
        };
        let t = match ev.num(t_, 'T') {
            Some(v) => v,
            None => missing("T", &mut self.diags),
        };
        let o = match ev.num(t_, 'O') {
            Some(v) => v,
            None => missing("O", &mut self.diags),
        };
        let s = ev
            .num(t_, 'S')
            .unwrap_or(if cx.top && !self.settings.check {
                self.settings.sweep_height
            } else {
                t + o
            });
        PathParams {
            f: ev.num(t_, 'F').unwrap_or(self.settings.feed),
            t,
            o,
            s,
            a: ev.num(t_, 'A').unwrap_or(4.0 * o),
            z: ev.num(t_, 'Z').unwrap_or(self.settings.probe_feed()),
            v: self.settings.sweep_speed,
            b: ev.num(t_, 'B'),
            d: ev.num(t_, 'D'),
            i: ev.num(t_, 'I'),
            w: ev.num(t_, 'W'),
            p: ev.num(t_, 'P'),
            u: ev.num(t_, 'U'),
            c: ev.num(t_, 'C').map(|c| c.trunc() as i64),
            m: ev.string(t_, 'M'),
            e: ev.string(t_, 'E'),
            r: ev.string(t_, 'R').unwrap_or_default(),
        }
    }

    fn chain_params(
        &mut self,
        first: &RawSegment,
        params: &PathParams,
        ev: &Eval,
    ) -> (Option<f64>, Option<f64>) {
        let text = first.text.as_ref();
        if let Some(t) = text {
            for (k, _) in &t.params {
                if !CHAIN_KEYS.contains(*k) {
                    self.diags.error(
                        Msg::Unsupported,
                        first.origin.clone(),
                        args![k, text_context(t)],
                    );
                }
            }
        }
        let i = ev.num(text, 'I').or(params.i);
        let w = ev.num(text, 'W').or(params.w);
        if text.is_some_and(|t| t.has('I')) && i.is_some_and(|i| le(i, 0.0)) {
            self.diags.error(
                Msg::MustBePositive,
                first.origin.clone(),
                args!["I", fmt_num(i.unwrap_or(0.0))],
            );
        }
        if text.is_some_and(|t| t.has('W')) && w.is_some_and(|w| le(w, 0.0)) {
            self.diags.error(
                Msg::MustBePositive,
                first.origin.clone(),
                args!["W", fmt_num(w.unwrap_or(0.0))],
            );
        }
        if let Some(c) = ev.num(text, 'C') {
            if c.trunc() <= 0.0 {
                self.diags.error(
                    Msg::MustBePositive,
                    first.origin.clone(),
                    args!["C", fmt_num(c.trunc())],
                );
            }
        }
        (i, w)
    }

    fn chain_seg(
        &mut self,
        seg: &RawSegment,
        style: Style,
        geom: Geom,
        params: &PathParams,
        ev: &Eval,
        _first: bool,
    ) -> Result<ChainSeg, Abort> {
        let text = seg.text.as_ref();
        if let Some(t) = text {
            self.check_text(t, seg.kind.allowed_keys(), &seg.origin, ev);
            if t.has('S') {
                let s = ev.num(text, 'S').unwrap_or(params.s);
                if le(s, params.t) {
                    self.diags.error(
                        Msg::SNotAboveT,
                        seg.origin.clone(),
                        args![fmt_num(s), fmt_num(params.t)],
                    );
                }
            }
        }
        self.validate_child(&seg.origin, text, params, ev);
        let b = ev.num(text, 'B').or(params.b);
        let d = ev.num(text, 'D').or(params.d);
        let bars = if style == Style::Support {
            let p = ev.num(text, 'P').or(params.p);
            let u = ev.num(text, 'U').or(params.u);
            support_bars(&geom, params.o, p, u, b, d, &seg.origin)?
        } else {
            None
        };
        Ok(ChainSeg {
            geom,
            style,
            f: ev.num(text, 'F').unwrap_or(params.f),
            b,
            d,
            q: ev.string(text, 'Q'),
            bt: seg.backtrack(),
            bars,
            origin: seg.origin.clone(),
        })
    }

    /// Unsupported keys and values that are not numbers.
    fn check_text(&mut self, t: &ParamText, allowed: &str, origin: &Origin, ev: &Eval) {
        for (k, raw) in &t.params {
            if !allowed.contains(*k) {
                self.diags
                    .error(Msg::Unsupported, origin.clone(), args![k, text_context(t)]);
                continue;
            }
            if "ABCDFHIOPSTUWZ".contains(*k) {
                let v = ev.vars.interpolate(raw).unwrap_or_else(|_| raw.clone());
                if parse_number(&v).is_none() {
                    self.diags.push(Diagnostic::warning(
                        Msg::NotANumber,
                        origin.clone(),
                        args![k, v],
                    ));
                }
            }
            if *k == 'N' && raw.trim().parse::<i64>().is_err() {
                self.diags.push(Diagnostic::warning(
                    Msg::NotANumber,
                    origin.clone(),
                    args![k, raw],
                ));
            }
        }
    }

    /// Range checks of a path (§4.3, all values) .
    fn validate(
        &mut self,
        origin: &Origin,
        p: &PathParams,
        _text: Option<&ParamText>,
        _ev: &Eval,
        _path: bool,
    ) {
        let d = &mut self.diags;
        let pos = |d: &mut Diags, key: &str, v: f64| {
            if le(v, 0.0) {
                d.error(Msg::MustBePositive, origin.clone(), args![key, fmt_num(v)]);
            }
        };
        pos(d, "F", p.f);
        if let Some(i) = p.i {
            pos(d, "I", i);
        }
        if let Some(c) = p.c {
            if c <= 0 {
                d.error(Msg::MustBePositive, origin.clone(), args!["C", c]);
            }
        }
        pos(d, "V", p.v);
        pos(d, "O", p.o);
        pos(d, "T", p.t);
        if le(p.s, p.t) {
            d.error(
                Msg::SNotAboveT,
                origin.clone(),
                args![fmt_num(p.s), fmt_num(p.t)],
            );
        }
        if let Some(b) = p.b {
            if ge(b, p.t) {
                d.error(
                    Msg::BAboveT,
                    origin.clone(),
                    args![fmt_num(b), fmt_num(p.t)],
                );
            }
        }
        if let Some(dd) = p.d {
            if ge(dd, p.t) {
                d.error(
                    Msg::DAboveT,
                    origin.clone(),
                    args![fmt_num(dd), fmt_num(p.t)],
                );
            }
        }
        pos(d, "A", p.a);
        if let Some(w) = p.w {
            pos(d, "W", w);
        }
        if let (Some(b), Some(dd)) = (p.b, p.d) {
            if ge(b, dd) {
                d.error(
                    Msg::DNotAboveB,
                    origin.clone(),
                    args![fmt_num(dd), fmt_num(b)],
                );
            }
        }
        if let Some(pp) = p.p {
            pos(d, "P", pp);
        }
        if let Some(u) = p.u {
            pos(d, "U", u);
        }
    }

    /// Range checks of an element's own values against the path's T.
    fn validate_child(
        &mut self,
        origin: &Origin,
        text: Option<&ParamText>,
        p: &PathParams,
        ev: &Eval,
    ) {
        let Some(t) = text else { return };
        if let Some(f) = ev.num(text, 'F') {
            if le(f, 0.0) {
                self.diags
                    .error(Msg::MustBePositive, origin.clone(), args!["F", fmt_num(f)]);
            }
        }
        if t.has('I') {
            if let Some(i) = ev.num(text, 'I').filter(|i| le(*i, 0.0)) {
                self.diags
                    .error(Msg::MustBePositive, origin.clone(), args!["I", fmt_num(i)]);
            }
        }
        if let Some(b) = ev.num(text, 'B') {
            if ge(b, p.t) {
                self.diags.error(
                    Msg::BAboveT,
                    origin.clone(),
                    args![fmt_num(b), fmt_num(p.t)],
                );
            }
        }
        if let Some(d) = ev.num(text, 'D') {
            if ge(d, p.t) {
                self.diags.error(
                    Msg::DAboveT,
                    origin.clone(),
                    args![fmt_num(d), fmt_num(p.t)],
                );
            }
        }
    }

    /// Checks and loads the target of a subpath embedding (§5.5).
    fn connect(
        &mut self,
        raw: &RawPath,
        seg: &RawSegment,
        params: &PathParams,
        ev: &Eval,
        cx: &BuildCtx,
    ) -> Result<Option<Arc<Model>>, Abort> {
        let text = seg.text.as_ref();
        let end_origin = with_pos(&seg.origin, seg.shape.end());
        let t_sub = ev.num(text, 'T').unwrap_or(params.t);
        let target_text = ev.string(text, '>');
        if params.t < t_sub {
            let at = target_text
                .as_deref()
                .map(|t| format!(" {t}"))
                .unwrap_or_default();
            self.diags.error(
                Msg::TLessThanSub,
                raw.start_origin(),
                args![fmt_num(params.t), fmt_num(t_sub), at],
            );
        }
        let Some(target_text) = target_text else {
            return Err(Diagnostic::error(
                Msg::ValueMissing,
                seg.origin.clone(),
                args![">..."],
            ));
        };
        // restrictions: the path's E, else the first matching /e pair
        let own_e = match params.e.as_deref().map(|e| (e, regex(e))) {
            Some((_, Ok(re))) => Some(re),
            Some((e, Err(err))) => {
                self.diags
                    .error(Msg::BadE, raw.start_origin(), args![e, err]);
                None
            }
            None => None,
        };
        let allowed = match &own_e {
            Some(re) => re.is_match(&target_text),
            None => self
                .restrictions
                .iter()
                .find(|(parent, _)| parent.is_match(&raw.name))
                .is_none_or(|(_, child)| child.is_match(&target_text)),
        };
        if !allowed {
            self.diags.error(
                Msg::Forbidden,
                end_origin.clone(),
                args![target_text, raw.name],
            );
        }
        let Some(m) = self.patterns.path_ci.find(&target_text) else {
            return Err(Diagnostic::error(
                Msg::InvalidPathName,
                seg.origin.clone(),
                args![target_text],
            ));
        };
        let target_name = m.as_str().to_string();
        if cx.depth > 9 {
            return Err(Diagnostic::error(
                Msg::NestingTooDeep,
                seg.origin.clone(),
                args![target_name],
            ));
        }
        let assignment = Vars(
            text.map(|t| {
                t.vars
                    .iter()
                    .map(|(n, v)| (*n, ev.vars.interpolate(v).unwrap_or_else(|_| v.clone())))
                    .collect()
            })
            .unwrap_or_default(),
        );
        let mut files = Vec::new();
        if !self.raw.contains_key(&target_name) {
            files = self.search(&target_name, &raw.file.path)?;
        }
        let target = self.build(
            &target_name,
            &assignment,
            &BuildCtx {
                depth: cx.depth + 1,
                top: false,
            },
        )?;
        let Some(target) = target else {
            let list: Vec<String> = files.iter().map(|f| f.display().to_string()).collect();
            self.diags.error(
                Msg::CouldNotFind,
                end_origin,
                args![target_name, list.join(", ")],
            );
            return Ok(None);
        };
        // material, bit and thickness must agree
        let m_line = ev.string(text, 'M').or_else(|| params.m.clone());
        if m_line.is_none() || target.params.m.is_none() {
            self.diags
                .error(Msg::ValueMissing, seg.origin.clone(), args!["M"]);
        }
        let missing = "***Missing***".to_string();
        let (ml, mt) = (
            m_line.unwrap_or_else(|| missing.clone()),
            target.params.m.clone().unwrap_or(missing),
        );
        if ml != mt {
            let d = Diagnostic::error(
                Msg::MMismatch,
                seg.origin.clone(),
                args![ml, target.label(), mt],
            )
            .with_related(target.raw.start_origin(), "referenced path");
            self.diags.push(d);
        }
        let o_line = ev.num(text, 'O').unwrap_or(params.o);
        if !(near(o_line, target.params.o) || o_line.is_nan() || target.params.o.is_nan()) {
            let d = Diagnostic::error(
                Msg::OMismatch,
                seg.origin.clone(),
                args![fmt_num(o_line), target.label(), fmt_num(target.params.o)],
            )
            .with_related(target.raw.start_origin(), "referenced path");
            self.diags.push(d);
        }
        if !(near(t_sub, target.params.t) || t_sub.is_nan() || target.params.t.is_nan()) {
            let d = Diagnostic::error(
                Msg::TMismatch,
                seg.origin.clone(),
                args![fmt_num(t_sub), target.label(), fmt_num(target.params.t)],
            )
            .with_related(target.raw.start_origin(), "referenced path");
            self.diags.push(d);
        }
        self.check_assignment(&target, &assignment, &seg.origin);
        Ok(Some(target))
    }

    /// Assignments of an embedding against the target's definitions (§6.5).
    fn check_assignment(&mut self, target: &Model, assignment: &Vars, origin: &Origin) {
        let defs = target
            .raw
            .start_text
            .as_ref()
            .map(|t| t.vars.clone())
            .unwrap_or_default();
        let missing_values: String = defs
            .iter()
            .filter(|(n, _)| assignment.get(*n).is_none())
            .map(|(n, _)| *n)
            .collect();
        if !missing_values.is_empty() {
            self.diags
                .error(Msg::MissingValues, origin.clone(), args![missing_values]);
        }
        let missing_defs: String = assignment
            .0
            .iter()
            .filter(|(n, _)| !defs.iter().any(|(d, _)| d == n))
            .map(|(n, _)| *n)
            .collect();
        if !missing_defs.is_empty() {
            self.diags
                .error(Msg::MissingDefinitions, origin.clone(), args![missing_defs]);
        }
        for (name, def) in &defs {
            let Some(value) = assignment.get(*name) else {
                continue;
            };
            match parse_definition(*name, def) {
                Ok(d) if d.accepts(value) => {}
                Ok(_) => self.diags.error(
                    Msg::ValueNotInDefinition,
                    origin.clone(),
                    args![value, def.trim(), name],
                ),
                Err((msg, a)) => self.diags.error(msg, origin.clone(), a),
            }
        }
    }
}

/// Traversal order of a path's segments (§5.2), with turn markers (seed manual §4.2.15).
pub fn traverse(raw: &RawPath, start: P2, end: P2, diags: &mut Diags) -> Vec<Step> {
    let segs = &raw.segments;
    let mut taken = vec![false; segs.len()];
    let mut out: Vec<Step> = Vec::new();
    let mut trail: Vec<usize> = Vec::new();
    let mut p = start;
    let at = |s: &RawSegment, p: P2| -> bool {
        match &s.shape {
            Shape::Circle { c, .. } => c.near(p),
            sh => sh.start().near(p) || sh.end().near(p),
        }
    };
    let is_turn = |p: P2| raw.turns.iter().any(|m| m.pos.near(p));
    // end points on a grid much coarser than the point tolerance: a point's candidates are
    // in its cell or a neighbour cell (keeps the walk linear on large paths)
    const CELL: f64 = 1e-3;
    let cell = |p: P2| ((p.x / CELL).floor() as i64, (p.y / CELL).floor() as i64);
    let mut grid: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
    for (i, s) in segs.iter().enumerate() {
        let (a, b) = (s.shape.start(), s.shape.end());
        grid.entry(cell(a)).or_default().push(i);
        if cell(b) != cell(a) {
            grid.entry(cell(b)).or_default().push(i);
        }
    }
    let candidates = |taken: &[bool], p: P2| -> Vec<usize> {
        let (cx, cy) = cell(p);
        let mut v: Vec<usize> = Vec::new();
        for dx in -1..=1 {
            for dy in -1..=1 {
                if let Some(list) = grid.get(&(cx + dx, cy + dy)) {
                    v.extend(
                        list.iter()
                            .copied()
                            .filter(|&i| !taken[i] && at(&segs[i], p)),
                    );
                }
            }
        }
        v.sort_unstable();
        v.dedup();
        v
    };
    let mut untaken = segs.len();
    loop {
        let remaining = untaken > 0;
        let cands = candidates(&taken, p);
        if cands.is_empty() {
            let must_return = if remaining { true } else { !p.near(end) };
            if must_return && is_turn(p) && !trail.is_empty() {
                // walk back to the last point where untraversed segments start (or the end)
                while let Some(k) = trail.pop() {
                    let step = out[k];
                    if matches!(segs[step.index].shape, Shape::Circle { .. }) {
                        continue;
                    }
                    out.push(Step {
                        index: step.index,
                        reversed: !step.reversed,
                        turn_back: true,
                    });
                    let sh = &segs[step.index].shape;
                    p = if step.reversed { sh.end() } else { sh.start() };
                    let open = !candidates(&taken, p).is_empty();
                    if open || (!remaining && p.near(end)) {
                        break;
                    }
                }
                continue;
            }
            if !remaining {
                break;
            }
            if p.near(end) {
                let first = (0..segs.len()).find(|&i| !taken[i]).unwrap_or(0);
                let count = taken.iter().filter(|t| !**t).count();
                let o = with_pos(&segs[first].origin, segs[first].shape.start());
                diags.error(Msg::NotReached, o, args![count]);
            } else {
                let o = out.last().map_or_else(
                    || raw.origin(),
                    |s| {
                        let sh = &segs[s.index].shape;
                        with_pos(
                            &segs[s.index].origin,
                            if s.reversed { sh.end() } else { sh.start() },
                        )
                    },
                );
                diags.error(Msg::NoMoreSegments, o, args![p]);
            }
            break;
        }
        let best = *cands
            .iter()
            .min_by(|&&a, &&b| {
                let (sa, sb) = (&segs[a], &segs[b]);
                let ka = (
                    sa.order(),
                    sa.kind.preference(),
                    sa.shape.start().dist(sa.shape.end()),
                );
                let kb = (
                    sb.order(),
                    sb.kind.preference(),
                    sb.shape.start().dist(sb.shape.end()),
                );
                ka.partial_cmp(&kb).unwrap_or(std::cmp::Ordering::Equal)
            })
            .unwrap_or(&cands[0]);
        taken[best] = true;
        untaken -= 1;
        let s = &segs[best];
        let reversed = matches!(s.shape, Shape::Path(_)) && s.shape.end().near(p);
        out.push(Step {
            index: best,
            reversed,
            turn_back: false,
        });
        trail.push(out.len() - 1);
        if let Shape::Path(_) = s.shape {
            p = if reversed {
                s.shape.start()
            } else {
                s.shape.end()
            };
        }
    }
    if let Some(last) = out.last() {
        let sh = &segs[last.index].shape;
        let last_end = if last.reversed { sh.start() } else { sh.end() };
        let last_end = if matches!(sh, Shape::Circle { .. }) {
            sh.start()
        } else {
            last_end
        };
        if !last_end.near(end) {
            let o = raw
                .end
                .as_ref()
                .map_or_else(|| raw.origin(), |m| m.origin.clone());
            diags.error(Msg::EndNotAtLast, o, args![end]);
        }
    }
    out
}

/// A turn-back copy of a segment: sweeps and embeddings return as sweeps, mill and mark
/// segments are milled again.
fn turn_back_kind(kind: SegKind) -> SegKind {
    match kind {
        SegKind::Mill(s) => SegKind::Mill(s),
        _ => SegKind::Sweep(SweepKind::Hidden),
    }
}

/// One step of the traversal: a segment (index into the path's segments), maybe reversed;
/// `turn_back` marks the automatic way back from a turn marker.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Step {
    pub index: usize,
    pub reversed: bool,
    pub turn_back: bool,
}

/// Parameter values of one build, interpolated with its variables.
struct Eval<'v> {
    vars: &'v Vars,
}

impl Eval<'_> {
    fn string(&self, t: Option<&ParamText>, key: char) -> Option<String> {
        let raw = t?.raw(key)?;
        Some(
            self.vars
                .interpolate(raw)
                .unwrap_or_else(|_| raw.to_string()),
        )
    }
    fn num(&self, t: Option<&ParamText>, key: char) -> Option<f64> {
        parse_number(&self.string(t, key)?)
    }
}

/// `<CODE> @ [x y]` of a text, used in "Unsupported" messages.
fn text_context(t: &ParamText) -> String {
    match &t.origin {
        Origin::Entity(e) => format!("{} @ {}", e.code_name, e.pos),
        o => o.context(),
    }
}

/// The same origin with another reported position.
fn with_pos(o: &Origin, pos: P2) -> Origin {
    match o {
        Origin::Entity(e) => {
            let mut e = e.clone();
            e.pos = pos;
            Origin::Entity(e)
        }
        o => o.clone(),
    }
}

/// Support-bar pieces along a geometry (reference-output.md §8.1); `None` when it is too short.
fn support_bars(
    g: &Geom,
    o: f64,
    p: Option<f64>,
    u: Option<f64>,
    b: Option<f64>,
    d: Option<f64>,
    origin: &Origin,
) -> Result<Option<Vec<Geom>>, Abort> {
    let need = |v: Option<f64>, k: &str| {
        v.ok_or_else(|| Diagnostic::error(Msg::ValueMissing, origin.clone(), args![k]))
    };
    let p = need(p, "P")?;
    let u = need(u, "U")?;
    let b = need(b, "B")?;
    let d = need(d, "D")?;
    let len = g.length();
    let n = (len / (u + p)).floor();
    if n.is_nan() || n < 1.0 || !n.is_finite() {
        return Ok(None);
    }
    let delta = d - b;
    let i = delta.min(p / 2.0);
    let v = len / n - p - 2.0 * i;
    let e = p / 2.0 + o / 2.0;
    let w = v - o;
    let bar = p + o;
    let step = 2.0 * i + v + p;
    let mut pieces = vec![g.sub(0.0, e)];
    for k in 0..(n as usize - 1) {
        let s = e + k as f64 * step;
        pieces.push(g.sub(s, s + i));
        pieces.push(g.sub(s + i, s + i + w));
        pieces.push(g.sub(s + i + w, s + 2.0 * i + w));
        pieces.push(g.sub(s + 2.0 * i + w, s + 2.0 * i + w + bar));
    }
    let t = len - e - 2.0 * i - w;
    pieces.push(g.sub(t, t + i));
    pieces.push(g.sub(t + i, t + i + w));
    pieces.push(g.sub(t + i + w, t + 2.0 * i + w));
    pieces.push(g.sub(t + 2.0 * i + w, len));
    Ok(Some(pieces))
}

/// Files held in memory (tests, unsaved editor buffers).
#[derive(Debug, Default, Clone)]
pub struct MemFileSystem {
    pub files: std::collections::BTreeMap<PathBuf, Vec<u8>>,
}

impl MemFileSystem {
    pub fn add(&mut self, path: impl Into<PathBuf>, content: impl Into<Vec<u8>>) -> &mut Self {
        self.files.insert(path.into(), content.into());
        self
    }
}

impl FileSystem for MemFileSystem {
    fn read(&self, path: &Path) -> std::io::Result<Vec<u8>> {
        self.files
            .get(path)
            .cloned()
            .ok_or_else(|| std::io::Error::new(std::io::ErrorKind::NotFound, "not found"))
    }
    fn list_dir(&self, dir: &Path) -> std::io::Result<Vec<PathBuf>> {
        let dir = if dir == Path::new(".") {
            Path::new("")
        } else {
            dir
        };
        Ok(self
            .files
            .keys()
            .filter(|p| p.parent() == Some(dir))
            .cloned()
            .collect())
    }
    fn is_dir(&self, dir: &Path) -> bool {
        let dir = if dir == Path::new(".") {
            Path::new("")
        } else {
            dir
        };
        self.files.keys().any(|p| p.parent() == Some(dir))
    }
}
