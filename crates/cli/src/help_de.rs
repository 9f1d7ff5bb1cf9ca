//! The descriptions of the commands and their arguments in German, for help pages in a
//! German run. The English texts are the doc comments in `main.rs` and `args.rs`; this table
//! follows them (a test fails for any argument or command without a German text).

use clap::Command;

/// Descriptions of the subcommands.
fn about(cmd: &str) -> Option<&'static str> {
    Some(match cmd {
        "compile" => "Pfadzeichnungen (DXF oder .mpath) in G-Code übersetzen (ein Pfad je Datei; ein Ordner: jede Zeichnung darin)",
        "check" => "Jeden Pfad jeder Zeichnung prüfen, DXF oder .mpath (Ordner: alle *.dxf und *.mpath darin); schreibt nichts",
        "verify" => "G-Code-Programme unabhängig vom Übersetzer prüfen: Eilgänge ins Material, Vorschübe, Bögen, Zahlen (Exit-Status 1 bei jedem Fehler)",
        "adjust-z" => "Aus NAME_Clean.gcode und der gemessenen NAME_Z.txt das Programm NAME_Milling.gcode machen",
        "dxf2text" => "Eine DXF-Zeichnung als MillPath-Text ausgeben (auch als textconv-Treiber für git)",
        "text2dxf" => "MillPath-Text als DXF-Zeichnung schreiben, oder mit --into in eine vorhandene Zeichnung",
        "merge" => "Merge-Treiber für git, für Zeichnungen und MillPath-Texte: `millpath merge %O %A %B %P`",
        "fmt" => "MillPath-Dateien an Ort und Stelle formatieren (Ordner: alle *.mpath darin)",
        "render" => "Die Werkzeugbahn eines Pfads zeichnen: eine eigenständige HTML-Seite (3-D-Ansicht), ein SVG oder ein PNG der Draufsicht",
        "diff" => "Was sich zwischen zwei Fassungen von Zeichnungen geändert hat und was es am Teil bewirkt: ALT NEU, REV -- DATEI… oder REV..REV (Exit-Status 0: keine Änderung, 1: geändert, 2: Fehler)",
        "difftool" => "Der sichtbare Vergleich für `git difftool -t millpath`: LOCAL REMOTE [MERGED] als HTML-Seite (ihr Pfad wird ausgegeben)",
        "lsp" => "Sprachserver über Standardein- und -ausgabe (für Editoren)",
        "post" => "Die Postprozessoren: die eingebauten auflisten, einen als Post-Datei zum Anpassen ausgeben",
        "list" => "Die eingebauten Posts auflisten: Name, Familie, Beschreibung",
        "show" => "Einen eingebauten Post als Post-Datei ausgeben (mit der unveränderten Datei übersetzt gibt es die Ausgabe des eingebauten)",
        "pathdxf2gcode" => "Ersatz für die Befehlszeile von PathDxf2GCode",
        "pathgcodeadjustz" => "Ersatz für die Befehlszeile von PathGCodeAdjustZ",
        "help" => "Diese Hilfe oder die Hilfe des angegebenen Befehls anzeigen",
        _ => return None,
    })
}

/// Descriptions of the arguments: by command and argument id, else by id alone.
fn arg(cmd: &str, id: &str) -> Option<&'static str> {
    let own = match (cmd, id) {
        ("compile", "files") => Some("Zeichnungen (.dxf oder .mpath; ein Name ohne Endung bekommt .dxf) oder Ordner"),
        ("check", "paths") => Some("Zeichnungen (.dxf oder .mpath) oder Ordner"),
        ("show", "name") => Some("Der Name des eingebauten Posts"),
        ("check", "max_warnings") => Some("Exit-Status 1 bei mehr als N Warnungen, auch ohne Fehler (wie bei ESLint; Standard: max_warnings aus millpath.toml, sonst keine Grenze)"),
        ("check", "format") => Some("Form des Berichts: human (Text), json, github (Anmerkungen im Workflow, Pfade relativ zum Repository) oder sarif (Code-Scanning)"),
        ("verify", "files") => Some("Die zu prüfenden G-Code-Programme"),
        ("verify", "dialect") => Some("Wessen Vorschub-Regeln gelten"),
        ("verify", "format") => Some("Form des Berichts: human (Text) oder json"),
        ("verify", "surface") => Some("Die Programme gegen diese auf der Maschine gemessene Oberfläche prüfen statt gegen ihren eigenen Eintrag (MILLPATH-SURFACE …): ein Antast-Protokoll (LinuxCNC PROBEOPEN, GRBL-Konsole mit [PRB:…], Zeilen x y z), eine ausgefüllte _Z.txt oder ein angepasstes Programm"),
        ("verify", "clamp") => Some("Ein Sperrbereich (Quader), den das Werkzeug nie berühren darf, in mm (mehrfach möglich); ohne --clamp und --config: die [[clamp]]-Quader der nächsten millpath.toml über jedem Programm"),
        ("verify", "config") => Some("Die [[clamp]]-Quader aus dieser millpath.toml lesen"),
        ("verify", "tolerance") => Some("Mit --surface: größter XY-Abstand in mm zwischen Messungen derselben Rasterlinie"),
        ("verify" | "adjust-z", "lang") => Some("Sprache der Meldungen (Standard: lang aus millpath.toml, sonst Englisch)"),
        ("adjust-z", "probe_log") => Some("Die gemessenen Höhen aus diesem Protokoll der Steuerung lesen (LinuxCNC PROBEOPEN, GRBL-Konsole mit [PRB:…], Zeilen x y z oder eine ausgefüllte _Z.txt) statt aus den Werten der NAME_Z.txt; nur ein Programm"),
        ("adjust-z", "tolerance") => Some("Mit --probe-log: größter XY-Abstand in mm zwischen einer Messung und ihrem Antastpunkt"),
        ("adjust-z", "post") => Some("Der Post, mit dem die Programme geschrieben wurden, Name eines eingebauten oder eine Post-Datei (Standard: `post =` oder `dialect =` ihrer millpath.toml); die Wege einer Höhenkarte werden in seinen Worten geschrieben"),
        ("adjust-z", "files") => Some("Die angetasteten Programme: NAME_Clean.gcode (oder NAME; NAME_Z.txt wird daneben gelesen)"),
        ("dxf2text", "file") => Some("Die auszugebende DXF-Zeichnung"),
        ("dxf2text", "output") => Some("In diese Datei schreiben statt auf die Standardausgabe (`-`: Standardausgabe)"),
        ("dxf2text", "force") => Some("Eine vorhandene Datei von -o ersetzen, die nicht der Text dieser Zeichnung ist (nicht zurückgeschriebene Änderungen gingen verloren)"),
        ("dxf2text", "extended") => Some("Polylinien und Blöcke werden zu einfachen Elementen (oder `input = \"extended\"`)"),
        ("dxf2text" | "text2dxf", "config") => Some("Einstellungsdatei (Standard: die nächste millpath.toml über der Eingabe)"),
        ("text2dxf", "file") => Some("Der zu wandelnde MillPath-Text (.mpath)"),
        ("text2dxf", "output") => Some("Die zu schreibende DXF-Datei (Standard: der Text mit .dxf, oder die Zeichnung von --into; `-`: Standardausgabe)"),
        ("text2dxf", "path_pattern") => Some("Pfadnamen-Muster: welche Layer Pfad-Layer sind (ihre Elemente werden geschrieben oder ersetzt)"),
        ("text2dxf", "file_pattern") => Some("Dateinamen-Muster (wie bei compile; text2dxf liest keine anderen Dateien, es ändert hier also nichts)"),
        ("text2dxf", "extended") => Some("Der Text kam von `dxf2text --extended`: Polylinien und Blockreferenzen auf den Pfad-Layern wurden zu Elementen, also ersetzt --into (und die Prüfung vor dem Überschreiben) auch sie"),
        ("merge", "base") => Some("Der gemeinsame Vorgänger (%O von git; leer oder fehlend: beide Seiten haben die Datei hinzugefügt)"),
        ("merge", "ours") => Some("Unsere Version (%A von git), die das Ergebnis ersetzt"),
        ("merge", "theirs") => Some("Ihre Version (%B von git)"),
        ("merge", "path") => Some("Der Name der Datei im Repository (%P von git): ihre Endung sagt .dxf oder .mpath, und der Konflikt einer Zeichnung wird daneben geschrieben"),
        ("fmt", "paths") => Some("MillPath-Dateien (.mpath) oder Ordner"),
        ("render", "cut") => Some("Das gefräste Teil (das Material nach dem Programm, nach Tiefe gefärbt) auch ins SVG und PNG zeichnen (die HTML-Seite hat es immer)"),
        ("render", "cut_cell") => Some("Zellgröße des gefrästen Teils in mm (Standard: cut_cell aus millpath.toml, sonst die der Prüfung, O/8 wo die Fläche es erlaubt)"),
        ("render", "file") => Some("Die Zeichnung (.dxf oder .mpath; ein Name ohne Endung bekommt .dxf)"),
        ("render", "surface") => Some("Die auf der Maschine gemessene Oberfläche unter den Bewegungen zeichnen: ein Antast-Protokoll (LinuxCNC PROBEOPEN, GRBL-Konsole mit [PRB:…], Zeilen x y z), eine ausgefüllte _Z.txt oder ein angepasstes Programm (NAME_Milling.gcode)"),
        ("diff", "format") => Some("Form des Berichts: human (Text), json, markdown (ein Kommentar im Pull-Request)"),
        ("diff", "no_compile") => Some("Die Zeichnungen nur wie geschrieben vergleichen: nicht übersetzen"),
        ("diff", "revs") => Some("ALT NEU (zwei Zeichnungen), oder eine git-Revision REV oder REV..REV (Standard HEAD)"),
        ("diff", "files") => Some("Mit einer Revision: die zu vergleichenden Zeichnungen (Standard: die, die git als geändert nennt)"),
        ("diff", "html") => Some("Den sichtbaren Vergleich als HTML-Seite hierhin schreiben (entfernt rot, hinzugefügt grün, andere Tiefe blau; Umschalter vorher/nachher; Klick auf eine Bewegung zeigt ihr Element)"),
        ("diff", "svg") => Some("Den sichtbaren Vergleich als SVG hierhin schreiben"),
        ("diff", "png") => Some("Den sichtbaren Vergleich als PNG hierhin schreiben (kein Browser nötig)"),
        ("diff", "at") => Some("Mit ALT NEU: beide sind Fassungen dieser Zeichnung (Kopien an anderer Stelle, wie ein Editor sie schreibt): ihre Teilpfade und millpath.toml gelten"),
        ("difftool", "local") => Some("Die alte Fassung ($LOCAL von git)"),
        ("difftool", "remote") => Some("Die neue Fassung ($REMOTE von git)"),
        ("difftool", "merged") => Some("Die Zeichnung im Arbeitsverzeichnis ($MERGED von git): wo Teilpfade und millpath.toml liegen"),
        ("difftool", "html") => Some("Die Seite hierhin schreiben (Standard: millpath-diff-NAME.html im temporären Ordner)"),
        ("difftool", "open") => Some("Die Seite im Browser öffnen"),
        _ => None,
    };
    own.or(match id {
        "feed" => Some("Vorschub der Fräsbewegungen, mm/min (oder `feed` in millpath.toml)"),
        "sweep_speed" => Some("Geschwindigkeit der Leerfahrten für die Zeitschätzung, mm/min (oder `sweep_speed`)"),
        "sweep_height" => Some("Höhe der Leerfahrten des obersten Pfads, mm (oder `sweep_height`)"),
        "probe_feed" => Some("Vorschub beim Antasten, mm/min (Standard: der Vorschub)"),
        "search_dirs" => Some("Weiterer Ordner, in dem Teilpfade gesucht werden (mehrfach möglich)"),
        "path_pattern" => Some("Pfadnamen-Muster"),
        "file_pattern" => Some("Dateinamen-Muster"),
        "restrictions" => Some("ELTERN:KIND — Pfade, die auf ELTERN passen, dürfen nur Teilpfade einbetten, die auf KIND passen"),
        "debug_texts" => Some("Zeigen, welchem Element jeder Text zugeordnet wurde, der auf REGEX passt"),
        "lang" => Some("Sprache der Meldungen"),
        "config" => Some("Einstellungsdatei (Standard: die nächste millpath.toml über der ersten Eingabe)"),
        "dialect" => Some("Steuerung, für die die Programme geschrieben werden (oder `dialect`; Standard reference)"),
        "post" => Some("Post, der die Programme schreibt: ein eingebauter Name (`millpath post list`) oder eine Post-Datei (oder `post` in millpath.toml; vor --dialect)"),
        "plunge_feed" => Some("Eintauchvorschub in linuxcnc/grbl, mm/min (oder `plunge_feed`; Standard der halbe Vorschub)"),
        "spindle_rpm" => Some("Spindeldrehzahl in linuxcnc/grbl: M3 S… am Anfang, M5 am Ende (oder `spindle_rpm`)"),
        "spindle_dwell" => Some("Sekunden Wartezeit nach dem Spindelstart (oder `spindle_dwell`; Standard 2)"),
        "feed_override" => Some("Vorschub-Override (Prozent, 1–1000), mit dem die Zeitschätzung rechnet: die Vorschübe skalieren, Eilgänge und Beschleunigungsphasen nicht (oder `feed_override`; Standard 100)"),
        "heightmap_step" => Some("Ein Raster über den Fräsbewegungen antasten, Punkte alle STEP mm (oder `step` in `[heightmap]`; linuxcnc und grbl)"),
        "heightmap_margin" => Some("Rand um die Fräsbewegungen für die Höhenkarte, mm (oder `margin` in `[heightmap]`; Standard 0)"),
        "probe_split" => Some("Bei gezeichneten Messpunkten Bewegungen länger als L mm in Teilstücken fräsen, jedes an seinem eigenen Anfang korrigiert (oder `probe_split`; linuxcnc und grbl)"),
        "extended" => Some("Polylinien, Blöcke, Linientyp-Namen anderer CAD-Programme und $INSUNITS lesen (oder `input = \"extended\"`; Standard: wie PathDxf2GCode, mit einer Warnung für das Ignorierte)"),
        "quiet" => Some("Nur den Bericht ausgeben: keine Fortschrittszeilen, kein Fortschrittsbalken"),
        "top" => Some("Materialoberkante T, mm (Standard: der Kommentar (MILLPATH-STOCK …) des Programms)"),
        "tool" => Some("Werkzeugdurchmesser O, mm"),
        "bottom" => Some("Tiefste gezeichnete Tiefe, mm: Schnitte darunter sind Fehler"),
        "max" => Some("Größte erlaubte Abweichung zwischen gemessener und Soll-Höhe, mm"),
        "textconv" => Some("Als textconv-Treiber von git: eine unlesbare Zeichnung ergibt eine Fehlerzeile als Text (Exit-Status 0), damit `git diff` weiterläuft"),
        "into" => Some("Die Pfade in diese vorhandene Zeichnung schreiben: Elemente und Texte der Pfad-Layer werden ersetzt, jeder andere Layer, jedes andere Objekt, jeder Block und jede Einstellung bleibt"),
        "force" => Some("Eine vorhandene DXF-Datei überschreiben, auch wenn dabei Zeichnungsinhalt verloren geht"),
        "delete_missing_paths" => Some("Mit --into: die Pfade der Zeichnung löschen, die der Text nicht definiert (ohne diese Option nennt --into sie und schreibt nichts)"),
        "check" => Some("Nur prüfen: Exit-Status 1 und die nicht formatierten Dateien auflisten"),
        "path" => Some("Der zu zeichnende Pfad (Standard: der erste Pfad der Datei)"),
        "html" => Some("Die HTML-Seite hierhin schreiben (Standard, wenn weder --svg noch --png angegeben ist: <Zeichnung>_toolpath.html)"),
        "svg" => Some("Eine SVG-Zeichnung hierhin schreiben"),
        "png" => Some("Ein PNG-Bild der Draufsicht hierhin schreiben (kein Browser nötig)"),
        "stdio" => Some("Für Editoren angenommen; die Standardein- und -ausgabe ist der einzige Weg"),
        "args" => Some("Die Befehlszeile des Referenzwerkzeugs, unverändert"),
        "subcommand" => Some("Der Befehl, dessen Hilfe angezeigt wird"),
        _ => None,
    })
}

/// `cmd` with its about text and every argument's description in German (clap's own help
/// and version flags are translated with the other fixed words of its help pages).
pub fn german(cmd: Command) -> Command {
    let cmd = cmd.about("Übersetzt von Hand gezeichnete CNC-Fräspfade (DXF oder .mpath) in G-Code");
    let names: Vec<String> = cmd
        .get_subcommands()
        .map(|s| s.get_name().to_string())
        .collect();
    names.iter().fold(cmd, |cmd, name| {
        cmd.mut_subcommand(name, |sub| {
            let sub = match about(name) {
                Some(a) => sub.about(a).long_about(None::<&str>),
                None => sub,
            };
            let ids: Vec<String> = sub
                .get_arguments()
                .map(|a| a.get_id().to_string())
                .collect();
            ids.iter().fold(sub, |sub, id| match arg(name, id) {
                Some(h) => sub.mut_arg(id, |a| a.help(h).long_help(None::<&str>)),
                None => sub,
            })
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    /// Every command and every argument of the command line has a German description.
    #[test]
    fn every_command_and_argument_has_german_help() {
        let cmd = crate::Cli::command();
        let mut missing = Vec::new();
        for sub in cmd.get_subcommands() {
            let name = sub.get_name();
            if about(name).is_none() {
                missing.push(name.to_string());
            }
            for a in sub.get_arguments() {
                let id = a.get_id().as_str();
                let clap_own = matches!(id, "help" | "version");
                if !clap_own && arg(name, id).is_none() {
                    missing.push(format!("{name} {id}"));
                }
            }
        }
        assert!(missing.is_empty(), "no German help for: {missing:?}");
    }

    #[test]
    fn the_help_page_takes_the_german_texts() {
        let mut cmd = german(crate::Cli::command());
        let sub = cmd.find_subcommand_mut("compile").unwrap();
        let help = sub.render_help().to_string();
        assert!(help.contains("Vorschub der Fräsbewegungen"), "{help}");
        assert!(!help.contains("Feed for milling moves"), "{help}");
    }
}
