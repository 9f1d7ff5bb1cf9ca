//! The `millpath` command line: parses the arguments and dispatches to `commands/`.

#[macro_use]
mod out;
mod args;
mod claims;
mod clap_de;
mod commands;
mod compat;
mod config;
mod help_de;
mod inputs;
mod interrupt;
mod measured;
mod numbers;
mod other_post;
mod output;
mod overrides;
mod png;
mod read;
mod report;
mod stale;
mod surface_file;
mod verify_clamps;
mod workers;
mod write;

#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

use args::{
    lang_for, stdout_dash, DialectArg, Format, LangArg, MachineArgs, NameArgs, VerifyFormat,
};
use clap::{Parser, Subcommand};
use commands::verify;
use millpath_core::Lang;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

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
        /// Report format: human text, json, github (workflow annotations, paths relative to the
        /// repository) or sarif (code scanning)
        #[arg(long, value_enum, default_value = "human")]
        format: Format,
        /// Print only the report: no progress lines, no progress bar
        #[arg(long, short = 'q')]
        quiet: bool,
        /// Exit 1 when there are more than N warnings, also without errors (as ESLint's;
        /// default: max_warnings of millpath.toml, else no limit)
        #[arg(long, value_name = "N", value_parser = numbers::warning_count, allow_hyphen_values = true)]
        max_warnings: Option<u32>,
        /// Drawings (.dxf or .mpath) or folders
        #[arg(required = true)]
        paths: Vec<PathBuf>,
    },
    /// Check G-code programs independently of the compiler: rapids into material, feeds,
    /// arcs, numbers (exit 1 on any error)
    Verify {
        /// Whose rules apply: feed rates, and how a line is read (a post's family)
        #[arg(long, value_enum, default_value = "reference")]
        dialect: DialectArg,
        /// Material top T, mm (default: the program's (MILLPATH-STOCK …) comment)
        #[arg(long, allow_hyphen_values = true, value_parser = numbers::decimal)]
        top: Option<f64>,
        /// Tool diameter O, mm
        #[arg(long, value_parser = numbers::decimal)]
        tool: Option<f64>,
        /// Deepest drawn depth, mm: cuts below it are errors
        #[arg(long, allow_hyphen_values = true, value_parser = numbers::decimal)]
        bottom: Option<f64>,
        /// Message language (default: English)
        #[arg(long, value_enum)]
        lang: Option<LangArg>,
        /// Report format: human text or json
        #[arg(long, value_enum, default_value = "human")]
        format: VerifyFormat,
        /// Judge the programs against this surface as measured on the machine instead of their
        /// own (MILLPATH-SURFACE …) record: a probe log (LinuxCNC PROBEOPEN, GRBL console with
        /// [PRB:…], x y z lines), a filled-in _Z.txt or an adjusted program
        #[arg(long, value_name = "FILE")]
        surface: Option<String>,
        /// With --surface: largest XY distance, mm, between measurements of one grid line
        #[arg(long, value_name = "MM", default_value_t = millpath_core::probe::adjustz::DEFAULT_TOLERANCE, requires = "surface", value_parser = numbers::decimal)]
        tolerance: f64,
        /// A keep-out box the tool must never touch, mm (repeatable); without --clamp and
        /// --config: the [[clamp]] boxes of the millpath.toml nearest each program
        #[arg(
            long,
            value_name = "NAME,XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX",
            allow_hyphen_values = true
        )]
        clamp: Vec<String>,
        /// Read the [[clamp]] boxes from this millpath.toml
        #[arg(long, value_name = "FILE")]
        config: Option<PathBuf>,
        /// G-code programs to check
        #[arg(required = true)]
        files: Vec<PathBuf>,
    },
    /// Turn NAME_Clean.gcode and the measured NAME_Z.txt into NAME_Milling.gcode
    AdjustZ {
        /// Largest allowed difference between measured and nominal height, mm (no default, also
        /// with --probe-log: a probe that triggered on a chip or on nothing is refused, not milled)
        #[arg(long, short = 'm', value_parser = numbers::decimal)]
        max: f64,
        /// Message language (default: English)
        #[arg(long, value_enum)]
        lang: Option<LangArg>,
        /// Read the measured heights from this log of the controller (LinuxCNC PROBEOPEN,
        /// GRBL console with [PRB:…], x y z lines or a filled-in _Z.txt) instead of NAME_Z.txt's
        /// values; one program only
        #[arg(long, value_name = "FILE")]
        probe_log: Option<String>,
        /// With --probe-log: largest XY distance, mm, between a measurement and its probe point
        #[arg(long, value_name = "MM", default_value_t = millpath_core::probe::adjustz::DEFAULT_TOLERANCE, requires = "probe_log", value_parser = numbers::decimal)]
        tolerance: f64,
        /// The post the programs were written with, a built-in's name or a post file (default:
        /// `post =` or `dialect =` of their millpath.toml); a height map's moves are written in
        /// its words
        #[arg(long, value_name = "NAME|FILE")]
        post: Option<String>,
        /// The probed programs: NAME_Clean.gcode (or NAME; NAME_Z.txt is read beside it)
        #[arg(required = true)]
        files: Vec<String>,
    },
    /// Print a DXF drawing as MillPath text (usable as a git textconv driver)
    Dxf2text {
        /// The DXF drawing to print
        file: PathBuf,
        /// Write to this file instead of standard output (`-`: standard output)
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// As git's textconv driver: an unreadable drawing gives an error line as its text
        /// (exit 0), so that `git diff` goes on
        #[arg(long)]
        textconv: bool,
        /// Replace an existing -o file that is not this drawing's text (edits not written
        /// back would be lost)
        #[arg(long)]
        force: bool,
        #[command(flatten)]
        names: NameArgs,
    },
    /// Write MillPath text as a DXF drawing, or into an existing drawing with --into
    ///
    /// An existing DXF that holds anything text2dxf does not write back (other layers,
    /// dimensions, blocks) is not overwritten: use --into to keep it, or --force. --into
    /// does not delete the drawing's paths that the text lacks (it names them) unless
    /// --delete-missing-paths, and leaves a drawing that already holds the text's paths
    /// untouched.
    // the conversion options, with what two of them mean for text2dxf
    #[command(
        mut_arg("path_pattern", |a| a.help("Path-name pattern: which layers are path layers (their elements are written or replaced)")),
        mut_arg("file_pattern", |a| a.help("File-name pattern (as for compile; text2dxf reads no other files, so it changes nothing)")),
        mut_arg("extended", |a| a.help("The text came from `dxf2text --extended`: polylines and block references on the path layers were turned into elements, so --into (and the check before overwriting) replaces them too")),
    )]
    Text2dxf {
        /// The MillPath text to convert (.mpath)
        file: PathBuf,
        /// The DXF file to write (default: FILE with .dxf, or the --into drawing; `-`: standard output)
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// Write the paths into this existing drawing: the path layers' elements and texts are
        /// replaced, every other layer, entity, block and setting is kept
        #[arg(long, value_name = "DRAWING.dxf")]
        into: Option<PathBuf>,
        /// Overwrite an existing DXF even if drawing content would be lost
        #[arg(long, conflicts_with = "into")]
        force: bool,
        /// With --into: delete the paths of the drawing that the text does not define
        /// (without it, --into names them and writes nothing)
        #[arg(long, requires = "into")]
        delete_missing_paths: bool,
        #[command(flatten)]
        names: NameArgs,
    },
    /// git's merge driver for drawings and MillPath texts: `millpath merge %O %A %B %P`
    ///
    /// Merges OURS and THEIRS with their common BASE by path and element; the result replaces
    /// OURS. A conflict exits 1: a .mpath gets git's conflict markers, a drawing stays as it
    /// was and the merged text with the markers is written beside it (NAME.merge.mpath).
    Merge {
        /// The common ancestor (git's %O; empty or missing: both sides added the file)
        base: PathBuf,
        /// Our version (git's %A), replaced by the merge
        ours: PathBuf,
        /// Their version (git's %B)
        theirs: PathBuf,
        /// The file's name in the repository (git's %P): its extension says .dxf or .mpath,
        /// and a drawing's conflict is written beside it
        path: Option<PathBuf>,
        #[command(flatten)]
        names: NameArgs,
    },
    /// Format MillPath files in place (directories: all *.mpath below)
    Fmt {
        /// Only check: exit 1 and list the files that are not formatted
        #[arg(long)]
        check: bool,
        /// Message language
        #[arg(long, value_enum)]
        lang: Option<LangArg>,
        /// MillPath files (.mpath) or folders
        #[arg(required = true)]
        paths: Vec<PathBuf>,
    },
    /// Draw the toolpath of a path: a standalone HTML page (3-D viewer), an SVG or a PNG top view
    Render {
        #[command(flatten)]
        machine: MachineArgs,
        /// The drawing (.dxf or .mpath; a name without extension gets .dxf)
        file: PathBuf,
        /// The path to draw (default: the first path of the file)
        #[arg(long)]
        path: Option<String>,
        /// Write the HTML page here (default when neither --svg nor --png is given:
        /// FILE_toolpath.html)
        #[arg(long)]
        html: Option<PathBuf>,
        /// Write an SVG drawing here
        #[arg(long)]
        svg: Option<PathBuf>,
        /// Write a PNG picture of the top view here (no browser needed)
        #[arg(long)]
        png: Option<PathBuf>,
        /// Draw the surface measured on the machine under the moves: a probe log (LinuxCNC
        /// PROBEOPEN, GRBL console with [PRB:…], x y z lines), a filled-in _Z.txt or an
        /// adjusted program (NAME_Milling.gcode)
        #[arg(long, value_name = "FILE")]
        surface: Option<String>,
        /// Draw the cut part (the stock after the program, coloured by depth) in the SVG and
        /// PNG too (the HTML page always has it)
        #[arg(long)]
        cut: bool,
        /// Cell edge of the cut part, mm (default: cut_cell of millpath.toml, else the
        /// checker's, O/8 where the area allows)
        #[arg(long, value_name = "MM", value_parser = numbers::decimal)]
        cut_cell: Option<f64>,
    },
    /// What changed between two versions of drawings and what it does to the part: OLD NEW,
    /// REV -- FILE… or REV..REV (exit 0: no change, 1: changed, 2: error)
    Diff {
        #[command(flatten)]
        machine: MachineArgs,
        /// Report format: human text, json, markdown (a pull-request comment)
        #[arg(long, value_enum, default_value = "human")]
        format: commands::diff::DiffFormat,
        /// Compare the drawings as written only: do not compile them
        #[arg(long)]
        no_compile: bool,
        /// OLD NEW (two drawings), or a git revision REV or REV..REV (default HEAD)
        #[arg(value_name = "OLD NEW | REV")]
        revs: Vec<String>,
        /// With a revision: the drawings to compare (default: those git lists as changed)
        #[arg(last = true, value_name = "FILE")]
        files: Vec<PathBuf>,
        /// Write the visual diff as an HTML page here (removed red, added green, other depth
        /// blue; before/after toggle; click a move for its element)
        #[arg(long)]
        html: Option<PathBuf>,
        /// Write the visual diff as an SVG here
        #[arg(long)]
        svg: Option<PathBuf>,
        /// Write the visual diff as a PNG here (no browser needed)
        #[arg(long)]
        png: Option<PathBuf>,
        /// With OLD NEW: both are versions of this drawing (copies elsewhere, as an editor
        /// writes them): its subpaths and millpath.toml are used
        #[arg(long, value_name = "FILE")]
        at: Option<PathBuf>,
    },
    /// The visual diff for `git difftool -t millpath`: LOCAL REMOTE [MERGED] as an HTML page
    /// (its path printed)
    Difftool {
        #[command(flatten)]
        machine: MachineArgs,
        /// The old version (git's $LOCAL)
        local: PathBuf,
        /// The new version (git's $REMOTE)
        remote: PathBuf,
        /// The drawing in the work tree (git's $MERGED): where subpaths and millpath.toml are
        merged: Option<PathBuf>,
        /// Write the page here (default: millpath-diff-NAME.html in the temporary folder)
        #[arg(long)]
        html: Option<PathBuf>,
        /// Open the page in the browser
        #[arg(long)]
        open: bool,
    },
    /// The post-processors: list the built-in ones, print one as a post file to adapt
    Post {
        #[command(subcommand)]
        action: PostAction,
        /// Message language
        #[arg(long, value_enum, global = true)]
        lang: Option<LangArg>,
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

#[derive(Subcommand)]
enum PostAction {
    /// List the built-in posts: name, family, description
    List,
    /// Print a built-in post as a post file (compiling with the file unchanged gives the
    /// built-in's output)
    Show {
        /// The built-in post's name
        name: String,
    },
}

/// Tunes memory for a command that runs a few milliseconds: no transparent huge pages. The
/// allocator asks for them (its arena is advised as huge pages), which serves the language
/// server's large analyses (a fifth faster on a 20,000-element chain) but makes a short
/// `check` zero 2 MiB on every first touch (about 9 times, 1 ms of its 7).
///
/// Also, memory freed is given back to the system at once rather than after 10 ms: a long
/// drawing's stages (its text and tree, then its paths, then its model and the order of a
/// chain's passes) each free what the next does not need, and with the delay the next
/// stage's peak stacked on the freed pages (a 500,000-segment chain: 544 MB instead of 402).
/// Not for the language server, whose next analysis reuses those pages.
fn short_lived() {
    // SAFETY: sets one of the allocator's integer options; it reads them at each purge.
    unsafe {
        libmimalloc_sys::mi_option_set(MI_OPTION_PURGE_DELAY, 0);
    }
    #[cfg(target_os = "linux")]
    // SAFETY: PR_SET_THP_DISABLE takes plain integers and touches no memory of ours; an
    // error (an old kernel) leaves the setting as it was, which is harmless.
    unsafe {
        libc::prctl(libc::PR_SET_THP_DISABLE, 1, 0, 0, 0);
    }
}

/// The language server: memory freed is given back to the system after a second (mimalloc's
/// default: 10 ms), so that the analysis after a keystroke reuses the pages of the one before
/// instead of faulting in fresh ones (2 MiB huge pages, zeroed by the kernel: on a 20,000-element
/// document about as long as the analysis itself).
fn keeps_memory_while_typing() {
    // SAFETY: as in `short_lived`
    unsafe {
        libmimalloc_sys::mi_option_set(MI_OPTION_PURGE_DELAY, 1000);
    }
}

/// `diff` and `merge` compile two versions, then read both analyses again: memory freed is
/// kept for a second, so each stage reuses the pages of the one before instead of faulting
/// in fresh ones (a 100,000-element diff: 342,000 page faults → 166,000, 4.8 → 3.2 s CPU,
/// 3.0 → 2.0 s on an idle machine).
fn keeps_memory_between_stages() {
    // SAFETY: as in `short_lived`
    unsafe {
        libmimalloc_sys::mi_option_set(MI_OPTION_PURGE_DELAY, 1000);
    }
}

/// `mi_option_purge_delay` of mimalloc v2's `mi_option_e` (mimalloc.h), which the sys
/// crate does not name.
const MI_OPTION_PURGE_DELAY: libmimalloc_sys::mi_option_t = 15;

fn main() -> ExitCode {
    if std::env::args_os().nth(1).is_none_or(|c| c != "lsp") {
        short_lived();
    } else {
        keeps_memory_while_typing();
    }
    if std::env::args_os()
        .nth(1)
        .is_some_and(|c| c == "diff" || c == "difftool" || c == "merge")
    {
        keeps_memory_between_stages();
    }
    let raw: Vec<String> = std::env::args().collect();
    // the commands that write files remove their temporaries when interrupted
    if raw.get(1).is_some_and(|c| {
        [
            "compile",
            "adjust-z",
            "fmt",
            "text2dxf",
            "dxf2text",
            "render",
            "pathdxf2gcode",
            "pathgcodeadjustz",
        ]
        .contains(&c.as_str())
    }) {
        interrupt::install();
    }
    // The compatibility commands take the reference's command line unchanged.
    match raw.get(1).map(String::as_str) {
        Some("pathdxf2gcode") => return leave(commands::pathdxf2gcode::run(&raw[2..])),
        Some("pathgcodeadjustz") => return leave(commands::pathgcodeadjustz::run(&raw[2..])),
        _ => {}
    }
    // clap's own messages (option errors, help headings) in the language of the run
    let cli: Cli = clap_de::parse(&raw);
    let code = match cli.command {
        Command::Compile { machine, files } => commands::compile::run(&machine, &files),
        Command::Check {
            machine,
            format,
            quiet,
            max_warnings,
            paths,
        } => commands::check::run(&machine, format, (quiet, max_warnings), &paths),
        Command::Verify {
            dialect,
            top,
            tool,
            bottom,
            lang,
            format,
            surface,
            tolerance,
            clamp,
            config,
            files,
        } => verify::run(&verify::Args {
            dialect: match dialect {
                DialectArg::Reference => millpath_verify::Dialect::Reference,
                DialectArg::Linuxcnc | DialectArg::Rs274 => millpath_verify::Dialect::LinuxCnc,
                DialectArg::Marlin => millpath_verify::Dialect::Marlin,
                DialectArg::Grbl => millpath_verify::Dialect::Grbl,
                DialectArg::Xcam => millpath_verify::Dialect::Xcam,
            },
            top,
            tool,
            bottom,
            lang: match lang_for(lang, None, files.first().map(PathBuf::as_path)) {
                Lang::De => millpath_verify::Lang::De,
                Lang::En => millpath_verify::Lang::En,
            },
            json: format == VerifyFormat::Json,
            surface: surface.map(|file| (file, tolerance)),
            clamps: clamp,
            config,
            files,
        }),
        Command::AdjustZ {
            max,
            lang,
            probe_log,
            tolerance,
            post,
            files,
        } => {
            let first = files.first().map(Path::new);
            let lang = lang_for(lang, None, first);
            match commands::adjust_z::post_of(post.as_deref(), first, lang) {
                Err(e) => {
                    eprintln!("{e}");
                    2
                }
                Ok(post) => match probe_log {
                    Some(log) => {
                        commands::adjust_z::run_with_log(max, &log, tolerance, lang, &files, &post)
                    }
                    None => commands::adjust_z::run(max, None, lang, &files, false, &post),
                },
            }
        }
        Command::Dxf2text {
            file,
            output,
            textconv,
            force,
            names,
        } => commands::dxf2text::run(
            &file,
            stdout_dash(output),
            (textconv, force),
            &names.machine(),
        ),
        Command::Text2dxf {
            file,
            output,
            into,
            force,
            delete_missing_paths,
            names,
        } => commands::text2dxf::run(
            &file,
            output.as_deref(),
            into.as_deref(),
            force,
            delete_missing_paths,
            &names.machine(),
        ),
        Command::Merge {
            base,
            ours,
            theirs,
            path,
            names,
        } => commands::merge::run(&base, &ours, &theirs, path.as_deref(), &names.machine()),
        Command::Post { action, lang } => {
            let lang = lang_for(lang, None, None);
            match action {
                PostAction::List => commands::post::list(lang),
                PostAction::Show { name } => commands::post::show(&name, lang),
            }
        }
        Command::Fmt { check, lang, paths } => {
            let lang = lang_for(lang, None, paths.first().map(PathBuf::as_path));
            commands::fmt::run(check, &paths, lang)
        }
        Command::Render {
            machine,
            file,
            path,
            html,
            svg,
            png,
            surface,
            cut,
            cut_cell,
        } => {
            let outputs = (html, svg, png);
            commands::render::run(
                &machine,
                &file,
                path.as_deref(),
                outputs,
                surface.as_deref(),
                (cut, cut_cell),
            )
        }
        Command::Diff {
            machine,
            format,
            no_compile,
            revs,
            files,
            html,
            svg,
            png,
            at,
        } => commands::diff::run(&commands::diff::Args {
            machine,
            format,
            compile: !no_compile,
            revs,
            files,
            pictures: commands::diff::Pictures { html, svg, png },
            at,
        }),
        Command::Difftool {
            machine,
            local,
            remote,
            merged,
            html,
            open,
        } => commands::diff::difftool(&machine, &local, &remote, merged.as_deref(), html, open),
        Command::Lsp { .. } => millpath_lsp::run_stdio(),
        Command::Pathdxf2gcode { args } => commands::pathdxf2gcode::run(&args),
        Command::Pathgcodeadjustz { args } => commands::pathgcodeadjustz::run(&args),
    };
    leave(code)
}

/// Ends the process with `code` once a command is done. On Linux it skips the exit handlers:
/// all they do is mimalloc handing its pages back (a dozen `madvise` calls) right before the
/// kernel frees the whole address space anyway.
fn leave(code: u8) -> ExitCode {
    // none of the temporaries is left (an early return that forgot one)
    drop(millpath_core::temporaries::remove_all_and_hold());
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
