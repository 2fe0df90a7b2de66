//! [`BindError`]: a binding the program does not satisfy, naming the field.

use std::fmt;

/// A field of the bindings is wrong: `field` is its path in the
/// `[impl.NAME]` table (`ops.add`, `float.fields`, `ready.until_call`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BindError {
    /// The field, e.g. `ops.add`.
    pub field: String,
    /// What is wrong with it.
    pub message: String,
}

impl BindError {
    /// An error of `field`.
    pub fn new(field: &str, message: impl Into<String>) -> BindError {
        BindError {
            field: field.to_string(),
            message: message.into(),
        }
    }
}

impl fmt::Display for BindError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "`{}`: {}", self.field, self.message)
    }
}

impl std::error::Error for BindError {}
