//! The cast: the one registry of implementations every command takes its
//! implementations and roles from.
//!
//! An [`Entry`] says what an implementation is (name, kind, number type,
//! levels, whether it traces, its variants and faults, its roles) and how
//! to open it. The built-in entries come from the kinds
//! ([`crate::impls::KINDS`]); a project file (`harness.toml`, or `--cast
//! FILE`) declares more, one `[impl.NAME]` table each, whose `kind` field
//! picks the kind module that reads the rest of the table.
//!
//! # Adding a kind
//! One module in `harness/src/impls/` and one line in
//! [`crate::impls::KINDS`]. The module defines a unit struct implementing
//! [`Kind`]: its `name` is the `kind = "..."` value, `builtins` gives its
//! built-in entries (usually none), and `declare` reads its own fields of an
//! `[impl.NAME]` table through [`file::Fields`] (a missing or malformed
//! field is a [`file::FieldError`] naming file, line and field; a field it
//! does not read is refused) and returns an [`Entry`] whose [`Opener`]
//! opens an [`Implementation`] under a label. Nothing else in the harness
//! changes: every command finds the new entries in the cast.

pub mod entry;
pub mod file;
pub mod label;

use crate::implementation::{ImplError, Implementation, Numbers};
pub use entry::{Entry, Kind, Opener, Origin, Request, Roles, VariantInfo, VariantRole};
use file::{FieldError, Fields, Source};
pub use label::{BadLabel, Label};
use std::path::{Path, PathBuf};
use toml::de::DeValue;

/// The names of the implementations playing the roles, for the reports.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RoleNames {
    /// The f64 oracle.
    pub oracle: String,
    /// The tracer, which is also the base of bit-exact comparisons.
    pub tracer: String,
}

/// Why a label could not be opened.
#[derive(Debug, thiserror::Error)]
pub enum OpenError {
    #[error(transparent)]
    Label(#[from] BadLabel),
    #[error("unknown implementation `{name}` (expected one of {known})")]
    Unknown { name: String, known: String },
    #[error("{name} has no variant or fault `{variant}` ({accepted})")]
    Variant {
        name: String,
        variant: String,
        accepted: String,
    },
    #[error(transparent)]
    Impl(#[from] ImplError),
}

/// Why a project file could not be read.
#[derive(Debug, thiserror::Error)]
pub enum CastError {
    #[error("the project file: {0}")]
    Read(common::input::InputError),
    #[error(transparent)]
    Field(#[from] FieldError),
}

/// The registry: the built-in entries and those of the project file.
pub struct Cast {
    entries: Vec<Entry>,
    file: Option<PathBuf>,
}

impl Cast {
    /// The built-in entries only.
    pub fn builtin() -> Cast {
        Cast {
            entries: crate::impls::KINDS
                .iter()
                .flat_map(|k| k.builtins())
                .collect(),
            file: None,
        }
    }

    /// The cast of this run: the built-ins and the project file's entries
    /// (`--cast FILE`, else `harness.toml` in the current directory when
    /// there is one).
    pub fn load(flag: Option<&Path>) -> Result<Cast, CastError> {
        let mut cast = Cast::builtin();
        if let Some(path) = file::locate(flag) {
            let text = common::input::read_text(&path).map_err(CastError::Read)?;
            cast.declare(Source {
                file: &path,
                text: &text,
            })?;
            cast.file = Some(path);
        }
        Ok(cast)
    }

    /// The built-ins and the entries of a project file's text.
    pub fn with_project(file: &Path, text: &str) -> Result<Cast, FieldError> {
        let mut cast = Cast::builtin();
        cast.declare(Source { file, text })?;
        cast.file = Some(file.to_path_buf());
        Ok(cast)
    }

    /// Add `entry` unless the cast has an entry of its name (a project
    /// file's declaration of that name wins).
    pub fn add_unless_declared(&mut self, entry: Entry) {
        if self.get(&entry.name).is_none() {
            self.entries.push(entry);
        }
    }

    /// The project file read, if any.
    pub fn file(&self) -> Option<&Path> {
        self.file.as_deref()
    }

    /// Add the entries and roles a project file declares.
    fn declare(&mut self, source: Source<'_>) -> Result<(), FieldError> {
        let doc = file::parse(source)?;
        let mut top = Fields::new(source, "", doc.get_ref(), 0);
        let declared = top.raw("impl");
        let roles = top.raw("roles");
        top.finish("`impl` or `roles`")?;
        if let Some(value) = declared {
            let DeValue::Table(tables) = value.get_ref() else {
                return Err(source.error(
                    value.span().start,
                    "impl",
                    "expected tables [impl.NAME]",
                ));
            };
            for (name, table) in tables {
                let entry = self.declare_one(source, name.get_ref(), table)?;
                self.entries.push(entry);
            }
        }
        if let Some(value) = roles {
            self.declare_roles(source, value)?;
        }
        Ok(())
    }

    /// One `[impl.NAME]` table.
    fn declare_one(
        &self,
        source: Source<'_>,
        name: &str,
        table: &toml::Spanned<DeValue<'_>>,
    ) -> Result<Entry, FieldError> {
        let path = format!("impl.{name}");
        let at = table.span().start;
        let DeValue::Table(table) = table.get_ref() else {
            return Err(source.error(at, &path, "expected a table"));
        };
        let mut fields = Fields::new(source, &path, table, at);
        if let Err(why) = name.parse::<Label>().map(|l| l.variants.is_empty()) {
            return Err(source.error(at, &path, why.to_string()));
        }
        if name.contains('+') {
            return Err(source.error(at, &path, "a name cannot contain `+` (it starts a variant)"));
        }
        if let Some(other) = self.get(name) {
            return Err(source.error(
                at,
                &path,
                format!("`{name}` is already an implementation ({})", other.origin),
            ));
        }
        let kind_name = fields.required_string("kind")?;
        let kind = crate::impls::KINDS
            .iter()
            .find(|k| k.name() == kind_name)
            .ok_or_else(|| {
                fields.error(
                    "kind",
                    format!(
                        "unknown kind `{kind_name}` (expected one of {})",
                        kind_names()
                    ),
                )
            })?;
        let line = fields.line();
        let mut entry = kind.declare(name, &mut fields)?;
        fields.finish(&format!("the fields of kind `{kind_name}`"))?;
        entry.name = name.to_string();
        entry.roles = Roles::default();
        entry.origin = Origin::Declared {
            file: source.file.to_path_buf(),
            line,
        };
        Ok(entry)
    }

    /// The `[roles]` table: `oracle` and `tracer` name entries.
    fn declare_roles(
        &mut self,
        source: Source<'_>,
        value: &toml::Spanned<DeValue<'_>>,
    ) -> Result<(), FieldError> {
        let DeValue::Table(table) = value.get_ref() else {
            return Err(source.error(value.span().start, "roles", "expected a table [roles]"));
        };
        let mut fields = Fields::new(source, "roles", table, value.span().start);
        let oracle = fields.string("oracle")?;
        let tracer = fields.string("tracer")?;
        if let Some(name) = oracle {
            let entry = self.get(name).ok_or_else(|| {
                fields.error("oracle", format!("unknown implementation `{name}`"))
            })?;
            if entry.numbers != Numbers::F64 {
                return Err(fields.error(
                    "oracle",
                    format!(
                        "the oracle must compute with f64; {name} computes with {}",
                        entry.numbers
                    ),
                ));
            }
            self.entries
                .iter_mut()
                .for_each(|e| e.roles.oracle = e.name == name);
        }
        if let Some(name) = tracer {
            let entry = self.get(name).ok_or_else(|| {
                fields.error("tracer", format!("unknown implementation `{name}`"))
            })?;
            if !entry.bit_exact() || !entry.traces {
                return Err(fields.error(
                    "tracer",
                    format!("the tracer must compute with float316 and trace; {name} does not"),
                ));
            }
            self.entries
                .iter_mut()
                .for_each(|e| e.roles.tracer = e.name == name);
        }
        fields.finish("`oracle` or `tracer`")
    }

    /// Every entry: the built-ins in the design's order, then the declared
    /// ones in the file's order.
    pub fn entries(&self) -> &[Entry] {
        &self.entries
    }

    /// The entry called `name`.
    pub fn get(&self, name: &str) -> Option<&Entry> {
        self.entries.iter().find(|e| e.name == name)
    }

    /// The f64 oracle.
    pub fn oracle(&self) -> &Entry {
        self.role(|r| r.oracle)
    }

    /// The tracer used for localization.
    pub fn tracer(&self) -> &Entry {
        self.role(|r| r.tracer)
    }

    fn role(&self, plays: impl Fn(&Roles) -> bool) -> &Entry {
        self.entries
            .iter()
            .find(|e| plays(&e.roles))
            .expect("the built-in entries play every role")
    }

    /// Who plays the oracle and the tracer.
    pub fn role_names(&self) -> RoleNames {
        RoleNames {
            oracle: self.oracle().name.clone(),
            tracer: self.tracer().name.clone(),
        }
    }

    /// The bit-exact group: every Float316 entry, the tracer first.
    pub fn bit_exact_group(&self) -> Vec<&Entry> {
        let tracer = self.tracer();
        std::iter::once(tracer)
            .chain(
                self.entries
                    .iter()
                    .filter(|e| e.bit_exact() && e.name != tracer.name),
            )
            .collect()
    }

    /// The entry and the checked label of `text`: the name must be an
    /// entry's and every variant one it accepts.
    pub fn resolve(&self, text: &str) -> Result<(&Entry, Label), OpenError> {
        let label: Label = text.parse()?;
        let entry = self.get(&label.name).ok_or_else(|| OpenError::Unknown {
            name: label.name.clone(),
            known: self.names().join(", "),
        })?;
        if let Some(v) = label
            .variants
            .iter()
            .find(|v| !entry.variants.iter().any(|a| &a.name == *v))
        {
            let names: Vec<&str> = entry.variants.iter().map(|a| a.name.as_str()).collect();
            return Err(OpenError::Variant {
                name: entry.name.clone(),
                variant: v.clone(),
                accepted: if names.is_empty() {
                    "it has none".into()
                } else {
                    format!("it has {}", names.join(", "))
                },
            });
        }
        Ok((entry, label))
    }

    /// Open the implementation a label names.
    pub fn open(&self, text: &str) -> Result<Box<dyn Implementation>, OpenError> {
        self.open_for_scene(text, None)
    }

    /// Open it for `scene` (`None`: the seed scene).
    pub fn open_for_scene(
        &self,
        text: &str,
        scene: Option<&reference::Scene>,
    ) -> Result<Box<dyn Implementation>, OpenError> {
        let (entry, label) = self.resolve(text)?;
        Ok(entry.open(&label, scene)?)
    }

    /// Every entry's name.
    pub fn names(&self) -> Vec<&str> {
        self.entries.iter().map(|e| e.name.as_str()).collect()
    }
}

/// The kinds' names, for messages.
fn kind_names() -> String {
    crate::impls::KINDS
        .iter()
        .map(|k| k.name())
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests;
