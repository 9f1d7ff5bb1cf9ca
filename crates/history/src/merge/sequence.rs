//! The order of a merged sequence of keyed items (paths in a text, elements in a path):
//! ours in our order, with the items only theirs holds placed after the item that precedes
//! them on their side. Each key comes with its three versions for the caller to decide.

use super::doc::Key;
use std::collections::{HashMap, HashSet};

/// One key of the merged sequence with its item in the base, ours and theirs.
pub struct Slot<'a, V> {
    pub base: Option<&'a V>,
    pub ours: Option<&'a V>,
    pub theirs: Option<&'a V>,
}

/// Every key of ours and theirs once, in merged order (keys only the base holds were
/// deleted on both sides and are left out).
pub fn slots<'a, V>(
    base: &'a [(Key, V)],
    ours: &'a [(Key, V)],
    theirs: &'a [(Key, V)],
) -> Vec<Slot<'a, V>> {
    let index = |items: &'a [(Key, V)]| -> HashMap<&'a Key, &'a V> {
        items.iter().map(|(k, v)| (k, v)).collect()
    };
    let (b, o, t) = (index(base), index(ours), index(theirs));
    // theirs-only keys, grouped after the last key of ours that precedes them on their side
    let mut first: Vec<&Key> = Vec::new();
    let mut after: HashMap<&Key, Vec<&Key>> = HashMap::new();
    let mut anchor: Option<&Key> = None;
    for (k, _) in theirs {
        if o.contains_key(k) {
            anchor = Some(k);
        } else {
            match anchor {
                Some(a) => after.entry(a).or_default().push(k),
                None => first.push(k),
            }
        }
    }
    let mut order: Vec<&Key> = first;
    for (k, _) in ours {
        order.push(k);
        if let Some(v) = after.remove(k) {
            order.extend(v);
        }
    }
    let mut seen = HashSet::new();
    order
        .into_iter()
        .filter(|k| seen.insert(*k))
        .map(|k| Slot {
            base: b.get(k).copied(),
            ours: o.get(k).copied(),
            theirs: t.get(k).copied(),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn keyed(names: &[&str]) -> Vec<(Key, String)> {
        names
            .iter()
            .map(|n| {
                let k = Key {
                    class: "x".into(),
                    at: n.to_string(),
                    nth: 0,
                };
                (k, n.to_string())
            })
            .collect()
    }

    fn merged(base: &[&str], ours: &[&str], theirs: &[&str]) -> Vec<String> {
        let (b, o, t) = (keyed(base), keyed(ours), keyed(theirs));
        slots(&b, &o, &t)
            .iter()
            .map(|s| s.ours.or(s.theirs).unwrap().clone())
            .collect()
    }

    #[test]
    fn theirs_additions_follow_their_predecessor() {
        assert_eq!(
            merged(
                &["a", "b", "c"],
                &["a", "b", "c", "o"],
                &["t0", "a", "b", "t1", "c"]
            ),
            ["t0", "a", "b", "t1", "c", "o"]
        );
    }

    #[test]
    fn keys_deleted_by_ours_still_come_to_the_caller() {
        // the caller decides whether theirs' unchanged `b` is dropped
        assert_eq!(merged(&["a", "b"], &["a"], &["a", "b"]), ["a", "b"]);
    }
}
