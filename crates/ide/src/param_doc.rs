//! Meaning, unit, default and allowed places of each parameter letter.

use millpath_core::front::drawing::{SegKind, Style as CoreStyle, PATH_KEYS_HEIGHTMAP, PROBE_KEYS};
use millpath_syntax::Kind;
use millpath_syntax::Style;

/// Meaning, unit and default of a parameter letter.
pub fn param_doc(key: char, german: bool) -> Option<(&'static str, &'static str, &'static str)> {
    let en = match key {
        'A' => ("largest helix diameter", "mm", "4·O"),
        'B' => (
            "bottom: milling depth",
            "mm",
            "inherited from the path start",
        ),
        'C' => ("G81 depth (not used)", "", "none"),
        'D' => (
            "marking depth; top of support bars",
            "mm",
            "inherited from the path start",
        ),
        'E' => (
            "subpaths this path may embed (regular expression)",
            "",
            "the /e restrictions",
        ),
        'F' => (
            "feed for milling moves",
            "mm/min",
            "the machine feed (/f, millpath.toml)",
        ),
        'H' => ("extra height of a subpath or probe", "mm", "0"),
        'I' => (
            "infeed per pass; helix pitch",
            "mm",
            "inherited from the path start",
        ),
        'K' => (
            "height map: probe a grid every <step> mm over the cuts, K<step> or K<step>+<margin> (linuxcnc, grbl)",
            "mm",
            "none ([heightmap] of millpath.toml)",
        ),
        'L' => ("z-probe label", "", "none"),
        'M' => (
            "material (must match between project and subpath)",
            "",
            "none",
        ),
        'N' => (
            "order at branch points (lower first)",
            "",
            "unnumbered: after numbered segments",
        ),
        'O' => ("bit diameter", "mm", "required"),
        'P' => ("support-bar length", "mm", "inherited from the path start"),
        'Q' => ("comment, written into the G-code", "", "none"),
        'R' => ("suffix of the output file names", "", "none"),
        'S' => (
            "sweep height",
            "mm",
            "top level: /s; subpaths and checks: T+O",
        ),
        'T' => ("top of the material (thickness)", "mm", "required"),
        'U' => (
            "smallest distance between support bars",
            "mm",
            "inherited from the path start",
        ),
        'W' => (
            "first depth of sweepless milling",
            "mm",
            "none (fast milling)",
        ),
        'Z' => ("probe feed", "mm/min", "the probe feed (/z), else the feed"),
        '>' => ("name of the embedded subpath", "", "required on sub lines"),
        '@' => (
            "use the start text of another path of this file",
            "",
            "none",
        ),
        ':' => (
            "variable: definition at the start, assignment on sub lines",
            "",
            "none",
        ),
        _ => return None,
    };
    if !german {
        return Some(en);
    }
    Some(match key {
        'A' => ("größter Helix-Durchmesser", "mm", "4·O"),
        'B' => ("Boden: Frästiefe", "mm", "vom Pfadanfang geerbt"),
        'C' => ("G81-Tiefe (nicht benutzt)", "", "keiner"),
        'D' => (
            "Markierungstiefe; Oberkante der Haltestege",
            "mm",
            "vom Pfadanfang geerbt",
        ),
        'E' => (
            "erlaubte Teilpfade (regulärer Ausdruck)",
            "",
            "die /e-Regeln",
        ),
        'F' => (
            "Vorschub der Fräsbewegungen",
            "mm/min",
            "Maschinenvorschub (/f, millpath.toml)",
        ),
        'H' => ("Zusatzhöhe eines Teilpfads oder Fühlpunkts", "mm", "0"),
        'I' => (
            "Zustellung je Durchgang; Helix-Steigung",
            "mm",
            "vom Pfadanfang geerbt",
        ),
        'K' => (
            "Höhenkarte: ein Raster alle <Abstand> mm über den Fräsbewegungen antasten, K<Abstand> oder K<Abstand>+<Rand> (linuxcnc, grbl)",
            "mm",
            "keine ([heightmap] der millpath.toml)",
        ),
        'L' => ("Name des Fühlpunkts", "", "keiner"),
        'M' => (
            "Material (muss bei Projekt und Teilpfad gleich sein)",
            "",
            "keiner",
        ),
        'N' => (
            "Reihenfolge an Verzweigungen (kleinere zuerst)",
            "",
            "ohne: nach nummerierten Segmenten",
        ),
        'O' => ("Fräserdurchmesser", "mm", "nötig"),
        'P' => ("Haltesteg-Länge", "mm", "vom Pfadanfang geerbt"),
        'Q' => ("Kommentar im G-Code", "", "keiner"),
        'R' => ("Zusatz der Ausgabe-Dateinamen", "", "keiner"),
        'S' => (
            "Leerfahrt-Höhe",
            "mm",
            "Hauptpfad: /s; Teilpfade und Prüfung: T+O",
        ),
        'T' => ("Materialoberkante (Dicke)", "mm", "nötig"),
        'U' => (
            "kleinster Abstand der Haltestege",
            "mm",
            "vom Pfadanfang geerbt",
        ),
        'W' => (
            "erste Tiefe beim leerfahrtlosen Fräsen",
            "mm",
            "keiner (schnelles Fräsen)",
        ),
        'Z' => (
            "Fühl-Vorschub",
            "mm/min",
            "Fühl-Vorschub (/z), sonst Vorschub",
        ),
        '>' => (
            "Name des eingebetteten Teilpfads",
            "",
            "nötig bei Teilpfad-Linien",
        ),
        '@' => (
            "Starttext eines anderen Pfads dieser Datei verwenden",
            "",
            "keiner",
        ),
        ':' => (
            "Variable: Definition am Start, Zuweisung an Teilpfad-Linien",
            "",
            "keiner",
        ),
        _ => en,
    })
}

/// Where a key is allowed, as element kinds.
pub(crate) fn allowed_in(key: char) -> Vec<&'static str> {
    let mut v = Vec::new();
    if PATH_KEYS_HEIGHTMAP.contains(key) || key == '@' {
        v.push("start");
    }
    for (name, kind) in [
        ("mill/mark/bars", SegKind::Mill(CoreStyle::Mill)),
        (
            "sweep",
            SegKind::Sweep(millpath_core::front::drawing::SweepKind::Dashed),
        ),
        ("drill", SegKind::Drill(CoreStyle::Mill)),
        ("helix", SegKind::Helix(CoreStyle::Support)),
        ("sub", SegKind::Subpath),
    ] {
        if kind.allowed_keys().contains(key) {
            v.push(name);
        }
    }
    if PROBE_KEYS.contains(key) {
        v.push("probe");
    }
    v
}

/// The keys that make sense on an element of this kind.
pub(crate) fn keys_for(kind: &Kind) -> &'static str {
    match kind {
        Kind::Start => "ABCDEFIKMOPRSTUWZ@:",
        Kind::Mill | Kind::Mark | Kind::Bars => "BCDFINPQSUW",
        Kind::Sweep => "NS",
        Kind::Sub => "HMNOT>:",
        Kind::Probe => "HLTZ",
        Kind::Drill(Style::Mark) => "CDFQ",
        Kind::Drill(_) => "BCFQ",
        Kind::Helix(Style::Mill) => "BFIQ",
        Kind::Helix(Style::Mark) => "DFIQ",
        Kind::Helix(Style::Bars) => "BDFIPQU",
        _ => "",
    }
}
