//! Subpath connection: restrictions, search, material/bit/thickness agreement and variable assignments (reference-input.md §5.5, §6.5).

use crate::args;
use crate::build::eval::{with_pos, BuildCtx, Eval};
use crate::diag::{Diagnostic, Msg, Origin};
use crate::front::drawing::{RawPath, RawSegment};
use crate::geom::near;
use crate::load::regex_cache::regex;
use crate::load::session::{Abort, Session};
use crate::model::*;
use crate::params::{fmt_num, parse_definition, Vars};
use std::sync::Arc;

impl Session<'_> {
    /// Checks and loads the target of a subpath embedding (§5.5).
    pub(crate) fn connect(
        &mut self,
        raw: &RawPath,
        seg: &RawSegment,
        params: &PathParams,
        ev: &Eval,
        cx: &BuildCtx,
    ) -> Result<Option<Arc<Model>>, Abort> {
        let text = seg.text.as_deref();
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
        let target_name = m.to_string();
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
            // a known name that differs only in case (`>2100.1p` for 2100.1P): say so, except
            // on the reference's command line, whose messages stay the reference's
            if let Some(name) = self
                .case_twin(&target_name)
                .filter(|_| !self.settings.reference_check)
            {
                self.diags.error(
                    Msg::SubpathNotFoundCase,
                    end_origin,
                    args![target_name, list.join(", "), name],
                );
                return Ok(None);
            }
            // {2}, {3} for people only (the reference line names the files, maybe none):
            // the file that defines the path, or the folders searched and the file pattern
            let (known, place) = match self.raw.get(&target_name) {
                Some(r) => ("known", r.file.path.display().to_string()),
                None => {
                    let mut dirs = vec![raw
                        .file
                        .path
                        .parent()
                        .map_or_else(|| ".".into(), |d| d.display().to_string())];
                    dirs.extend(
                        self.settings
                            .search_dirs
                            .iter()
                            .map(|d| d.display().to_string()),
                    );
                    let dirs: Vec<String> = dirs
                        .into_iter()
                        .map(|d| if d.is_empty() { ".".into() } else { d })
                        .collect();
                    ("searched", dirs.join(", "))
                }
            };
            self.diags.error(
                Msg::CouldNotFind,
                end_origin,
                args![
                    target_name,
                    list.join(", "),
                    place,
                    self.settings.file_pattern,
                    known
                ],
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
    pub(crate) fn check_assignment(&mut self, target: &Model, assignment: &Vars, origin: &Origin) {
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
