//! Scenes as data: the scene description (format version 1, [`desc`]), its
//! checks ([`check`]), and its lowering ([`lower()`]) to the intermediate
//! form ([`ir`]) that every implementation is made from: the reference
//! interprets it, the GPU back end generates WGSL from it. See
//! `docs/scenes.md`.
//!
//! Entry points: [`load`] (a file), [`parse`] (a string), [`lower()`].

pub mod build;
pub mod check;
pub mod desc;
pub mod ir;
pub mod lower;
pub mod sites;
pub mod stats;

pub use check::Checked;
pub use ir::{Formulation, Program};
pub use lower::lower;

use std::path::Path;

/// The largest scene file read, in bytes.
pub const MAX_FILE_BYTES: u64 = 1 << 20;

/// Why a scene cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The file could not be read.
    #[error("cannot read scene file {file}: {message}")]
    Read { file: String, message: String },
    /// The JSON is malformed, or a field is unknown, missing or mistyped.
    #[error("{path}: {message} (line {line}, column {column})")]
    Syntax {
        path: String,
        message: String,
        line: usize,
        column: usize,
    },
    /// A field's value cannot be used.
    #[error("{path}: {message}")]
    Field { path: String, message: String },
    /// An error in a named file.
    #[error("{file}: {error}")]
    File {
        file: String,
        error: Box<SceneError>,
    },
}

/// Parse and check a description.
pub fn parse(text: &str) -> Result<Checked, SceneError> {
    let de = &mut serde_json::Deserializer::from_str(text);
    let description: desc::Description = serde_path_to_error::deserialize(de).map_err(|e| {
        let path = e.path().to_string();
        let inner = e.into_inner();
        SceneError::Syntax {
            path: if path == "." { "(top)".into() } else { path },
            message: strip_position(&inner.to_string()),
            line: inner.line(),
            column: inner.column(),
        }
    })?;
    check::check(description)
}

/// serde_json appends " at line L column C"; the error prints them itself.
fn strip_position(message: &str) -> String {
    match message.rfind(" at line ") {
        Some(i) => message[..i].to_string(),
        None => message.to_string(),
    }
}

/// Read, parse and check the description in `path`: a regular file of at
/// most [`MAX_FILE_BYTES`] (a FIFO or a device is refused, not read).
pub fn load(path: &Path) -> Result<Checked, SceneError> {
    let file = path.display().to_string();
    let text = read(path)?;
    parse(&text).map_err(|error| SceneError::File {
        file,
        error: Box::new(error),
    })
}

/// The text of a scene file (see [`load`]).
pub fn read(path: &Path) -> Result<String, SceneError> {
    common::input::read_text_limited(path, MAX_FILE_BYTES).map_err(|e| SceneError::Read {
        file: path.display().to_string(),
        message: e.to_string(),
    })
}

/// The seed scene's description (`vectors/scenes/seed.json`).
pub const SEED: &str = include_str!("../../../vectors/scenes/seed.json");

/// Whether `scene` computes exactly what the seed scene computes (its
/// Float316 program equals the seed's, names aside): the scene the
/// hand-written implementations hold.
pub fn is_seed(scene: &Checked) -> bool {
    let seed = parse(SEED).expect("the shipped seed scene is valid");
    let form = Formulation::Float316;
    lower(scene, form).without_names() == lower(&seed, form).without_names()
}

/// Whether `text` is a scene description (it has a `version` field at the
/// top), rather than the seed scene's parameter file.
pub fn is_description(text: &str) -> bool {
    serde_json::from_str::<serde_json::Value>(text).is_ok_and(|v| v.get("version").is_some())
}
