//! [`JackProgram`]: a user's program loaded for binding: a folder of .jack
//! files (compiled with our compiler under the OS profile) or of .vm files,
//! with the [`Signatures`] its sources tell.

use super::signatures::Signatures;
use crate::JackError;
use hack_vm::{DivideRule, Profile, Program};
use jack_compiler::VmClass;
use std::path::Path;
use std::sync::Arc;

/// A loaded program and what is known of its subroutines.
#[derive(Clone, Debug)]
pub struct JackProgram {
    /// The decoded VM program.
    pub program: Arc<Program>,
    /// Declarations (from .jack) or call-site arities (from .vm).
    pub signatures: Signatures,
    /// The OS profile it was compiled for and runs under.
    pub profile: Profile,
    /// `Math.divide`'s rounding on its machines: the profile's, unless
    /// [`JackProgram::with_divide`] chose the other (the fault
    /// `web-divide`, which changes nothing else).
    pub divide: DivideRule,
}

impl JackProgram {
    /// The same program, its machines' `Math.divide` rounding by `divide`
    /// (compiled and laid out as before, under its own profile).
    pub fn with_divide(mut self, divide: DivideRule) -> JackProgram {
        self.divide = divide;
        self
    }

    /// Compile Jack `sources` (file name, text) under `profile`.
    pub fn from_jack<N: AsRef<str>, S: AsRef<str>>(
        sources: &[(N, S)],
        profile: Profile,
    ) -> Result<JackProgram, JackError> {
        let compiler = match profile {
            Profile::Desktop => jack_compiler::Profile::Desktop,
            Profile::Web => jack_compiler::Profile::Web,
        };
        let classes = jack_compiler::compile_sources(sources, compiler)?;
        let vm: Vec<(String, String)> = classes.into_iter().map(VmClass::into_file).collect();
        Ok(JackProgram {
            program: Program::from_sources(&vm)?,
            signatures: Signatures::from_jack(sources),
            profile,
            divide: DivideRule::of(profile),
        })
    }

    /// Load VM `sources` (file name, text) as they are.
    pub fn from_vm<N: AsRef<str>, S: AsRef<str>>(
        sources: &[(N, S)],
        profile: Profile,
    ) -> Result<JackProgram, JackError> {
        Ok(JackProgram {
            program: Program::from_sources(sources)?,
            signatures: Signatures::from_vm(sources),
            profile,
            divide: DivideRule::of(profile),
        })
    }

    /// The program of folder `dir`: its .jack files compiled if it has any,
    /// else its .vm files.
    pub fn from_dir(dir: &Path, profile: Profile) -> Result<JackProgram, JackError> {
        let io = |e: std::io::Error| JackError::Io(format!("{}: {e}", dir.display()));
        let mut files: Vec<std::path::PathBuf> = std::fs::read_dir(dir)
            .map_err(io)?
            .filter_map(Result::ok)
            .map(|e| e.path())
            .filter(|p| p.is_file())
            .collect();
        files.sort();
        let read = |ext: &str| -> Result<Vec<(String, String)>, JackError> {
            files
                .iter()
                .filter(|p| p.extension().is_some_and(|x| x == ext))
                .map(|p| {
                    let name = p
                        .file_name()
                        .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
                    let text = std::fs::read_to_string(p)
                        .map_err(|e| JackError::Io(format!("{}: {e}", p.display())))?;
                    Ok((name, text))
                })
                .collect()
        };
        let jack = read("jack")?;
        if !jack.is_empty() {
            return JackProgram::from_jack(&jack, profile);
        }
        let vm = read("vm")?;
        if vm.is_empty() {
            return Err(JackError::Io(format!(
                "{}: no .jack or .vm files",
                dir.display()
            )));
        }
        JackProgram::from_vm(&vm, profile)
    }
}
