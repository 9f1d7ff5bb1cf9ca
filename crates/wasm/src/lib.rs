//! millpath in the browser: the compiler and the editor answers (`millpath-ide`) over files
//! held in memory, exported to JavaScript by wasm-bindgen. Every answer is JSON text, made by
//! [`playground::Playground`]; this file only forwards.
//!
//! Built natively too: its tests (`tests/playground.rs`) run the page's calls on the examples
//! against `compile_file` over the disk. The page's build uses `[profile.playground]` (root
//! `Cargo.toml`): opt-level "z", LTO, one codegen unit.

mod offsets;
pub mod playground;

use wasm_bindgen::prelude::*;

/// The page's one compiler: its files and their analyses.
#[wasm_bindgen]
pub struct Millpath(playground::Playground);

#[wasm_bindgen]
impl Millpath {
    #[wasm_bindgen(constructor)]
    pub fn new(lang: &str) -> Millpath {
        Millpath(playground::Playground::new(lang))
    }
    pub fn version() -> String {
        millpath_core::banner()
    }
    pub fn set_lang(&mut self, lang: &str) {
        self.0.set_lang(lang)
    }
    pub fn set_post(&mut self, name: &str) {
        self.0.set_post(name)
    }
    pub fn posts() -> String {
        playground::Playground::posts()
    }
    pub fn set_file(&mut self, path: &str, content: &str) {
        self.0.set_file(path, content)
    }
    pub fn remove_file(&mut self, path: &str) {
        self.0.remove_file(path)
    }
    pub fn diagnostics(&self, path: &str) -> String {
        self.0.diagnostics(path)
    }
    pub fn hover(&self, path: &str, at: usize) -> String {
        self.0.hover(path, at)
    }
    pub fn completion(&self, path: &str, at: usize) -> String {
        self.0.completion(path, at)
    }
    pub fn format(&self, path: &str) -> String {
        self.0.format(path)
    }
    pub fn path_at(&self, path: &str, at: usize) -> String {
        self.0.path_at(path, at)
    }
    pub fn compile(&self, path: &str, name: Option<String>) -> String {
        self.0.compile(path, name)
    }
    pub fn toolpath(&self, path: &str, name: Option<String>) -> String {
        self.0.toolpath(path, name)
    }
    pub fn dxf2text(&self, path: &str, bytes: &[u8]) -> String {
        self.0.dxf2text(path, bytes)
    }
    pub fn text2dxf(&self, path: &str) -> String {
        self.0.text2dxf(path)
    }
}
