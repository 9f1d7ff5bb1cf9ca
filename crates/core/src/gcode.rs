//! G-code emission: motion primitives, chains, bars, drills, helixes, sweeps, subpaths, probe
//! expressions, the peephole optimizer and statistics (reference-output.md §4–§14).

use crate::args;
use crate::diag::{Diagnostic, Lang, Msg, Origin};
use crate::drawing::Style;
use crate::geom::{f3, ge, gt, le, lt, near, Geom, Transform, P2, P3};
use crate::model::*;

/// Relative epsilon factor of the start height: guarantees that the first Z move is emitted.
const START_OFFSET: f64 = 1.0 + 2.0 * 1e-6;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// `G00 X… Y…`
    HSweep,
    /// `G00 Z…`
    VSweep,
    Mill,
    Drill,
    Comment,
}

#[derive(Debug, Clone)]
pub struct Item {
    pub kind: Kind,
    pub text: String,
    pub len: f64,
    pub feed: f64,
    /// Where a move goes (axes it does not name stay); for the toolpath view.
    pub target: Target,
    /// Index into the emitter's element origins.
    pub source: Option<u32>,
}

/// The end of a move: the axes it sets, and for arcs the centre and direction.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Target {
    pub x: Option<f64>,
    pub y: Option<f64>,
    pub z: Option<f64>,
    pub arc: Option<(P2, bool)>,
}

impl Target {
    fn z(z: f64) -> Target {
        Target {
            z: Some(z),
            ..Default::default()
        }
    }
    fn xy(x: f64, y: f64) -> Target {
        Target {
            x: Some(x),
            y: Some(y),
            ..Default::default()
        }
    }
    fn xyz(p: P2, z: f64) -> Target {
        Target {
            x: Some(p.x),
            y: Some(p.y),
            z: Some(z),
            arc: None,
        }
    }
    fn arc(p: P2, z: f64, c: P2, ccw: bool) -> Target {
        Target {
            arc: Some((c, ccw)),
            ..Target::xyz(p, z)
        }
    }
}

/// A probe with its name, for Z expressions.
#[derive(Debug, Clone)]
pub struct NamedProbe {
    pub placed: PlacedProbe,
    pub name: String,
}

/// What gets emitted where: transformation into output coordinates and the extra height.
#[derive(Clone, Copy)]
struct Frame<'m> {
    model: &'m Model,
    t: Transform,
    h: f64,
}

struct Emitter<'a> {
    items: Vec<Item>,
    pos: P3,
    probes: &'a [NamedProbe],
    errors: Vec<Diagnostic>,
    /// Set after a skipped element: the position is no longer trustworthy.
    lost: bool,
    /// Check only: no texts are made.
    dry: bool,
    /// Origins of the elements emitted so far, and the current one.
    sources: Vec<Origin>,
    source: Option<u32>,
}

/// Trace comment text: trimmed, `)` → `]`, `\` → `/`.
pub fn as_comment(indent: usize, text: &str) -> String {
    format!(
        "{}({})",
        " ".repeat(indent),
        text.trim().replace(')', "]").replace('\\', "/")
    )
}

fn bt(b: bool) -> &'static str {
    if b {
        "True"
    } else {
        "False"
    }
}

type Skip = Diagnostic;

impl<'a> Emitter<'a> {
    /// Texts are only made when they are written: a check needs the moves, not the words.
    fn comment(&mut self, indent: usize, text: impl FnOnce() -> String) {
        let text = if self.dry {
            String::new()
        } else {
            as_comment(indent, &text())
        };
        let source = self.source;
        self.items.push(Item {
            kind: Kind::Comment,
            text,
            len: 0.0,
            feed: 0.0,
            target: Target::default(),
            source,
        });
    }
    fn push(&mut self, kind: Kind, text: impl FnOnce(&Self) -> String, len: f64, feed: f64) {
        let text = if self.dry { String::new() } else { text(self) };
        let source = self.source;
        self.items.push(Item {
            kind,
            text,
            len,
            feed,
            target: Target::default(),
            source,
        });
    }
    /// A horizontal rapid `G00 X Y` with its recorded length.
    fn move_xy(&mut self, x: f64, y: f64, len: f64) {
        self.push(
            Kind::HSweep,
            |_: &Emitter| format!("G00 X{} Y{}", f3(x), f3(y)),
            len,
            0.0,
        );
        self.to(Target::xy(x, y));
    }
    /// Sets where the last move goes.
    fn to(&mut self, t: Target) {
        if let Some(it) = self.items.last_mut() {
            it.target = t;
        }
    }

    /// `F3(z)`, or with probes `F3(z)(=F3(z)+w*[#n-TH]…)` weighted by the 4 nearest probes.
    fn zexpr(&self, z: f64, xy: P2) -> String {
        if self.probes.is_empty() {
            return f3(z);
        }
        let mut weights: Vec<(f64, usize)> = self
            .probes
            .iter()
            .enumerate()
            .map(|(i, p)| (1.0 / (p.placed.pos.dist(xy) + 0.001), i))
            .collect();
        // descending, ties keep tour order (stable sort)
        weights.sort_by(|a, b| b.0.partial_cmp(&a.0).unwrap_or(std::cmp::Ordering::Equal));
        weights.truncate(4);
        let sum: f64 = weights.iter().map(|w| w.0).sum();
        let mut s = format!("{}(={}", f3(z), f3(z));
        for (w, i) in weights {
            let p = &self.probes[i];
            s.push_str(&format!(
                "+{}*[{}-{}]",
                f3(w / sum),
                p.name,
                f3(p.placed.height())
            ));
        }
        s.push(')');
        s
    }

    fn drill_or_pull(&mut self, xy: P2, from: f64, to: f64, th: f64, feed: f64) {
        if near(to, from) {
            return;
        }
        self.comment(4, || format!("DrillOrPullZFromTo {} {}", f3(from), f3(to)));
        if to > th || to > from {
            let t = |e: &Emitter| format!("G00 Z{}", e.zexpr(to, xy));
            self.push(Kind::VSweep, t, (from - to).abs(), 0.0);
            self.to(Target::z(to));
        } else {
            if from > th {
                let t = |e: &Emitter| format!("G00 Z{}", e.zexpr(th, xy));
                self.push(Kind::VSweep, t, (from - th).abs(), 0.0);
                self.to(Target::z(th));
            }
            if !near(to, th) {
                let t = |e: &Emitter| format!("G01 Z{}", e.zexpr(to, xy));
                self.push(Kind::Drill, t, (th - to).abs(), feed);
                self.to(Target::z(to));
            }
        }
    }

    fn sweep_xy(&mut self, from: P3, to: P3) {
        let d = from.dist(to);
        if !near(d, 0.0) {
            self.move_xy(to.x, to.y, d);
        }
    }

    #[allow(clippy::too_many_arguments)]
    fn safe_sweep(&mut self, from: P3, to: P3, th: f64, s: f64, feed: f64, backtrack: bool) {
        self.comment(2, || {
            format!(
                "SweepAndDrillSafelyFromTo {from} {to} s={} bt={}",
                f3(s),
                bt(backtrack)
            )
        });
        if from.xy().near(to.xy()) {
            self.drill_or_pull(from.xy(), from.z, to.z, th, feed);
        } else {
            self.drill_or_pull(from.xy(), from.z, s, th, feed);
            self.sweep_xy(from.xy().with_z(s), to);
            self.drill_or_pull(to.xy(), s, to.z, th, feed);
        }
        self.pos = to;
    }

    fn mill(&mut self, g: &Geom, from_z: f64, to_z: f64, th: f64, feed: f64, backtrack: bool) {
        self.drill_or_pull(self.pos.xy(), self.pos.z, from_z, th, feed);
        let (a, b) = (g.start(), g.end());
        match *g {
            Geom::Line { .. } => {
                self.comment(2, || {
                    format!(
                        "MillLine s={a} e={b} fr={} to={} bt={}",
                        f3(from_z),
                        f3(to_z),
                        bt(backtrack)
                    )
                });
                let t = |e: &Emitter| {
                    format!(
                        "G01 F{} X{} Y{} Z{}",
                        f3(feed),
                        f3(b.x),
                        f3(b.y),
                        e.zexpr(to_z, a)
                    )
                };
                self.push(Kind::Mill, t, a.dist(b), feed);
                self.to(Target::xyz(b, to_z));
            }
            Geom::Arc { c, r, a0, a1, ccw } => {
                self.comment(2, || {
                    format!(
                        "MillArc l={c} r={} a0={} a1={} fr={} to={} p0={a} p1={b} bt={}",
                        f3(r),
                        f3(a0),
                        f3(a1),
                        f3(from_z),
                        f3(to_z),
                        bt(backtrack)
                    )
                });
                let t = |e: &Emitter| {
                    format!(
                        "{} F{} I{} J{} X{} Y{} Z{}",
                        if ccw { "G03" } else { "G02" },
                        f3(feed),
                        f3(c.x - a.x),
                        f3(c.y - a.y),
                        f3(b.x),
                        f3(b.y),
                        e.zexpr(to_z, a)
                    )
                };
                self.push(Kind::Mill, t, g.length(), feed);
                self.to(Target::arc(b, to_z, c, ccw));
            }
        }
        self.pos = b.with_z(to_z);
    }

    /// The support profile of one pass (§8.2); `b`, `d` are the bar depths.
    #[allow(clippy::too_many_arguments)]
    fn profile(
        &mut self,
        pieces: &[Geom],
        forward: bool,
        z: f64,
        b: f64,
        d: f64,
        th: f64,
        feed: f64,
        backtrack: bool,
    ) {
        const STEPS: [&str; 4] = ["Bar", "Down", "Between", "Up"];
        let ordered: Vec<Geom> = if forward {
            pieces.to_vec()
        } else {
            pieces.iter().rev().map(Geom::reversed).collect()
        };
        for (k, piece) in ordered.iter().enumerate() {
            let step = STEPS[k % 4];
            self.comment(2, || format!("Support.{step}"));
            let (fr, to) = match step {
                "Bar" => (z.max(d), z.max(d)),
                "Down" => (z.max(d), z.max(b)),
                "Between" => (z.max(b), z.max(b)),
                _ => (z.max(b), z.max(d)),
            };
            self.mill(piece, fr, to, th, feed, backtrack);
        }
    }

    fn emit_model(&mut self, fr: Frame) {
        for e in &fr.model.elements {
            self.sources.push(element_origin(e).clone());
            self.source = Some(self.sources.len() as u32 - 1);
            let r = match e {
                Element::Chain(c) => self.chain(fr, c),
                Element::Drill(d) => self.drill(fr, d),
                Element::Helix(h) => self.helix(fr, h),
                Element::Sweep(s) => self.sweep(fr, s),
                Element::Subpath(s) => {
                    self.subpath(fr, s);
                    Ok(())
                }
            };
            if let Err(d) = r {
                self.errors.push(d);
                self.lost = true;
            }
        }
    }

    fn subpath(&mut self, fr: Frame, emb: &Embedding) {
        let Some(target) = &emb.target else { return };
        let Some(t) = sub_transform(target, emb, &fr.t) else {
            return;
        };
        let label = format!("{} t={}", target.label(), t.describe());
        self.comment(2, || format!("START Subpath {label}"));
        self.emit_model(Frame {
            model: target,
            t,
            h: fr.h + emb.h,
        });
        self.comment(2, || format!("END Subpath {label}"));
    }

    fn sweep(&mut self, fr: Frame, s: &Sweep) -> Result<(), Skip> {
        let (a, b) = (fr.t.apply(s.a), fr.t.apply(s.b));
        if self.lost {
            self.pos = a.with_z(self.pos.z);
            self.lost = false;
        } else if !self.pos.xy().assert_near(a) {
            return Err(Diagnostic::error(
                Msg::NotNear,
                s.origin.clone(),
                args![a, self.pos.xy()],
            ));
        }
        let p = &fr.model.params;
        let height = fr.h + s.s;
        self.safe_sweep(self.pos, b.with_z(height), fr.h + p.t, height, p.f, s.bt);
        Ok(())
    }

    fn drill(&mut self, fr: Frame, d: &Drill) -> Result<(), Skip> {
        let p = &fr.model.params;
        let c = fr.t.apply(d.c);
        let (key, depth) = if d.style == Style::Mark {
            ("D", d.d)
        } else {
            ("B", d.b)
        };
        let depth = depth.ok_or_else(|| missing(key, &d.origin))?;
        self.comment(2, || format!("Drill l={c}"));
        if let Some(q) = &d.q {
            self.comment(4, || format!("Q:{q}"));
        }
        self.drill_or_pull(c, self.pos.z, fr.h + depth, fr.h + p.t, d.f);
        self.pos.z = fr.h + depth;
        Ok(())
    }

    fn helix(&mut self, fr: Frame, hx: &Helix) -> Result<(), Skip> {
        let p = &fr.model.params;
        let h = fr.h;
        let c = fr.t.apply(hx.c);
        let th = h + p.t;
        let (key, depth) = if hx.style == Style::Mill {
            ("B", hx.b)
        } else {
            ("D", hx.d)
        };
        let bottom = h + depth.ok_or_else(|| missing(key, &hx.origin))?;
        let infeed = hx.i.ok_or_else(|| missing("I", &hx.origin))?;
        let r1 = hx.r - p.o / 2.0;
        self.drill_or_pull(self.pos.xy(), self.pos.z, th + p.o, th, hx.f);
        if let Some(q) = &hx.q {
            self.comment(4, || format!("Q:{q}"));
        }
        self.comment(2, || format!("MillHelix l={c} r={}", f3(hx.r)));
        self.move_xy(c.x, c.y - r1, r1);
        let (mut d, mut done) = (th, th);
        let mut z = self.pos.z;
        let half = r1 * std::f64::consts::PI;
        while gt(done, bottom) {
            self.comment(4, || format!("MillSemiCircle l={}", f3(d)));
            let b1 = (d - infeed / 2.0).max(bottom);
            let t = |e: &Emitter| {
                format!(
                    "G02 F{} I0 J{} X{} Y{} Z{}",
                    f3(hx.f),
                    f3(r1),
                    f3(c.x),
                    f3(c.y + r1),
                    e.zexpr(b1, c)
                )
            };
            self.push(Kind::Mill, t, half, hx.f);
            self.to(Target::arc(P2::new(c.x, c.y + r1), b1, c, false));
            let b0 = (b1 - infeed / 2.0).max(bottom);
            let t = |e: &Emitter| {
                format!(
                    "G02 F{} I0 J{} X{} Y{} Z{}",
                    f3(hx.f),
                    f3(-r1),
                    f3(c.x),
                    f3(c.y - r1),
                    e.zexpr(b0, c)
                )
            };
            self.push(Kind::Mill, t, half, hx.f);
            self.to(Target::arc(P2::new(c.x, c.y - r1), b0, c, false));
            z = b0;
            done = d;
            d -= infeed;
        }
        self.pos = P3 {
            x: c.x,
            y: c.y - r1,
            z,
        };
        if let (Style::Support, Some(pieces)) = (hx.style, &hx.bars) {
            let b = hx.b.ok_or_else(|| missing("B", &hx.origin))?;
            let dd = hx.d.ok_or_else(|| missing("D", &hx.origin))?;
            let pieces: Vec<Geom> = pieces.iter().map(|g| g.transform(&fr.t)).collect();
            while gt(done, h + b) {
                let z = (done - infeed).max(h + b);
                // deliberate difference: bar depths are raised by h like everything else
                self.profile(&pieces, true, z, h + b, h + dd, th, hx.f, false);
                done = z;
            }
        }
        if le(hx.r, p.o) {
            self.move_xy(c.x, c.y, r1);
            self.pos = c.with_z(self.pos.z);
        } else {
            // deliberate difference: the pull-up height is raised by h as well
            let s = h + p.s;
            let t = |e: &Emitter| format!("G00 Z{}", e.zexpr(s, c));
            self.push(Kind::VSweep, t, s - done, 0.0);
            self.to(Target::z(s));
            self.move_xy(c.x, c.y, r1);
            self.pos = c.with_z(s);
        }
        Ok(())
    }

    fn chain(&mut self, fr: Frame, ch: &Chain) -> Result<(), Skip> {
        let p = &fr.model.params;
        let h = fr.h;
        let infeed = ch.i.ok_or_else(|| missing("I", &ch.origin))?;
        let first = match ch.w {
            Some(w) => h + w,
            None => h + p.t - infeed,
        };
        let mut passes: Vec<Vec<f64>> = Vec::with_capacity(ch.segs.len());
        let mut geoms = Vec::with_capacity(ch.segs.len());
        for s in &ch.segs {
            let (key, depth) = if s.style == Style::Mark {
                ("D", s.d)
            } else {
                ("B", s.b)
            };
            let bottom = h + depth.ok_or_else(|| missing(key, &s.origin))?;
            passes.push(pass_depths(first, bottom, infeed));
            geoms.push(s.geom.transform(&fr.t));
        }
        let th = h + p.t;
        if ch.w.is_some() {
            self.sweepless(fr, ch, &passes, &geoms, th)
        } else {
            self.fast(fr, ch, &passes, &geoms, th)
        }
    }

    fn fast(
        &mut self,
        fr: Frame,
        ch: &Chain,
        passes: &[Vec<f64>],
        geoms: &[Geom],
        th: f64,
    ) -> Result<(), Skip> {
        let p = &fr.model.params;
        let mut done_count = vec![0usize; passes.len()];
        let head = geoms[0].start().with_z(passes[0][0]);
        let s = fr.h + p.s;
        let ends: Vec<(P2, P2)> = geoms.iter().map(|g| (g.start(), g.end())).collect();
        for (si, forward) in crate::chain_order::fast_order(&ends, passes, head) {
            let z = passes[si][done_count[si]];
            done_count[si] += 1;
            let g = if forward {
                geoms[si]
            } else {
                geoms[si].reversed()
            };
            let seg = &ch.segs[si];
            self.safe_sweep(self.pos, g.start().with_z(z), th, s, seg.f, false);
            self.segment_pass(fr, seg, &g, forward, z, th);
        }
        let end = geoms[geoms.len() - 1].end();
        self.safe_sweep(self.pos, end.with_z(s), p.t, s, p.f, false);
        Ok(())
    }

    fn sweepless(
        &mut self,
        fr: Frame,
        ch: &Chain,
        passes: &[Vec<f64>],
        geoms: &[Geom],
        th: f64,
    ) -> Result<(), Skip> {
        let runs = passes.iter().map(Vec::len).max().unwrap_or(0);
        let chain_start = geoms[0].start();
        let chain_end = geoms[geoms.len() - 1].end();
        let back = runs > 1 && !chain_start.near(chain_end);
        let mut head = chain_start;
        let mut edges: Vec<(usize, f64, bool)> = Vec::new();
        for k in 0..runs {
            let mut run = Vec::new();
            for (si, g) in geoms.iter().enumerate() {
                let z = passes[si][k.min(passes[si].len() - 1)];
                let forward = if head.near(g.start()) {
                    true
                } else if head.near(g.end()) {
                    false
                } else {
                    return Err(Diagnostic::error(
                        Msg::NotNear,
                        ch.segs[si].origin.clone(),
                        args![head, g.start()],
                    ));
                };
                head = if forward { g.end() } else { g.start() };
                run.push((si, z, forward));
            }
            edges.extend(run.iter().copied());
            if back && k + 1 < runs {
                for &(si, z, fwd) in run.iter().rev() {
                    edges.push((si, z, !fwd));
                }
                head = chain_start;
            }
        }
        for (si, z, forward) in edges {
            let seg = &ch.segs[si];
            let g = if forward {
                geoms[si]
            } else {
                geoms[si].reversed()
            };
            self.drill_or_pull(self.pos.xy(), self.pos.z, z, th, seg.f);
            self.segment_pass(fr, seg, &g, forward, z, th);
        }
        Ok(())
    }

    /// One pass of one chain segment (§7.4). `g` is already in pass direction.
    fn segment_pass(
        &mut self,
        fr: Frame,
        seg: &ChainSeg,
        g: &Geom,
        forward: bool,
        z: f64,
        th: f64,
    ) {
        if let Some(q) = &seg.q {
            self.comment(4, || format!("Q:{q}"));
        }
        // deliberate difference: the clamp uses the raised bottom (+h)
        let full_bottom = fr.h
            + if seg.style == Style::Mill {
                seg.b
            } else {
                seg.d
            }
            .unwrap_or(f64::NAN);
        if let (Style::Support, Some(pieces), Some(b), Some(d)) =
            (seg.style, &seg.bars, seg.b, seg.d)
        {
            if lt(z, full_bottom) {
                let pieces: Vec<Geom> = pieces.iter().map(|p| p.transform(&fr.t)).collect();
                self.profile(&pieces, forward, z, fr.h + b, fr.h + d, th, seg.f, seg.bt);
                return;
            }
        }
        let depth = z.max(full_bottom);
        self.mill(g, depth, depth, th, seg.f, seg.bt);
    }
}

fn element_origin(e: &Element) -> &Origin {
    match e {
        Element::Chain(c) => &c.origin,
        Element::Drill(d) => &d.origin,
        Element::Helix(h) => &h.origin,
        Element::Sweep(s) => &s.origin,
        Element::Subpath(s) => &s.origin,
    }
}

fn missing(key: &str, origin: &Origin) -> Diagnostic {
    Diagnostic::error(Msg::ValueMissing, origin.clone(), args![key])
}

/// Pass depths from `first` down to `bottom` in steps of `infeed` (§7.1).
pub fn pass_depths(first: f64, bottom: f64, infeed: f64) -> Vec<f64> {
    let mut out = Vec::new();
    let mut z = first;
    while ge(z, bottom) && out.len() < 100_000 {
        out.push(z);
        z -= infeed;
    }
    if out.last().is_none_or(|l| !near(*l, bottom)) {
        out.push(bottom);
    }
    out
}

/// The peephole optimizer: a horizontal sweep followed (past comments) by another one is
/// commented out.
pub fn optimize(items: &mut [Item]) {
    let mut next_is_h = false;
    for it in items.iter_mut().rev() {
        match it.kind {
            Kind::Comment => {}
            Kind::HSweep => {
                if next_is_h {
                    it.kind = Kind::Comment;
                    it.text = format!("; {}", it.text);
                }
                next_is_h = true;
            }
            _ => next_is_h = false,
        }
    }
}

#[derive(Debug, Clone, Default, PartialEq)]
pub struct Stats {
    pub mill: f64,
    pub mill_min: f64,
    pub drill: f64,
    pub drill_min: f64,
    pub sweep: f64,
    pub sweep_min: f64,
    pub count: usize,
}

const TICKS_PER_MINUTE: f64 = 600_000_000.0;

impl Stats {
    pub fn of(items: &[Item], sweep_speed: f64) -> Stats {
        let mut s = Stats::default();
        for it in items {
            match it.kind {
                Kind::Mill => {
                    s.mill += it.len;
                    s.mill_min += it.len / it.feed;
                }
                Kind::Drill => {
                    s.drill += it.len;
                    s.drill_min += it.len / it.feed;
                }
                Kind::HSweep | Kind::VSweep => {
                    s.sweep += it.len;
                    s.sweep_min += it.len / sweep_speed;
                }
                Kind::Comment => continue,
            }
            s.count += 1;
        }
        s.mill_min *= 1.4;
        s.drill_min *= 1.4;
        s.sweep_min *= 1.4;
        s
    }

    /// The five statistics texts, e.g. `Fräslänge:     115 mm   ca.  2 min`.
    pub fn lines(&self, lang: Lang) -> [String; 5] {
        let labels = match lang {
            Lang::En => [
                "Milling length:",
                "Drill length:",
                "Sweeps:",
                "Sum:",
                "Command count:",
            ],
            Lang::De => [
                "Fräslänge:",
                "Bohrungen:",
                "Leerfahrten:",
                "Summe:",
                "Befehlszahl:",
            ],
        };
        let ticks = |m: f64| (m * TICKS_PER_MINUTE).trunc();
        let (tm, td, ts) = (
            ticks(self.mill_min),
            ticks(self.drill_min),
            ticks(self.sweep_min),
        );
        let minutes = |t: f64| (t / TICKS_PER_MINUTE).ceil();
        let line = |l: &str, len: f64, t: f64| {
            format!("{l:<12} {:>5.0} mm   ca.{:>3.0} min", len, minutes(t))
        };
        [
            line(labels[0], self.mill, tm),
            line(labels[1], self.drill, td),
            line(labels[2], self.sweep, ts),
            line(labels[3], self.mill + self.drill + self.sweep, tm + td + ts),
            format!("{:<12} {}", labels[4], self.count),
        ]
    }
}

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
}

fn prologue(banner: &str, file_name: &str, start: f64) -> Vec<String> {
    vec![
        "%".into(),
        as_comment(0, banner),
        as_comment(0, file_name),
        "F150".into(),
        "G17 G21 G40 G49 G54 G80 G90 G94".into(),
        "T1".into(),
        as_comment(
            0,
            &format!(
                "SweepSafelyTo {}",
                P3 {
                    x: 0.0,
                    y: 0.0,
                    z: start
                }
            ),
        ),
        format!("G00 Z{}", f3(start)),
        "G00 X0.000 Y0.000".into(),
    ]
}

/// Generates the G-code of a top-level model. `Err` holds the errors that make the output
/// The body moves of a model (dry: without texts), its probes and start height.
fn emit(model: &Model, dry: bool) -> Result<Emitted, Vec<Diagnostic>> {
    if model.elements.is_empty() {
        return Err(vec![Diagnostic::error(
            Msg::NoSegments,
            model.raw.start_origin(),
            vec![],
        )]);
    }
    let top = Transform::top_level(model.start, model.end);
    let mut placed = Vec::new();
    collect_probes(model, &top, 0.0, &mut placed);
    let probes: Vec<NamedProbe> = probe_tour(placed)
        .into_iter()
        .enumerate()
        .map(|(i, p)| NamedProbe {
            placed: p,
            name: format!("#{}", 51 + i),
        })
        .collect();
    let sx = model.params.s * START_OFFSET;
    let mut em = Emitter {
        items: Vec::new(),
        pos: P3 {
            x: 0.0,
            y: 0.0,
            z: sx,
        },
        probes: &probes,
        errors: Vec::new(),
        lost: false,
        dry,
        sources: Vec::new(),
        source: None,
    };
    em.comment(2, || format!("Model {}", model.label()));
    em.emit_model(Frame {
        model,
        t: top,
        h: 0.0,
    });
    let last_z = em.pos.z;
    em.push(
        Kind::VSweep,
        |_: &Emitter| format!("G00 Z{}", f3(sx)),
        (last_z - sx).abs(),
        0.0,
    );
    if !em.errors.is_empty() {
        return Err(em.errors);
    }
    let mut items = em.items;
    optimize(&mut items);
    Ok(Emitted {
        items,
        sources: em.sources,
        probes,
        sx,
    })
}

struct Emitted {
    items: Vec<Item>,
    sources: Vec<Origin>,
    probes: Vec<NamedProbe>,
    sx: f64,
}

/// One move of the toolpath view.
#[derive(Debug, Clone, PartialEq)]
pub struct Move {
    /// `rapid`, `mill` or `drill`.
    pub kind: &'static str,
    pub from: P3,
    pub to: P3,
    /// Centre and direction (counter-clockwise?) of arcs.
    pub arc: Option<(P2, bool)>,
    /// The element the move comes from.
    pub source: Option<Origin>,
}

/// The moves of a path as the machine makes them (after the optimizer), and its probes.
#[derive(Debug, Clone, PartialEq)]
pub struct Toolpath {
    pub moves: Vec<Move>,
    pub probes: Vec<(String, P2)>,
}

/// The toolpath of a top-level model.
pub fn toolpath(model: &Model) -> Result<Toolpath, Vec<Diagnostic>> {
    let e = emit(model, true)?;
    let mut pos = P3 {
        x: 0.0,
        y: 0.0,
        z: e.sx,
    };
    let mut moves = Vec::new();
    for it in &e.items {
        let kind = match it.kind {
            Kind::HSweep | Kind::VSweep => "rapid",
            Kind::Mill => "mill",
            Kind::Drill => "drill",
            Kind::Comment => continue,
        };
        let t = it.target;
        let to = P3 {
            x: t.x.unwrap_or(pos.x),
            y: t.y.unwrap_or(pos.y),
            z: t.z.unwrap_or(pos.z),
        };
        let source = it.source.and_then(|i| e.sources.get(i as usize).cloned());
        moves.push(Move {
            kind,
            from: pos,
            to,
            arc: t.arc,
            source,
        });
        pos = to;
    }
    let probes = e
        .probes
        .iter()
        .map(|p| (p.name.clone(), p.placed.pos))
        .collect();
    Ok(Toolpath { moves, probes })
}

/// What a check needs: the emission errors and the statistics, without any text.
pub fn check(model: &Model, sweep_speed: f64) -> Result<Stats, Vec<Diagnostic>> {
    Ok(Stats::of(&emit(model, true)?.items, sweep_speed))
}

/// Generates the G-code of a top-level model. `Err` holds the errors that make the output
/// unusable (the caller writes nothing then).
pub fn generate(
    model: &Model,
    file_name: &str,
    banner: &str,
    sweep_speed: f64,
    lang: Lang,
) -> Result<Generated, Vec<Diagnostic>> {
    let Emitted {
        items, probes, sx, ..
    } = emit(model, false)?;
    let s = model.params.s;

    let stats = Stats::of(&items, sweep_speed);
    let mut lines = prologue(banner, file_name, sx);
    lines.extend(items.into_iter().map(|i| i.text));
    lines.extend(stats.lines(lang).iter().map(|l| format!("  ({l})")));
    lines.push("M30".into());
    lines.push("%".into());
    let body = join(&lines);
    if probes.is_empty() {
        return Ok(Generated {
            output: Output::Milling(body),
            stats,
        });
    }
    // probing program and Z file
    let mut pl = prologue(banner, file_name, s);
    let mut cur = P2::default();
    for p in &probes {
        if !near(p.placed.pos.dist(cur), 0.0) {
            pl.push(format!(
                "G00 X{} Y{}",
                f3(p.placed.pos.x),
                f3(p.placed.pos.y)
            ));
        }
        cur = p.placed.pos;
        pl.push(format!("G00 Z{}", f3(p.placed.height() + model.params.o)));
        pl.push(format!("G38.3 Z0 F{}", f3(p.placed.probe.z)));
        pl.push("G04 P4".into());
        pl.push(format!("G00 Z{}", f3(s)));
    }
    if !near(cur.dist(P2::default()), 0.0) {
        pl.push("G00 X0.000 Y0.000".into());
    }
    pl.push(format!("G00 Z{}", f3(s)));
    pl.push("M30".into());
    pl.push("%".into());
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
                f3(p.placed.height())
            );
            format!("{} {}=", as_comment(0, &inner), p.name)
        })
        .collect();
    Ok(Generated {
        output: Output::Probing {
            probing: join(&pl),
            z_txt: join(&z_lines),
            clean: body,
        },
        stats,
    })
}

fn join(lines: &[String]) -> String {
    let mut s = lines.join("\n");
    s.push('\n');
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pass_depths_follow_the_reference() {
        let p = pass_depths(2.0 - 1.2, -0.3, 1.2);
        assert_eq!(p.len(), 2);
        assert!((p[0] - 0.8).abs() < 1e-12 && p[1] == -0.3);
        let p = pass_depths(1.0 - 0.6, -0.1, 0.6);
        assert_eq!(
            p.iter().map(|z| f3(*z)).collect::<Vec<_>>(),
            ["0.400", "-0.100"]
        );
        // a mark below the first pass gets a single pass at D
        assert_eq!(pass_depths(0.8, 1.5, 1.2), vec![1.5]);
    }

    #[test]
    fn optimizer_keeps_only_the_last_sweep_of_a_run() {
        let mk = |k, t: &str| Item {
            kind: k,
            text: t.into(),
            len: 1.0,
            feed: 1.0,
            target: Target::default(),
            source: None,
        };
        let mut v = vec![
            mk(Kind::HSweep, "G00 X1 Y1"),
            mk(Kind::Comment, "(c)"),
            mk(Kind::HSweep, "G00 X2 Y2"),
            mk(Kind::VSweep, "G00 Z1"),
            mk(Kind::HSweep, "G00 X3 Y3"),
        ];
        optimize(&mut v);
        assert_eq!(v[0].text, "; G00 X1 Y1");
        assert_eq!(v[2].text, "G00 X2 Y2");
        assert_eq!(v[4].text, "G00 X3 Y3");
        let s = Stats::of(&v, 500.0);
        assert_eq!(s.count, 3);
    }

    #[test]
    fn statistics_lines() {
        let s = Stats {
            mill: 115.374,
            mill_min: 115.374 / 150.0 * 1.4,
            drill: 3.5,
            drill_min: 3.5 / 150.0 * 1.4,
            sweep: 65.99,
            sweep_min: 65.99 / 500.0 * 1.4,
            count: 8,
        };
        let de = s.lines(Lang::De);
        assert_eq!(de[0], "Fräslänge:     115 mm   ca.  2 min");
        assert_eq!(de[4], "Befehlszahl: 8");
        let en = s.lines(Lang::En);
        assert_eq!(en[0], "Milling length:   115 mm   ca.  2 min");
        assert_eq!(en[1], "Drill length:     4 mm   ca.  1 min");
        assert_eq!(en[3], "Sum:           185 mm   ca.  2 min");
        assert_eq!(
            Stats::default().lines(Lang::De)[1],
            "Bohrungen:       0 mm   ca.  0 min"
        );
    }

    #[test]
    fn comments_are_sanitised() {
        assert_eq!(as_comment(2, " a)b\\c "), "  (a]b/c)");
    }
}
