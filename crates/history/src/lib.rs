//! millpath history: what changed between two versions of a drawing.
//!
//! A version (`version.rs`) is a drawing read as its canonical text (a DXF through
//! `dxf2text`, a `.mpath` through `fmt`), so both kinds compare alike and in any mix.
//! `matching.rs` pairs paths by name and elements by kind, geometry and parameters (the
//! order of the entities is no change) for `millpath diff`; the merge keys elements by an
//! identity of its own (`merge/doc.rs`), made to merge an element field by field.
//! `effect.rs` compiles both versions and says what reached the G-code; `report.rs` writes
//! the result (human, JSON, markdown) in English or German. `merge/` is git's merge
//! driver: a three-way merge of the canonical text by path and element identity, and of
//! drawings through that text (`merge/drawing.rs`).
//!
//! Dependencies point one way: this crate uses `core`, `syntax` and `ide`; nothing below it
//! imports it.

pub mod compiled;
pub mod diff;
pub mod matching;
pub mod merge;
pub mod picture;
pub mod report;
pub mod version;

pub use compiled::Options;
pub use diff::{diff, ChangeKind, Diff, EffectGroup, ElementChange, PathDiff, PathStatus, Side};
pub use matching::{match_elements, match_paths, ElementMatch, Pairing, PathPairing, Relation};
pub use version::{Element, PathVersion, Version};
