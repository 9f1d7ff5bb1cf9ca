//! The toolpath view: moves as JSON, the standalone page and the SVG top view.

use crate::preview::{top_model, TopModel};
use crate::Workspace;
use millpath_core::diag::Origin;
use std::path::{Path, PathBuf};

/// The toolpath of a path as JSON for the toolpath view: moves with kind, start, end, depth,
/// arc and source element; probes; bounds.
pub fn toolpath(
    ws: &Workspace,
    path: &Path,
    name: Option<&str>,
) -> Result<serde_json::Value, String> {
    use serde_json::json;
    // `errors`: missing machine settings (placeholders in use), shown by the view
    let TopModel {
        model,
        lang,
        errors,
        ..
    } = top_model(ws, path, name)?;
    let name = model.name().to_string();
    let tp = millpath_core::emit::toolpath(&model).map_err(|e| {
        e.iter()
            .map(|d| d.message(lang))
            .collect::<Vec<_>>()
            .join("; ")
    })?;
    let mut texts: std::collections::HashMap<PathBuf, crate::LineIndex> =
        std::collections::HashMap::new();
    let mut source_json = |o: &Origin| -> serde_json::Value {
        match o {
            Origin::Span {
                file, start, line, ..
            } => {
                let idx = texts
                    .entry(file.path.clone())
                    .or_insert_with(|| ws.line_index(&ws.text(&file.path).unwrap_or_default()));
                let p = idx.pos(*start);
                let text = ws
                    .text(&file.path)
                    .and_then(|t| t.lines().nth(p.line as usize).map(|l| l.trim().to_string()))
                    .unwrap_or_default();
                json!({ "file": file.path.display().to_string(), "line": line - 1, "character": p.col, "label": format!("{}:{line}", file.name), "text": text })
            }
            Origin::Entity(e) => json!({
                "file": e.file.path.display().to_string(), "line": e.line.saturating_sub(1), "character": 0,
                "label": format!("{}:{}", e.file.name, e.line), "text": format!("{} on layer {} at {}", e.code_name, e.layer, e.pos),
            }),
            o => {
                json!({ "file": o.file().map(|f| f.path.display().to_string()), "line": 0, "character": 0, "label": o.context(), "text": "" })
            }
        }
    };
    let (mut minx, mut miny, mut maxx, mut maxy) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let (mut minz, mut maxz) = (f64::INFINITY, f64::NEG_INFINITY);
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
                minz = minz.min(m.to.z);
                maxz = maxz.max(m.to.z);
            }
            json!({
                "kind": m.kind,
                "from": [m.from.x, m.from.y, m.from.z],
                "to": [m.to.x, m.to.y, m.to.z],
                "depth": m.to.z,
                "arc": m.arc.map(|(c, ccw)| json!({ "cx": c.x, "cy": c.y, "ccw": ccw })),
                "source": m.source.as_ref().map(&mut source_json),
            })
        })
        .collect();
    let probes: Vec<serde_json::Value> = tp
        .probes
        .iter()
        .map(|(n, p)| json!({ "name": n, "x": p.x, "y": p.y }))
        .collect();
    if !minz.is_finite() {
        minz = 0.0;
        maxz = 0.0;
    }
    Ok(json!({
        "path": name,
        "file": path.display().to_string(),
        "moves": moves,
        "probes": probes,
        "bounds": { "minX": minx, "minY": miny, "maxX": maxx, "maxY": maxy, "minZ": minz, "maxZ": maxz },
        "warnings": errors,
    }))
}

/// The toolpath view as a standalone HTML page (the page of `editors/toolpath` with the data
/// embedded).
pub fn toolpath_html(data: &serde_json::Value) -> String {
    const PAGE: &str = include_str!("../../../editors/toolpath/toolpath.html");
    const SLOT: &str = r#"<script id="toolpath-data" type="application/json">null</script>"#;
    let json = data.to_string().replace("</", "<\\/");
    PAGE.replacen(
        SLOT,
        &format!(r#"<script id="toolpath-data" type="application/json">{json}</script>"#),
        1,
    )
}

/// The toolpath as a standalone SVG (top view; cuts coloured by depth, rapid moves dashed,
/// probes as circles).
pub fn toolpath_svg(data: &serde_json::Value) -> String {
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
                colour(f(&m["depth"]))
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
