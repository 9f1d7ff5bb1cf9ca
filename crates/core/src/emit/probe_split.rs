//! `probe_split = L` (issue 21): with drawn probes, reference-output.md §12.4 corrects a
//! line or arc once, with the weights of its start point; a long move on a tilted board ends
//! too deep or too shallow. Split into pieces of at most L mm, each piece's Z word carries
//! the correction of its own start, so the error along the move is that of one piece.
//! linuxcnc and grbl only (the reference dialect writes PathDxf2GCode's moves).
//!
//! `probe_split = L` (linuxcnc, grbl, drawn probes): how many pieces of ≤ L a move becomes (≤
//! 10,000, else an error at the element), the equal pieces of a line or arc (sub-arcs on the same
//! circle, the last ending exactly at the move's end).

use crate::geom::Geom;

/// Pieces one move may become: a 5 m move at the shortest `probe_split` (0.5 mm). Beyond
/// that the move is refused (a located error), so one drawn line cannot make millions of
/// lines; the program as a whole stays within `MAX_ITEMS` as always.
pub(crate) const MAX_PIECES: usize = 10_000;

/// How many pieces of at most `l` mm a move of `len` mm becomes (1: it stays whole);
/// `Err(n)` when that would be more than [`MAX_PIECES`]. A move within a micrometre of a
/// multiple of `l` is not given an extra sliver.
pub(crate) fn piece_count(len: f64, l: f64) -> Result<usize, f64> {
    if !(len.is_finite() && l.is_finite() && l > 0.0) || len <= l + 1e-6 {
        return Ok(1);
    }
    let n = ((len - 1e-6) / l).ceil().max(1.0);
    if n > MAX_PIECES as f64 {
        return Err(n);
    }
    Ok(n as usize)
}

/// `g` cut into `n` pieces of equal length, in its direction. Each piece starts exactly where
/// the one before ends, and the last ends exactly at `g`'s end (the same point the whole
/// move would write).
pub(crate) fn pieces(g: &Geom, n: usize) -> Vec<Geom> {
    if n <= 1 {
        return vec![*g];
    }
    let len = g.length();
    let mut out: Vec<Geom> = (0..n)
        .map(|k| g.sub(len * k as f64 / n as f64, len * (k + 1) as f64 / n as f64))
        .collect();
    match (g, out.first_mut()) {
        (Geom::Line { a, .. }, Some(Geom::Line { a: fa, .. })) => *fa = *a,
        (Geom::Arc { a0, .. }, Some(Geom::Arc { a0: fa0, .. })) => *fa0 = *a0,
        _ => {}
    }
    match (g, out.last_mut()) {
        (Geom::Line { b, .. }, Some(Geom::Line { b: lb, .. })) => *lb = *b,
        (Geom::Arc { a1, .. }, Some(Geom::Arc { a1: la1, .. })) => *la1 = *a1,
        _ => {}
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::P2;

    #[test]
    fn counts() {
        assert_eq!(piece_count(60.0, 10.0), Ok(6));
        assert_eq!(piece_count(60.0000001, 10.0), Ok(6), "no sliver");
        assert_eq!(piece_count(61.0, 10.0), Ok(7));
        assert_eq!(piece_count(9.0, 10.0), Ok(1));
        assert_eq!(piece_count(10.0, 10.0), Ok(1));
        assert_eq!(piece_count(0.0, 10.0), Ok(1));
        assert_eq!(piece_count(5000.0, 0.5), Ok(10_000));
        assert_eq!(piece_count(5001.0, 0.5), Err(10_002.0));
        assert_eq!(piece_count(f64::NAN, 1.0), Ok(1));
    }

    #[test]
    fn lines_are_cut_evenly_and_end_where_they_ended() {
        let g = Geom::Line {
            a: P2::new(5.0, -3.0),
            b: P2::new(65.0, -3.0),
        };
        let p = pieces(&g, 6);
        assert_eq!(p.len(), 6);
        assert_eq!(p[0].start(), g.start());
        assert_eq!(p[5].end(), g.end());
        for w in p.windows(2) {
            assert_eq!(w[0].end(), w[1].start(), "pieces join exactly");
        }
        for (k, q) in p.iter().enumerate() {
            assert!((q.length() - 10.0).abs() < 1e-9);
            assert!((q.start().x - (5.0 + 10.0 * k as f64)).abs() < 1e-9);
        }
        assert_eq!(pieces(&g, 1), vec![g]);
    }

    #[test]
    fn arcs_become_sub_arcs_on_the_same_circle() {
        for ccw in [true, false] {
            let (a0, a1) = if ccw { (180.0, 0.0) } else { (0.0, 180.0) };
            let g = Geom::Arc {
                c: P2::new(50.0, -3.0),
                r: 15.0,
                a0,
                a1,
                ccw,
            };
            let n = piece_count(g.length(), 5.0).unwrap();
            assert_eq!(n, 10, "47.1 mm in pieces of at most 5");
            let p = pieces(&g, n);
            assert!(p[0].start().dist(g.start()) < 1e-12);
            assert!(p[n - 1].end().dist(g.end()) < 1e-12);
            let total: f64 = p.iter().map(Geom::length).sum();
            assert!((total - g.length()).abs() < 1e-9);
            for q in &p {
                match *q {
                    Geom::Arc { c, r, ccw: d, .. } => {
                        assert_eq!((c, r, d), (P2::new(50.0, -3.0), 15.0, ccw));
                    }
                    Geom::Line { .. } => panic!("an arc's piece is an arc"),
                }
                assert!(q.length() <= 5.0 + 1e-9);
            }
            for w in p.windows(2) {
                assert!(w[0].end().dist(w[1].start()) < 1e-12);
            }
            // the pieces run the arc's way: ccw from 180° and cw from 0° both pass below
            // the centre (the other way round they would pass above)
            let first = p[0].end();
            assert!(first.y < -3.0, "{first:?}");
            assert!(
                (first.x - 50.0).abs() > 10.0,
                "the first piece stays near its start"
            );
        }
    }
}
