//! Compile errors: where (file, line, column) and what (a plain sentence,
//! the official message of spec §4.2 where there is one).

use std::fmt;
use std::path::PathBuf;

/// A position in a source file, 1-based; the column counts characters.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Pos {
    /// Line number, from 1.
    pub line: u32,
    /// Column number (in characters), from 1.
    pub col: u32,
}

impl fmt::Display for Pos {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}", self.line, self.col)
    }
}

/// What went wrong. The Display texts are the messages of the official web
/// IDE where the spec gives them.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ErrorKind {
    /// The text does not follow the Jack grammar (the sentence says how).
    #[error("{0}")]
    Syntax(String),
    /// Expressions or statements nested deeper than the compiler allows.
    #[error("Nesting deeper than {0} levels")]
    TooDeep(usize),
    /// The class is not named like its file.
    #[error("Class name {class} doesn't match file name {file}")]
    ClassNameMismatch { class: String, file: String },
    /// Two files declare the same class.
    #[error("Class {0} is declared in more than one file")]
    DuplicateClass(String),
    /// A subroutine name used twice in one class.
    #[error("Subroutine {0} already declared")]
    DuplicateSubroutine(String),
    /// Some path through the body does not end in a return.
    #[error("Subroutine {0}: not all code paths return a value")]
    MissingReturn(String),
    /// `return;` in a non-void subroutine.
    #[error("A non void subroutine must return a value")]
    ReturnWithoutValue,
    /// A name that is no local, argument, field or static.
    #[error("Undeclared variable {0}")]
    UndeclaredVariable(String),
    /// A type that is neither primitive, an OS class nor a compiled class.
    #[error("Unknown type {0}")]
    UnknownType(String),
    /// A call into a class that is neither built in nor compiled.
    #[error("Class {0} doesn't exist")]
    UnknownClass(String),
    /// A call of a subroutine the class does not have.
    #[error("Class {class} doesn't contain a function/constructor {name}")]
    UnknownSubroutine { class: String, name: String },
    /// Wrong number of arguments.
    #[error("{class}.{name} expected {expected} arguments, got {got}")]
    ArgumentCount {
        class: String,
        name: String,
        expected: usize,
        got: usize,
    },
    /// `C.m()` where m is a method.
    #[error("Method {class}.{name} was called as a function/constructor")]
    MethodCalledAsFunction { class: String, name: String },
    /// A function or constructor called on an object (or unqualified).
    /// `label` is "Function"/"Constructor", or in the web profile for user
    /// classes the capitalised subroutine name (an upstream bug, kept).
    #[error("{label} {class}.{name} was called as a method")]
    FunctionCalledAsMethod {
        label: String,
        class: String,
        name: String,
    },
    /// A class named like an OS class redefines an OS subroutine with
    /// another signature.
    #[error("OS subroutine {class}.{name} must follow the interface {interface}")]
    OsInterface {
        class: String,
        name: String,
        interface: String,
    },
}

/// One compile error with its location.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{file}:{pos}: {kind}")]
pub struct CompileError {
    /// The source file name as given (e.g. `Main.jack`).
    pub file: String,
    /// Where in the file.
    pub pos: Pos,
    /// What.
    pub kind: ErrorKind,
}

/// All compile errors of one run, in file order then source order.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CompileErrors(pub Vec<CompileError>);

impl fmt::Display for CompileErrors {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, e) in self.0.iter().enumerate() {
            if i > 0 {
                writeln!(f)?;
            }
            write!(f, "{e}")?;
        }
        Ok(())
    }
}

impl std::error::Error for CompileErrors {}

/// Failure of [`crate::compile_dir`].
#[derive(Debug, thiserror::Error)]
pub enum CompileDirError {
    /// A file or the directory could not be read (also: not UTF-8).
    #[error("cannot read {path}")]
    Io {
        path: PathBuf,
        source: std::io::Error,
    },
    /// A source is not a readable regular UTF-8 file of bounded size (a
    /// bad byte is located by line and column).
    #[error(transparent)]
    Input(#[from] common::input::InputError),
    /// The directory holds no `.jack` file.
    #[error("no .jack files in {0}")]
    NoSources(PathBuf),
    /// The sources do not compile.
    #[error("{0}")]
    Compile(CompileErrors),
}
