//! Splitting a campaign across machines: shard `K/N` holds the vectors
//! whose identity hashes to `K` modulo `N`. `K` counts from 0, as
//! Kubernetes' `JOB_COMPLETION_INDEX` does, so shards are `0/N` to
//! `N-1/N`. The hash is FNV-1a over the vector's slug (its operation and
//! operands, or its point or pixel), so a vector's shard depends only on
//! the vector and `N`, never on its neighbours in the set.

use crate::set::{Vector, VectorSet};
use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;

/// One shard of `count`, numbered from 0.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct Shard {
    /// Which shard, `0..count`.
    pub index: u32,
    /// How many shards the campaign has.
    pub count: u32,
}

impl Shard {
    /// The whole campaign as one shard.
    pub const WHOLE: Shard = Shard { index: 0, count: 1 };

    /// Whether `vector` belongs to this shard.
    pub fn contains(self, vector: &Vector) -> bool {
        identity_hash(vector) % u64::from(self.count) == u64::from(self.index)
    }

    /// The vectors of `set` in this shard, in their order, under the
    /// whole set's name (merging shard reports matches sets by that name;
    /// a caller that shows the shard names it itself, as the nightly does).
    pub fn of_set(self, set: &VectorSet) -> VectorSet {
        if self == Shard::WHOLE {
            return set.clone();
        }
        VectorSet {
            vectors: set
                .vectors
                .iter()
                .filter(|v| self.contains(v))
                .cloned()
                .collect(),
            ..set.clone()
        }
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

impl FromStr for Shard {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let bad = || format!("`{s}` is not a shard K/N with 0 <= K < N (K counts from 0)");
        let (k, n) = s.split_once('/').ok_or_else(bad)?;
        let index: u32 = k.trim().parse().map_err(|_| bad())?;
        let count: u32 = n.trim().parse().map_err(|_| bad())?;
        if count == 0 || index >= count {
            return Err(bad());
        }
        Ok(Shard { index, count })
    }
}

/// FNV-1a (64 bits) over the vector's slug: stable across runs, machines
/// and versions of the generators.
pub fn identity_hash(vector: &Vector) -> u64 {
    common::hash::fnv1a(vector.slug().bytes())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gen::testfloat::{cases, CaseLevel};
    use common::Op;

    #[test]
    fn shards_partition_a_set() {
        let vectors = cases(Op::Add, CaseLevel::One, 1);
        let n = 4;
        let mut seen = 0;
        for k in 0..n {
            let shard = Shard { index: k, count: n };
            let part: Vec<_> = vectors.iter().filter(|v| shard.contains(v)).collect();
            assert!(
                part.len() > vectors.len() / 8,
                "shard {k} has {}",
                part.len()
            );
            seen += part.len();
        }
        assert_eq!(seen, vectors.len());
    }

    #[test]
    fn a_vector_keeps_its_shard_whatever_its_neighbours() {
        let vectors = cases(Op::Mul, CaseLevel::One, 1);
        let whole = VectorSet::new("mul", crate::Level::Ops, "", None, vectors);
        // Every third vector, in reverse order: each has other neighbours
        // and another position than in the whole set.
        let other = VectorSet {
            vectors: whole.vectors.iter().rev().step_by(3).cloned().collect(),
            ..whole.clone()
        };
        for index in 0..5 {
            let shard = Shard { index, count: 5 };
            let from_whole = shard.of_set(&whole).vectors;
            let from_other = shard.of_set(&other).vectors;
            assert!(!from_other.is_empty(), "shard {shard} of the part is empty");
            for v in &other.vectors {
                assert_eq!(
                    from_whole.contains(v),
                    from_other.contains(v),
                    "{v} moved shard with its neighbours"
                );
            }
        }
    }

    #[test]
    fn the_hash_is_fnv_1a_of_the_slug_alone() {
        let mut v = cases(Op::Mul, CaseLevel::One, 1).remove(0);
        // FNV-1a of this slug, computed independently of this code: the
        // hash is pinned, since changing it would move every saved campaign.
        assert_eq!(v.slug(), "op-mul-0--1-0-0--1-0");
        assert_eq!(identity_hash(&v), 0x95b6f607845baef3);
        // The category is no part of a vector's identity.
        if let Vector::Op(op) = &mut v {
            op.category = "another-category".into();
        }
        assert_eq!(identity_hash(&v), 0x95b6f607845baef3);
    }

    #[test]
    fn shard_syntax() {
        assert_eq!("0/4".parse::<Shard>(), Ok(Shard { index: 0, count: 4 }));
        assert_eq!("3/4".parse::<Shard>().unwrap().to_string(), "3/4");
        for bad in ["4/4", "1/0", "1", "a/b", "-1/3"] {
            let e = bad.parse::<Shard>().unwrap_err();
            assert!(e.contains("counts from 0"), "{bad}: {e}");
        }
    }
}
