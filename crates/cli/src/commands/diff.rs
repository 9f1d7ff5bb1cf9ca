//! `millpath diff`: what changed between two versions of drawings, and what it does to the
//! part (`millpath-history`). Versions come from files (`diff OLD NEW`) or from git
//! (`diff REV -- FILE…`, `diff REV..REV [-- FILE…]`; without files, the drawings git lists
//! as changed), read with the `git` binary (`git show REV:./NAME`). Exit 0: no change, 1:
//! changed, 2: an error.

use crate::args::{lang_of, settings_for, MachineArgs};
use crate::report;
use millpath_core::diag::{Diagnostic, FileRef, Msg, Origin};
use millpath_core::MemFileSystem;
use millpath_core::{InputMode, Lang};
use millpath_history::{report as out, Side, Version};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::Arc;

#[derive(Clone, Copy, clap::ValueEnum, Default, PartialEq)]
pub enum DiffFormat {
    #[default]
    Human,
    Json,
    Markdown,
}

/// Where one version of a file comes from.
struct Source {
    /// The label in the report (`part.dxf`, `HEAD:part.dxf`).
    label: String,
    /// The file it stands for on disk (subpaths and millpath.toml are found beside it).
    file: PathBuf,
    /// Its bytes; `None`: the file does not exist in this version.
    bytes: Option<Vec<u8>>,
    /// The files of its git revision (subpaths, `millpath.toml`) at their work-tree paths;
    /// `None`: the work tree.
    tree: Option<Arc<MemFileSystem>>,
}

pub struct Args {
    pub machine: MachineArgs,
    pub format: DiffFormat,
    pub compile: bool,
    pub revs: Vec<String>,
    pub files: Vec<PathBuf>,
    /// The visual diff: HTML page, SVG, PNG.
    pub pictures: Pictures,
    /// With OLD NEW: the drawing both stand for (an editor's copies of two revisions): its
    /// subpaths and millpath.toml are used.
    pub at: Option<PathBuf>,
}

#[derive(Default)]
pub struct Pictures {
    pub html: Option<PathBuf>,
    pub svg: Option<PathBuf>,
    pub png: Option<PathBuf>,
}

impl Pictures {
    fn any(&self) -> bool {
        self.html.is_some() || self.svg.is_some() || self.png.is_some()
    }
}

pub fn run(a: &Args) -> u8 {
    let first =
        a.at.clone()
            .or_else(|| a.files.first().cloned())
            .or_else(|| a.revs.last().map(PathBuf::from));
    let lang = lang_of(&a.machine, first.as_deref());
    let pairs = match sources(a, lang) {
        Ok(p) => p,
        Err(e) => {
            eprintln!("{e}");
            return 2;
        }
    };
    if a.pictures.any() && pairs.len() != 1 {
        eprintln!(
            "{}",
            match lang {
                Lang::En => "error: --html, --svg and --png draw one drawing: name one file",
                Lang::De =>
                    "Fehler: --html, --svg und --png zeichnen eine Zeichnung: eine Datei angeben",
            }
        );
        return 2;
    }
    // `--svg part.mpath` for `--svg part.svg`: no drawing is replaced by its picture
    let inputs: Vec<PathBuf> = pairs
        .iter()
        .flat_map(|(o, n)| [&o.file, &n.file])
        .chain(a.at.as_ref())
        .filter_map(|f| dunce::canonicalize(f).ok())
        .collect();
    let p = &a.pictures;
    let outputs = [
        (p.html.as_deref(), "HTML"),
        (p.svg.as_deref(), "SVG"),
        (p.png.as_deref(), "PNG"),
    ];
    if crate::output::output_is_input(&outputs, &inputs, lang) {
        return 2;
    }
    let options = match crate::overrides::overrides(&a.machine, lang) {
        Ok(o) => o,
        Err(e) => {
            eprintln!("{e}");
            return 2;
        }
    };
    if let Err(e) = option_values(&a.machine, lang) {
        eprintln!("{e}");
        return 2;
    }
    let mut changed = false;
    let mut status = 0;
    let mut texts = Vec::new();
    let mut jsons = Vec::new();
    for (old, new) in &pairs {
        let (o, n) = match both_versions(old, new, &a.machine, lang) {
            (Ok(o), Ok(n)) => (o, n),
            (Err(e), _) | (_, Err(e)) => {
                eprintln!("{e}");
                return 2;
            }
        };
        let d = millpath_history::diff(
            Side {
                version: &o,
                file: &old.file,
                files: old.tree.clone(),
                options: options.as_ref(),
            },
            Side {
                version: &n,
                file: &new.file,
                files: new.tree.clone(),
                options: options.as_ref(),
            },
            a.compile,
        );
        changed |= d.changed();
        let title = format!("{} → {}", old.label, new.label);
        let texts_of = (
            (old.label.as_str(), o.text.as_str()),
            (new.label.as_str(), n.text.as_str()),
        );
        status |= pictures(&a.pictures, &d, &title, texts_of, lang);
        match a.format {
            DiffFormat::Human => texts.push(out::human(&d, &title, lang)),
            DiffFormat::Markdown => texts.push(out::markdown(&d, &title, lang)),
            DiffFormat::Json => jsons.push(out::json(&d, &old.label, &new.label)),
        }
    }
    let text = match a.format {
        DiffFormat::Json => {
            let v = serde_json::json!({ "changed": changed, "files": jsons });
            format!("{}\n", serde_json::to_string_pretty(&v).unwrap_or_default())
        }
        _ if pairs.is_empty() => match lang {
            Lang::En => "No drawing changed.\n".to_string(),
            Lang::De => "Keine Zeichnung geändert.\n".to_string(),
        },
        _ => texts.join("\n"),
    };
    if crate::output::emit(None, &text, lang) != 0 || status != 0 {
        return 2;
    }
    u8::from(changed)
}

/// The values the options give, checked as compile checks them (`--feed=-5`, `--feed nan`,
/// `--plunge-feed 0` …): an option in error stops the diff (exit 2) rather than making both
/// versions "not compile" with no reason given.
fn option_values(m: &MachineArgs, lang: Lang) -> Result<(), String> {
    // a margin alone may widen a version's [heightmap]: checked per version
    let alone = MachineArgs {
        heightmap_margin: None,
        ..m.clone()
    };
    let s = settings_for(&alone, None, false)?;
    let mut errors: Vec<String> = s
        .number_errors()
        .iter()
        .filter(|d| matches!(d.origin, Origin::Options))
        .map(|d| report::human(d, lang))
        .collect();
    // compile's rule for the three machine values, for those the options give
    let given = [
        ("feed", m.feed),
        ("sweep_speed", m.sweep_speed),
        ("sweep_height", m.sweep_height),
    ];
    for (name, v) in given {
        if let Some(v) = v.filter(|v| v.is_finite() && *v <= 0.0) {
            let d = Diagnostic::error(
                Msg::MustBePositive,
                Origin::Options,
                millpath_core::args![name, millpath_core::params::fmt_num(v)],
            );
            errors.push(report::human(&d, lang));
        }
    }
    if errors.is_empty() {
        Ok(())
    } else {
        Err(errors.join("\n"))
    }
}

/// Writes the visual diff; 0, or 1 when a file could not be written (said on stderr).
fn pictures(
    p: &Pictures,
    d: &millpath_history::Diff,
    title: &str,
    (old, new): ((&str, &str), (&str, &str)),
    lang: Lang,
) -> u8 {
    use millpath_history::picture;
    let writing = match lang {
        Lang::En => "Writing",
        Lang::De => "Schreiben von",
    };
    let mut status = 0;
    if let Some(out) = &p.html {
        eprintln!("---- {writing} {}", out.display());
        let page = picture::html(d, title, old, new, lang == Lang::De);
        status |= crate::output::emit(Some(out), &page, lang);
    }
    if let Some(out) = &p.svg {
        eprintln!("---- {writing} {}", out.display());
        status |= crate::output::emit(Some(out), &picture::svg(d), lang);
    }
    if let Some(out) = &p.png {
        eprintln!("---- {writing} {}", out.display());
        let written = crate::png::svg_to_png(&picture::svg(d)).and_then(|bytes| {
            crate::write::write_atomic_bytes(out, &bytes).map_err(|e| e.to_string())
        });
        if let Err(e) = written {
            eprintln!(
                "{}: {}: {e}",
                report::severity_word(millpath_core::diag::Severity::Error, lang),
                out.display()
            );
            status |= 1;
        }
    }
    status
}

/// `millpath difftool LOCAL REMOTE [MERGED]` (git difftool): the visual diff of two versions
/// as an HTML page, located at MERGED (the drawing in the work tree: its subpaths and
/// millpath.toml); the page's path is printed, and opened with `--open`.
pub fn difftool(
    machine: &MachineArgs,
    local: &Path,
    remote: &Path,
    merged: Option<&Path>,
    html: Option<PathBuf>,
    open: bool,
) -> u8 {
    let lang = lang_of(machine, merged.or(Some(remote)));
    let source = |p: &Path| -> Result<Source, String> {
        let bytes = std::fs::read(p).map_err(|e| cannot_read(p, e, lang))?;
        // git's temporary copies have the drawing's extension; the drawing itself is MERGED
        Ok(Source {
            label: merged.unwrap_or(p).display().to_string(),
            file: absolute(merged.unwrap_or(p)),
            bytes: Some(bytes),
            tree: None,
        })
    };
    let (old, new) = match (source(local), source(remote)) {
        (Ok(o), Ok(n)) => (o, n),
        (Err(e), _) | (_, Err(e)) => {
            eprintln!("{e}");
            return 2;
        }
    };
    let (o, n) = match both_versions(&old, &new, machine, lang) {
        (Ok(o), Ok(n)) => (o, n),
        (Err(e), _) | (_, Err(e)) => {
            eprintln!("{e}");
            return 2;
        }
    };
    let options = match crate::overrides::overrides(machine, lang) {
        Ok(o) => o,
        Err(e) => {
            eprintln!("{e}");
            return 2;
        }
    };
    if let Err(e) = option_values(machine, lang) {
        eprintln!("{e}");
        return 2;
    }
    let d = millpath_history::diff(
        Side {
            version: &o,
            file: &old.file,
            files: None,
            options: options.as_ref(),
        },
        Side {
            version: &n,
            file: &new.file,
            files: None,
            options: options.as_ref(),
        },
        true,
    );
    let name = new
        .file
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let out =
        html.unwrap_or_else(|| std::env::temp_dir().join(format!("millpath-diff-{name}.html")));
    let title = format!("{} ({} → {})", old.label, local.display(), remote.display());
    let page = millpath_history::picture::html(
        &d,
        &title,
        (&local.display().to_string(), &o.text),
        (&remote.display().to_string(), &n.text),
        lang == Lang::De,
    );
    if crate::output::emit(Some(&out), &page, lang) != 0 {
        return 2;
    }
    print!("{}", out::human(&d, &title, lang));
    println!("{}", out.display());
    if open {
        let opener = if cfg!(target_os = "macos") {
            "open"
        } else if cfg!(windows) {
            "explorer"
        } else {
            "xdg-open"
        };
        if let Err(e) = Command::new(opener).arg(&out).spawn() {
            eprintln!("{opener}: {e}");
        }
    }
    0
}

/// Both versions read at once (a large drawing's conversion takes a while).
fn both_versions(
    old: &Source,
    new: &Source,
    m: &MachineArgs,
    lang: Lang,
) -> (Result<Version, String>, Result<Version, String>) {
    std::thread::scope(|s| {
        let o = s.spawn(|| version(old, m, lang));
        let n = version(new, m, lang);
        let o = o
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
        (o, n)
    })
}

/// A version from its source (an absent file: no paths).
fn version(s: &Source, m: &MachineArgs, lang: Lang) -> Result<Version, String> {
    let Some(bytes) = &s.bytes else {
        return Ok(Version::of_text(String::new()));
    };
    let (path_pattern, file_pattern, input) = match (&s.tree, &m.config) {
        // a revision's drawing is read with the revision's millpath.toml (and the options)
        (Some(tree), None) => {
            // the options' own errors (a post that does not exist, a bad --restrict) stop the
            // diff here as with files; a margin alone may widen the revision's [heightmap]
            let options_alone = MachineArgs {
                heightmap_margin: None,
                ..m.clone()
            };
            settings_for(&options_alone, None, false)?;
            let mut settings = millpath_core::Settings::default();
            if let Some(cfg) = crate::config::load_from(&**tree, &s.file, lang) {
                cfg?.apply(&mut settings, &mut crate::config::Have::default());
            }
            let input = if m.extended {
                InputMode::Extended
            } else {
                settings.input
            };
            (
                m.path_pattern.clone().unwrap_or(settings.path_pattern),
                m.file_pattern.clone().unwrap_or(settings.file_pattern),
                input,
            )
        }
        _ => {
            let settings = settings_for(m, Some(&s.file), false)?;
            (settings.path_pattern, settings.file_pattern, settings.input)
        }
    };
    let patterns = millpath_core::load::names::Patterns::shared(&path_pattern, &file_pattern)
        .map_err(|(c, p, e)| format!("/{c} '{p}': {e}"))?;
    // messages name what the user gave (the label), not the file it stands for
    Version::read(&PathBuf::from(&s.label), bytes, &patterns, input).map_err(|diags| {
        diags
            .iter()
            .map(|d| report::human(d, lang))
            .collect::<Vec<_>>()
            .join("\n")
    })
}

fn cannot_read(path: &Path, e: impl std::fmt::Display, lang: Lang) -> String {
    let d = Diagnostic::error(
        Msg::CannotRead,
        Origin::File(FileRef::new(path.to_path_buf())),
        millpath_core::args![path.display(), e],
    );
    report::human(&d, lang)
}

/// The pairs of versions to compare.
fn sources(a: &Args, lang: Lang) -> Result<Vec<(Source, Source)>, String> {
    let de = lang == Lang::De;
    if a.files.is_empty() && a.revs.len() == 2 {
        // diff OLD NEW
        let read = |p: &str| -> Result<Source, String> {
            let path = PathBuf::from(p);
            let bytes = std::fs::read(&path).map_err(|e| cannot_read(&path, e, lang))?;
            Ok(Source {
                label: p.to_string(),
                file: a
                    .at
                    .as_deref()
                    .map_or_else(|| dunce::canonicalize(&path).unwrap_or(path), absolute),
                bytes: Some(bytes),
                tree: None,
            })
        };
        return Ok(vec![(read(&a.revs[0])?, read(&a.revs[1])?)]);
    }
    if a.at.is_some() {
        return Err(if de {
            "Fehler: --at gilt mit ALT NEU (zwei Zeichnungen)".into()
        } else {
            "error: --at goes with OLD NEW (two drawings)".into()
        });
    }
    if a.revs.len() > 1 {
        return Err(if de {
            "Fehler: `millpath diff` braucht ALT NEU, REV -- DATEI… oder REV..REV".into()
        } else {
            "error: `millpath diff` takes OLD NEW, REV -- FILE… or REV..REV".into()
        });
    }
    let rev = a.revs.first().map_or("HEAD", String::as_str);
    let (from, to) = match rev.split_once("..") {
        Some((f, t)) => (
            if f.is_empty() { "HEAD" } else { f },
            Some(if t.is_empty() { "HEAD" } else { t }),
        ),
        None => (rev, None),
    };
    let files: Vec<(PathBuf, PathBuf)> = if a.files.is_empty() {
        changed_drawings(from, to, lang)?
    } else {
        a.files.iter().map(|f| (f.clone(), f.clone())).collect()
    };
    // repository paths shown from the current folder
    let cwd = std::env::current_dir().unwrap_or_default();
    let short = |p: PathBuf| p.strip_prefix(&cwd).map(Path::to_path_buf).unwrap_or(p);
    let mut out = Vec::new();
    // each revision's files read once, for all drawings
    let mut trees: HashMap<String, Arc<MemFileSystem>> = HashMap::new();
    let mut tree_of = |rev: &str| -> Result<Arc<MemFileSystem>, String> {
        if let Some(t) = trees.get(rev) {
            return Ok(t.clone());
        }
        let t = Arc::new(revision_files(rev, lang)?);
        trees.insert(rev.to_string(), t.clone());
        Ok(t)
    };
    for (old_file, new_file) in files {
        let (old_file, new_file) = (short(old_file), short(new_file));
        let mut old = git_source(from, &old_file, lang)?;
        old.tree = Some(tree_of(from)?);
        let new = match to {
            Some(t) => {
                let mut s = git_source(t, &new_file, lang)?;
                s.tree = Some(tree_of(t)?);
                s
            }
            None => Source {
                label: new_file.display().to_string(),
                file: absolute(&new_file),
                bytes: match std::fs::read(&new_file) {
                    Ok(b) => Some(b),
                    Err(e) if e.kind() == std::io::ErrorKind::NotFound => None,
                    Err(e) => return Err(cannot_read(&new_file, e, lang)),
                },
                tree: None,
            },
        };
        if old.bytes.is_none() && new.bytes.is_none() {
            return Err(cannot_read(
                &new_file,
                if de {
                    format!("weder in {from} noch danach vorhanden")
                } else {
                    format!("in neither {from} nor after it")
                },
                lang,
            ));
        }
        out.push((old, new));
    }
    Ok(out)
}

fn absolute(p: &Path) -> PathBuf {
    dunce::canonicalize(p).unwrap_or_else(|_| {
        std::env::current_dir()
            .map(|d| d.join(p))
            .unwrap_or_else(|_| p.to_path_buf())
    })
}

/// A file as it was in a git revision (`git show REV:./NAME` in its folder).
fn git_source(rev: &str, file: &Path, lang: Lang) -> Result<Source, String> {
    let abs = absolute(file);
    let dir = abs.parent().unwrap_or(Path::new("."));
    let name = abs
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    // the folder may be gone in the working tree: ask from the repository's top
    let (cwd, spec) = if dir.is_dir() {
        (dir.to_path_buf(), format!("{rev}:./{name}"))
    } else {
        (
            std::env::current_dir().unwrap_or_default(),
            format!("{rev}:./{}", file.display()),
        )
    };
    let o = Command::new("git")
        .arg("-C")
        .arg(&cwd)
        .args(["show", &spec])
        .output()
        .map_err(|e| cannot_read(Path::new("git"), e, lang))?;
    let bytes = if o.status.success() {
        Some(o.stdout)
    } else {
        let err = String::from_utf8_lossy(&o.stderr);
        // a file the revision does not have is an added (or removed) drawing
        if err.contains("does not exist") || err.contains("exists on disk, but not in") {
            None
        } else {
            return Err(cannot_read(
                file,
                format!("git show {spec}: {}", err.trim()),
                lang,
            ));
        }
    };
    // a full commit id (a merge base in CI) shown short, as git does
    let shown = if rev.len() == 40 && rev.bytes().all(|b| b.is_ascii_hexdigit()) {
        &rev[..10]
    } else {
        rev
    };
    Ok(Source {
        label: format!("{shown}:{}", file.display()),
        file: abs,
        bytes,
        tree: None,
    })
}

/// A file of a revision larger than this is left out of [`revision_files`] (drawings and
/// settings are far smaller; a repository's large assets are not read).
const MAX_REVISION_FILE: u64 = 32 << 20;
/// Files of a revision are read up to this many bytes in all.
const MAX_REVISION_BYTES: u64 = 512 << 20;

/// The files of a git revision at their work-tree paths (`git ls-tree`, `git cat-file
/// --batch`), and the `millpath.toml` files above the repository (not versioned) from the
/// disk: what the compiler reads for a version of that revision, subpaths and settings as
/// they were then.
fn revision_files(rev: &str, lang: Lang) -> Result<MemFileSystem, String> {
    use std::io::{BufRead, Read, Write};
    let top = git(&["rev-parse", "--show-toplevel"], lang)?;
    let top = PathBuf::from(String::from_utf8_lossy(&top).trim().to_string());
    let top = dunce::canonicalize(&top).unwrap_or(top);
    let mut files = MemFileSystem::default();
    for dir in top.ancestors().skip(1) {
        let toml = dir.join("millpath.toml");
        if let Ok(bytes) = std::fs::read(&toml) {
            files.add(toml, bytes);
        }
    }
    let listed = git(&["ls-tree", "-r", "-z", "-l", "--full-tree", rev], lang)?;
    // "MODE TYPE ID SIZE\tPATH"
    let mut wanted: Vec<(String, PathBuf)> = Vec::new();
    let mut total = 0u64;
    for entry in listed.split(|&b| b == 0) {
        let entry = String::from_utf8_lossy(entry);
        let Some((meta, name)) = entry.split_once('\t') else {
            continue;
        };
        let meta: Vec<&str> = meta.split_whitespace().collect();
        let [_, "blob", id, size] = meta[..] else {
            continue;
        };
        let Ok(size) = size.parse::<u64>() else {
            continue;
        };
        if size > MAX_REVISION_FILE || total + size > MAX_REVISION_BYTES {
            continue;
        }
        total += size;
        wanted.push((id.to_string(), top.join(name)));
    }
    let mut child = Command::new("git")
        .arg("-C")
        .arg(&top)
        .args(["cat-file", "--batch"])
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .spawn()
        .map_err(|e| cannot_read(Path::new("git"), e, lang))?;
    let ids: String = wanted.iter().map(|(id, _)| format!("{id}\n")).collect();
    let mut stdin = child.stdin.take();
    // written while the answers are read: a pipe holds far less than a revision
    let writer = std::thread::spawn(move || {
        if let Some(s) = stdin.as_mut() {
            let _ = s.write_all(ids.as_bytes());
        }
        drop(stdin);
    });
    let mut out = std::io::BufReader::new(child.stdout.take().ok_or("git cat-file")?);
    for (_, path) in &wanted {
        let mut header = String::new();
        if out.read_line(&mut header).unwrap_or(0) == 0 {
            break;
        }
        // "ID TYPE SIZE", or "ID missing"
        let Some(size) = header
            .split_whitespace()
            .nth(2)
            .and_then(|s| s.parse::<u64>().ok())
            .filter(|&s| s <= MAX_REVISION_FILE)
        else {
            continue;
        };
        let mut bytes = Vec::with_capacity(size as usize);
        if (&mut out).take(size + 1).read_to_end(&mut bytes).is_err() {
            break;
        }
        bytes.truncate(size as usize);
        files.add(path.clone(), bytes);
    }
    let _ = writer.join();
    let _ = child.wait();
    Ok(files)
}

/// The drawings (`*.dxf`, `*.mpath`) git lists as changed between the revisions (or the
/// revision and the working tree), renames paired: (old file, new file).
fn changed_drawings(
    from: &str,
    to: Option<&str>,
    lang: Lang,
) -> Result<Vec<(PathBuf, PathBuf)>, String> {
    let top = git(&["rev-parse", "--show-toplevel"], lang)?;
    let top = PathBuf::from(String::from_utf8_lossy(&top).trim().to_string());
    let mut args = vec!["diff", "--name-status", "-M", "-z", from];
    args.extend(to);
    args.extend(["--", "*.dxf", "*.DXF", "*.mpath"]);
    let listed = git(&args, lang)?;
    let fields: Vec<String> = listed
        .split(|&b| b == 0)
        .map(|f| String::from_utf8_lossy(f).into_owned())
        .collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < fields.len() {
        let status = &fields[i];
        if status.is_empty() {
            break;
        }
        if status.starts_with('R') || status.starts_with('C') {
            if let (Some(a), Some(b)) = (fields.get(i + 1), fields.get(i + 2)) {
                out.push((top.join(a), top.join(b)));
            }
            i += 3;
        } else {
            if let Some(a) = fields.get(i + 1) {
                out.push((top.join(a), top.join(a)));
            }
            i += 2;
        }
    }
    Ok(out)
}

fn git(args: &[&str], lang: Lang) -> Result<Vec<u8>, String> {
    let o = Command::new("git")
        .args(args)
        .output()
        .map_err(|e| cannot_read(Path::new("git"), e, lang))?;
    if !o.status.success() {
        return Err(format!(
            "{}: git {}: {}",
            report::severity_word(millpath_core::diag::Severity::Error, lang),
            args.join(" "),
            String::from_utf8_lossy(&o.stderr).trim()
        ));
    }
    Ok(o.stdout)
}
