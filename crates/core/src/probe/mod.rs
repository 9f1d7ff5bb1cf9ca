//! Z probes after the machine has measured them: `_Z.txt` and adjust-z (reference-output.md §15).

pub mod adjustz;
