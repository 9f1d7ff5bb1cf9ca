//! What GRBL 1.1's parser refuses that other controllers take (the `grbl` dialect): codes
//! and words it does not have (`error:20`), value words no command of the line uses
//! (`error:36`), and an arc or probe code without axis words (`error:26`). GRBL drops such a
//! line whole, so the checker leaves the machine's state as it was. Held against GRBL's own
//! parser by the test `grbl_parser`.

use crate::finding::SyntaxError;
use crate::parse::Block;

/// G codes ×10 GRBL 1.1h knows.
const G_CODES: &[u32] = &[
    0, 10, 20, 30, 40, 100, 170, 180, 190, 200, 210, 280, 281, 300, 301, 382, 383, 384, 385, 400,
    431, 490, 530, 540, 550, 560, 570, 580, 590, 610, 800, 900, 910, 911, 920, 921, 930, 940,
];

/// M codes GRBL 1.1h knows (M7 and M56 only in builds that enable them; the default has not).
const M_CODES: &[u32] = &[0, 1, 2, 3, 4, 5, 8, 9, 30];

/// The letters GRBL reads.
const LETTERS: &str = "GMXYZIJKRFPSTNL";

/// Why GRBL refuses the line, if it does. `gs`: the line's G codes ×10; `ms`: its M codes;
/// `arc_in_effect`: the motion mode in effect before the line is G2/G3; `plane`: the plane
/// (G17 as 170) in effect after the line.
pub(crate) fn refusal(
    b: &Block,
    gs: &[u32],
    ms: &[u32],
    arc_in_effect: bool,
    plane: u32,
) -> Option<SyntaxError> {
    if let Some(w) = b.words.iter().find(|w| !LETTERS.contains(w.letter)) {
        return Some(SyntaxError::NotInGrbl(format!("the word {}", w.letter)));
    }
    if let Some(g) = gs.iter().find(|g| !G_CODES.contains(g)) {
        return Some(SyntaxError::NotInGrbl(g_name(*g)));
    }
    if let Some(m) = ms.iter().find(|m| !M_CODES.contains(m)) {
        return Some(SyntaxError::NotInGrbl(format!("M{m}")));
    }
    let has_axes = ['X', 'Y', 'Z'].iter().any(|&l| b.has(l));
    let motion = gs
        .iter()
        .copied()
        .find(|g| matches!(g, 0 | 10 | 20 | 30 | 382..=385 | 800));
    if let Some(m @ (20 | 30 | 382..=385)) = motion {
        if !has_axes {
            return Some(SyntaxError::NoAxisWords(g_name(m)));
        }
    }
    // G10, G28, G30, G53 and G92 take the axis words instead of the motion mode
    let axes_taken = gs.iter().any(|g| matches!(g, 100 | 280 | 300 | 530 | 920));
    let arc = has_axes
        && !axes_taken
        && match motion {
            Some(m) => m == 20 || m == 30,
            None => arc_in_effect,
        };
    let offsets = match plane {
        180 => "IKR",
        190 => "JKR",
        _ => "IJR",
    };
    let dwell_or_g10 = gs.iter().any(|g| matches!(g, 40 | 100));
    for l in ['I', 'J', 'K', 'R', 'P', 'L'] {
        let used = match l {
            'P' => dwell_or_g10,
            'L' => gs.contains(&100),
            _ => arc && offsets.contains(l),
        };
        if b.has(l) && !used {
            return Some(SyntaxError::UnusedWord(l));
        }
    }
    None
}

fn g_name(code: u32) -> String {
    if code.is_multiple_of(10) {
        format!("G{:02}", code / 10)
    } else {
        format!("G{}.{}", code / 10, code % 10)
    }
}
