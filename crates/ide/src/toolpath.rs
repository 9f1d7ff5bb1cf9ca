//! The toolpath view: moves as JSON, the standalone page and the SVG top view.
//!
//! The toolpath as JSON (`toolpath_until`: stops inside the emitters when asked; moves rounded to 3
//! decimals, sources shared by index, tool O, stock T, statistics; `warnings`: placeholder machine
//! settings; `clamps` and each move's `hits`; `cut`), the standalone page
//! (`editors/toolpath/toolpath.html` by `include_str!`), the SVG top view.

use crate::preview::{top_model_from, top_model_until, TopModel};
use crate::Workspace;
use millpath_core::diag::Origin;
use std::path::{Path, PathBuf};

/// Rounded to the output precision (3 decimals), without float noise in the JSON.
fn r3(v: f64) -> f64 {
    let r = (v * 1000.0).round() / 1000.0;
    if r == 0.0 {
        0.0
    } else {
        r
    }
}

/// The toolpath of a path as JSON for the toolpath view: one entry per move of the written
/// program (after the optimizer) with kind, start, end, arc, source element (for chains the
/// segment's), G-code line and text, feed and time; probes; bounds; tool, stock and
/// statistics. Numbers are rounded to the output precision.
pub fn toolpath(
    ws: &Workspace,
    path: &Path,
    name: Option<&str>,
) -> Result<serde_json::Value, String> {
    toolpath_until(ws, path, name, &|| false).unwrap_or_else(|| Err("cancelled".into()))
}

/// [`toolpath`] that gives up (`None`) when `stop()` turns true: inside the emitter of the
/// moves and of the written program, and between the stages.
pub fn toolpath_until(
    ws: &Workspace,
    path: &Path,
    name: Option<&str>,
    stop: &dyn Fn() -> bool,
) -> Option<Result<serde_json::Value, String>> {
    let built = top_model_until(ws, path, name, stop);
    if stop() {
        return None;
    }
    let tp = built.map(|t| {
        let moves =
            millpath_core::emit::toolpath_until(&t.model, &t.controller, t.sweep_speed, Some(stop));
        (t, moves)
    });
    if stop() {
        return None;
    }
    let program = match &tp {
        Ok((t, _)) => written(&t.model, path, &t.controller, t.sweep_speed, t.lang, stop),
        Err(_) => None,
    };
    if stop() {
        return None;
    }
    Some(tp.and_then(|(t, moves)| toolpath_json(ws, path, t, moves, program)))
}

/// The moves of a path as [`toolpath`] finds them, without what only the page needs (no
/// JSON, no written program, no cut part, no clamp hits): what `millpath diff` compares.
pub fn toolpath_moves(
    ws: &Workspace,
    path: &Path,
    name: Option<&str>,
) -> Result<millpath_core::emit::Toolpath, String> {
    let t = top_model_until(ws, path, name, &|| false)?;
    millpath_core::emit::toolpath_until(&t.model, &t.controller, t.sweep_speed, None).map_err(|e| {
        e.iter()
            .map(|d| d.message(t.lang))
            .collect::<Vec<_>>()
            .join("; ")
    })
}

/// [`toolpath_moves`] of a document already analysed: its paths are taken from the
/// analysis (read and parsed once for any number of paths and for the effective values);
/// an analysis with errors in the document reads the file again, as `compile` would.
pub fn toolpath_moves_of(
    ws: &Workspace,
    a: &crate::Analysis,
    name: &str,
) -> Result<millpath_core::emit::Toolpath, String> {
    let analysed = (crate::is_text_file(&a.path) && !a.has_errors()).then_some(a);
    let t = top_model_from(ws, &a.path, analysed, Some(name), &|| false)?;
    millpath_core::emit::toolpath_until(&t.model, &t.controller, t.sweep_speed, None).map_err(|e| {
        e.iter()
            .map(|d| d.message(t.lang))
            .collect::<Vec<_>>()
            .join("; ")
    })
}

/// The JSON of [`toolpath`] from the built model, its moves and its written program.
fn toolpath_json(
    ws: &Workspace,
    path: &Path,
    built: TopModel,
    moves: Result<millpath_core::emit::Toolpath, Vec<millpath_core::Diagnostic>>,
    program: Option<String>,
) -> Result<serde_json::Value, String> {
    use serde_json::json;
    // `errors`: missing machine settings (placeholders in use), shown by the view
    let TopModel {
        model,
        lang,
        errors,
        controller,
        clamps,
        cut_cell,
        ..
    } = built;
    let name = model.name().to_string();
    let tp = moves.map_err(|e| {
        e.iter()
            .map(|d| d.message(lang))
            .collect::<Vec<_>>()
            .join("; ")
    })?;
    // the written program: its moves against the clamps, its stock for the cut part
    let hits = clamp_hits(program.as_deref(), &model, &controller, &clamps);
    let cut = program.as_deref().and_then(|p| {
        let (top, tool) = (model.params.t, model.params.o);
        crate::cut_view::cut_json(p, &controller, top, tool, cut_cell)
    });
    // each file's line index and lines, made once (a program has many elements per file)
    let mut texts: std::collections::HashMap<PathBuf, (crate::LineIndex, Vec<String>)> =
        std::collections::HashMap::new();
    let mut source_json = |o: &Origin| -> serde_json::Value {
        match o {
            Origin::Span {
                file, start, line, ..
            } => {
                let (idx, lines) = texts.entry(file.path.clone()).or_insert_with(|| {
                    let text = ws.text(&file.path).unwrap_or_default();
                    let lines = text.lines().map(|l| l.trim().to_string()).collect();
                    (ws.line_index(&text), lines)
                });
                let p = idx.pos(*start as usize);
                let text = lines.get(p.line as usize).cloned().unwrap_or_default();
                json!({ "file": file.path.display().to_string(), "line": line - 1, "character": p.col, "label": format!("{}:{line}", file.name), "text": text })
            }
            Origin::Entity(e) => json!({
                "file": e.file.path.display().to_string(), "line": e.line.saturating_sub(1), "character": 0,
                "label": format!("{}:{}", e.file.name, e.line), "text": match lang {
                    millpath_core::Lang::En => format!("{} on layer {} at {}", e.code_name, e.layer, e.pos),
                    millpath_core::Lang::De => format!("{} auf Layer {} bei {}", e.code_name, e.layer, e.pos),
                },
            }),
            o => {
                json!({ "file": o.file().map(|f| f.path.display().to_string()), "line": 0, "character": 0, "label": o.context(), "text": "" })
            }
        }
    };
    let (mut minx, mut miny, mut maxx, mut maxy) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let (mut minz, mut maxz) = (f64::INFINITY, f64::NEG_INFINITY);
    let xyz = |p: millpath_core::geom::P3| [r3(p.x), r3(p.y), r3(p.z)];
    // the sources of one element are shared: one JSON object per origin, referenced by index
    let mut sources: Vec<serde_json::Value> = Vec::new();
    let mut source_index: std::collections::HashMap<String, usize> =
        std::collections::HashMap::new();
    let moves: Vec<serde_json::Value> = tp
        .moves
        .iter()
        .map(|m| {
            for p in [m.from, m.to] {
                minx = minx.min(p.x);
                miny = miny.min(p.y);
                maxx = maxx.max(p.x);
                maxy = maxy.max(p.y);
            }
            if let Some((c, _)) = m.arc {
                let r = c.dist(m.to.xy());
                minx = minx.min(c.x - r);
                miny = miny.min(c.y - r);
                maxx = maxx.max(c.x + r);
                maxy = maxy.max(c.y + r);
            }
            if m.kind != "rapid" {
                minz = minz.min(m.to.z).min(m.from.z);
                maxz = maxz.max(m.to.z).max(m.from.z);
            }
            let source = m.source.as_ref().map(|o| {
                let key = format!("{o:?}");
                *source_index.entry(key).or_insert_with(|| {
                    sources.push(source_json(o));
                    sources.len() - 1
                })
            });
            let mut v = json!({
                "kind": m.kind,
                "from": xyz(m.from),
                "to": xyz(m.to),
                "arc": m.arc.map(|(c, ccw)| json!({ "cx": r3(c.x), "cy": r3(c.y), "ccw": ccw })),
                "source": source,
                "line": m.line,
                "gcode": m.gcode,
                "feed": r3(m.feed),
                "t": r3(m.seconds),
            });
            // the clamps this move runs into (only on such moves: large programs stay small)
            if let Some(h) = hits.get(&m.line) {
                v["hits"] = json!(h);
            }
            v
        })
        .collect();
    let probes: Vec<serde_json::Value> = tp
        .probes
        .iter()
        .map(|p| json!({ "name": p.name, "x": r3(p.pos.x), "y": r3(p.pos.y), "z": r3(p.z) }))
        .collect();
    if !minz.is_finite() {
        minz = 0.0;
        maxz = 0.0;
    }
    // `[heightmap]`: its probe points at the nominal top (not measured yet)
    let heightmap = tp
        .heightmap
        .as_ref()
        .map(|g| crate::heightmap_view::heightmap_json(&g.xs, &g.ys, None, model.params.t));
    let stats = &tp.stats;
    let mut stat_lines = tp.stats.lines(lang).to_vec();
    stat_lines.extend(stats.model_line(lang));
    stat_lines.extend(stats.split_line(lang));
    stat_lines.push(stats.time_line(lang));
    let mut data = json!({
        // the page's words follow the settings' language, as the statistics above
        "lang": match lang {
            millpath_core::Lang::En => "en",
            millpath_core::Lang::De => "de",
        },
        "path": name,
        "file": path.display().to_string(),
        "moves": moves,
        "sources": sources,
        "probes": probes,
        "start": xyz(tp.start),
        "tool": { "diameter": r3(model.params.o) },
        "stock": { "top": r3(model.params.t) },
        "stats": stat_lines,
        "seconds": r3(stats.seconds()),
        "time": millpath_core::emit::stats::hms(stats.seconds()),
        "bounds": { "minX": r3(minx), "minY": r3(miny), "maxX": r3(maxx), "maxY": r3(maxy), "minZ": r3(minz), "maxZ": r3(maxz) },
        "warnings": errors,
        "heightmap": serde_json::Value::Null,
        "cut": cut,
        "clamps": clamps.iter().map(|c| json!({ "name": c.name, "min": c.min, "max": c.max })).collect::<Vec<_>>(),
    });
    if let Some(hm) = heightmap {
        crate::heightmap_view::grow_bounds(&mut data, &hm);
        data["heightmap"] = hm;
    }
    Ok(data)
}

/// The program compile writes (the clean program when there are probes); `None` when it
/// cannot be written.
fn written(
    model: &millpath_core::model::Model,
    path: &Path,
    controller: &millpath_core::emit::Controller,
    sweep_speed: f64,
    lang: millpath_core::Lang,
    stop: &dyn Fn() -> bool,
) -> Option<String> {
    let file_name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let banner = millpath_core::banner();
    let g = millpath_core::emit::generate_until(
        model,
        &file_name,
        &banner,
        sweep_speed,
        lang,
        controller,
        Some(stop),
    )
    .ok()?;
    Some(match g.output {
        millpath_core::emit::Output::Milling(p) => p,
        millpath_core::emit::Output::Probing { clean, .. } => clean,
    })
}

/// The clamps each G-code line's move touches (indexes into `clamps`), by the same check as
/// compile's on the program compile writes; empty without clamps.
fn clamp_hits(
    program: Option<&str>,
    model: &millpath_core::model::Model,
    controller: &millpath_core::emit::Controller,
    clamps: &[millpath_verify::Clamp],
) -> std::collections::HashMap<usize, Vec<usize>> {
    let mut by_line: std::collections::HashMap<usize, Vec<usize>> = Default::default();
    let Some(program) = program.filter(|_| !clamps.is_empty()) else {
        return by_line;
    };
    // read by the post's family, as compile's check reads the program
    let found = millpath_core::second_opinion::clamp_hits(
        program,
        model,
        controller.dialect,
        &controller.post,
        clamps,
    );
    for (line, k) in found {
        by_line.entry(line).or_default().push(k);
    }
    by_line
}

/// The toolpath view as a standalone HTML page (the page of `editors/toolpath` with the data
/// embedded).
pub fn toolpath_html(data: &serde_json::Value) -> String {
    const PAGE: &str = include_str!("../assets/toolpath.html");
    const SLOT: &str = r#"<script id="toolpath-data" type="application/json">null</script>"#;
    let json = data.to_string().replace("</", "<\\/");
    PAGE.replacen(
        SLOT,
        &format!(r#"<script id="toolpath-data" type="application/json">{json}</script>"#),
        1,
    )
}

/// The toolpath as a standalone SVG (top view; cuts coloured by depth, rapid moves dashed,
/// probes as circles); `cut`: the cut part under the moves.
pub fn toolpath_svg(data: &serde_json::Value, cut: bool) -> String {
    use std::fmt::Write;
    let b = &data["bounds"];
    let f = |v: &serde_json::Value| v.as_f64().unwrap_or(0.0);
    let (minx, miny, maxx, maxy, minz, maxz) = (
        f(&b["minX"]),
        f(&b["minY"]),
        f(&b["maxX"]),
        f(&b["maxY"]),
        f(&b["minZ"]),
        f(&b["maxZ"]),
    );
    let (w, h) = ((maxx - minx).max(1.0), (maxy - miny).max(1.0));
    let pad = w.max(h) * 0.05 + 2.0;
    let colour = |z: f64| {
        let t = if maxz > minz {
            ((maxz - z) / (maxz - minz)).clamp(0.0, 1.0)
        } else {
            1.0
        };
        format!("hsl({:.0},80%,45%)", 220.0 - 220.0 * t)
    };
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="{} {} {} {}" width="{:.0}mm" height="{:.0}mm">"#,
        minx - pad,
        -(maxy + pad),
        w + 2.0 * pad,
        h + 2.0 * pad,
        w + 2.0 * pad,
        h + 2.0 * pad
    );
    let _ = writeln!(
        s,
        r#"<g transform="scale(1,-1)" fill="none" stroke-linecap="round">"#
    );
    let stroke = (w.max(h) / 400.0).max(0.05);
    if cut && data["cut"].is_object() {
        s.push_str(&crate::cut_view::cut_svg(&data["cut"]));
    }
    if data["heightmap"].is_object() {
        s.push_str(&crate::heightmap_view::svg(&data["heightmap"], stroke));
    }
    for m in data["moves"].as_array().into_iter().flatten() {
        let kind = m["kind"].as_str().unwrap_or("");
        let (fx, fy) = (f(&m["from"][0]), f(&m["from"][1]));
        let (tx, ty) = (f(&m["to"][0]), f(&m["to"][1]));
        let style = if kind == "rapid" {
            format!(
                r##"stroke="#888" stroke-width="{}" stroke-dasharray="{} {}""##,
                stroke / 2.0,
                stroke * 3.0,
                stroke * 3.0
            )
        } else {
            format!(
                r#"stroke="{}" stroke-width="{stroke}""#,
                colour(f(&m["to"][2]))
            )
        };
        if (tx - fx).hypot(ty - fy) < 1e-9 {
            if kind != "rapid" {
                let _ = writeln!(
                    s,
                    r#"<circle cx="{tx}" cy="{ty}" r="{}" {style}/>"#,
                    stroke * 1.5
                );
            }
        } else if m["arc"].is_object() {
            let (cx, cy) = (f(&m["arc"]["cx"]), f(&m["arc"]["cy"]));
            let ccw = m["arc"]["ccw"].as_bool().unwrap_or(true);
            let r = (fx - cx).hypot(fy - cy);
            let (a0, a1) = ((fy - cy).atan2(fx - cx), (ty - cy).atan2(tx - cx));
            let mut sweep = if ccw { a1 - a0 } else { a0 - a1 };
            while sweep <= 1e-9 {
                sweep += std::f64::consts::TAU;
            }
            let large = u8::from(sweep > std::f64::consts::PI);
            let _ = writeln!(
                s,
                r#"<path d="M{fx} {fy} A{r} {r} 0 {large} {} {tx} {ty}" {style}/>"#,
                u8::from(ccw)
            );
        } else {
            let _ = writeln!(
                s,
                r#"<line x1="{fx}" y1="{fy}" x2="{tx}" y2="{ty}" {style}/>"#
            );
        }
    }
    for p in data["probes"].as_array().into_iter().flatten() {
        let _ = writeln!(
            s,
            r##"<circle cx="{}" cy="{}" r="3" stroke="#0a7d3a" stroke-width="{stroke}"/>"##,
            f(&p["x"]),
            f(&p["y"])
        );
    }
    s.push_str("</g>\n</svg>\n");
    s
}
