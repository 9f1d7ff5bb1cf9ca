//! What the checker's test files share: a reproducible random source, the mutation of a
//! program's lines, and hand-made programs with their options.
// each test file uses a part of it
#![allow(dead_code)]

use millpath_verify::Options;

/// xorshift64*: reproducible without a dependency.
pub struct Rng(pub u64);

impl Rng {
    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// One random change to a program's lines: a line removed, doubled, swapped, cut short, a
/// character replaced from `alphabet`, an absurd value appended, or the program cut there.
pub fn mutate(prog: &mut Vec<String>, rng: &mut Rng, alphabet: &[u8]) {
    let i = rng.below(prog.len());
    match rng.below(7) {
        0 => {
            prog.remove(i);
            if prog.is_empty() {
                prog.push(String::new());
            }
        }
        1 => {
            let l = prog[i].clone();
            prog.insert(i, l);
        }
        2 => {
            // change a digit or a letter
            let mut chars: Vec<char> = prog[i].chars().collect();
            if !chars.is_empty() {
                let k = rng.below(chars.len());
                chars[k] = alphabet[rng.below(alphabet.len())] as char;
            }
            prog[i] = chars.into_iter().collect();
        }
        3 => {
            // truncate the line
            let chars: Vec<char> = prog[i].chars().collect();
            let k = rng.below(chars.len() + 1);
            prog[i] = chars[..k].iter().collect();
        }
        4 => {
            let j = rng.below(prog.len());
            prog.swap(i, j);
        }
        5 => {
            // absurd or extreme values
            let v = [
                "1e6",
                "-999999.999",
                "0.0000001",
                "NaN",
                "1e308",
                "00000000000000000000001",
            ][rng.below(6)];
            let letter = ["X", "Y", "Z", "I", "J", "R", "F", "P"][rng.below(8)];
            prog[i] = format!("{} {letter}{v}", prog[i]);
        }
        _ => prog.truncate(i.max(1)),
    }
}

pub const HEADER: &str =
    "%\nF150\nG17 G21 G40 G49 G54 G80 G90 G94\nT1\nG00 Z5.000\nG00 X0.000 Y0.000\n";
// the header has 6 lines: the body starts on line 7

/// A program of `body` between the usual header and end.
pub fn program(body: &str) -> String {
    format!("{HEADER}{body}M30\n%\n")
}

/// Options with a stock top and a tool diameter.
pub fn opts(top: f64, tool: f64) -> Options {
    Options {
        top: Some(top),
        tool: Some(tool),
        ..Default::default()
    }
}
