//! The custom requests `millpath/gcodePreview` and `millpath/toolpath`.

use crate::conv::*;
use crate::state::*;
use serde::{Deserialize, Serialize};
use serde_json::Value;
use tower_lsp_server::jsonrpc::{Error, Result};
use tower_lsp_server::ls_types::*;

/// Parameters of `millpath/gcodePreview`.
#[derive(Debug, Deserialize, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct PreviewParams {
    pub text_document: TextDocumentIdentifier,
    /// The path to preview; default: the first path of the document.
    pub path: Option<String>,
}

/// Result of `millpath/gcodePreview`: the files `millpath compile` would write.
#[derive(Debug, Deserialize, Serialize, PartialEq)]
#[serde(rename_all = "camelCase")]
pub struct PreviewResult {
    pub path: String,
    pub gcode: String,
    pub probing: Option<String>,
    pub z_txt: Option<String>,
    pub stats: Vec<String>,
    /// The exact estimated time, `h:mm:ss` (empty when the path is refused).
    pub time: String,
    pub errors: Vec<String>,
}

impl Backend {
    pub async fn gcode_preview(&self, params: PreviewParams) -> Result<PreviewResult> {
        let (a, ws) = self.analysis(&params.text_document.uri).await?;
        let name = params.path;
        // a cancelled request stops the compile as well
        let (_guard, cancelled) = crate::cancel::on_drop();
        let pv = blocking(move || {
            millpath_ide::preview_of_until(&a, &ws, name.as_deref(), &|| cancelled.get())
        })
        .await?
        .ok_or_else(crate::cancel::request_cancelled)?
        .map_err(refused)?;
        Ok(PreviewResult {
            path: pv.path,
            gcode: pv.gcode,
            probing: pv.probing,
            z_txt: pv.z_txt,
            stats: pv.stats,
            time: pv.time,
            errors: pv.errors,
        })
    }

    pub async fn toolpath(&self, params: PreviewParams) -> Result<Value> {
        let path = to_path(&params.text_document.uri)
            .ok_or_else(|| Error::invalid_params("not a file URI"))?;
        let ws = self.snapshot();
        let name = params.path;
        let (_guard, cancelled) = crate::cancel::on_drop();
        blocking(move || {
            millpath_ide::toolpath_until(&ws, &path, name.as_deref(), &|| cancelled.get())
        })
        .await?
        .ok_or_else(crate::cancel::request_cancelled)?
        .map_err(refused)
    }
}

/// A path the preview or the toolpath cannot show: an error answer with the reason.
fn refused(reason: String) -> Error {
    let mut err = Error::invalid_request();
    err.message = reason.into();
    err
}
