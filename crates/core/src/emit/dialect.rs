//! Controller dialects and the post that writes for one. The text of every line is the
//! post's (`crates/post`, `posts/*.toml`): `reference` writes what PathDxf2GCode writes, byte
//! for byte (reference-output.md §4); `linuxcnc` and `grbl` write programs those controllers
//! run as drawn (the feed after the modal line, a feed on every plunge, the optional spindle
//! start and stop, a stock comment for verifiers, no `%` lines for GRBL). What stays code
//! here is what the dialect *decides*: plunge feeds, which events a program has.

use crate::emit::timing::TimeModel;
use crate::load::settings::Settings;
use crate::machine::{Dialect, DEFAULT_SPINDLE_DWELL};
use crate::model::Model;
use crate::probe::heightmap::Heightmap;
use crate::stock::stock_of;
use millpath_post::{Event, Globals, Post, Value, Var};
use std::sync::Arc;

impl Dialect {
    /// The built-in post that writes this dialect's programs.
    pub fn post(self) -> &'static Post {
        millpath_post::builtin::get(self.name()).expect("every dialect has its built-in post")
    }

    /// [`Dialect::post`] shared, as a [`Controller`] holds it.
    pub fn shared_post(self) -> Arc<Post> {
        builtin_shared(self.name()).expect("every dialect has its built-in post")
    }
}

/// A built-in post shared: each one once per process (a fixed number), so that every
/// program of a built-in shares it.
fn builtin_shared(name: &str) -> Option<Arc<Post>> {
    use std::sync::{Mutex, OnceLock};
    static SHARED: OnceLock<Mutex<Vec<Arc<Post>>>> = OnceLock::new();
    let post = millpath_post::builtin::get(name)?;
    let mut all = SHARED
        .get_or_init(Default::default)
        .lock()
        .unwrap_or_else(|e| e.into_inner());
    if let Some(p) = all.iter().find(|p| p.origin == post.origin) {
        return Some(p.clone());
    }
    let p = Arc::new(post.clone());
    all.push(p.clone());
    Some(p)
}

/// The dialect and post a `post =` setting or `--post` option names: a built-in post's name
/// (the dialect of that name), or a post file relative to `base`, read by `read`. A post
/// file named like a built-in (`post show` prints them so) keeps that dialect's rules (the
/// reference's plunge feeds and refusals); any other writes as a controller of its family.
/// A family the checker cannot read is refused by the settings' checks (the second opinion
/// may not be skipped). The error is the message in `lang`.
pub fn select_post(
    name_or_path: &str,
    base: &std::path::Path,
    read: &dyn Fn(&std::path::Path) -> Result<String, String>,
    lang: crate::diag::Lang,
) -> Result<(Dialect, Option<Arc<Post>>), String> {
    let post_lang = match lang {
        crate::diag::Lang::De => millpath_post::Lang::De,
        _ => millpath_post::Lang::En,
    };
    let post = millpath_post::resolve(name_or_path, base, read).map_err(|e| e.render(post_lang))?;
    let builtin = post.origin.starts_with("builtin:");
    if let (true, Some(d)) = (builtin, Dialect::from_name(&post.name)) {
        return Ok((d, None));
    }
    let dialect = match (Dialect::from_name(&post.name), post.family) {
        (Some(d), _) => d,
        (None, millpath_post::Family::Rs274) => Dialect::LinuxCnc,
        // grbl, and the families the checker may not read: refused, located, by the
        // settings' checks (`machine::Reading`)
        (None, _) => Dialect::Grbl,
    };
    // a built-in post without a dialect of its own (mach3, fluidnc …): its family's rules;
    // a post file is shared by the settings and programs that use it, and dropped with the
    // last of them (an editor reloading an edited post keeps no old version)
    let shared = match builtin.then(|| builtin_shared(&post.name)).flatten() {
        Some(p) => p,
        None => Arc::new(post),
    };
    Ok((dialect, Some(shared)))
}

/// What the program writer needs to know about the controller.
#[derive(Debug, Clone, PartialEq)]
pub struct Controller {
    pub dialect: Dialect,
    /// The post that writes the text (the dialect's built-in, or a post file).
    pub post: Arc<Post>,
    /// Feed of plunges (mm/min); `None`: half the element's feed.
    pub plunge_feed: Option<f64>,
    /// Spindle speed; `None`: the program does not switch the spindle.
    pub spindle_rpm: Option<f64>,
    /// Seconds to wait after the spindle start.
    pub spindle_dwell: f64,
    /// The time model and machine of the estimates; `None`: the reference's time model.
    pub machine: Option<TimeModel>,
    /// `[heightmap]`: the probing set is a grid over the cuts (its probe feed resolved).
    pub heightmap: Option<Heightmap>,
    /// `probe_split` (mm): with drawn probes, cutting moves are written in pieces of at most
    /// this length, each corrected at its own start (`emit/probe_split.rs`).
    pub probe_split: Option<f64>,
    /// The height map is the drawing's own (`K`), for the messages that name where it came from.
    pub heightmap_in_drawing: bool,
}

impl Default for Controller {
    fn default() -> Self {
        Controller::reference()
    }
}

impl Controller {
    /// PathDxf2GCode's programs.
    pub fn reference() -> Controller {
        Controller {
            dialect: Dialect::Reference,
            post: Dialect::Reference.shared_post(),
            plunge_feed: None,
            spindle_rpm: None,
            spindle_dwell: DEFAULT_SPINDLE_DWELL,
            machine: None,
            heightmap: None,
            probe_split: None,
            heightmap_in_drawing: false,
        }
    }

    pub fn of(s: &Settings) -> Controller {
        Controller {
            dialect: s.dialect,
            post: s.post.clone().unwrap_or_else(|| s.dialect.shared_post()),
            plunge_feed: s.plunge_feed,
            spindle_rpm: s.spindle_rpm,
            spindle_dwell: s.spindle_dwell,
            machine: s.time_model(),
            heightmap: s.heightmap.map(|h| Heightmap {
                probe_feed: Some(h.probe_feed.unwrap_or(s.probe_feed())),
                ..h
            }),
            probe_split: s.probe_split,
            heightmap_in_drawing: false,
        }
    }

    /// [`Controller::of`] for a compiled model: a height map said in its drawing (`K`) over
    /// the `[heightmap]` of millpath.toml, and `--heightmap-step`/`--heightmap-margin` over
    /// both. The drawing is the part's own truth; the file gives what `K` cannot say (area,
    /// probe feed and depth) and a margin `K` leaves out; an option is this run's choice.
    pub fn for_model(s: &Settings, model: &Model) -> Controller {
        let mut c = Controller::of(s);
        if let Some(k) = model.params.heightmap {
            let base = c.heightmap.unwrap_or(Heightmap {
                probe_feed: Some(s.probe_feed()),
                ..Heightmap::with_step(k.step)
            });
            let (step_option, margin_option) = s.heightmap_options;
            c.heightmap = Some(Heightmap {
                step: if step_option { base.step } else { k.step },
                margin: match (margin_option, k.margin) {
                    (false, Some(m)) => m,
                    _ => base.margin,
                },
                ..base
            });
            c.heightmap_in_drawing = true;
        }
        c
    }

    /// The feed written on a plunge of an element milled at `element_feed`: `None` in the
    /// reference dialect (no F word, the modal feed applies); else `plunge_feed`, but never
    /// faster than the element's own feed, or — without `plunge_feed` — half the element's
    /// feed.
    pub fn plunge(&self, element_feed: f64) -> Option<f64> {
        if self.dialect == Dialect::Reference {
            return None;
        }
        Some(match self.plunge_feed {
            Some(p) => p.min(element_feed),
            None => element_feed / 2.0,
        })
    }

    /// The text of one event as lines (a template may hold several; an empty one none).
    pub(crate) fn lines(
        &self,
        event: Event,
        vars: &[(Var, Value)],
        g: &Globals,
        out: &mut Vec<String>,
    ) {
        if !self.post.has(event) {
            return;
        }
        let text = self.post.text(event, vars, g);
        out.extend(text.split('\n').map(str::to_string));
    }

    /// The program's values every template may use.
    pub(crate) fn globals<'m>(model: &'m Model, file_name: &'m str) -> Globals<'m> {
        // the same figures the compiler's own second opinion uses
        let (top, tool, bottom) = stock_of(model);
        Globals {
            file_name,
            program_name: model.name(),
            tool_diameter: tool,
            clearance: model.params.s,
            stock_top: top,
            stock_bottom: bottom.unwrap_or(top),
            program_feed: model.params.f,
        }
    }

    /// Does the program switch the spindle? (A dialect without a spindle ignores the speed,
    /// as the reference does.)
    fn spindle_rpm(&self) -> Option<f64> {
        self.spindle_rpm.filter(|_| self.post.capabilities.spindle)
    }

    /// The lines before the body: `start` is the first sweep height; `spindle` is false for
    /// the probing program (the probe touches with a standing spindle).
    pub(crate) fn prologue(
        &self,
        banner: &str,
        file_name: &str,
        model: &Model,
        start: f64,
        spindle: bool,
    ) -> Vec<String> {
        let g = Controller::globals(model, file_name);
        let mut v = Vec::new();
        if self.post.format.percent {
            v.push("%".into());
        }
        v.push(self.post.comment(0, banner, &g));
        v.push(self.post.comment(0, file_name, &g));
        self.lines(Event::Stock, &[], &g, &mut v);
        self.lines(Event::ProgramStart, &[], &g, &mut v);
        self.lines(Event::Tool, &[(Var::ToolNumber, Value::Int(1))], &g, &mut v);
        if let (true, Some(rpm)) = (spindle, self.spindle_rpm()) {
            self.lines(Event::SpindleOn, &[(Var::Rpm, Value::Num(rpm))], &g, &mut v);
            if self.spindle_dwell > 0.0 && self.post.capabilities.dwell {
                let secs = [(Var::Seconds, Value::Num(self.spindle_dwell))];
                self.lines(Event::Dwell, &secs, &g, &mut v);
            }
        }
        let p = crate::geom::P3 {
            x: 0.0,
            y: 0.0,
            z: start,
        };
        v.push(self.post.comment(0, &format!("SweepSafelyTo {p}"), &g));
        let z = [(Var::Z, Value::Num(start)), (Var::ZProbe, Value::Text(""))];
        self.lines(Event::RapidZ, &z, &g, &mut v);
        let xy = [(Var::X, Value::Num(0.0)), (Var::Y, Value::Num(0.0))];
        self.lines(Event::RapidXy, &xy, &g, &mut v);
        v
    }

    /// A rapid to `at` (the probing programs').
    pub(crate) fn rapid_xy(&self, g: &Globals, at: crate::geom::P2, out: &mut Vec<String>) {
        let xy = [(Var::X, Value::Num(at.x)), (Var::Y, Value::Num(at.y))];
        self.lines(Event::RapidXy, &xy, g, out);
    }

    /// A vertical rapid to `z` (the probing programs': no probes correct it).
    pub(crate) fn rapid_z(&self, g: &Globals, event: Event, z: f64, out: &mut Vec<String>) {
        let vars = [(Var::Z, Value::Num(z)), (Var::ZProbe, Value::Text(""))];
        self.lines(event, &vars, g, out);
    }

    /// The lines after the body (and the statistics).
    pub(crate) fn epilogue(&self, spindle: bool, g: &Globals) -> Vec<String> {
        let mut v = Vec::new();
        let mut end = Vec::new();
        self.lines(Event::ProgramEnd, &[], g, &mut end);
        if spindle && self.spindle_rpm().is_some() {
            let mut off = Vec::new();
            self.lines(Event::SpindleOff, &[], g, &mut off);
            // a program end that starts by stopping the spindle (Marlin's `M5`, which has
            // no end of its own) says it once
            if !end.starts_with(&off) {
                v.extend(off);
            }
        }
        v.extend(end);
        if self.post.format.percent {
            v.push("%".into());
        }
        v
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An editor reloads a post file at every save: each version is freed with the last
    /// settings and programs that use it, none is kept for the process (issue 32).
    #[test]
    fn a_reloaded_post_file_is_freed_with_its_last_user() {
        let mut versions = Vec::new();
        for k in 0..200 {
            let text = millpath_post::builtin::source("linuxcnc")
                .unwrap()
                .replace("name = \"linuxcnc\"", &format!("name = \"mine{k}\""));
            let read = |_: &std::path::Path| Ok(text.clone());
            let base = std::path::Path::new("/project");
            let (dialect, post) =
                select_post("posts/mine.toml", base, &read, crate::diag::Lang::En).unwrap();
            assert_eq!(dialect, Dialect::LinuxCnc);
            let post = post.unwrap();
            assert_eq!(post.name, format!("mine{k}"));
            let s = Settings {
                post: Some(post.clone()),
                ..Settings::default()
            };
            let c = Controller::of(&s);
            assert!(Arc::ptr_eq(&c.post, &post), "the settings' post is shared");
            versions.push(Arc::downgrade(&post));
        }
        assert!(
            versions.iter().all(|v| v.upgrade().is_none()),
            "every version freed once its settings and controllers are gone"
        );
        // a built-in is shared, not copied per use
        let (_, a) = select_post(
            "mach3",
            std::path::Path::new(""),
            &|_| unreachable!(),
            crate::diag::Lang::En,
        )
        .unwrap();
        let (_, b) = select_post(
            "mach3",
            std::path::Path::new(""),
            &|_| unreachable!(),
            crate::diag::Lang::En,
        )
        .unwrap();
        assert!(Arc::ptr_eq(&a.unwrap(), &b.unwrap()));
    }

    #[test]
    fn plunge_feeds() {
        let mut c = Controller::reference();
        assert_eq!(c.plunge(150.0), None);
        c.dialect = Dialect::LinuxCnc;
        assert_eq!(c.plunge(60.0), Some(30.0));
        c.plunge_feed = Some(100.0);
        assert_eq!(c.plunge(150.0), Some(100.0));
        assert_eq!(c.plunge(60.0), Some(60.0), "never faster than the element");
    }
}
