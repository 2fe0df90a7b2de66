//! The project file, `harness.toml`: where it is found, and how its fields
//! are read so that every error names the file, the line, the column and
//! the field.
//!
//! ```toml
//! [impl.my-port]          # one table per declared implementation
//! kind = "reference"      # which kind module reads the other fields
//! numbers = "float316"
//! variants = ["newton-3"]
//!
//! [roles]                 # optional: who plays the f64 oracle and the tracer
//! oracle = "ref-f64"
//! tracer = "ref-f316"
//! ```

use std::fmt;
use std::path::{Path, PathBuf};
use toml::de::{DeTable, DeValue};
use toml::Spanned;

/// The project file's name, looked for in the current directory.
pub const PROJECT_FILE: &str = "harness.toml";

/// The project file to read: `--cast FILE` when given, else `harness.toml`
/// in the current directory when there is one.
pub fn locate(flag: Option<&Path>) -> Option<PathBuf> {
    match flag {
        Some(path) => Some(path.to_path_buf()),
        None => {
            let here = Path::new(PROJECT_FILE);
            here.is_file().then(|| here.to_path_buf())
        }
    }
}

/// An error in a project file, at a place in it.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub struct FieldError {
    pub file: PathBuf,
    /// 1-based.
    pub line: usize,
    /// 1-based, in characters.
    pub column: usize,
    /// The dotted path of the field (`impl.my-port.numbers`), empty for a
    /// syntax error.
    pub field: String,
    pub message: String,
}

impl fmt::Display for FieldError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}:{}: ", self.file.display(), self.line, self.column)?;
        if !self.field.is_empty() {
            write!(f, "{}: ", self.field)?;
        }
        f.write_str(&self.message)
    }
}

/// A project file's text, to turn byte offsets into lines and columns.
#[derive(Clone, Copy)]
pub struct Source<'a> {
    pub file: &'a Path,
    pub text: &'a str,
}

impl Source<'_> {
    /// An error at byte offset `at`.
    pub fn error(&self, at: usize, field: &str, message: impl Into<String>) -> FieldError {
        let before = &self.text[..at.min(self.text.len())];
        let line = before.matches('\n').count() + 1;
        let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
        FieldError {
            file: self.file.to_path_buf(),
            line,
            column,
            field: field.to_string(),
            message: message.into(),
        }
    }

    /// The 1-based line of byte offset `at`.
    pub fn line_of(&self, at: usize) -> usize {
        self.error(at, "", "").line
    }
}

/// Parse the whole document; a syntax error is located.
pub fn parse<'a>(source: Source<'a>) -> Result<Spanned<DeTable<'a>>, FieldError> {
    DeTable::parse(source.text).map_err(|e| {
        let at = e.span().map_or(0, |s| s.start);
        source.error(at, "", e.message().trim_end().to_string())
    })
}

/// The fields of one table (`[impl.NAME]`, `[roles]`), read one by one.
/// Every read is remembered: [`Fields::finish`] refuses the fields nobody
/// read, so a misspelt field is an error, never silently ignored.
pub struct Fields<'a> {
    source: Source<'a>,
    /// The table's dotted path (`impl.my-port`).
    path: String,
    table: &'a DeTable<'a>,
    /// Where the table starts, for errors about a missing field.
    at: usize,
    read: Vec<String>,
}

impl<'a> Fields<'a> {
    /// The fields of `table`, found at `at` under the dotted `path`.
    pub fn new(source: Source<'a>, path: &str, table: &'a DeTable<'a>, at: usize) -> Self {
        Fields {
            source,
            path: path.to_string(),
            table,
            at,
            read: Vec::new(),
        }
    }

    /// The project file these fields are in.
    pub fn file(&self) -> &'a Path {
        self.source.file
    }

    /// The directory relative paths of the file are taken from.
    pub fn dir(&self) -> &'a Path {
        self.source
            .file
            .parent()
            .filter(|d| !d.as_os_str().is_empty())
            .unwrap_or(Path::new("."))
    }

    /// The 1-based line where the table starts.
    pub fn line(&self) -> usize {
        self.source.line_of(self.at)
    }

    fn field(&self, key: &str) -> String {
        if self.path.is_empty() {
            key.to_string()
        } else {
            format!("{}.{key}", self.path)
        }
    }

    /// An error about `key`: at its value when it is there, else at the
    /// table.
    pub fn error(&self, key: &str, message: impl Into<String>) -> FieldError {
        let at = self.table.get(key).map_or(self.at, |v| v.span().start);
        self.source.error(at, &self.field(key), message)
    }

    /// The raw value of `key`, for a kind with fields of its own shape
    /// (the value's span locates its errors through [`Fields::error_at`]).
    pub fn raw(&mut self, key: &str) -> Option<&'a Spanned<DeValue<'a>>> {
        self.read.push(key.to_string());
        self.table.get(key)
    }

    /// An error inside the value of `key`, at byte offset `at`.
    pub fn error_at(&self, key: &str, at: usize, message: impl Into<String>) -> FieldError {
        self.source.error(at, &self.field(key), message)
    }

    /// A string field, if present.
    pub fn string(&mut self, key: &str) -> Result<Option<&'a str>, FieldError> {
        match self.raw(key).map(|v| v.get_ref()) {
            None => Ok(None),
            Some(DeValue::String(s)) => Ok(Some(s.as_ref())),
            Some(other) => Err(self.error(
                key,
                format!("expected a string, found {}", other.type_str()),
            )),
        }
    }

    /// A string field that must be present.
    pub fn required_string(&mut self, key: &str) -> Result<&'a str, FieldError> {
        self.string(key)?
            .ok_or_else(|| self.error(key, "missing (required)"))
    }

    /// A string field parsed with `FromStr`; the parse error is the message.
    pub fn parsed<T>(&mut self, key: &str) -> Result<Option<T>, FieldError>
    where
        T: std::str::FromStr,
        T::Err: fmt::Display,
    {
        self.string(key)?
            .map(|s| s.parse::<T>().map_err(|e| self.error(key, e.to_string())))
            .transpose()
    }

    /// An array of strings, empty when absent.
    pub fn strings(&mut self, key: &str) -> Result<Vec<&'a str>, FieldError> {
        let Some(value) = self.raw(key) else {
            return Ok(Vec::new());
        };
        let DeValue::Array(items) = value.get_ref() else {
            return Err(self.error(
                key,
                format!(
                    "expected an array of strings, found {}",
                    value.get_ref().type_str()
                ),
            ));
        };
        items
            .iter()
            .enumerate()
            .map(|(i, item)| match item.get_ref() {
                DeValue::String(s) => Ok(s.as_ref()),
                other => Err(self.error_at(
                    key,
                    item.span().start,
                    format!("item {i}: expected a string, found {}", other.type_str()),
                )),
            })
            .collect()
    }

    /// A boolean field, if present.
    pub fn bool(&mut self, key: &str) -> Result<Option<bool>, FieldError> {
        match self.raw(key).map(|v| v.get_ref()) {
            None => Ok(None),
            Some(DeValue::Boolean(b)) => Ok(Some(*b)),
            Some(other) => Err(self.error(
                key,
                format!("expected true or false, found {}", other.type_str()),
            )),
        }
    }

    /// A path field, relative to the project file's directory.
    pub fn path(&mut self, key: &str) -> Result<Option<PathBuf>, FieldError> {
        Ok(self.string(key)?.map(|p| self.dir().join(p)))
    }

    /// Refuse every field that was not read.
    pub fn finish(self, known: &str) -> Result<(), FieldError> {
        let unread = self
            .table
            .iter()
            .find(|(k, _)| !self.read.iter().any(|r| r == k.get_ref().as_ref()));
        match unread {
            None => Ok(()),
            Some((key, _)) => Err(self.source.error(
                key.span().start,
                &self.field(key.get_ref()),
                format!("unknown field (expected {known})"),
            )),
        }
    }
}
