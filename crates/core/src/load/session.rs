//! A compilation session: settings, loading files through a [`FileSystem`] (each parse
//! shared through the process-wide parse cache), the registry of known paths and the
//! models built so far (reference-input.md §3, §7.5).
//!
//! `Session`: loading a file once, registering its paths, duplicates (reference-input.md §3.1);
//! `stop`, asked during a check (the editor abandons stale analyses); `traversals`, the editor's
//! memo of walks (`build/traverse_memo.rs`); `one_file` (the command line's check and compile):
//! once the models are built the drawing's segments are dropped (`release_segments`; a model keeps
//! its path's head, `RawPath::head`), and a text's tree is dropped before its paths are made.

use crate::args;
use crate::diag::{Diagnostic, Diags, FileRef, Lang, Msg, Origin};
use crate::front::drawing::RawPath;
use crate::front::dxf::dxf_to_drawing;
use crate::front::options::FrontOptions;
use crate::load::fs::{
    is_text_file, with_file_bytes, with_stamped_file_bytes, FileSystem, MAX_FILE_BYTES,
};
use crate::load::names::Patterns;
use crate::load::parse_cache::{self, FileStamp, ParseKey, ParsedFile};
use crate::load::regex_cache::regex;
use crate::load::settings::Settings;
use crate::model::*;
use crate::params::Vars;
use regex::Regex;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// An error that aborts the current top-level file.
pub type Abort = Diagnostic;

pub struct Session<'a> {
    pub settings: Settings,
    pub patterns: Arc<Patterns>,
    pub(crate) restrictions: Vec<(Arc<Regex>, Arc<Regex>)>,
    pub(crate) debug: Option<Arc<Regex>>,
    pub(crate) fs: &'a dyn FileSystem,
    pub diags: Diags,
    /// Progress lines (`---- Reading …`), in order.
    pub info: Vec<String>,
    pub(crate) raw: HashMap<String, Arc<RawPath>>,
    pub(crate) loaded: HashMap<PathBuf, Vec<String>>,
    pub(crate) models: HashMap<(String, Vars), Option<Arc<Model>>>,
    /// Asked now and then during a check: `true` gives up (the editor's document changed,
    /// the result is useless). The outcome of a stopped run is then incomplete.
    pub stop: Option<&'a dyn Fn() -> bool>,
    /// The editor's walks of its previous analysis, taken again where nothing they read
    /// changed (`build/traverse_memo.rs`); `None` outside the editor.
    pub traversals: Option<&'a crate::build::traverse_memo::TraversalMemo>,
    /// The session serves one `compile_file` call (a command line's check or compile of one
    /// file): once its models are built, the drawings' segments are dropped before the
    /// program is generated ([`Session::release_segments`]).
    pub one_file: bool,
}

impl<'a> Session<'a> {
    /// Creates a session; invalid patterns and restrictions are reported as option errors.
    pub fn new(settings: Settings, fs: &'a dyn FileSystem) -> Result<Session<'a>, Vec<Diagnostic>> {
        let mut errors = settings.number_errors();
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
                stop: None,
                traversals: None,
                one_file: false,
            }),
            _ => Err(errors),
        }
    }

    /// Whether [`Session::stop`] says to give up.
    pub fn stopped(&self) -> bool {
        self.stop.is_some_and(|stop| stop())
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
        let key = |stamp| ParseKey {
            path: path.to_path_buf(),
            stamp,
            path_pattern: self.settings.path_pattern.clone(),
            debug_pattern: self.settings.debug_pattern.clone(),
            lang: self.lang(),
            input: self.settings.input,
        };
        let (parsed, stamp) = if parse_cache::may_hold(path) {
            match self.fs.stamp(path) {
                Some(stamp) => (
                    parse_cache::parsed(key(stamp), || self.parse_file(path)),
                    Some(stamp),
                ),
                None => (Arc::new(self.parse_file(path)), None),
            }
        } else {
            match self.parse_stamped_file(path) {
                (parsed, Some(stamp)) => (parse_cache::parsed(key(stamp), || parsed), Some(stamp)),
                (parsed, None) => (Arc::new(parsed), None),
            }
        };
        if let Some(stamp) = stamp {
            if self.one_file && parsed.segment_count() > parse_cache::MAX_KEPT_SEGMENTS {
                parse_cache::forget(&key(stamp));
            }
        }
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

    /// Drops the segments of every path this session alone holds (the models keep what
    /// they need; see [`crate::front::drawing::RawPath::head`]): a long chain's drawing is
    /// not held beside its model while the program is generated. Paths shared with the
    /// parse cache or a caller stay whole. Nothing may be built afterwards.
    pub fn release_segments(&mut self) {
        for p in self.raw.values_mut() {
            if let Some(p) = Arc::get_mut(p) {
                p.segments = Vec::new();
            }
        }
    }

    /// Registers the paths of a file read elsewhere (an editor's parsed buffer), as if
    /// `load_file` had read it; returns their names in drawing order.
    pub fn add_paths(&mut self, path: &Path, paths: Vec<RawPath>) -> Vec<String> {
        self.register(path, paths.into_iter().map(Arc::new).collect())
    }

    /// The models built so far, taken out of the session: the editor keeps them with its
    /// analysis, so that they are freed with it (after the answer) and not with the session.
    pub fn take_models(&mut self) -> Vec<Arc<Model>> {
        self.models.drain().filter_map(|(_, m)| m).collect()
    }

    /// [`Session::add_paths`] of paths the caller keeps too (the editor, without a copy).
    pub fn add_shared_paths(&mut self, path: &Path, paths: Vec<Arc<RawPath>>) -> Vec<String> {
        self.register(path, paths)
    }

    pub(crate) fn register(&mut self, path: &Path, paths: Vec<Arc<RawPath>>) -> Vec<String> {
        let mut names = Vec::new();
        for p in paths {
            names.push(p.name.clone());
            // the reference takes `1000_1a` silently (§1.3); the manual's names end in a capital
            if let Some(meant) = self.patterns.meant_case(&p.name) {
                if !self.settings.reference_check {
                    self.diags.push(Diagnostic::warning(
                        Msg::PathNameCase,
                        p.start_origin(),
                        args![p.name, self.settings.path_pattern, meant],
                    ));
                }
            }
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
    pub(crate) fn parse_file(&self, path: &Path) -> ParsedFile {
        with_file_bytes(self.fs, path, |bytes| self.parse_bytes(path, bytes))
    }

    /// [`Session::parse_file`] and the stamp of the version read.
    fn parse_stamped_file(&self, path: &Path) -> (ParsedFile, Option<FileStamp>) {
        with_stamped_file_bytes(self.fs, path, |read| match read {
            Ok((bytes, stamp)) => (self.parse_bytes(path, Ok(bytes)), stamp),
            Err(e) => (self.parse_bytes(path, Err(e)), None),
        })
    }

    fn parse_bytes(&self, path: &Path, bytes: std::io::Result<&[u8]>) -> ParsedFile {
        let mut diags = Diags::default();
        let mut info = Vec::new();
        let result = match bytes {
            Err(e) if e.kind() == std::io::ErrorKind::FileTooLarge => Err(Diagnostic::error(
                Msg::FileTooLarge,
                Origin::Input,
                args![path.display(), MAX_FILE_BYTES >> 20],
            )),
            Err(e) => Err(Diagnostic::error(
                Msg::CannotRead,
                Origin::Input,
                args![path.display(), e],
            )),
            Ok(bytes) => {
                let file = FileRef::new(path.to_path_buf());
                let parsed = self
                    .parse_drawing(bytes, &file, &mut diags, &mut info)
                    .map(|d| d.paths.into_iter().map(Arc::new).collect());
                crate::front::extended::hint_line_types(
                    &mut diags.list,
                    self.settings.input,
                    self.lang(),
                );
                parsed
            }
        };
        ParsedFile {
            result,
            diags: diags.list,
            info,
        }
    }

    /// The paths of a parsed text file with every check of reading it (syntax, kinds, path
    /// names): the one code for `check`/`compile` and the editor, which keeps the tree.
    pub fn text_paths(
        &self,
        ast: &millpath_syntax::File,
        errors: Vec<millpath_syntax::SyntaxError>,
        src: &str,
        file: &Arc<FileRef>,
        diags: &mut Diags,
    ) -> Result<(crate::front::text::TextDrawing, Vec<RawPath>), Diagnostic> {
        let (text, broken) = Self::text_objects(ast, errors, src, file, diags)?;
        let paths = self.paths_of_text(&text, &broken, file, diags)?;
        Ok((text, paths))
    }

    /// The first half of [`Session::text_paths`]: the drawn objects, and the names of the
    /// paths holding a line that did not parse. The tree is not needed after it (a long
    /// file's tree is dropped before its paths are made).
    fn text_objects(
        ast: &millpath_syntax::File,
        errors: Vec<millpath_syntax::SyntaxError>,
        src: &str,
        file: &Arc<FileRef>,
        diags: &mut Diags,
    ) -> Result<(crate::front::text::TextDrawing, Vec<String>), Diagnostic> {
        let broken = Self::broken_paths(ast, &errors);
        let text = crate::front::text::objects_of(ast, errors, src, file, diags)?;
        Ok((text, broken))
    }

    /// The names of the paths of a text holding a line that did not parse.
    pub fn broken_paths(
        ast: &millpath_syntax::File,
        errors: &[millpath_syntax::SyntaxError],
    ) -> Vec<String> {
        ast.paths()
            .filter(|b| {
                errors
                    .iter()
                    .any(|e| b.span.start <= e.span.start && e.span.start < b.span.end)
            })
            .map(|b| b.name.value.clone())
            .collect()
    }

    /// The second half of [`Session::text_paths`]: the paths of the objects (made here or by
    /// the editor from its previous version, `front/text_edit.rs`); `broken`: the names of
    /// [`Session::broken_paths`].
    pub fn paths_of_text(
        &self,
        text: &crate::front::text::TextDrawing,
        broken: &[String],
        file: &Arc<FileRef>,
        diags: &mut Diags,
    ) -> Result<Vec<RawPath>, Diagnostic> {
        let mut paths = crate::front::drawing::build_paths(
            &text.objects,
            file,
            &self.patterns.path_cs,
            &self.settings.path_pattern,
            diags,
        )?;
        for p in &mut paths {
            p.broken = broken.contains(&p.name);
        }
        // a start line that did not parse is no missing parameters text
        diags.list.retain(|d| {
            !(d.msg == Msg::ParametersTextMissing
                && matches!(&d.origin, Origin::Path { name, .. } if broken.iter().any(|b| **b == **name)))
        });
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
        Ok(paths)
    }

    pub(crate) fn parse_drawing(
        &self,
        bytes: &[u8],
        file: &Arc<FileRef>,
        diags: &mut Diags,
        info: &mut Vec<String>,
    ) -> Result<crate::front::drawing::DrawingFile, Diagnostic> {
        let verb = if self.lang() == Lang::De {
            "Einlesen von"
        } else {
            "Reading"
        };
        if is_text_file(&file.path) {
            info.push(format!("---- {verb} {}", file.path.display()));
            let src = crate::load::text_file::decode(bytes)
                .map_err(|_| {
                    Diagnostic::error(
                        Msg::TextNulBytes,
                        Origin::File(file.clone()),
                        args![file.path.display()],
                    )
                })?
                .text;
            let (text, broken) = {
                let (ast, errors) = millpath_syntax::parse(&src);
                Self::text_objects(&ast, errors, &src, file, diags)?
            };
            let paths = self.paths_of_text(&text, &broken, file, diags)?;
            return Ok(crate::front::drawing::DrawingFile {
                paths,
                debug: Vec::new(),
                version: String::new(),
            });
        }
        let dxf = millpath_dxf::read_dxf(bytes).map_err(|e| {
            Diagnostic::error(
                Msg::CannotLoadDxf,
                Origin::File(file.clone()),
                vec![
                    file.path.display().to_string(),
                    crate::diag::dxf_error_arg(&e),
                ],
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
            input: self.settings.input,
        };
        let drawing = dxf_to_drawing(&dxf, file, &opts, diags)?;
        info.extend(drawing.debug.iter().cloned());
        Ok(drawing)
    }

    /// A known path whose name differs from `name` only in case (the hint of a subpath not
    /// found); the first in name order.
    pub(crate) fn case_twin(&self, name: &str) -> Option<String> {
        if self.raw.contains_key(name) {
            return None;
        }
        let mut twins: Vec<&String> = self
            .raw
            .keys()
            .filter(|k| k.eq_ignore_ascii_case(name))
            .collect();
        twins.sort();
        twins.first().map(|s| s.to_string())
    }

    pub fn raw_path(&self, name: &str) -> Option<Arc<RawPath>> {
        self.raw.get(name).cloned()
    }

    /// The raw path of a name, searching the folder of `near_file` and the search directories
    /// when it is not known yet (editors: hover and go-to-definition of subpath names).
    pub fn lookup(&mut self, name: &str, near_file: &Path) -> Option<Arc<RawPath>> {
        if !self.raw.contains_key(name) {
            let _ = self.search(name, near_file);
        }
        self.raw.get(name).cloned()
    }
}
