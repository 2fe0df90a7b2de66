//! Errors of loading a VM program (spec §2.1, §2.2, §2.6). Runtime problems
//! are not errors of this kind: they are [`crate::End`] values of a run.

use std::path::PathBuf;

/// Why a VM program could not be loaded.
#[derive(Debug, thiserror::Error)]
pub enum LoadError {
    /// A syntax or load-time check failed at a line of a file.
    #[error("{file}:{line}: {message}")]
    Syntax {
        /// File name (base name for a directory load).
        file: String,
        /// 1-based line number.
        line: usize,
        /// What is wrong, worded like the web IDE where the spec quotes it.
        message: String,
    },
    /// A check on the whole program failed (no line to point at).
    #[error("{0}")]
    Program(String),
    /// A file is not a readable regular UTF-8 file of bounded size.
    #[error(transparent)]
    Input(#[from] common::input::InputError),
    /// A file or directory could not be read.
    #[error("cannot read {path}: {source}")]
    Io {
        /// The path that failed.
        path: PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },
}

impl LoadError {
    pub(crate) fn at(file: &str, line: usize, message: impl Into<String>) -> Self {
        LoadError::Syntax {
            file: file.to_string(),
            line,
            message: message.into(),
        }
    }
}
