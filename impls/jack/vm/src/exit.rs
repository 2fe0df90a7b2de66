//! How a run ends.

use std::fmt;

/// Jack call stack: function names, outermost first, innermost last.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct CallStack(pub Vec<String>);

impl fmt::Display for CallStack {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0.join(" > "))
    }
}

/// The end of a run or of a host call.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Exit {
    /// A host call ([`crate::Machine::call`]) returned this value.
    Returned(i16),
    /// The VM halted with exit code 0: `Sys.halt`, running past the end of a
    /// function, or a return from the entry function (e.g. after the
    /// synthetic `Sys.init` has run `Main.main`).
    Halted,
    /// `Sys.error(code)` (called by the program or raised by a built-in).
    SysError {
        /// The error code.
        code: i16,
        /// Where it was called.
        stack: CallStack,
    },
    /// The instruction budget ran out; the run can be continued.
    Budget {
        /// What was running.
        stack: CallStack,
    },
    /// A runtime error of the web IDE (spec §2.5), or of a built-in.
    RuntimeError {
        /// The message, e.g. "Argument offset out of bounds".
        message: String,
        /// Where it happened.
        stack: CallStack,
    },
    /// The official tool would loop forever inside a built-in.
    Hang {
        /// Why.
        message: String,
        /// Where.
        stack: CallStack,
    },
    /// A keyboard read waits for a key the key script never delivers.
    BlockedForever {
        /// Where.
        stack: CallStack,
    },
}

impl Exit {
    /// The call stack recorded with this end, if any.
    pub fn stack(&self) -> Option<&CallStack> {
        match self {
            Exit::Returned(_) | Exit::Halted => None,
            Exit::SysError { stack, .. }
            | Exit::Budget { stack }
            | Exit::RuntimeError { stack, .. }
            | Exit::Hang { stack, .. }
            | Exit::BlockedForever { stack } => Some(stack),
        }
    }
}

impl fmt::Display for Exit {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Exit::Returned(v) => write!(f, "returned {v}"),
            Exit::Halted => f.write_str("halted"),
            Exit::SysError { code, stack } => write!(f, "Sys.error({code}) in {stack}"),
            Exit::Budget { stack } => write!(f, "instruction budget exhausted in {stack}"),
            Exit::RuntimeError { message, stack } => {
                write!(f, "runtime error: {message} in {stack}")
            }
            Exit::Hang { message, stack } => write!(f, "hang: {message} in {stack}"),
            Exit::BlockedForever { stack } => {
                write!(f, "blocked forever waiting for a key in {stack}")
            }
        }
    }
}
