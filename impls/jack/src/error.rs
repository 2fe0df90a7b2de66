//! Errors of the facade: the raymarcher does not build or does not start,
//! or a run ends in a way no Float316 outcome describes.

use hack_vm::Exit;

/// Why the Jack raymarcher could not be used.
#[derive(Debug, thiserror::Error)]
pub enum JackError {
    /// The embedded Jack sources do not compile.
    #[error("the Jack raymarcher does not compile: {0}")]
    Compile(#[from] jack_compiler::CompileErrors),
    /// The compiled VM code does not load.
    #[error("the compiled raymarcher does not load: {0}")]
    Load(#[from] hack_vm::LoadError),
    /// A function the facade calls is missing from the program.
    #[error("the raymarcher has no function {0}")]
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
}

impl From<hack_vm::UnknownFunction> for JackError {
    fn from(e: hack_vm::UnknownFunction) -> Self {
        JackError::MissingFunction(e.0)
    }
}
