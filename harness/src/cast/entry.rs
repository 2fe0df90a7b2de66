//! What the cast holds: an [`Entry`] per implementation, made by a
//! [`Kind`], and the [`Opener`] that opens it. The kinds (`crate::impls`)
//! import this module, never the registry in `cast/mod.rs`, which is the
//! only one that lists them.

use super::file::{FieldError, Fields};
use super::label::Label;
use crate::implementation::{ImplError, Implementation, Numbers};
use std::fmt;
use std::path::PathBuf;
use vectors::Level;

/// One kind of implementation: a module of `harness/src/impls/`, listed in
/// [`crate::impls::KINDS`].
pub trait Kind: Sync {
    /// The `kind = "..."` value of the project file.
    fn name(&self) -> &'static str;

    /// The built-in entries of this kind (the six of the design belong to
    /// the `reference`, `jack` and `shader` kinds).
    fn builtins(&self) -> Vec<Entry> {
        Vec::new()
    }

    /// The entry `[impl.NAME]` of a project file declares: read this kind's
    /// fields from `fields` (the cast has read `kind`; fields left unread
    /// are refused), and fill in the entry with [`Entry::new`].
    fn declare(&self, name: &str, fields: &mut Fields<'_>) -> Result<Entry, FieldError>;
}

/// What opening an implementation is asked for.
#[derive(Clone, Copy, Debug)]
pub struct Request<'a> {
    /// The label it is opened under: the entry's name and the variants
    /// (already checked against the entry's list); it becomes the
    /// implementation's [`Implementation::label`].
    pub label: &'a Label,
    /// A scene other than the seed scene, for `harness render --scene`;
    /// a kind that cannot take one says so.
    pub scene: Option<&'a reference::Scene>,
}

impl Request<'_> {
    /// The error of a kind that renders only the seed scene, when asked
    /// for another.
    pub fn seed_scene_only(&self) -> Result<(), ImplError> {
        match self.scene {
            Some(scene) if *scene != reference::Scene::default() => {
                Err(ImplError::Unsupported(format!(
                    "another scene than the seed scene ({} holds the seed scene only)",
                    self.label.name
                )))
            }
            _ => Ok(()),
        }
    }
}

/// How an entry opens its implementation.
pub trait Opener: Send + Sync {
    /// Open the implementation for `request`. Fails with
    /// [`ImplError::Unavailable`] (saying why) when it cannot run here.
    fn open(&self, request: &Request<'_>) -> Result<Box<dyn Implementation>, ImplError>;
}

/// Whether a variant trades precision for speed or is a deliberate fault.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum VariantRole {
    /// A precision variant (rendered for the speed-against-error plot).
    Precision,
    /// A deliberate fault (for the self-test).
    Fault,
}

/// A variant or fault an entry accepts after `+` in a label.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct VariantInfo {
    pub name: String,
    pub role: VariantRole,
}

/// The roles an entry plays; the bit-exact group is every entry computing
/// with Float316 ([`Entry::bit_exact`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct Roles {
    /// The f64 oracle: error figures are taken against it.
    pub oracle: bool,
    /// The tracer used for localization: a side that cannot trace is
    /// checked against it and replayed op by op.
    pub tracer: bool,
}

/// Where an entry comes from.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Origin {
    /// One of the harness's own.
    Builtin,
    /// Declared in a project file, at this line.
    Declared { file: PathBuf, line: usize },
}

impl fmt::Display for Origin {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Origin::Builtin => f.write_str("built-in"),
            Origin::Declared { file, line } => write!(f, "{}:{line}", file.display()),
        }
    }
}

/// One implementation of the cast.
pub struct Entry {
    /// The name labels start with (no `+`).
    pub name: String,
    /// The kind module that made it.
    pub kind: &'static str,
    /// One line saying what it is.
    pub about: String,
    /// The numbers it computes with: decides its group and the policy.
    pub numbers: Numbers,
    /// The levels it answers.
    pub levels: Vec<Level>,
    /// Whether it records op traces.
    pub traces: bool,
    /// Whether it answers slowly (an emulator): the nightly's exhaustive
    /// unary checks give it every N-th input only.
    pub slow: bool,
    /// The variants and faults a label may add.
    pub variants: Vec<VariantInfo>,
    pub roles: Roles,
    pub origin: Origin,
    /// Whether it runs in the harness's process, so that the cast opens it
    /// behind the containment layer ([`crate::contain::Contained`]); a
    /// kind that runs its own processes contains them itself.
    pub in_process: bool,
    opener: Box<dyn Opener>,
}

impl Entry {
    /// An entry with no variants and no roles, of origin built-in (the
    /// cast sets the origin of declared entries).
    pub fn new(
        name: &str,
        kind: &'static str,
        numbers: Numbers,
        opener: impl Opener + 'static,
    ) -> Entry {
        Entry {
            name: name.to_string(),
            kind,
            about: String::new(),
            numbers,
            levels: Level::ALL.to_vec(),
            traces: false,
            slow: false,
            variants: Vec::new(),
            roles: Roles::default(),
            origin: Origin::Builtin,
            in_process: true,
            opener: Box::new(opener),
        }
    }

    /// With this description.
    pub fn about(mut self, about: impl Into<String>) -> Self {
        self.about = about.into();
        self
    }

    /// Answering only these levels.
    pub fn levels(mut self, levels: &[Level]) -> Self {
        self.levels = levels.to_vec();
        self
    }

    /// Recording op traces.
    pub fn traces(mut self) -> Self {
        self.traces = true;
        self
    }

    /// Running in a process of its own, which its kind watches (no
    /// containment layer in the harness's process).
    pub fn own_process(mut self) -> Self {
        self.in_process = false;
        self
    }

    /// Answering slowly (an emulator).
    pub fn slow(mut self) -> Self {
        self.slow = true;
        self
    }

    /// Accepting these variants and faults.
    pub fn variants(mut self, variants: Vec<VariantInfo>) -> Self {
        self.variants = variants;
        self
    }

    /// Playing these roles.
    pub fn roles(mut self, roles: Roles) -> Self {
        self.roles = roles;
        self
    }

    /// Whether it belongs to the bit-exact group (it computes with
    /// Float316, so every other Float316 implementation must agree with it
    /// bit for bit).
    pub fn bit_exact(&self) -> bool {
        self.numbers == Numbers::Float316
    }

    /// Whether it answers `level`.
    pub fn answers(&self, level: Level) -> bool {
        self.levels.contains(&level)
    }

    /// Open it under `label` (its name and variants that apply); an
    /// in-process implementation comes behind the containment layer, so
    /// that its panics and endless loops are contained failures.
    pub(super) fn open(
        &self,
        label: &Label,
        scene: Option<&reference::Scene>,
    ) -> Result<Box<dyn Implementation>, ImplError> {
        let opened = self.opener.open(&Request { label, scene })?;
        Ok(if self.in_process {
            crate::contain::Contained::boxed(opened)
        } else {
            opened
        })
    }
}
