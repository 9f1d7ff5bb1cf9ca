//! How a DXF layer names a path (reference-input.md §1): the effective layer of a name CAD
//! programs forbid, and the path name of a layer.

/// Normalised path name of a layer: drop a trailing `~letters` suffix, `_` → `.`.
pub fn path_name_of_layer(layer: &str) -> String {
    split_layer_suffix(layer).0.replace('_', ".")
}

/// A layer's base and whether it had a trailing `~letters` suffix (a parameter-text layer).
pub(crate) fn split_layer_suffix(layer: &str) -> (&str, bool) {
    match layer.rfind('~') {
        Some(p)
            if p + 1 < layer.len() && layer[p + 1..].chars().all(|c| c.is_ascii_alphabetic()) =>
        {
            (&layer[..p], true)
        }
        _ => (layer, false),
    }
}

/// Layer names with characters CAD programs forbid end up on layer `0` (as in netDxf).
pub(crate) fn effective_layer(name: &str) -> &str {
    if name.chars().any(|c| "\\/:*?\"<>|;,=`".contains(c)) {
        "0"
    } else {
        name
    }
}
