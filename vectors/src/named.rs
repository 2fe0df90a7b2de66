//! The catalogue of named, committed vector sets (`vectors/sets/NAME.json`)
//! and how each is built, so that `harness vectors regenerate` rebuilds them
//! deterministically. `*-small` sets run in `cargo test`; `*-nightly` sets
//! in the nightly job.

use crate::gen::{ops, pixels, sdf};
use crate::set::{ImageVector, Level, Vector, VectorSet};

/// How one named set is built.
#[derive(Clone, Copy, Debug)]
pub struct SetSpec {
    /// The set's name and file stem.
    pub name: &'static str,
    /// Its level.
    pub level: Level,
    /// The generator seed.
    pub seed: u64,
    /// Vectors per (operation,) category.
    pub per_category: usize,
    /// What it is for.
    pub description: &'static str,
}

/// Every committed set.
pub const SETS: [SetSpec; 7] = [
    SetSpec {
        name: "ops-small",
        level: Level::Ops,
        seed: 316,
        per_category: 3,
        description: "Float316 operations, every category, a few each: cargo test",
    },
    SetSpec {
        name: "ops-nightly",
        level: Level::Ops,
        seed: 3160,
        per_category: 150,
        description: "Float316 operations, every category: the nightly job",
    },
    SetSpec {
        name: "sdf-small",
        level: Level::Sdf,
        seed: 316,
        per_category: 3,
        description: "scene queries, every category, a few each: cargo test",
    },
    SetSpec {
        name: "sdf-nightly",
        level: Level::Sdf,
        seed: 3160,
        per_category: 120,
        description: "scene queries, every category: the nightly job",
    },
    SetSpec {
        name: "pixels-small",
        level: Level::Pixels,
        seed: 316,
        per_category: 2,
        description: "pixels of every category, two each: cargo test",
    },
    SetSpec {
        name: "pixels-nightly",
        level: Level::Pixels,
        seed: 3160,
        per_category: 60,
        description: "pixels of every category: the nightly job",
    },
    SetSpec {
        name: "image",
        level: Level::Image,
        seed: 0,
        per_category: 1,
        description: "the whole 512x256 image",
    },
];

/// The spec of a named set.
pub fn spec(name: &str) -> Option<SetSpec> {
    SETS.into_iter().find(|s| s.name == name)
}

/// The small set of a level, the default of `harness diff`.
pub fn small_set_name(level: Level) -> &'static str {
    match level {
        Level::Ops => "ops-small",
        Level::Sdf => "sdf-small",
        Level::Pixels => "pixels-small",
        Level::Image => "image",
    }
}

impl SetSpec {
    /// Build the set. Pixel sets need facts about a render for their
    /// silhouette, shadow-edge and dither-tie categories.
    pub fn build(&self, facts: Option<&pixels::PixelFacts>) -> VectorSet {
        let vectors = match self.level {
            Level::Ops => ops::generate(self.seed, self.per_category),
            Level::Sdf => sdf::generate(self.seed, self.per_category),
            Level::Pixels => pixels::generate(self.seed, self.per_category, facts),
            Level::Image => vec![Vector::Image(ImageVector {
                category: "image".to_string(),
            })],
        };
        let seed = (self.level != Level::Image).then_some(self.seed);
        VectorSet::new(self.name, self.level, self.description, seed, vectors)
    }
}
