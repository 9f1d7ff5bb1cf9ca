//! The peephole optimizer (reference-output.md §13).

use crate::emit::{Item, Kind};

/// The peephole optimizer: a horizontal sweep followed (past comments) by another one is
/// commented out.
pub fn optimize(items: &mut [Item]) {
    let mut next_is_h = false;
    for it in items.iter_mut().rev() {
        match it.kind {
            Kind::Comment => {}
            Kind::HSweep => {
                if next_is_h {
                    it.kind = Kind::Comment;
                    it.text = format!("; {}", it.text);
                }
                next_is_h = true;
            }
            _ => next_is_h = false,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::emit::stats::Stats;
    use crate::emit::Target;

    #[test]
    fn optimizer_keeps_only_the_last_sweep_of_a_run() {
        let mk = |k, t: &str| Item {
            kind: k,
            text: t.into(),
            len: 1.0,
            feed: 1.0,
            target: Target::default(),
            source: None,
            shape: Default::default(),
        };
        let mut v = vec![
            mk(Kind::HSweep, "G00 X1 Y1"),
            mk(Kind::Comment, "(c)"),
            mk(Kind::HSweep, "G00 X2 Y2"),
            mk(Kind::VSweep, "G00 Z1"),
            mk(Kind::HSweep, "G00 X3 Y3"),
        ];
        optimize(&mut v);
        assert_eq!(v[0].text, "; G00 X1 Y1");
        assert_eq!(v[2].text, "G00 X2 Y2");
        assert_eq!(v[4].text, "G00 X3 Y3");
        let s = Stats::of(&v, 500.0);
        assert_eq!(s.count, 3);
    }
}
