//! The effective parameters of elements with their origins, as data for other crates
//! (`millpath diff` compares them between two versions): the rows hover shows.

use crate::common::object_index;
use crate::provenance::{provenance_in, Inherited};
use crate::Analysis;
use crate::FastMap;
use millpath_core::front::drawing::{RawPath, RawSegment};

/// One effective parameter: key, value as written, where it comes from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Effective {
    pub key: char,
    pub value: String,
    pub source: String,
}

/// The effective parameters of the elements that start at the given byte offsets of the
/// analysed text, in their order (empty for an offset where no element of a path starts).
/// One walk over the text, whatever the number of offsets; paths and their segments are
/// found through maps made once (a path of 100,000 elements stays linear).
pub fn effective_values(a: &Analysis, offsets: &[usize]) -> Vec<Vec<Effective>> {
    let wanted: FastMap<usize, usize> = offsets.iter().enumerate().map(|(i, &o)| (o, i)).collect();
    let mut out = vec![Vec::new(); offsets.len()];
    let mut paths: FastMap<&str, &RawPath> = FastMap::default();
    for p in a.paths.iter().rev() {
        // the first of a name wins, as `raw_path` finds it
        paths.insert(p.name.as_str(), &**p);
    }
    let mut segments: FastMap<&str, (FastMap<usize, &RawSegment>, Inherited)> = FastMap::default();
    for p in a.ast.paths() {
        for el in p.elements() {
            let Some(&i) = wanted.get(&el.span.start) else {
                continue;
            };
            let Some(object) = object_index(a, el) else {
                continue;
            };
            let Some(path) = paths.get(&*a.objects[object].path).copied() else {
                continue;
            };
            let (by_object, inherited) = segments.entry(path.name.as_str()).or_insert_with(|| {
                let mut by_object = FastMap::default();
                for s in path.segments.iter().rev() {
                    // the first segment of an object wins, as `find` gives it
                    by_object.insert(s.object, s);
                }
                (by_object, Inherited::default())
            });
            let seg = by_object.get(&object).copied();
            out[i] = provenance_in(a, path, el, seg, inherited)
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
