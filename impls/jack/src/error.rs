//! Errors of the facade: a Jack program does not build, its bindings do not
//! fit it, or a run ends in a way no Float316 outcome describes.

use hack_vm::Exit;

/// Why a Jack program could not be used.
#[derive(Debug, thiserror::Error)]
pub enum JackError {
    /// The Jack sources do not compile.
    #[error("the Jack program does not compile: {0}")]
    Compile(#[from] jack_compiler::CompileErrors),
    /// The VM code does not load.
    #[error("the VM code does not load: {0}")]
    Load(#[from] hack_vm::LoadError),
    /// The program's folder cannot be read.
    #[error("{0}")]
    Io(String),
    /// A binding does not fit the program (names the field).
    #[error("bad binding {0}")]
    Bind(#[from] crate::BindError),
    /// A function the facade calls is missing from the program.
    #[error("the program has no function {0}")]
    MissingFunction(String),
    /// A run ended in a way that is not a Float316 outcome (a runtime error
    /// of the VM, a halt, a wait for a key): a bug in the Jack program.
    #[error("{what}: the VM run ended unexpectedly: {exit}")]
    Unexpected {
        /// What was running.
        what: String,
        /// How it ended.
        exit: Exit,
    },
    /// An argument the facade cannot pass to the Jack program.
    #[error("{0}")]
    BadArgument(String),
    /// The query needs a binding that was not given.
    #[error("unsupported: {0}")]
    Unsupported(String),
}

impl From<hack_vm::UnknownFunction> for JackError {
    fn from(e: hack_vm::UnknownFunction) -> Self {
        JackError::MissingFunction(e.0)
    }
}
