//! Drawings under version control: what changed between versions of a drawing, merged.
//! `merge` is git's merge driver: a three-way merge of the canonical text by path and
//! element identity (`merge/`), and of drawings through that text (`merge/drawing.rs`).

pub mod merge;
