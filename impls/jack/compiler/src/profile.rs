//! Which official tool the compiler imitates (spec §0).

use std::fmt;
use std::str::FromStr;

/// The tool whose checks the compiler reproduces. Code generation is the same
/// for both; only the semantic checks differ.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Profile {
    /// The long-standing desktop tools the seed program was developed with:
    /// a variable, parameter or return type may name a class that is not in
    /// the program, and calls into such a class are not checked (the class
    /// may come as a .vm file). Messages name the subroutine kind correctly.
    #[default]
    Desktop,
    /// The nand2tetris web IDE exactly: "Unknown type T", "Class C doesn't
    /// exist" for every unknown class, and its message quirks.
    Web,
}

impl Profile {
    /// The name used on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Profile::Desktop => "desktop",
            Profile::Web => "web",
        }
    }
}

impl fmt::Display for Profile {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A profile name that is neither `desktop` nor `web`.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown profile '{0}' (expected desktop or web)")]
pub struct UnknownProfile(pub String);

impl FromStr for Profile {
    type Err = UnknownProfile;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "desktop" => Ok(Profile::Desktop),
            "web" => Ok(Profile::Web),
            other => Err(UnknownProfile(other.to_string())),
        }
    }
}
