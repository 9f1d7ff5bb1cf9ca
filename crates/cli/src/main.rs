//! The `millpath` command line.

#[macro_use]
mod out;
mod compat;
mod config;
mod png;
mod report;
mod verify;
mod workers;
mod write;

#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

use clap::{Parser, Subcommand, ValueEnum};
use millpath_core::diag::{Diagnostic, Diags, Msg, Origin, Severity};
use millpath_core::probe::adjustz;
use millpath_core::{compile_file, complete_input, Lang, OsFileSystem, Session, Settings};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

fn banner() -> String {
    millpath_core::banner()
}

#[derive(Parser)]
#[command(
    name = "millpath",
    version,
    about = "Compiles hand-drawn CNC milling paths (DXF or .mpath) to G-code"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(clap::Args, Clone, Default)]
struct MachineArgs {
    /// Feed for milling moves, mm/min (or `feed` in millpath.toml)
    #[arg(long, short = 'f')]
    feed: Option<f64>,
    /// Sweep speed for time estimates, mm/min (or `sweep_speed`)
    #[arg(long, short = 'v')]
    sweep_speed: Option<f64>,
    /// Sweep height of the top-level path, mm (or `sweep_height`)
    #[arg(long, short = 's')]
    sweep_height: Option<f64>,
    /// Probe feed, mm/min (default: the feed)
    #[arg(long, short = 'z')]
    probe_feed: Option<f64>,
    /// Further directory to search for subpaths (repeatable)
    #[arg(long = "search-dir", short = 'd')]
    search_dirs: Vec<PathBuf>,
    /// Path-name pattern
    #[arg(long)]
    path_pattern: Option<String>,
    /// File-name pattern
    #[arg(long)]
    file_pattern: Option<String>,
    /// PARENT:CHILD — paths matching PARENT may only embed subpaths matching CHILD
    #[arg(long = "restrict", short = 'e')]
    restrictions: Vec<String>,
    /// Show which element each text matching REGEX was assigned to
    #[arg(long)]
    debug_texts: Option<String>,
    /// Message language
    #[arg(long, value_enum)]
    lang: Option<LangArg>,
    /// Settings file (default: nearest millpath.toml above the first input)
    #[arg(long)]
    config: Option<PathBuf>,
    /// Controller the programs are written for (or `dialect`; default reference)
    #[arg(long, value_parser = dialect_parser())]
    dialect: Option<millpath_core::Dialect>,
    /// Plunge feed in linuxcnc/grbl, mm/min (or `plunge_feed`; default half the feed)
    #[arg(long)]
    plunge_feed: Option<f64>,
    /// Spindle speed in linuxcnc/grbl: M3 S… at the start, M5 at the end (or `spindle_rpm`)
    #[arg(long)]
    spindle_rpm: Option<f64>,
    /// Seconds to wait after the spindle start (or `spindle_dwell`; default 2)
    #[arg(long)]
    spindle_dwell: Option<f64>,
    /// Read polylines, blocks, line-type names of other CAD programs and $INSUNITS (or
    /// `input = "extended"`; default: as PathDxf2GCode, with a warning for what it ignores)
    #[arg(long)]
    extended: bool,
}

/// The settings the conversions use: path and file names, the message language.
#[derive(clap::Args, Clone, Default)]
struct NameArgs {
    /// Path-name pattern
    #[arg(long)]
    path_pattern: Option<String>,
    /// File-name pattern
    #[arg(long)]
    file_pattern: Option<String>,
    /// Message language
    #[arg(long, value_enum)]
    lang: Option<LangArg>,
    /// Settings file (default: nearest millpath.toml above the input)
    #[arg(long)]
    config: Option<PathBuf>,
    /// Polylines and blocks become plain elements (or `input = "extended"`)
    #[arg(long)]
    extended: bool,
}

impl NameArgs {
    fn machine(&self) -> MachineArgs {
        MachineArgs {
            path_pattern: self.path_pattern.clone(),
            file_pattern: self.file_pattern.clone(),
            lang: self.lang,
            config: self.config.clone(),
            extended: self.extended,
            ..MachineArgs::default()
        }
    }
}

/// `-o -` means standard output.
fn stdout_dash(output: Option<PathBuf>) -> Option<PathBuf> {
    output.filter(|p| p.as_os_str() != "-")
}

fn dialect_parser() -> impl clap::builder::TypedValueParser<Value = millpath_core::Dialect> {
    use clap::builder::TypedValueParser;
    let names = millpath_core::Dialect::ALL.map(|d| d.name());
    clap::builder::PossibleValuesParser::new(names)
        .map(|s| millpath_core::Dialect::from_name(&s).unwrap_or_default())
}

#[derive(Clone, Copy, ValueEnum)]
enum LangArg {
    En,
    De,
}

#[derive(Clone, Copy, ValueEnum, Default, PartialEq)]
enum Format {
    #[default]
    Human,
    Json,
    Github,
    Sarif,
}

#[derive(Clone, Copy, ValueEnum, Default, PartialEq)]
enum DialectArg {
    #[default]
    Reference,
    Linuxcnc,
    Grbl,
}

#[derive(Clone, Copy, ValueEnum, Default, PartialEq)]
enum VerifyFormat {
    #[default]
    Human,
    Json,
}

#[derive(Subcommand)]
enum Command {
    /// Compile path drawings (DXF or .mpath) to G-code (one path per file; a folder: every
    /// drawing below it)
    Compile {
        #[command(flatten)]
        machine: MachineArgs,
        /// Drawings (.dxf or .mpath; a name without extension gets .dxf) or folders
        #[arg(required = true)]
        files: Vec<String>,
    },
    /// Check every path of every drawing, DXF or .mpath (folders: all *.dxf and *.mpath
    /// below); writes nothing
    Check {
        #[command(flatten)]
        machine: MachineArgs,
        #[arg(long, value_enum, default_value = "human")]
        format: Format,
        /// No progress bar (it is shown only on a terminal, for many files)
        #[arg(long, short = 'q')]
        quiet: bool,
        /// Drawings (.dxf or .mpath) or folders
        #[arg(required = true)]
        paths: Vec<PathBuf>,
    },
    /// Check G-code programs independently of the compiler: rapids into material, feeds,
    /// arcs, numbers (exit 1 on any error)
    Verify {
        /// Whose feed-rate rules apply
        #[arg(long, value_enum, default_value = "reference")]
        dialect: DialectArg,
        /// Material top T, mm (default: the program's (MILLPATH-STOCK …) comment)
        #[arg(long, allow_hyphen_values = true)]
        top: Option<f64>,
        /// Tool diameter O, mm
        #[arg(long)]
        tool: Option<f64>,
        /// Deepest drawn depth, mm: cuts below it are errors
        #[arg(long, allow_hyphen_values = true)]
        bottom: Option<f64>,
        #[arg(long, value_enum)]
        lang: Option<LangArg>,
        #[arg(long, value_enum, default_value = "human")]
        format: VerifyFormat,
        #[arg(required = true)]
        files: Vec<PathBuf>,
    },
    /// Turn NAME_Clean.gcode and the measured NAME_Z.txt into NAME_Milling.gcode
    AdjustZ {
        /// Largest allowed difference between measured and nominal height, mm
        #[arg(long, short = 'm')]
        max: f64,
        #[arg(long, value_enum)]
        lang: Option<LangArg>,
        #[arg(required = true)]
        files: Vec<String>,
    },
    /// Print a DXF drawing as MillPath text (usable as a git textconv driver)
    Dxf2text {
        file: PathBuf,
        /// Write to this file instead of standard output (`-`: standard output)
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// As git's textconv driver: an unreadable drawing gives an error line as its text
        /// (exit 0), so that `git diff` goes on
        #[arg(long)]
        textconv: bool,
        #[command(flatten)]
        names: NameArgs,
    },
    /// Write MillPath text as a DXF drawing
    Text2dxf {
        file: PathBuf,
        /// The DXF file to write (default: FILE with .dxf; `-`: standard output)
        #[arg(short, long)]
        output: Option<PathBuf>,
        #[command(flatten)]
        names: NameArgs,
    },
    /// Format MillPath files in place (directories: all *.mpath below)
    Fmt {
        /// Only check: exit 1 and list the files that are not formatted
        #[arg(long)]
        check: bool,
        #[arg(required = true)]
        paths: Vec<PathBuf>,
    },
    /// Draw the toolpath of a path: a standalone HTML page (3-D viewer), an SVG or a PNG top view
    Render {
        file: PathBuf,
        /// The path to draw (default: the first path of the file)
        #[arg(long)]
        path: Option<String>,
        /// Write the HTML page here (default when no --svg: FILE_toolpath.html)
        #[arg(long)]
        html: Option<PathBuf>,
        /// Write an SVG drawing here
        #[arg(long)]
        svg: Option<PathBuf>,
        /// Write a PNG picture of the top view here (no browser needed)
        #[arg(long)]
        png: Option<PathBuf>,
    },
    /// Language server over standard input and output (for editors)
    Lsp {
        /// Accepted for editor compatibility; stdio is the only transport
        #[arg(long)]
        stdio: bool,
    },
    /// Drop-in replacement for the PathDxf2GCode command line
    #[command(disable_help_flag = true)]
    Pathdxf2gcode {
        #[arg(trailing_var_arg = true, allow_hyphen_values = true)]
        args: Vec<String>,
    },
    /// Drop-in replacement for the PathGCodeAdjustZ command line
    #[command(disable_help_flag = true)]
    Pathgcodeadjustz {
        #[arg(trailing_var_arg = true, allow_hyphen_values = true)]
        args: Vec<String>,
    },
}

/// Tunes memory for a command that runs a few milliseconds: no transparent huge pages. The
/// allocator asks for them (its arena is advised as huge pages), which serves the language
/// server's large analyses (a fifth faster on a 20,000-element chain) but makes a short
/// `check` zero 2 MiB on every first touch (about 9 times, 1 ms of its 7).
fn short_lived() {
    #[cfg(target_os = "linux")]
    // SAFETY: PR_SET_THP_DISABLE takes plain integers and touches no memory of ours; an
    // error (an old kernel) leaves the setting as it was, which is harmless.
    unsafe {
        libc::prctl(libc::PR_SET_THP_DISABLE, 1, 0, 0, 0);
    }
}

fn main() -> ExitCode {
    if std::env::args_os().nth(1).is_none_or(|c| c != "lsp") {
        short_lived();
    }
    let raw: Vec<String> = std::env::args().collect();
    // The compatibility commands take the reference's command line unchanged.
    match raw.get(1).map(String::as_str) {
        Some("pathdxf2gcode") => return leave(run_dxf2gcode(&raw[2..])),
        Some("pathgcodeadjustz") => return leave(run_adjustz_compat(&raw[2..])),
        _ => {}
    }
    let cli = Cli::parse();
    let code = match cli.command {
        Command::Compile { machine, files } => run_compile(&machine, &files),
        Command::Check {
            machine,
            format,
            quiet,
            paths,
        } => run_check(&machine, format, quiet, &paths),
        Command::Verify {
            dialect,
            top,
            tool,
            bottom,
            lang,
            format,
            files,
        } => verify::run(&verify::Args {
            dialect: match dialect {
                DialectArg::Reference => millpath_verify::Dialect::Reference,
                DialectArg::Linuxcnc => millpath_verify::Dialect::LinuxCnc,
                DialectArg::Grbl => millpath_verify::Dialect::Grbl,
            },
            top,
            tool,
            bottom,
            lang: match lang {
                Some(LangArg::De) => millpath_verify::Lang::De,
                _ => millpath_verify::Lang::En,
            },
            json: format == VerifyFormat::Json,
            files,
        }),
        Command::AdjustZ { max, lang, files } => {
            let lang = lang.map_or(Lang::En, to_lang);
            run_adjustz(max, None, lang, &files, false)
        }
        Command::Dxf2text {
            file,
            output,
            textconv,
            names,
        } => run_dxf2text(&file, stdout_dash(output), textconv, &names.machine()),
        Command::Text2dxf {
            file,
            output,
            names,
        } => run_text2dxf(&file, output.as_deref(), &names.machine()),
        Command::Fmt { check, paths } => run_fmt(check, &paths),
        Command::Render {
            file,
            path,
            html,
            svg,
            png,
        } => run_render(&file, path.as_deref(), html, svg, png),
        Command::Lsp { .. } => millpath_lsp::run_stdio(),
        Command::Pathdxf2gcode { args } => run_dxf2gcode(&args),
        Command::Pathgcodeadjustz { args } => run_adjustz_compat(&args),
    };
    leave(code)
}

/// Ends the process with `code` once a command is done. On Linux it skips the exit handlers:
/// all they do is mimalloc handing its pages back (a dozen `madvise` calls) right before the
/// kernel frees the whole address space anyway.
fn leave(code: u8) -> ExitCode {
    #[cfg(target_os = "linux")]
    {
        use std::io::Write;
        // a closed pipe is no reason to change the exit status
        let _ = std::io::stdout().lock().flush();
        let _ = std::io::stderr().lock().flush();
        // SAFETY: `_exit` takes a plain integer and ends the process. Every file a command
        // writes is flushed and closed when its writer drops, before the command returns;
        // the only buffer left, stdout's, was flushed above.
        unsafe { libc::_exit(i32::from(code)) }
    }
    #[cfg(not(target_os = "linux"))]
    ExitCode::from(code)
}

fn to_lang(l: LangArg) -> Lang {
    match l {
        LangArg::En => Lang::En,
        LangArg::De => Lang::De,
    }
}

/// Writes the outputs; "Writing …" is printed only for a file that was written. False when
/// any write failed.
fn write_outputs(outputs: &[millpath_core::OutputFile], lang: Lang, diags: &mut Diags) -> bool {
    let verb = if lang == Lang::De {
        "Schreiben von"
    } else {
        "Writing"
    };
    let mut ok = true;
    for o in outputs {
        match write::write_atomic(&o.path, &o.content) {
            Ok(()) => eprintln!("---- {verb} {}", o.path.display()),
            Err(e) => {
                ok = false;
                diags.error(
                    Msg::CannotWrite,
                    Origin::Options,
                    millpath_core::args![o.path.display(), e],
                );
            }
        }
    }
    ok
}

fn print_stats(outcome: &millpath_core::FileOutcome, lang: Lang) {
    for (_, s) in &outcome.stats {
        let l = s.lines(lang);
        eprintln!("  {};  {};", l[0], l[1]);
        eprintln!("  {};  {};  {};", l[2], l[3], l[4]);
        if let Some(m) = s.model_line(lang) {
            eprintln!("  {m}");
        }
    }
}

fn flush_info(session: &mut Session) {
    for line in session.info.drain(..) {
        eprintln!("{line}");
    }
}

/// `millpath pathdxf2gcode …`: the reference command line.
fn run_dxf2gcode(args: &[String]) -> u8 {
    let parsed = compat::parse(args, compat::Tool::Dxf2GCode);
    let lang = parsed.settings.lang;
    eprintln!("---- {} (PathDxf2GCode-compatible)", banner());
    eprintln!();
    if args.is_empty() || parsed.help || !parsed.errors.is_empty() {
        for e in &parsed.errors {
            eprintln!("{}", e.reference_line(lang));
        }
        eprintln!();
        eprintln!("{}", compat::help_dxf2gcode(lang));
        return 2;
    }
    if parsed.files.is_empty() {
        eprintln!(
            "{}",
            Diagnostic::error(Msg::NoDxfFiles, Origin::Options, vec![]).reference_line(lang)
        );
        return 3;
    }
    let fs = OsFileSystem;
    let mut session = match Session::new(parsed.settings, &fs) {
        Ok(s) => s,
        Err(errs) => {
            for e in errs {
                eprintln!("{}", e.reference_line(lang));
            }
            eprintln!();
            eprintln!("{}", compat::help_dxf2gcode(lang));
            return 2;
        }
    };
    let mut write_errors = Diags::default();
    for f in &parsed.files {
        let input = complete_input(f);
        let outcome = compile_file(&mut session, &input, &banner());
        flush_info(&mut session);
        if write_outputs(&outcome.outputs, lang, &mut write_errors) {
            print_stats(&outcome, lang);
        }
    }
    let mut failed = false;
    // the reference prints no word on entity order, nor on the entities it ignores: those
    // warnings are for check, compile and the editor
    let ours = |d: &&Diagnostic| {
        !matches!(
            d.msg,
            Msg::OrderDecides
                | Msg::OrderDecidesText
                | Msg::OrderDecidesNoPin
                | Msg::IgnoredEntity
                | Msg::TextTakenFirst
        )
    };
    for d in session
        .diags
        .list
        .iter()
        .chain(write_errors.list.iter())
        .filter(ours)
    {
        eprintln!("{}", d.reference_line(lang));
        failed |= d.severity == Severity::Error;
    }
    u8::from(failed)
}

/// Settings: millpath.toml (nearest above the first input, or --config), then the flags.
fn settings_for(
    m: &MachineArgs,
    first_input: Option<&Path>,
    require_machine: bool,
) -> Result<Settings, String> {
    let mut s = Settings::default();
    let mut have = config::Have::default();
    let cfg_path = m
        .config
        .clone()
        .or_else(|| first_input.and_then(config::find));
    if let Some(p) = cfg_path {
        config::load(&p)?.apply(&mut s, &mut have);
    }
    if let Some(v) = m.feed {
        s.feed = v;
        have.feed = true;
    }
    if let Some(v) = m.sweep_speed {
        s.sweep_speed = v;
        have.sweep_speed = true;
    }
    if let Some(v) = m.sweep_height {
        s.sweep_height = v;
        have.sweep_height = true;
    }
    if m.probe_feed.is_some() {
        s.probe_feed = m.probe_feed;
    }
    s.search_dirs.extend(m.search_dirs.iter().cloned());
    if let Some(p) = &m.path_pattern {
        s.path_pattern = p.clone();
    }
    if let Some(p) = &m.file_pattern {
        s.file_pattern = p.clone();
    }
    for r in &m.restrictions {
        let (a, b) = r
            .split_once(':')
            .ok_or_else(|| format!("--restrict {r}: expected PARENT:CHILD"))?;
        s.restrictions.push((a.to_string(), b.to_string()));
    }
    s.debug_pattern = m.debug_texts.clone();
    if let Some(d) = m.dialect {
        s.dialect = d;
    }
    if m.plunge_feed.is_some() {
        s.plunge_feed = m.plunge_feed;
    }
    if m.spindle_rpm.is_some() {
        s.spindle_rpm = m.spindle_rpm;
    }
    if let Some(v) = m.spindle_dwell {
        s.spindle_dwell = v;
    }
    if let Some(l) = m.lang {
        s.lang = to_lang(l);
    }
    if m.extended {
        s.input = millpath_core::InputMode::Extended;
    }
    if require_machine {
        let missing: Vec<&str> = [
            ("--feed / feed", have.feed),
            ("--sweep-speed / sweep_speed", have.sweep_speed),
            ("--sweep-height / sweep_height", have.sweep_height),
        ]
        .iter()
        .filter(|(_, h)| !h)
        .map(|(n, _)| *n)
        .collect();
        if !missing.is_empty() {
            return Err(match s.lang {
                Lang::En => format!(
                    "missing machine settings: {} (give them as options or in millpath.toml)",
                    missing.join(", ")
                ),
                Lang::De => format!(
                    "Maschinenwerte fehlen: {} (als Option oder in millpath.toml angeben)",
                    missing.join(", ")
                ),
            });
        }
        for (name, v) in [
            ("feed", s.feed),
            ("sweep speed", s.sweep_speed),
            ("sweep height", s.sweep_height),
        ] {
            if v.is_nan() || v <= 0.0 {
                return Err(format!("{name} must be > 0 (is {v})"));
            }
        }
    }
    Ok(s)
}

fn lang_of(m: &MachineArgs) -> Lang {
    m.lang.map_or(Lang::En, to_lang)
}

fn print_human(diags: &[Diagnostic], lang: Lang) {
    let color = report::use_color(std::io::IsTerminal::is_terminal(&std::io::stderr()));
    for d in diags {
        eprintln!("{}", report::human_rich(d, lang, color));
    }
}

/// The files `compile` compiles: a folder gives every drawing below it (never `folder.dxf`);
/// a name without extension gets `.dxf` as in the reference.
fn compile_inputs(files: &[String]) -> Result<Vec<PathBuf>, String> {
    let mut inputs = Vec::new();
    for f in files {
        let p = Path::new(f);
        if p.is_dir() {
            let before = inputs.len();
            collect_files(&[p.to_path_buf()], is_drawing, &mut inputs);
            if inputs.len() == before {
                return Err(f.clone());
            }
        } else {
            inputs.push(complete_input(f));
        }
    }
    Ok(inputs)
}

fn run_compile(m: &MachineArgs, files: &[String]) -> u8 {
    let inputs = match compile_inputs(files) {
        Ok(i) => i,
        Err(dir) => {
            eprintln!(
                "{}",
                match lang_of(m) {
                    Lang::En => format!("error: no drawings (*.dxf, *.mpath) found in {dir}"),
                    Lang::De =>
                        format!("Fehler: keine Zeichnungen (*.dxf, *.mpath) in {dir} gefunden"),
                }
            );
            return 3;
        }
    };
    let settings = match settings_for(m, inputs.first().map(PathBuf::as_path), true) {
        Ok(s) => s,
        Err(e) => {
            eprintln!(
                "{}: {e}",
                report::severity_word(Severity::Error, lang_of(m))
            );
            return 2;
        }
    };
    let lang = settings.lang;
    let fs = OsFileSystem;
    let mut session = match Session::new(settings, &fs) {
        Ok(s) => s,
        Err(errs) => {
            print_human(&errs, lang);
            return 2;
        }
    };
    let mut write_errors = Diags::default();
    for input in inputs {
        let outcome = compile_file(&mut session, &input, &banner());
        flush_info(&mut session);
        if write_outputs(&outcome.outputs, lang, &mut write_errors) {
            print_stats(&outcome, lang);
            if let (Some(v), false) = (outcome.removed_volume, outcome.outputs.is_empty()) {
                // not in pathdxf2gcode's output, which stays the reference's
                let label = if lang == Lang::De {
                    "Abgetragenes Volumen"
                } else {
                    "Removed volume"
                };
                eprintln!("  {label}: {v:.0} mm³");
            }
        }
    }
    let all: Vec<Diagnostic> = session
        .diags
        .list
        .iter()
        .chain(write_errors.list.iter())
        .cloned()
        .collect();
    let all = report::tidy(all);
    print_human(&all, lang);
    u8::from(all.iter().any(|d| d.severity == Severity::Error))
}

/// Files given, and below directories given the files `accept` takes, sorted.
fn collect_files(paths: &[PathBuf], accept: fn(&Path) -> bool, out: &mut Vec<PathBuf>) {
    for p in paths {
        if p.is_dir() {
            let mut entries: Vec<PathBuf> = std::fs::read_dir(p)
                .map(|r| r.filter_map(|e| e.ok().map(|e| e.path())).collect())
                .unwrap_or_default();
            entries.sort();
            let (dirs, files): (Vec<PathBuf>, Vec<PathBuf>) =
                entries.into_iter().partition(|e| e.is_dir());
            out.extend(files.into_iter().filter(|f| accept(f)));
            collect_files(&dirs, accept, out);
        } else {
            out.push(p.clone());
        }
    }
}

fn is_drawing(f: &Path) -> bool {
    f.extension().is_some_and(|e| e.eq_ignore_ascii_case("dxf"))
        || millpath_core::load::fs::is_text_file(f)
}

/// What checking one file gives: its progress lines and its diagnostics, in order.
struct FileCheck {
    info: Vec<String>,
    diags: Vec<Diagnostic>,
}

/// The session that checks one file. Each file gets its own (files are checked on their own,
/// like separate lint targets), built inside the worker thread that checks the file.
fn check_session<'a>(
    settings: &Settings,
    fs: &'a OsFileSystem,
) -> Result<Session<'a>, Vec<Diagnostic>> {
    Session::new(settings.clone(), fs)
}

/// Checks one file in a session of its own.
fn check_file(settings: &Settings, input: &Path) -> Result<FileCheck, Vec<Diagnostic>> {
    let fs = OsFileSystem;
    let mut session = check_session(settings, &fs)?;
    compile_file(&mut session, input, &banner());
    Ok(FileCheck {
        info: std::mem::take(&mut session.info),
        diags: std::mem::take(&mut session.diags.list),
    })
}

/// From this many files on, `check` shows a progress bar (on a terminal, without `--quiet`).
const PROGRESS_MIN_FILES: usize = 50;

/// Checks every input on all cores; the results come back in input order.
fn check_all(
    settings: &Settings,
    inputs: &[PathBuf],
    quiet: bool,
) -> Vec<Result<FileCheck, Vec<Diagnostic>>> {
    use rayon::prelude::*;
    use std::io::IsTerminal;
    let bar = if !quiet && inputs.len() >= PROGRESS_MIN_FILES && std::io::stderr().is_terminal() {
        let bar = indicatif::ProgressBar::new(inputs.len() as u64);
        if let Ok(style) = indicatif::ProgressStyle::with_template(
            "{bar:40} {pos}/{len} files  {elapsed_precise} (eta {eta})",
        ) {
            bar.set_style(style);
        }
        bar
    } else {
        indicatif::ProgressBar::hidden()
    };
    let one = |input: &PathBuf| {
        let r = check_file(settings, input);
        bar.inc(1);
        r
    };
    // no thread to start for one file
    let pool = (inputs.len() > 1).then(workers::check_pool);
    let results = match pool {
        Some(Ok(pool)) => pool.install(|| inputs.par_iter().map(one).collect()),
        _ => inputs.iter().map(one).collect(),
    };
    bar.finish_and_clear();
    results
}

fn run_check(m: &MachineArgs, format: Format, quiet: bool, paths: &[PathBuf]) -> u8 {
    let mut inputs = Vec::new();
    collect_files(paths, is_drawing, &mut inputs);
    let mut settings = match settings_for(m, inputs.first().map(PathBuf::as_path), false) {
        Ok(s) => s,
        Err(e) => {
            eprintln!(
                "{}: {e}",
                report::severity_word(Severity::Error, lang_of(m))
            );
            return 2;
        }
    };
    settings.check = true;
    let lang = settings.lang;
    if inputs.is_empty() {
        // like the reference's "no files" (exit 3)
        let shown: Vec<String> = paths.iter().map(|p| p.display().to_string()).collect();
        eprintln!(
            "{}",
            match lang {
                Lang::En => format!(
                    "error: no drawings (*.dxf, *.mpath) found in {}",
                    shown.join(", ")
                ),
                Lang::De => format!(
                    "Fehler: keine Zeichnungen (*.dxf, *.mpath) in {} gefunden",
                    shown.join(", ")
                ),
            }
        );
        return 3;
    }
    let mut all = Vec::new();
    // Printed in input order, whatever order the workers finished in; gathered first and
    // written at once (a write per line cost more than reading a small drawing).
    let mut info = String::new();
    for result in check_all(&settings, &inputs, quiet) {
        match result {
            Ok(file) => {
                if format == Format::Human {
                    for line in file.info {
                        info.push_str(&line);
                        info.push('\n');
                    }
                }
                all.extend(file.diags);
            }
            Err(errs) => {
                eprint!("{info}");
                print_human(&errs, lang);
                return 2;
            }
        }
    }
    eprint!("{info}");
    let all = report::tidy(all);
    let errors = all.iter().filter(|d| d.severity == Severity::Error).count();
    match format {
        Format::Human => {
            // diagnostics and the summary are the report (stdout); progress lines stay on stderr
            let color = report::use_color(std::io::IsTerminal::is_terminal(&std::io::stdout()));
            let mut report = String::new();
            for d in &all {
                report.push_str(&report::human_rich(d, lang, color));
                report.push('\n');
            }
            out::write(&report);
            let warnings = all.len() - errors;
            outln!(
                "{}",
                match lang {
                    Lang::En => format!(
                        "checked {} file(s): {errors} error(s), {warnings} warning(s)",
                        inputs.len()
                    ),
                    Lang::De => format!(
                        "{} Datei(en) geprüft: {errors} Fehler, {warnings} Warnung(en)",
                        inputs.len()
                    ),
                }
            );
        }
        Format::Json => {
            let v: Vec<serde_json::Value> =
                all.iter().map(|d| report::json_value(d, lang)).collect();
            outln!("{}", serde_json::to_string_pretty(&serde_json::json!({ "files": inputs.len(), "errors": errors, "diagnostics": v })).unwrap_or_default());
        }
        Format::Github => {
            let lines: String = all
                .iter()
                .map(|d| format!("{}\n", report::github(d, lang)))
                .collect();
            out::write(&lines);
        }
        Format::Sarif => {
            outln!(
                "{}",
                serde_json::to_string_pretty(&report::sarif(&all, lang)).unwrap_or_default()
            );
        }
    }
    u8::from(errors > 0)
}

fn run_adjustz_compat(args: &[String]) -> u8 {
    let parsed = compat::parse(args, compat::Tool::AdjustZ);
    let lang = parsed.settings.lang;
    eprintln!("---- {} (PathGCodeAdjustZ-compatible)", banner());
    if args.is_empty() || parsed.help || !parsed.errors.is_empty() {
        for e in &parsed.errors {
            eprintln!("{}", e.reference_line(lang));
        }
        eprintln!();
        eprintln!("{}", compat::help_adjustz(lang));
        return 2;
    }
    if parsed.files.is_empty() {
        eprintln!(
            "{}",
            Diagnostic::error(Msg::NoDxfFiles, Origin::Options, vec![]).reference_line(lang)
        );
        return 3;
    }
    run_adjustz(
        parsed.m.unwrap_or(0.0),
        parsed.x.as_deref(),
        lang,
        &parsed.files,
        true,
    )
}

fn run_adjustz(
    max: f64,
    x: Option<&str>,
    lang: Lang,
    files: &[String],
    reference_lines: bool,
) -> u8 {
    let print = |d: &Diagnostic| {
        if reference_lines {
            eprintln!("{}", d.reference_line(lang));
        } else {
            eprintln!("{}", report::human(d, lang));
        }
    };
    let opt = if reference_lines {
        adjustz::MaxOption::Slash
    } else {
        adjustz::MaxOption::Long
    };
    // `--max NaN` or `inf` would switch the limit off: an option error, like a missing /m
    if let Some(d) = adjustz::check_max(max, &max.to_string(), opt) {
        print(&d);
        return 2;
    }
    let mut diags = Diags::default();
    let show = x.and_then(|p| regex::Regex::new(p).ok());
    let verb = |en: &str, de: &str| {
        if lang == Lang::De {
            de.to_string()
        } else {
            en.to_string()
        }
    };
    let read = |path: &str, diags: &mut Diags| {
        eprintln!("---- {} {path}", verb("Reading", "Einlesen von"));
        std::fs::read_to_string(path)
            .map_err(|e| {
                diags.error(
                    Msg::CannotRead,
                    Origin::Input,
                    millpath_core::args![path, e],
                );
            })
            .ok()
    };
    let mut planned = Vec::new();
    // every part: its inputs and its output, written or not
    let mut parts: Vec<(String, String, PathBuf)> = Vec::new();
    for f in files {
        let base = adjustz::base_path(f);
        let z_path = format!("{base}_Z.txt");
        let clean_path = format!("{base}_Clean.gcode");
        let milling = PathBuf::from(format!("{base}_Milling.gcode"));
        parts.push((z_path.clone(), clean_path.clone(), milling.clone()));
        let z_text = read(&z_path, &mut diags);
        let clean = read(&clean_path, &mut diags);
        let (Some(z_text), Some(clean)) = (z_text, clean) else {
            continue;
        };
        if let Some(re) = &show {
            for line in clean.lines().filter(|l| re.is_match(l)) {
                eprintln!("---- {line}");
            }
        }
        if let Some(content) =
            adjustz::adjust(&clean, &clean_path, &z_text, &z_path, max, opt, &mut diags)
        {
            planned.push((milling, content));
        }
    }
    // nothing is written when any file had an error
    let mut written = Vec::new();
    if !diags.has_errors() {
        for (path, content) in planned {
            eprintln!(
                "---- {} {}",
                verb("Writing", "Schreiben von"),
                path.display()
            );
            match write::write_atomic(&path, &content) {
                Ok(()) => written.push(path),
                Err(e) => diags.error(
                    Msg::CannotWrite,
                    Origin::Options,
                    millpath_core::args![path.display(), e],
                ),
            }
        }
    }
    // a refusal must not leave an older _Milling.gcode looking like the result
    for (z_path, clean_path, milling) in &parts {
        if !written.contains(milling) {
            remove_stale_milling(milling, &[clean_path, z_path], &mut diags);
        }
    }
    for d in &diags.list {
        print(d);
    }
    u8::from(diags.has_errors())
}

/// Removes `milling` when it is not newer than one of its existing `inputs` (it was not made
/// from them), with a warning; an unknown modification time counts as not newer.
fn remove_stale_milling(milling: &Path, inputs: &[&String], diags: &mut Diags) {
    let modified = |p: &Path| std::fs::metadata(p).and_then(|m| m.modified());
    if !milling.is_file() {
        return;
    }
    let own = modified(milling).ok();
    let newer_input = inputs.iter().find(|input| {
        let path = Path::new(input.as_str());
        path.is_file()
            && match (own, modified(path)) {
                (Some(own), Ok(t)) => t >= own,
                _ => true,
            }
    });
    let Some(input) = newer_input else {
        return;
    };
    match std::fs::remove_file(milling) {
        Ok(()) => diags.push(Diagnostic::warning(
            Msg::StaleMillingRemoved,
            Origin::Input,
            millpath_core::args![milling.display(), input],
        )),
        Err(e) => diags.error(
            Msg::CannotRemove,
            Origin::Input,
            millpath_core::args![milling.display(), e],
        ),
    }
}

fn patterns_for(
    m: &MachineArgs,
    input: &Path,
) -> Result<(std::sync::Arc<millpath_core::load::names::Patterns>, Lang), String> {
    let s = settings_for(m, Some(input), false)?;
    let p = millpath_core::load::names::Patterns::shared(&s.path_pattern, &s.file_pattern)
        .map_err(|(c, p, e)| format!("invalid /{c} pattern '{p}': {e}"))?;
    Ok((p, s.lang))
}

/// Writes `content` to `output`, or to standard output.
fn emit(output: Option<&Path>, content: &str, lang: Lang) -> u8 {
    match output {
        Some(p) => match write::write_atomic(p, content) {
            Ok(()) => 0,
            Err(e) => {
                let d = Diagnostic::error(
                    Msg::CannotWrite,
                    Origin::Options,
                    millpath_core::args![p.display(), e],
                );
                eprintln!("{}", report::human(&d, lang));
                1
            }
        },
        None => {
            out::write(content);
            0
        }
    }
}

/// Settings, patterns and the input bytes of a conversion; `Err(exit status)` after reporting.
fn conversion_input(
    file: &Path,
    m: &MachineArgs,
) -> Result<
    (
        std::sync::Arc<millpath_core::load::names::Patterns>,
        Lang,
        Vec<u8>,
    ),
    u8,
> {
    let (patterns, lang) = patterns_for(m, file).map_err(|e| {
        eprintln!("error: {e}");
        2
    })?;
    let bytes = std::fs::read(file).map_err(|e| {
        let d = Diagnostic::error(
            Msg::CannotRead,
            Origin::Input,
            millpath_core::args![file.display(), e],
        );
        eprintln!("{}", report::human(&d, lang));
        1
    })?;
    Ok((patterns, lang, bytes))
}

fn run_dxf2text(file: &Path, output: Option<PathBuf>, textconv: bool, m: &MachineArgs) -> u8 {
    let output = output.as_deref();
    let (patterns, lang, bytes) = match conversion_input(file, m) {
        Ok(x) => x,
        Err(code) if textconv => {
            // git shows this line as the file's text instead of giving up on the diff
            let what = if lang_of(m) == Lang::De {
                "nicht lesbar"
            } else {
                "unreadable"
            };
            return emit(
                output,
                &format!("# millpath: {} {what}\n", file.display()),
                lang_of(m),
            )
            .max(u8::from(code == 2));
        }
        Err(code) => return code,
    };
    let fref = millpath_core::diag::FileRef::new(file.to_path_buf());
    // conversion_input has already reported settings that do not load
    let input = settings_for(m, Some(file), false).map_or_else(|_| Default::default(), |s| s.input);
    match millpath_core::convert::dxf_to_text(&bytes, &fref, &patterns, input) {
        Ok((text, diags)) => {
            // what the text cannot carry (texts that belong to no element, …) is reported
            print_human(&diags, lang);
            emit(output, &text, lang)
        }
        Err(d) if textconv => {
            // the error as the text (one line per line of the message), exit 0: `git diff`
            // shows what is wrong with the drawing instead of dying
            eprintln!("{}", report::human(&d, lang));
            let text: String = report::human(&d, lang)
                .lines()
                .map(|l| format!("# {l}\n"))
                .collect();
            emit(output, &text, lang)
        }
        Err(d) => {
            eprintln!("{}", report::human(&d, lang));
            1
        }
    }
}

fn run_text2dxf(file: &Path, output: Option<&Path>, m: &MachineArgs) -> u8 {
    let (patterns, lang, bytes) = match conversion_input(file, m) {
        Ok(x) => x,
        Err(code) => return code,
    };
    let src = String::from_utf8_lossy(&bytes);
    let fref = millpath_core::diag::FileRef::new(file.to_path_buf());
    match millpath_core::convert::text_to_dxf(&src, &fref, &patterns) {
        Ok(dxf) => match output {
            Some(o) if o.as_os_str() == "-" => emit(None, &dxf, lang),
            Some(o) => emit(Some(o), &dxf, lang),
            None => emit(Some(&file.with_extension("dxf")), &dxf, lang),
        },
        Err(diags) => {
            print_human(&diags, lang);
            1
        }
    }
}

fn run_fmt(check: bool, paths: &[PathBuf]) -> u8 {
    let mut files = Vec::new();
    collect_files(paths, millpath_core::load::fs::is_text_file, &mut files);
    let mut status = 0;
    for f in files {
        let src = match std::fs::read_to_string(&f) {
            Ok(s) => s,
            Err(e) => {
                eprintln!("error: {}: {e}", f.display());
                status = 1;
                continue;
            }
        };
        let fref = millpath_core::diag::FileRef::new(f.clone());
        match millpath_core::convert::format_text(&src, &fref) {
            Ok(formatted) if formatted == src => {}
            Ok(formatted) => {
                if check {
                    outln!("{}: not formatted", f.display());
                    status = 1;
                } else if let Err(e) = write::write_atomic(&f, &formatted) {
                    eprintln!("error: {}: {e}", f.display());
                    status = 1;
                }
            }
            Err(diags) => {
                print_human(&diags, Lang::En);
                status = 1;
            }
        }
    }
    status
}

fn run_render(
    file: &Path,
    path: Option<&str>,
    html: Option<PathBuf>,
    svg: Option<PathBuf>,
    png: Option<PathBuf>,
) -> u8 {
    let file = complete_input(&file.to_string_lossy());
    let abs = std::fs::canonicalize(&file).unwrap_or_else(|_| file.clone());
    let ws = millpath_ide::Workspace::default();
    // like `compile`: no drawing with placeholder machine settings
    let missing = ws.settings_for(&abs).missing_machine();
    if !missing.is_empty() {
        eprintln!(
            "error: missing machine settings: {} (give them in millpath.toml)",
            missing.join(", ")
        );
        return 2;
    }
    let data = match millpath_ide::toolpath(&ws, &abs, path) {
        Ok(d) => d,
        Err(e) => {
            let lang = ws.settings_for(&abs).settings.lang;
            // say why: a missing or unreadable file, a file that is not a drawing, syntax
            // errors — not only that no path was found
            if let Err(err) = std::fs::read(&file) {
                let d = Diagnostic::error(
                    Msg::CannotRead,
                    Origin::File(millpath_core::diag::FileRef::new(file.clone())),
                    millpath_core::args![file.display(), err],
                );
                eprintln!("{}", report::human(&d, lang));
                return 1;
            }
            let errors: Vec<Diagnostic> = settings_for(&MachineArgs::default(), Some(&file), false)
                .ok()
                .and_then(|mut s| {
                    s.check = true;
                    check_file(&s, &file).ok()
                })
                .map(|c| report::tidy(c.diags))
                .unwrap_or_default()
                .into_iter()
                .filter(|d| d.severity == Severity::Error)
                .collect();
            if errors.is_empty() {
                eprintln!(
                    "{}: {}: {e}",
                    report::severity_word(Severity::Error, lang),
                    file.display()
                );
            } else {
                print_human(&errors, lang);
            }
            return 1;
        }
    };
    let lang = ws.settings_for(&abs).settings.lang;
    let html = html.or_else(|| {
        (svg.is_none() && png.is_none()).then(|| {
            PathBuf::from(format!(
                "{}_toolpath.html",
                file.with_extension("").display()
            ))
        })
    });
    let mut status = 0;
    if let Some(out) = html {
        eprintln!("---- Writing {}", out.display());
        status |= emit(Some(&out), &millpath_ide::toolpath_html(&data), lang);
    }
    if let Some(out) = svg {
        eprintln!("---- Writing {}", out.display());
        status |= emit(Some(&out), &millpath_ide::toolpath_svg(&data), lang);
    }
    if let Some(out) = png {
        eprintln!("---- Writing {}", out.display());
        let written = png::svg_to_png(&millpath_ide::toolpath_svg(&data))
            .and_then(|bytes| write::write_atomic_bytes(&out, &bytes).map_err(|e| e.to_string()));
        if let Err(e) = written {
            eprintln!("error: {}: {e}", out.display());
            status |= 1;
        }
    }
    status
}
