//! Front-ends: drawn objects from a DXF drawing or a `.mpath` text, and the paths built from
//! them (reference-input.md §1–§2).

pub mod drawing;
pub mod dxf;
pub mod extended;
pub mod layer;
pub mod linetype_alias;
pub mod mtext;
pub mod options;
pub mod text;
pub mod text_edit;
