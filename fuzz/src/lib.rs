//! The structure-aware fuzz target's parts, usable from a plain test too: `gen` builds valid
//! drawings from bytes, `invariants` compiles them through both front-ends and checks them.

pub mod gen;
pub mod invariants;

/// One fuzz input: a drawing built from `data`, checked (bytes too short for a drawing are
/// skipped).
pub fn run(data: &[u8]) {
    let mut u = arbitrary::Unstructured::new(data);
    if let Ok(case) = gen::case(&mut u) {
        invariants::check(&case);
    }
}
