//! Call sites: the statements of a Float316 program whose operation has a
//! variant ([`Tuning`]), each named by its frame path as the op traces name
//! it, and the pass that wraps the chosen ones in [`Stmt::Tuned`].
//!
//! A site's name is the function (`setup`, `sdf`, `pixel`), the enclosing
//! frames and named loops (a loop without its iteration number), and the
//! operation (`sqrt`, `length`, `normalize`), joined by `/`:
//! `pixel/shadow/normalize`, `sdf/scene/ball/length`. The second and later
//! sites of one path get `#2`, `#3`, ... in the order the lowering writes
//! them (`pixel/light/normalize#2`). Names depend only on the description's
//! structure, so a site keeps its name when another site is tuned.

use crate::ir::{Program, Stmt, Tuning, Unary, VecOp};
use std::collections::{BTreeMap, HashMap};

/// The operation of a statement that has a variant: `sqrt`, `length` or
/// `normalize`; `None` for any other statement.
pub fn op_of(s: &Stmt) -> Option<&'static str> {
    match s {
        Stmt::Unary {
            op: Unary::Sqrt, ..
        } => Some("sqrt"),
        Stmt::Length { .. } => Some("length"),
        Stmt::Vector {
            op: VecOp::Normalize,
            ..
        } => Some("normalize"),
        _ => None,
    }
}

/// Every site of `p`, in the order of its functions and statements.
pub fn sites(p: &Program) -> Vec<String> {
    let mut out = Vec::new();
    let mut q = p.clone();
    rewrite(&mut q, |name| {
        out.push(name.to_string());
        None
    });
    out
}

/// `p` with each site of `chosen` wrapped in [`Stmt::Tuned`] with its
/// variant. Names that are not sites of `p` are left out (the checker
/// refuses them first).
pub fn tune(p: &mut Program, chosen: &BTreeMap<String, Tuning>) {
    if !chosen.is_empty() {
        rewrite(p, |name| chosen.get(name).copied());
    }
}

/// Visit every site of `p` by name; wrap it when `pick` gives a variant.
fn rewrite(p: &mut Program, mut pick: impl FnMut(&str) -> Option<Tuning>) {
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

impl<F: FnMut(&str) -> Option<Tuning>> Walk<'_, F> {
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
        if let Some(op) = op_of(&s) {
            let path = format!("{}/{op}", self.path.join("/"));
            let n = self.seen.entry(path.clone()).or_insert(0);
            *n += 1;
            let name = if *n == 1 { path } else { format!("{path}#{n}") };
            return match (self.pick)(&name) {
                Some(variant) => Stmt::Tuned {
                    variant,
                    body: vec![s],
                },
                None => s,
            };
        }
        match s {
            Stmt::Frame { name, body } => {
                let body = self.nested(Some(&name), body);
                Stmt::Frame { name, body }
            }
            Stmt::Loop { count, name, body } => {
                let body = self.nested(name.as_deref(), body);
                Stmt::Loop { count, name, body }
            }
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
        let names = sites(&crate::lower(&seed, Formulation::Float316));
        for expected in [
            "setup/camera/normalize",
            "pixel/normalize",
            "pixel/normal/normalize",
            "pixel/light/normalize",
            "pixel/light/normalize#2",
            "pixel/shadow/normalize",
            "pixel/shadow/length",
        ] {
            assert!(names.iter().any(|n| n == expected), "{expected}: {names:?}");
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
            e.starts_with("variants[0].variant: unknown variant `newton-7`, expected `newton-1`"),
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
