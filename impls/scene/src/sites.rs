//! Call sites: the statements of a Float316 program that have a variant,
//! each named by its frame path as the op traces name it, and the pass that
//! applies a description's chosen variants.
//!
//! Two kinds of site: an operation with a [`Tuning`] (`sqrt`, `length`,
//! `normalize`, `mul`, `floor`: wrapped in [`Stmt::Tuned`]) and a named
//! loop (the march steps: its count lowered). A site's name is the function (`setup`,
//! `sdf`, `pixel`), the enclosing frames and named loops (a loop without
//! its iteration number), and the operation or the loop's name, joined by
//! `/`: `pixel/shadow/normalize`, `sdf/scene/ball/length`,
//! `pixel/shadow/shadow march step`. The second and later sites of one path
//! get `#2`, `#3`, ... in the order the lowering writes them
//! (`pixel/light/normalize#2`). Names depend only on the description's
//! structure, so a site keeps its name when another site is tuned.

use crate::ir::{Binary, Program, Stmt, Tuning, Unary, VecOp};
use serde::{Deserialize, Serialize};
use std::collections::{BTreeMap, HashMap};

/// A variant a description chooses for one site (`variants[i].variant`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub enum Choice {
    /// `"newton-1"`: an operation site with one Newton step.
    #[serde(rename = "newton-1")]
    Newton1,
    /// `"truncated-product"`: a `mul` site with the high halves' product.
    #[serde(rename = "truncated-product")]
    TruncatedProduct,
    /// `"floor-direct"`: a `floor` site without the nested `add`.
    #[serde(rename = "floor-direct")]
    FloorDirect,
    /// `{"steps": n}`: a loop site run at most `n` times (at most its
    /// description's count).
    #[serde(rename = "steps")]
    Steps(u32),
}

impl Choice {
    /// The operation variant this choice is; `None` for a step count.
    pub const fn tuning(self) -> Option<Tuning> {
        match self {
            Choice::Newton1 => Some(Tuning::Newton1),
            Choice::TruncatedProduct => Some(Tuning::TruncatedProduct),
            Choice::FloorDirect => Some(Tuning::FloorDirect),
            Choice::Steps(_) => None,
        }
    }
}

impl From<Tuning> for Choice {
    fn from(t: Tuning) -> Self {
        match t {
            Tuning::Newton1 => Choice::Newton1,
            Tuning::TruncatedProduct => Choice::TruncatedProduct,
            Tuning::FloorDirect => Choice::FloorDirect,
        }
    }
}

impl std::fmt::Display for Choice {
    /// `newton-1`, `16 steps`, `1 step`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match (self, self.tuning()) {
            (_, Some(t)) => f.write_str(t.name()),
            (Choice::Steps(1), _) => f.write_str("1 step"),
            (Choice::Steps(n), _) => write!(f, "{n} steps"),
            (_, None) => unreachable!("every other choice is a tuning"),
        }
    }
}

/// What a site is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// An operation that takes this [`Tuning`] (`newton-1` for `sqrt`,
    /// `length` and `normalize`, `truncated-product` for `mul`,
    /// `floor-direct` for `floor`).
    Op(Tuning),
    /// A named loop of at most this many iterations.
    Loop(u32),
}

/// The operation of a statement that has a variant (`sqrt`, `length`,
/// `normalize`, `mul`, `floor`) and the variant it takes; `None` for any
/// other statement.
pub fn op_of(s: &Stmt) -> Option<(&'static str, Tuning)> {
    match s {
        Stmt::Unary {
            op: Unary::Sqrt, ..
        } => Some(("sqrt", Tuning::Newton1)),
        Stmt::Length { .. } => Some(("length", Tuning::Newton1)),
        Stmt::Vector {
            op: VecOp::Normalize,
            ..
        } => Some(("normalize", Tuning::Newton1)),
        Stmt::Binary {
            op: Binary::Mul, ..
        } => Some(("mul", Tuning::TruncatedProduct)),
        Stmt::Unary {
            op: Unary::Floor, ..
        } => Some(("floor", Tuning::FloorDirect)),
        _ => None,
    }
}

/// Every site of `p` with its kind, in the order of its functions and
/// statements.
pub fn sites(p: &Program) -> Vec<(String, Kind)> {
    let mut out = Vec::new();
    let mut q = p.clone();
    rewrite(&mut q, |name, kind| {
        out.push((name.to_string(), kind));
        None
    });
    out
}

/// `p` with each site of `chosen` given its variant. Names that are not
/// sites of `p`, and choices that do not fit their site's kind, are left
/// out (the checker refuses them first).
pub fn tune(p: &mut Program, chosen: &BTreeMap<String, Choice>) {
    if !chosen.is_empty() {
        rewrite(p, |name, _| chosen.get(name).copied());
    }
}

/// Visit every site of `p` by name; apply what `pick` chooses.
fn rewrite(p: &mut Program, mut pick: impl FnMut(&str, Kind) -> Option<Choice>) {
    for f in &mut p.functions {
        let mut walk = Walk {
            path: vec![f.name.clone()],
            seen: HashMap::new(),
            pick: &mut pick,
        };
        f.body = walk.block(std::mem::take(&mut f.body));
    }
}

struct Walk<'a, F> {
    path: Vec<String>,
    seen: HashMap<String, u32>,
    pick: &'a mut F,
}

impl<F: FnMut(&str, Kind) -> Option<Choice>> Walk<'_, F> {
    /// The name of the next site called `last` at the current path.
    fn name(&mut self, last: &str) -> String {
        let path = format!("{}/{last}", self.path.join("/"));
        let n = self.seen.entry(path.clone()).or_insert(0);
        *n += 1;
        if *n == 1 {
            path
        } else {
            format!("{path}#{n}")
        }
    }

    fn nested(&mut self, name: Option<&str>, body: Vec<Stmt>) -> Vec<Stmt> {
        if let Some(n) = name {
            self.path.push(n.to_string());
        }
        let out = self.block(body);
        if name.is_some() {
            self.path.pop();
        }
        out
    }

    fn block(&mut self, block: Vec<Stmt>) -> Vec<Stmt> {
        block.into_iter().map(|s| self.stmt(s)).collect()
    }

    fn stmt(&mut self, s: Stmt) -> Stmt {
        if let Some((op, takes)) = op_of(&s) {
            let name = self.name(op);
            return match (self.pick)(&name, Kind::Op(takes)).and_then(Choice::tuning) {
                Some(variant) if variant == takes => Stmt::Tuned {
                    variant,
                    body: vec![s],
                },
                _ => s,
            };
        }
        match s {
            Stmt::Frame { name, body } => {
                let body = self.nested(Some(&name), body);
                Stmt::Frame { name, body }
            }
            Stmt::Loop {
                mut count,
                name: Some(name),
                body,
            } => {
                let site = self.name(&name);
                if let Some(Choice::Steps(n)) = (self.pick)(&site, Kind::Loop(count)) {
                    count = count.min(n);
                }
                let body = self.nested(Some(&name), body);
                Stmt::Loop {
                    count,
                    name: Some(name),
                    body,
                }
            }
            Stmt::Loop {
                count,
                name: None,
                body,
            } => Stmt::Loop {
                count,
                name: None,
                body: self.block(body),
            },
            Stmt::If {
                cond,
                then,
                otherwise,
            } => Stmt::If {
                cond,
                then: self.block(then),
                otherwise: self.block(otherwise),
            },
            Stmt::Switch { tag, cases } => Stmt::Switch {
                tag,
                cases: cases.into_iter().map(|c| self.block(c)).collect(),
            },
            Stmt::Tuned { variant, body } => Stmt::Tuned {
                variant,
                body: self.block(body),
            },
            other => other,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ir::Formulation;

    fn seed_with(variants: &str) -> Result<crate::Checked, crate::SceneError> {
        let mut v: serde_json::Value = serde_json::from_str(crate::SEED).unwrap();
        v["variants"] = serde_json::from_str(variants).unwrap();
        crate::parse(&v.to_string())
    }

    #[test]
    fn the_seed_sites_are_named_by_their_frame_paths_once_each() {
        let seed = crate::parse(crate::SEED).unwrap();
        let all = sites(&crate::lower(&seed, Formulation::Float316));
        let names: Vec<&str> = all.iter().map(|(n, _)| n.as_str()).collect();
        assert!(all.contains(&("pixel/march step".to_string(), Kind::Loop(64))));
        assert!(all.contains(&("pixel/shadow/shadow march step".to_string(), Kind::Loop(32))));
        for expected in [
            "setup/camera/normalize",
            "pixel/normalize",
            "pixel/normal/normalize",
            "pixel/light/normalize",
            "pixel/light/normalize#2",
            "pixel/shadow/normalize",
            "pixel/shadow/length",
        ] {
            assert!(names.contains(&expected), "{expected}: {names:?}");
        }
        let mut unique = names.clone();
        unique.sort();
        unique.dedup();
        assert_eq!(unique.len(), names.len(), "{names:?}");
    }

    #[test]
    fn a_tuned_site_is_one_tuned_statement_and_the_rest_is_unchanged() {
        let seed = crate::parse(crate::SEED).unwrap();
        let plain = crate::lower(&seed, Formulation::Float316);
        let tuned =
            seed_with(r#"[{"site": "pixel/shadow/normalize", "variant": "newton-1"}]"#).unwrap();
        let t = crate::lower(&tuned, Formulation::Float316);
        t.validate().unwrap();
        let wrapped: Vec<_> = t
            .statements()
            .into_iter()
            .filter(|s| matches!(s, Stmt::Tuned { .. }))
            .collect();
        assert_eq!(wrapped.len(), 1);
        assert_ne!(t, plain);
        assert_eq!(sites(&t), sites(&plain));
        // The float programs carry no variants.
        assert_eq!(
            crate::lower(&tuned, Formulation::Ieee),
            crate::lower(&seed, Formulation::Ieee)
        );
        assert!(!crate::is_seed(&tuned));
    }

    #[test]
    fn fewer_steps_lower_the_named_loops_count_only() {
        let seed = crate::parse(crate::SEED).unwrap();
        let plain = crate::lower(&seed, Formulation::Float316);
        let tuned =
            seed_with(r#"[{"site": "pixel/shadow/shadow march step", "variant": {"steps": 12}}]"#)
                .unwrap();
        let t = crate::lower(&tuned, Formulation::Float316);
        let counts = |p: &Program| -> Vec<u32> {
            p.statements()
                .into_iter()
                .filter_map(|s| match s {
                    Stmt::Loop { count, .. } => Some(*count),
                    _ => None,
                })
                .collect()
        };
        assert_eq!(counts(&plain), [64, 32]);
        assert_eq!(counts(&t), [64, 12]);
        assert_eq!(
            sites(&t),
            sites(&plain)
                .into_iter()
                .map(|(n, k)| match k {
                    Kind::Loop(32) => (n, Kind::Loop(12)),
                    other => (n, other),
                })
                .collect::<Vec<_>>()
        );
    }

    #[test]
    fn products_and_floors_are_sites_that_take_their_own_variants() {
        let seed = crate::parse(crate::SEED).unwrap();
        let all = sites(&crate::lower(&seed, Formulation::Float316));
        let kind = |name: &str| all.iter().find(|(n, _)| n == name).map(|(_, k)| *k);
        assert_eq!(
            kind("sdf/scene/floor/floor"),
            Some(Kind::Op(Tuning::FloorDirect))
        );
        assert_eq!(
            kind("sdf/scene/floor/floor#2"),
            Some(Kind::Op(Tuning::FloorDirect))
        );
        assert!(
            all.iter().any(|(n, k)| n.starts_with("pixel/light/mul")
                && *k == Kind::Op(Tuning::TruncatedProduct)),
            "{all:?}"
        );
        let tuned = seed_with(
            r#"[{"site": "sdf/scene/floor/floor", "variant": "floor-direct"},
                {"site": "pixel/light/mul", "variant": "truncated-product"}]"#,
        )
        .unwrap();
        let t = crate::lower(&tuned, Formulation::Float316);
        let variants: Vec<Tuning> = t
            .statements()
            .into_iter()
            .filter_map(|s| match s {
                Stmt::Tuned { variant, .. } => Some(*variant),
                _ => None,
            })
            .collect();
        assert_eq!(
            variants,
            [Tuning::FloorDirect, Tuning::TruncatedProduct],
            "in the order of the program"
        );
        let e = seed_with(r#"[{"site": "pixel/light/mul", "variant": "newton-1"}]"#)
            .unwrap_err()
            .to_string();
        assert_eq!(
            e,
            "variants[0].variant: `pixel/light/mul` takes `truncated-product`, not `newton-1`"
        );
        let e = seed_with(r#"[{"site": "pixel/normalize", "variant": "floor-direct"}]"#)
            .unwrap_err()
            .to_string();
        assert_eq!(
            e,
            "variants[0].variant: `pixel/normalize` takes `newton-1`, not `floor-direct`"
        );
    }

    #[test]
    fn a_choice_is_written_as_a_description_reads_it() {
        for (choice, text) in [
            (Choice::Newton1, r#""newton-1""#),
            (Choice::TruncatedProduct, r#""truncated-product""#),
            (Choice::FloorDirect, r#""floor-direct""#),
            (Choice::Steps(16), r#"{"steps":16}"#),
        ] {
            assert_eq!(serde_json::to_string(&choice).unwrap(), text);
            assert_eq!(serde_json::from_str::<Choice>(text).unwrap(), choice);
        }
        assert_eq!(Choice::Steps(16).to_string(), "16 steps");
        assert_eq!(Choice::Steps(1).to_string(), "1 step");
        assert_eq!(Choice::Newton1.to_string(), "newton-1");
    }

    #[test]
    fn a_variant_must_fit_its_site() {
        let e = seed_with(r#"[{"site": "pixel/march step", "variant": {"steps": 65}}]"#)
            .unwrap_err()
            .to_string();
        assert_eq!(e, "variants[0].variant: 65 is outside 1..=64");
        let e = seed_with(r#"[{"site": "pixel/march step", "variant": "newton-1"}]"#)
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("variants[0].variant: `pixel/march step` is a loop"),
            "{e}"
        );
        let e = seed_with(r#"[{"site": "pixel/normalize", "variant": {"steps": 3}}]"#)
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("variants[0].variant: `pixel/normalize` is an operation"),
            "{e}"
        );
    }

    #[test]
    fn an_unknown_site_or_variant_or_a_site_twice_is_refused_naming_the_field() {
        let e = seed_with(r#"[{"site": "pixel/nowhere/sqrt", "variant": "newton-1"}]"#)
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("variants[0].site: no call site `pixel/nowhere/sqrt`"),
            "{e}"
        );
        assert!(e.contains("pixel/shadow/normalize"), "{e}");
        let e = seed_with(r#"[{"site": "pixel/normalize", "variant": "newton-7"}]"#)
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with(
                "variants[0].variant: unknown variant `newton-7`, expected one of `newton-1`, \
                 `truncated-product`, `floor-direct`, `steps`"
            ),
            "{e}"
        );
        let twice = r#"[{"site": "pixel/normalize", "variant": "newton-1"},
                       {"site": "pixel/normalize", "variant": "newton-1"}]"#;
        let e = seed_with(twice).unwrap_err().to_string();
        assert!(
            e.starts_with("variants[1].site: site `pixel/normalize` is listed twice"),
            "{e}"
        );
    }
}
