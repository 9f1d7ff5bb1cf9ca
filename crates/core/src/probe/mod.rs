//! Z probes: collection and tour (reference-output.md §12.1), the height map's grid, and after the machine has
//! measured them, `_Z.txt` and adjust-z (§15).

pub mod adjustz;
pub mod heightmap;
pub mod tour;
