//! File layouts (reference-output.md §4, §12.2, §12.3): the milling program, the probing program and `_Z.txt`
//! (of drawn probes, or of a height map's grid: `heightmap_program.rs`).
//!
//! File layouts: milling program (reference-output.md §4), probing program (§12.2; in linuxcnc its
//! probes inside `(PROBEOPEN NAME_probes.txt)` … `(PROBECLOSE)`), `_Z.txt` (§12.3).

use crate::diag::{Diagnostic, Lang, Origin};
use crate::digest::{banner_index, banner_with_digest, set_digest};
use crate::emit::as_comment;
use crate::emit::dialect::Controller;
use crate::emit::heightmap_program::{grid_of, grid_set, probe_close, probe_open, GridSet};
use crate::emit::stats::Stats;
use crate::emit::{emit_into, emit_quick, emit_until, start_height, Emitted, LineSink};
use crate::geom::{near, F3, P2, P3};
use crate::model::*;
use millpath_post::{Event, Globals, LineWriter, Post, Value, Var};

/// The files of one compiled path.
#[derive(Debug, Clone, PartialEq)]
pub enum Output {
    Milling(String),
    Probing {
        probing: String,
        z_txt: String,
        clean: String,
    },
}

#[derive(Debug, Clone)]
pub struct Generated {
    pub output: Output,
    pub stats: Stats,
    /// For every line of the milling (or clean) program, the element that wrote it.
    pub line_sources: LineSources,
}

/// Which element wrote each line of a program: one index a line into the elements' origins
/// (4 bytes a line; a program can have millions of lines).
#[derive(Debug, Clone, Default)]
pub struct LineSources {
    lines: Vec<u32>,
    origins: Vec<Origin>,
}

impl LineSources {
    /// The element that wrote line `no` (1-based), if an element did.
    pub fn origin(&self, no: usize) -> Option<&Origin> {
        let k = *self.lines.get(no.checked_sub(1)?)?;
        self.origins.get(k as usize)
    }
}

/// What a check needs: the emission errors and the statistics, without any text.
pub fn check(model: &Model, sweep_speed: f64) -> Result<Stats, Vec<Diagnostic>> {
    check_for(model, sweep_speed, &Controller::reference())
}

/// [`check`] for a controller (its plunge feeds change the time estimates).
pub fn check_for(
    model: &Model,
    sweep_speed: f64,
    ctl: &Controller,
) -> Result<Stats, Vec<Diagnostic>> {
    check_until(model, sweep_speed, ctl, None)
}

/// [`check_for`] that gives up when `stop()` turns true (`Err` without diagnostics then).
pub fn check_until(
    model: &Model,
    sweep_speed: f64,
    ctl: &Controller,
    stop: Option<&dyn Fn() -> bool>,
) -> Result<Stats, Vec<Diagnostic>> {
    let e = emit_until(model, true, ctl, stop)?;
    refuse_bad_grid(model, ctl, &e)?;
    refuse_unwritable_probes(ctl, &e)?;
    let mut stats = Stats::timed(&e.rec.items, sweep_speed, start(e.sx), ctl.machine.as_ref());
    stats.split = e.split;
    Ok(stats)
}

/// The editor's quick check: the errors [`check_until`] finds, without the statistics (the
/// order of fast milling is skipped, see `emit_quick`).
pub fn quick_check_until(
    model: &Model,
    ctl: &Controller,
    stop: Option<&dyn Fn() -> bool>,
) -> Result<(), Vec<Diagnostic>> {
    let e = emit_quick(model, ctl, stop)?;
    refuse_bad_grid(model, ctl, &e)?;
    refuse_unwritable_probes(ctl, &e)
}

/// Drawn probes on a post that cannot write them are refused at the first probe.
fn refuse_unwritable_probes(ctl: &Controller, e: &Emitted) -> Result<(), Vec<Diagnostic>> {
    let Some(first) = e.probes.first() else {
        return Ok(());
    };
    match ctl.post.missing_for(true, false, false, false) {
        Some(missing) => Err(vec![Diagnostic::error(
            crate::diag::Msg::PostCannot,
            first.placed.probe.origin.clone(),
            crate::args![ctl.post.name.clone(), "Z probes", missing.key()],
        )]),
        None => Ok(()),
    }
}

/// A check refuses a height map's grid as compile does.
fn refuse_bad_grid(model: &Model, ctl: &Controller, e: &Emitted) -> Result<(), Vec<Diagnostic>> {
    match &ctl.heightmap {
        Some(hm) => grid_of(hm, ctl, model, &e.rec.items, &e.probes)
            .map(|_| ())
            .map_err(|d| vec![d]),
        None => Ok(()),
    }
}

/// Generates the G-code of a top-level model as the reference does. `Err` holds the errors
/// that make the output unusable (the caller writes nothing then).
pub fn generate(
    model: &Model,
    file_name: &str,
    banner: &str,
    sweep_speed: f64,
    lang: Lang,
) -> Result<Generated, Vec<Diagnostic>> {
    generate_for(
        model,
        file_name,
        banner,
        sweep_speed,
        lang,
        &Controller::reference(),
    )
}

/// [`generate`] for a controller dialect.
pub fn generate_for(
    model: &Model,
    file_name: &str,
    banner: &str,
    sweep_speed: f64,
    lang: Lang,
    ctl: &Controller,
) -> Result<Generated, Vec<Diagnostic>> {
    generate_until(model, file_name, banner, sweep_speed, lang, ctl, None)
}

/// [`generate_for`] that gives up when `stop()` turns true (the editor's preview of a
/// cancelled request): `Err` without diagnostics then.
pub fn generate_until(
    model: &Model,
    file_name: &str,
    banner: &str,
    sweep_speed: f64,
    lang: Lang,
    ctl: &Controller,
    stop: Option<&dyn Fn() -> bool>,
) -> Result<Generated, Vec<Diagnostic>> {
    let job = (model, file_name, banner, sweep_speed, lang, ctl, stop);
    generate_job(job, None).map(|(g, _)| g)
}

/// [`generate_until`] whose milling (or clean) program goes line by line to `sink` instead
/// of a text: a check reads a long program without holding it. The program's text in the
/// result is empty (the probing program and `_Z.txt` are there, not stamped with the set's
/// digest: its writer does that); the sink comes back after the last line.
#[allow(clippy::too_many_arguments)]
pub fn generate_into<S: LineSink>(
    model: &Model,
    file_name: &str,
    banner: &str,
    sweep_speed: f64,
    lang: Lang,
    ctl: &Controller,
    stop: Option<&dyn Fn() -> bool>,
    sink: S,
) -> Result<(Generated, S), Vec<Diagnostic>> {
    let job = (model, file_name, banner, sweep_speed, lang, ctl, stop);
    let (generated, sink) = generate_job(job, Some(Box::new(sink)))?;
    let sink: Option<Box<dyn std::any::Any>> = sink.map(|s| s as _);
    match sink.and_then(|s| s.downcast::<S>().ok()) {
        Some(sink) => Ok((generated, *sink)),
        // the sink given always comes back; were it not, nothing was generated
        None => Err(Vec::new()),
    }
}

type Sink = Box<dyn LineSink>;

/// What one generation is asked for: model, file name, banner, sweep speed, language,
/// controller, stop question.
type Job<'a> = (
    &'a Model,
    &'a str,
    &'a str,
    f64,
    Lang,
    &'a Controller,
    Option<&'a dyn Fn() -> bool>,
);

fn generate_job(
    (model, file_name, banner, sweep_speed, lang, ctl, stop): Job,
    sink: Option<Sink>,
) -> Result<(Generated, Option<Sink>), Vec<Diagnostic>> {
    let mut prologue = ctl.prologue(banner, file_name, model, start_height(model), true);
    if ctl.post.has(Event::Header) {
        let header = header_lines(model, ctl, file_name, stop)?;
        prologue.splice(0..0, header);
    }
    // the statistics are all this asks of the moves unless the planner or a height map's grid
    // reads them: then they are kept
    let fold = (ctl.machine.is_none() && ctl.heightmap.is_none()).then_some(sweep_speed);
    let Emitted {
        mut rec,
        probes,
        sx,
        sources,
        split,
        ..
    } = emit_into(model, ctl, stop, &prologue, sink, fold)?;
    if let Some(first) = probes.first() {
        if let Some(missing) = ctl.post.missing_for(true, false, false, false) {
            return Err(vec![Diagnostic::error(
                crate::diag::Msg::PostCannot,
                first.placed.probe.origin.clone(),
                crate::args![ctl.post.name.clone(), "Z probes", missing.key()],
            )]);
        }
    }
    let s = model.params.s;
    let items = &rec.items;

    let mut stats = match ctl.machine.as_ref() {
        Some(m) => Stats::timed(items, sweep_speed, start(sx), Some(m)),
        None => rec.stats(sweep_speed),
    };
    stats.split = split;
    // the file LinuxCNC logs the probe contacts to (PROBEOPEN), beside the set
    let log = crate::load::paths::output_prefix(std::path::Path::new(file_name), &model.params.r);
    let log = format!("{}_probes.txt", log.display());
    // a height map's probing set needs the cutting moves before they become lines
    let grid = match &ctl.heightmap {
        Some(hm) => {
            let grid = grid_of(hm, ctl, model, items, &probes).map_err(|e| vec![e])?;
            Some(grid_set(hm, ctl, model, &grid, banner, file_name, &log))
        }
        None => None,
    };
    let g = Controller::globals(model, file_name);
    let mut tail: Vec<String> = Vec::new();
    let stat_lines = stats.lines(lang).into_iter();
    for l in stat_lines
        .chain(stats.model_line(lang))
        .chain(stats.split_line(lang))
    {
        ctl.lines(
            Event::Statistics,
            &[(Var::Text, Value::Text(&l))],
            &g,
            &mut tail,
        );
    }
    tail.extend(ctl.epilogue(true, &g));
    // the program is the emitter's text (written line by line as it went), then the tail
    if rec.sink.is_none() {
        rec.text.reserve_exact(text_size(&tail));
    }
    rec.write_tail(&tail);
    let sink = rec.sink.take();
    let body = rec.text;
    let line_sources = LineSources {
        lines: rec.line_sources,
        origins: sources,
    };
    // a probing set: the Z file and both programs stamped with the set's digest (a program
    // that went to a sink is stamped where it went: `stage.rs`)
    let streamed = sink.is_some();
    let set = |z_lines: &[String], probing: &[String], clean: String| {
        let z_txt = join(z_lines);
        let probing = join_program(&ctl.post, probing);
        let (probing, clean) = if streamed {
            (probing, clean)
        } else {
            stamp_set(&ctl.post, banner, &z_txt, probing, clean)
        };
        Output::Probing {
            probing,
            z_txt,
            clean,
        }
    };
    if let Some(GridSet { probing, z_lines }) = grid {
        let output = set(&z_lines, &probing, body);
        return Ok((
            Generated {
                output,
                stats,
                line_sources,
            },
            sink,
        ));
    }
    if probes.is_empty() {
        return Ok((
            Generated {
                output: Output::Milling(body),
                stats,
                line_sources,
            },
            sink,
        ));
    }
    // probing program and Z file
    let mut pl = ctl.prologue(banner, file_name, model, s, false);
    probe_open(ctl, &log, &g, &mut pl);
    let mut cur = P2::default();
    for p in &probes {
        let at = p.placed.pos;
        if !near(at.dist(cur), 0.0) {
            ctl.rapid_xy(&g, at, &mut pl);
        }
        cur = at;
        let above = p.placed.height() + model.params.o;
        ctl.rapid_z(&g, Event::RapidZ, above, &mut pl);
        let probe = [
            (Var::X, Value::Num(at.x)),
            (Var::Y, Value::Num(at.y)),
            (Var::Z, Value::Num(0.0)),
            (Var::Feed, Value::Num(p.placed.probe.z)),
        ];
        ctl.lines(Event::Probe, &probe, &g, &mut pl);
        ctl.rapid_z(&g, Event::Retract, s, &mut pl);
    }
    probe_close(ctl, &g, &mut pl);
    if !near(cur.dist(P2::default()), 0.0) {
        ctl.rapid_xy(&g, P2::default(), &mut pl);
    }
    ctl.rapid_z(&g, Event::Retract, s, &mut pl);
    pl.extend(ctl.epilogue(false, &g));
    let z_lines: Vec<String> = probes
        .iter()
        .map(|p| {
            let label = p
                .placed
                .probe
                .l
                .as_ref()
                .map(|l| format!("/L:{l}"))
                .unwrap_or_default();
            let inner = format!(
                "{}{label}/T={}",
                p.placed.probe.center,
                F3(p.placed.height())
            );
            format!("{} {}=", as_comment(0, &inner), p.name)
        })
        .collect();
    let output = set(&z_lines, &pl, body);
    Ok((
        Generated {
            output,
            stats,
            line_sources,
        },
        sink,
    ))
}

/// The set's digest in the banner line of both programs (the line the reference's outputs
/// are compared without): adjust-z refuses files of different compiles. Returns the stamped
/// probing and clean programs.
fn stamp_set(
    post: &Post,
    banner: &str,
    z_txt: &str,
    probing: String,
    clean: String,
) -> (String, String) {
    let text = banner_with_digest(banner, &set_digest(z_txt, &clean));
    let stamped = post.comment(0, &text, &Globals::default());
    (
        stamp_banner(probing, &stamped),
        stamp_banner(clean, &stamped),
    )
}

/// `text` with its banner line replaced by `stamped` (in place: no copy of a long program).
pub(crate) fn stamp_banner(mut text: String, stamped: &str) -> String {
    let at = banner_index(&text);
    let mut start = 0;
    for _ in 0..at {
        match text[start..].find('\n') {
            Some(k) => start += k + 1,
            None => return text,
        }
    }
    let end = text[start..].find('\n').map_or(text.len(), |k| start + k);
    let end = if text[..end].ends_with('\r') {
        end - 1
    } else {
        end
    };
    let line = stamped_line(&text[start..end], stamped);
    text.replace_range(start..end, &line);
    text
}

/// The banner line `old` with its comment replaced by `stamped`: what the post wrote before
/// the comment (a line number) stays.
pub(crate) fn stamped_line(old: &str, stamped: &str) -> String {
    let at = old.find(['(', ';']).unwrap_or(0);
    format!("{}{stamped}", &old[..at])
}

/// Where the body's moves start: above the origin at the start height.
/// The post's `header` (a CAM format's part, before everything): the extent of the
/// program's cutting moves, found by a dry run of the emitter (only for a post that has a
/// header), and the stock's thickness.
fn header_lines(
    model: &Model,
    ctl: &Controller,
    file_name: &str,
    stop: Option<&dyn Fn() -> bool>,
) -> Result<Vec<String>, Vec<Diagnostic>> {
    let e = emit_until(model, true, ctl, stop)?;
    let (lo, hi) = crate::emit::extent::cut_extent(&e.rec.items, P2::default())
        .unwrap_or((P2::default(), P2::default()));
    let g = Controller::globals(model, file_name);
    let vars = [
        (Var::FrameXMin, Value::Num(lo.x)),
        (Var::FrameYMin, Value::Num(lo.y)),
        (Var::FrameXMax, Value::Num(hi.x)),
        (Var::FrameYMax, Value::Num(hi.y)),
        (Var::FrameDx, Value::Num(hi.x - lo.x)),
        (Var::FrameDy, Value::Num(hi.y - lo.y)),
        (Var::FrameDz, Value::Num(g.stock_top - g.stock_bottom)),
    ];
    let mut lines = Vec::new();
    ctl.lines(Event::Header, &vars, &g, &mut lines);
    Ok(lines)
}

fn start(sx: f64) -> P3 {
    P3 {
        x: 0.0,
        y: 0.0,
        z: sx,
    }
}

/// A program's lines as the post writes them (numbers, modal words, line ends).
fn join_program(post: &Post, lines: &[String]) -> String {
    let mut w = LineWriter::new(post);
    if w.is_plain() {
        return join(lines);
    }
    let mut s = String::new();
    for l in lines {
        s.push_str(&w.line(l));
        s.push_str(w.end());
    }
    s
}

fn join<S: AsRef<str>>(lines: &[S]) -> String {
    let mut s = String::with_capacity(text_size(lines));
    push_lines(&mut s, lines);
    s
}

/// Bytes of `lines` written one a line.
fn text_size<S: AsRef<str>>(lines: &[S]) -> usize {
    lines.iter().map(|l| l.as_ref().len() + 1).sum()
}

fn push_lines<S: AsRef<str>>(out: &mut String, lines: &[S]) {
    for l in lines {
        out.push_str(l.as_ref());
        out.push('\n');
    }
}
