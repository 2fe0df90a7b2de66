//! How a run ends.

use std::fmt;

/// Jack call stack, outermost first, innermost last, with consecutive
/// frames of one function collapsed into a run (a deep recursion is one
/// entry, printed `Main.main x 1048576`).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct CallStack {
    runs: Vec<(String, u64)>,
}

impl CallStack {
    /// Add a frame of `name` on top.
    pub fn push(&mut self, name: &str) {
        self.push_run(name, 1);
    }

    /// Add `count` frames of `name` on top.
    pub fn push_run(&mut self, name: &str, count: u64) {
        match self.runs.last_mut() {
            Some((last, n)) if last == name => *n += count,
            _ => self.runs.push((name.to_string(), count)),
        }
    }

    /// The runs: a function and how many consecutive frames it has.
    pub fn runs(&self) -> &[(String, u64)] {
        &self.runs
    }

    /// Number of frames.
    pub fn depth(&self) -> u64 {
        self.runs.iter().map(|r| r.1).sum()
    }

    /// The running function.
    pub fn innermost(&self) -> Option<&str> {
        self.runs.last().map(|r| r.0.as_str())
    }

    /// Every frame's function name, outermost first.
    pub fn names(&self) -> impl Iterator<Item = &str> {
        self.runs
            .iter()
            .flat_map(|(name, n)| std::iter::repeat_n(name.as_str(), *n as usize))
    }
}

impl<S: AsRef<str>> FromIterator<S> for CallStack {
    fn from_iter<I: IntoIterator<Item = S>>(names: I) -> Self {
        let mut stack = CallStack::default();
        for n in names {
            stack.push(n.as_ref());
        }
        stack
    }
}

impl fmt::Display for CallStack {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, (name, n)) in self.runs.iter().enumerate() {
            if i > 0 {
                f.write_str(" > ")?;
            }
            f.write_str(name)?;
            if *n > 1 {
                write!(f, " x {n}")?;
            }
        }
        Ok(())
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
