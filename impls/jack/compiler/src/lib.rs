//! Jack compiler: Jack source to Hack VM code, reproducing the official tools
//! (the nand2tetris JackCompiler's output, byte for byte): the grammar with its quirks, the semantic checks
//! with their messages, and the exact code templates and label numbering.
//!
//! Two [`Profile`]s select the checks: `desktop` (default, the tools the seed
//! program was written with: a type may name a class outside the program, and
//! calls into such a class are not checked, since it may come as VM code) and
//! `web` (the web IDE exactly: "Unknown type T", "Class C doesn't exist", and
//! its message quirks). Code generation is the same for both.
//!
//! Calls are validated against the OS subroutine table of `jack-os` first,
//! then against the classes compiled together.
//!
//! ```
//! use jack_compiler::{compile_sources, Profile};
//! let src = "class Main { function void main() { do Output.printInt(1 + 2); return; } }";
//! let vm = compile_sources(&[("Main.jack", src)], Profile::Desktop).unwrap();
//! assert_eq!(vm[0].class_name, "Main");
//! assert!(vm[0].code.starts_with("function Main.main 0\n"));
//! ```

pub mod ast;
mod codegen;
pub mod error;
mod flow;
pub mod lexer;
mod os_api;
pub mod parser;
mod program;

use std::path::Path;

pub use error::{CompileDirError, CompileError, CompileErrors, ErrorKind, Pos};
/// The profile type shared with the OS and the VM.
pub use jack_os::{Profile, ProfileParseError};
use program::{Program, ProgramClass};

/// The VM code of one class.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct VmClass {
    /// The class name (the .vm file is `<class_name>.vm`).
    pub class_name: String,
    /// The VM commands, one per line, ending with a newline.
    pub code: String,
    /// The position in the Jack source of each line of `code` (of the
    /// statement, term or call it was compiled from), to map a VM load
    /// error back to the Jack source.
    pub lines: Vec<Pos>,
}

impl VmClass {
    /// The name of the class's .vm file: `<class_name>.vm`.
    pub fn file_name(&self) -> String {
        format!("{}.vm", self.class_name)
    }

    /// Where in the Jack source VM line `line` (1-based) comes from.
    pub fn jack_pos(&self, line: usize) -> Option<Pos> {
        line.checked_sub(1).and_then(|i| self.lines.get(i)).copied()
    }

    /// The class as a (file name, VM code) pair, the form the Hack VM
    /// loads a program from.
    pub fn into_file(self) -> (String, String) {
        (self.file_name(), self.code)
    }
}

/// The class name a source file must declare: its base name without `.jack`.
pub fn class_name_of_file(file_name: &str) -> &str {
    let base = file_name.rsplit(['/', '\\']).next().unwrap_or(file_name);
    base.strip_suffix(".jack").unwrap_or(base)
}

/// Compiles a set of classes given as (file name, source) pairs, e.g.
/// `("Main.jack", "class Main { ... }")`. Returns one [`VmClass`] per source
/// in the given order, or every error found: the first syntax error of each
/// file and the semantic errors of every class that parsed.
pub fn compile_sources<N: AsRef<str>, S: AsRef<str>>(
    sources: &[(N, S)],
    profile: Profile,
) -> Result<Vec<VmClass>, CompileErrors> {
    let mut errors: Vec<(usize, CompileError)> = Vec::new();
    let mut push = |i: usize, pos: Pos, kind: ErrorKind| {
        let file = sources[i].0.as_ref().to_string();
        errors.push((i, CompileError { file, pos, kind }));
    };
    let parsed: Vec<Option<ast::Class>> = sources
        .iter()
        .enumerate()
        .map(|(i, (_, src))| match parser::parse_class(src.as_ref()) {
            Ok(c) => Some(c),
            Err((pos, kind)) => {
                push(i, pos, kind);
                None
            }
        })
        .collect();

    let mut program = Program::new(profile);
    for (i, class) in parsed.iter().enumerate() {
        match class {
            Some(c) => program.add(&c.name.text, ProgramClass::Parsed(c)),
            None => program.add(
                class_name_of_file(sources[i].0.as_ref()),
                ProgramClass::Unparsed,
            ),
        }
    }

    let mut out = Vec::new();
    for (i, class) in parsed.iter().enumerate() {
        let Some(class) = class else { continue };
        let file_class = class_name_of_file(sources[i].0.as_ref());
        if class.name.text != file_class {
            push(
                i,
                class.name.pos,
                ErrorKind::ClassNameMismatch {
                    class: class.name.text.clone(),
                    file: file_class.to_string(),
                },
            );
        }
        let first = (0..i).find(|&j| {
            parsed[j]
                .as_ref()
                .is_some_and(|c| c.name.text == class.name.text)
        });
        if first.is_some() {
            push(
                i,
                class.name.pos,
                ErrorKind::DuplicateClass(class.name.text.clone()),
            );
        }
        match codegen::compile_class(class, &program) {
            Ok((code, lines)) => out.push(VmClass {
                class_name: class.name.text.clone(),
                code,
                lines,
            }),
            Err(errs) => {
                for (pos, kind) in errs {
                    push(i, pos, kind);
                }
            }
        }
    }
    if errors.is_empty() {
        Ok(out)
    } else {
        errors.sort_by_key(|(i, e)| (*i, e.pos));
        Err(CompileErrors(errors.into_iter().map(|(_, e)| e).collect()))
    }
}

/// Compiles every `.jack` file of a directory (not recursive), in file name
/// order. Errors name files by their file name, e.g. `Main.jack:3:5: ...`.
pub fn compile_dir(dir: &Path, profile: Profile) -> Result<Vec<VmClass>, CompileDirError> {
    let io_err = |path: &Path, source| CompileDirError::Io {
        path: path.to_path_buf(),
        source,
    };
    let mut files = Vec::new();
    for entry in std::fs::read_dir(dir).map_err(|e| io_err(dir, e))? {
        let path = entry.map_err(|e| io_err(dir, e))?.path();
        if path.is_file() && path.extension().is_some_and(|x| x == "jack") {
            files.push(path);
        }
    }
    if files.is_empty() {
        return Err(CompileDirError::NoSources(dir.to_path_buf()));
    }
    files.sort();
    let mut sources = Vec::new();
    for path in &files {
        let text = common::input::read_text(path)?;
        let name = path
            .file_name()
            .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
        sources.push((name, text));
    }
    compile_sources(&sources, profile).map_err(CompileDirError::Compile)
}
