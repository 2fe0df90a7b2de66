//! The harness from a user's own `cargo test`: load the project's
//! `harness.toml`, compare two implementations on a level's committed set
//! or on a vector set file, and fail the test with the divergence
//! localized to its first Float316 operation. [`Verdict::text`] is
//! deterministic (no timings), ready for an insta snapshot.
//!
//! ```no_run
//! use harness::testkit::Project;
//! use vectors::Level;
//!
//! let project = Project::load(concat!(env!("CARGO_MANIFEST_DIR"), "/harness.toml")).unwrap();
//! project.diff_level("ref-f316", "my-port", Level::Ops).unwrap().assert_agrees();
//! ```

use crate::cast::{Cast, CastError, OpenError};
use crate::localize::{localize, Localization};
use crate::runner::{diff_set, LevelReport, RunOptions};
use crate::text;
use crate::verdict::Status;
use std::fmt::Write;
use std::path::Path;
use vectors::{Level, SetError, VectorSet};

/// A project: the built-in implementations and those of its project file.
pub struct Project {
    cast: Cast,
}

/// Why a comparison could not be made.
#[derive(Debug, thiserror::Error)]
pub enum ProjectError {
    #[error(transparent)]
    Cast(#[from] CastError),
    #[error("implementation `{label}`: {source}")]
    Open {
        label: String,
        #[source]
        source: OpenError,
    },
    #[error(transparent)]
    Set(#[from] SetError),
}

/// The outcome of one comparison: the level's report, and the first
/// bit-exact divergence localized.
#[derive(Debug)]
pub struct Verdict {
    pub report: LevelReport,
    pub localized: Option<Localization>,
    text: String,
}

impl Verdict {
    /// The status the command line's `harness diff` would exit with
    /// ([`crate::verdict`]): agreed, diverged, or not all compared.
    pub fn status(&self) -> Status {
        let mut verdict = crate::verdict::Verdict::new(false);
        verdict.add_level(&self.report, true);
        verdict.status()
    }

    /// Whether both implementations answered every vector and agree under
    /// the policy.
    pub fn agrees(&self) -> bool {
        self.status() == Status::Agreed
    }

    /// The report as text: runs that failed, the comparison, and the
    /// localization of the first divergence. Deterministic.
    pub fn text(&self) -> &str {
        &self.text
    }

    /// Panic with [`Verdict::text`] unless the implementations agree: the
    /// failure message of a test.
    #[track_caller]
    pub fn assert_agrees(&self) {
        assert!(self.agrees(), "the implementations disagree\n{}", self.text);
    }
}

impl Project {
    /// The project file at `path` (its relative paths are taken from its
    /// directory) and the built-ins.
    pub fn load(path: impl AsRef<Path>) -> Result<Project, ProjectError> {
        Ok(Project {
            cast: Cast::load(Some(path.as_ref()))?,
        })
    }

    /// Compare `a` and `b` (labels, as on the command line) on the
    /// committed small set of `level`.
    pub fn diff_level(&self, a: &str, b: &str, level: Level) -> Result<Verdict, ProjectError> {
        let set = vectors::load_named(vectors::named::small_set_name(level))?;
        self.diff(a, b, &set)
    }

    /// Compare `a` and `b` on the vector set file at `path`.
    pub fn diff_vectors(
        &self,
        a: &str,
        b: &str,
        path: impl AsRef<Path>,
    ) -> Result<Verdict, ProjectError> {
        self.diff(a, b, &VectorSet::load(path.as_ref())?)
    }

    /// Compare `a` and `b` on `set`.
    pub fn diff(&self, a: &str, b: &str, set: &VectorSet) -> Result<Verdict, ProjectError> {
        let open = |label: &str| {
            self.cast.open(label).map_err(|source| ProjectError::Open {
                label: label.to_string(),
                source,
            })
        };
        let (ia, ib) = (open(a)?, open(b)?);
        let report = diff_set(&[ia.as_ref(), ib.as_ref()], set, RunOptions::default());
        let first = report
            .comparisons
            .iter()
            .flat_map(|c| c.divergences.iter().filter(|d| d.localize.is_some()))
            .next();
        let localized = match first {
            Some(d) => {
                let tracer = open(&self.cast.tracer().name)?;
                localize(ia.as_ref(), ib.as_ref(), tracer.as_ref(), &d.input).ok()
            }
            None => None,
        };
        let mut text = text::level_report(&report);
        if let Some(l) = &localized {
            let _ = write!(text, "first divergence localized:\n{l}");
        }
        Ok(Verdict {
            report,
            localized,
            text,
        })
    }
}
