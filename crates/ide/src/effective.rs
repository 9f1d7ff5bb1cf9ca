//! The effective parameters of elements with their origins, as data for other crates
//! (`millpath diff` compares them between two versions): the rows hover shows.

use crate::common::segment_of;
use crate::provenance::provenance;
use crate::Analysis;
use std::collections::HashMap;

/// One effective parameter: key, value as written, where it comes from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Effective {
    pub key: char,
    pub value: String,
    pub source: String,
}

/// The effective parameters of the elements that start at the given byte offsets of the
/// analysed text, in their order (empty for an offset where no element of a path starts).
/// One walk over the text, whatever the number of offsets.
pub fn effective_values(a: &Analysis, offsets: &[usize]) -> Vec<Vec<Effective>> {
    let wanted: HashMap<usize, usize> = offsets.iter().enumerate().map(|(i, &o)| (o, i)).collect();
    let mut out = vec![Vec::new(); offsets.len()];
    for p in a.ast.paths() {
        for el in p.elements() {
            let Some(&i) = wanted.get(&el.span.start) else {
                continue;
            };
            let Some((path, seg)) = segment_of(a, el) else {
                continue;
            };
            out[i] = provenance(a, path, el, seg)
                .into_iter()
                .map(|r| Effective {
                    key: r.key,
                    value: r.value,
                    source: r.source,
                })
                .collect();
        }
    }
    // the same offset asked twice
    for (i, &o) in offsets.iter().enumerate() {
        if out[i].is_empty() {
            if let Some(&j) = wanted.get(&o) {
                if j != i {
                    out[i] = out[j].clone();
                }
            }
        }
    }
    out
}
