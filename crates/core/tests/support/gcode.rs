//! A small G-code reader for the oracle tests: the moves of a program as the emitter's items.

use millpath_core::emit::{Item, Kind, Target};
use millpath_core::geom::{P2, P3};

/// The words of a G-code line (comments dropped), upper-cased letters with their numbers.
pub fn words(line: &str) -> Vec<(char, f64)> {
    let mut code = String::new();
    let mut depth = 0;
    for c in line.chars() {
        match c {
            '(' => depth += 1,
            ')' => depth -= 1,
            ';' if depth == 0 => break,
            _ if depth == 0 => code.push(c),
            _ => {}
        }
    }
    let mut out = Vec::new();
    let chars: Vec<char> = code.chars().filter(|c| !c.is_whitespace()).collect();
    let mut i = 0;
    while i < chars.len() {
        let letter = chars[i].to_ascii_uppercase();
        let mut j = i + 1;
        while j < chars.len() && (chars[j].is_ascii_digit() || "+-.".contains(chars[j])) {
            j += 1;
        }
        let num: String = chars[i + 1..j].iter().collect();
        if let Ok(v) = num.parse() {
            out.push((letter, v));
        }
        i = j.max(i + 1);
    }
    out
}

/// The moves of a program in absolute XY-plane millimetres (G0/G1/G2/G3 with X Y Z I J F):
/// what the synthetic programs use.
pub fn items_of(gcode: &str, start: [f64; 3]) -> Vec<Item> {
    let (mut pos, mut motion, mut feed) = (start, 0, 0.0);
    let mut out = Vec::new();
    for (number, line) in gcode.lines().enumerate() {
        let w = words(line);
        let mut to = pos;
        let (mut i, mut j, mut moved) = (0.0, 0.0, false);
        for (l, v) in &w {
            match l {
                'G' if [0.0, 1.0, 2.0, 3.0].contains(v) => motion = *v as i32,
                'X' => (to[0], moved) = (*v, true),
                'Y' => (to[1], moved) = (*v, true),
                'Z' => (to[2], moved) = (*v, true),
                'I' => i = *v,
                'J' => j = *v,
                'F' => feed = *v,
                _ => {}
            }
        }
        if !moved {
            continue;
        }
        let d = [to[0] - pos[0], to[1] - pos[1], to[2] - pos[2]];
        let (kind, arc, len) = match motion {
            0 => (
                Kind::HSweep,
                None,
                (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt(),
            ),
            1 => (
                Kind::Mill,
                None,
                (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt(),
            ),
            _ => {
                let ccw = motion == 3;
                let c = P2 {
                    x: pos[0] + i,
                    y: pos[1] + j,
                };
                let a0 = (pos[1] - c.y).atan2(pos[0] - c.x);
                let a1 = (to[1] - c.y).atan2(to[0] - c.x);
                let tau = std::f64::consts::TAU;
                let mut sweep = if ccw { a1 - a0 } else { a0 - a1 };
                sweep = sweep.rem_euclid(tau);
                if sweep < 1e-9 {
                    sweep = tau;
                }
                (Kind::Mill, Some((c, ccw)), (i * i + j * j).sqrt() * sweep)
            }
        };
        out.push(Item {
            kind,
            len,
            feed,
            target: Target {
                x: Some(to[0]),
                y: Some(to[1]),
                z: Some(to[2]),
                arc,
            },
            // the line number (1-based), for the per-line comparison
            source: Some(number as u32 + 1),
            shape: Default::default(),
        });
        pos = to;
    }
    out
}

/// Where the oracle starts a program (as millpath's estimate starts its own): at rest above
/// the origin at the height of the first rapid in Z, if the program begins with one.
pub fn start_of(gcode: &str, default_z: f64) -> P3 {
    let at = |z| P3 { x: 0.0, y: 0.0, z };
    for line in gcode.lines() {
        let w = words(line);
        let has = |l: char| w.iter().any(|(c, _)| *c == l);
        if !(has('X') || has('Y') || has('Z')) {
            continue;
        }
        let rapid = w.iter().any(|&(c, v)| c == 'G' && v == 0.0);
        return match w.iter().find(|(c, _)| *c == 'Z') {
            Some(&(_, z)) if rapid && !has('X') && !has('Y') => at(z),
            _ => at(default_z),
        };
    }
    at(default_z)
}
