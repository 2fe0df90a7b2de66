//! The numerical-stability rows of a report: for every category of a
//! vector set (the hard-case catalogue of the op vectors, the scene's hard
//! places of the SDF and pixel sets), how each implementation's answers
//! ended (value, `Sys.error`, hang, out of domain), how many differ from
//! the tracer (`ref-f316`) bit for bit, and the worst error against the
//! oracle (`ref-f64`).
//! Built from answers and comparisons the runner already produced: nothing
//! is evaluated here.

use crate::model::{OutcomeTally, StabilityRow, WorstError};
use common::{Outcome, OutcomeKind};
use harness::compare::{answer_error, Comparison, PointError, Policy};
use harness::implementation::{Answer, Numbers};
use harness::runner::ImplRun;
use std::collections::BTreeMap;
use vectors::{Level, Vector, VectorSet};

/// Whom the rows measure against.
#[derive(Clone, Copy, Debug)]
pub struct Bases<'a> {
    /// The f64 oracle of the worst errors.
    pub oracle: &'a str,
    /// The implementation bit-exact divergences are counted against.
    pub bit_exact: &'a str,
}

/// The categories of a set, in order of first appearance.
fn categories(set: &VectorSet) -> Vec<&str> {
    let mut seen: Vec<&str> = Vec::new();
    for v in &set.vectors {
        if !seen.contains(&v.category()) {
            seen.push(v.category());
        }
    }
    seen
}

/// Vectors of `category` on which `label` differs from `base`, from the
/// bit-exact comparisons of the runner (their groups count every
/// divergence, kept or not).
fn diverging(base: &str, label: &str, category: &str, exact: &[Comparison]) -> Option<u64> {
    if label == base {
        return Some(0);
    }
    exact
        .iter()
        .find(|c| {
            c.policy == Policy::Exact
                && ((c.a == base && c.b == label) || (c.b == base && c.a == label))
        })
        .map(|c| {
            c.groups
                .iter()
                .filter(|g| g.category == category && !g.tolerated)
                .map(|g| g.count as u64)
                .sum()
        })
}

fn tally<'a>(answers: impl Iterator<Item = &'a Outcome<Answer>>) -> OutcomeTally {
    let mut t = OutcomeTally::default();
    for a in answers {
        match a.kind() {
            OutcomeKind::Value => t.value += 1,
            OutcomeKind::SysError => t.sys_error += 1,
            OutcomeKind::Hang => t.hang += 1,
            OutcomeKind::OutOfDomain => t.out_of_domain += 1,
        }
    }
    t
}

/// The stability rows of one set. `runs` are every implementation's
/// answers to `set` (those without answers are left out: the runner's
/// report lists them); `exact` are the runner's comparisons of the Float316
/// group with `bases.bit_exact`; `repro(implementation, vector)` gives a command
/// that reproduces a worst error. Sets of the image level have no
/// categories to speak of and give no rows.
pub fn rows(
    set: &VectorSet,
    runs: &[ImplRun],
    exact: &[Comparison],
    bases: Bases<'_>,
    mut repro: impl FnMut(&str, &Vector) -> Option<String>,
) -> Vec<StabilityRow> {
    let oracle_label = bases.oracle;
    if set.level == Level::Image {
        return Vec::new();
    }
    let answered: Vec<(&ImplRun, &Vec<Outcome<Answer>>)> = runs
        .iter()
        .filter_map(|r| r.answers.as_ref().ok().map(|a| (r, a)))
        .filter(|(_, a)| a.len() == set.vectors.len())
        .collect();
    let oracle = answered
        .iter()
        .find(|(r, _)| r.label == oracle_label && r.numbers == Numbers::F64)
        .map(|(_, a)| *a);
    categories(set)
        .into_iter()
        .map(|category| {
            let indices: Vec<usize> = (0..set.vectors.len())
                .filter(|&i| set.vectors[i].category() == category)
                .collect();
            let mut outcomes = BTreeMap::new();
            // (error, index in `answered`, vector index)
            let mut worst: Option<(PointError, usize, usize)> = None;
            for (k, (run, answers)) in answered.iter().enumerate() {
                let mut t = tally(indices.iter().map(|&i| &answers[i]));
                t.diverging = match run.numbers {
                    Numbers::Float316 => diverging(bases.bit_exact, &run.label, category, exact),
                    Numbers::F64 | Numbers::F32 | Numbers::Ieee { .. } => None,
                };
                outcomes.insert(run.label.clone(), t);
                let Some(oracle) = oracle.filter(|_| run.label != oracle_label) else {
                    continue;
                };
                for &i in &indices {
                    let (Outcome::Value(s), Outcome::Value(o)) = (&answers[i], &oracle[i]) else {
                        continue;
                    };
                    let Some(e) = answer_error(s, o, run.numbers) else {
                        continue;
                    };
                    let better = worst.is_none_or(|(w, ..)| {
                        e.rel
                            .total_cmp(&w.rel)
                            .then(e.abs.total_cmp(&w.abs))
                            .is_gt()
                    });
                    if better {
                        worst = Some((e, k, i));
                    }
                }
            }
            let worst = worst.map(|(e, k, i)| {
                let (run, answers) = answered[k];
                let vector = &set.vectors[i];
                let oracle_answer = oracle.map_or_else(String::new, |o| o[i].to_string());
                WorstError {
                    implementation: run.label.clone(),
                    case: vector.to_string(),
                    vector: format!("{} #{i}", set.name),
                    answers: format!("{} vs {oracle_label} {oracle_answer}", answers[i]),
                    abs: e.abs,
                    rel: e.rel,
                    repro: repro(&run.label, vector),
                }
            });
            StabilityRow {
                set: set.name.clone(),
                category: category.to_string(),
                vectors: indices.len() as u64,
                outcomes,
                worst,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use common::{Op, F316};
    use harness::implementation::Num;
    use harness::runner::compare_runs;
    use vectors::OpVector;

    fn op(category: &str, a: F316, b: F316) -> Vector {
        Vector::Op(OpVector {
            category: category.into(),
            op: Op::Div,
            a,
            b: Some(b),
        })
    }

    fn run(label: &str, numbers: Numbers, answers: Vec<Outcome<Answer>>) -> ImplRun {
        ImplRun {
            label: label.into(),
            numbers,
            answers: Ok(answers),
            seconds: 0.0,
            checks_domain: true,
            levels: vectors::Level::ALL.to_vec(),
        }
    }

    fn num(n: Num) -> Outcome<Answer> {
        Outcome::Value(Answer::Num { value: n })
    }

    #[test]
    fn tallies_outcomes_divergences_and_the_worst_error_per_category() {
        let one = F316::ONE;
        let two = F316::new(0, 128, 8192);
        let set = VectorSet::new(
            "hand-made",
            Level::Ops,
            "",
            None,
            vec![
                op("div-by-zero", one, F316::ZERO),
                op("plain", one, two),
                op("div-by-zero", two, F316::ZERO),
                op("plain", two, two),
                op("plain", two, one),
            ],
        );
        let half = F316::new(0, 126, 8192);
        let (f316, f64) = (|t| num(Num::F316(t)), |x| num(Num::F64(x)));
        let runs = vec![
            run(
                "ref-f316",
                Numbers::Float316,
                vec![
                    Outcome::SysError(1),
                    f316(half),
                    Outcome::SysError(1),
                    f316(one),
                    f316(two),
                ],
            ),
            run(
                "jack",
                Numbers::Float316,
                vec![
                    Outcome::SysError(1),
                    f316(half),
                    Outcome::Hang,
                    f316(one),
                    // One bit off: a divergence, and an error against f64.
                    f316(F316::new(0, 128, 8193)),
                ],
            ),
            run(
                "ref-f64",
                Numbers::F64,
                vec![
                    Outcome::OutOfDomain,
                    f64(0.5),
                    Outcome::OutOfDomain,
                    f64(1.0),
                    f64(2.0),
                ],
            ),
            run(
                "ref-f32",
                Numbers::F32,
                vec![
                    Outcome::OutOfDomain,
                    num(Num::F32(0.5)),
                    Outcome::OutOfDomain,
                    num(Num::F32(1.0)),
                    num(Num::F32(2.0)),
                ],
            ),
        ];
        let exact = compare_runs(&set, &runs[..2]);
        let mut reproduced = Vec::new();
        let bases = Bases {
            oracle: "ref-f64",
            bit_exact: "ref-f316",
        };
        let rows = rows(&set, &runs, &exact, bases, |imp, v| {
            reproduced.push((imp.to_string(), v.to_string()));
            Some(format!("repro {imp}"))
        });
        assert_eq!(rows.len(), 2);
        let (zero, plain) = (&rows[0], &rows[1]);
        assert_eq!((zero.category.as_str(), zero.vectors), ("div-by-zero", 2));
        assert_eq!((plain.category.as_str(), plain.vectors), ("plain", 3));
        assert_eq!(plain.set, "hand-made");
        let t = |row: &StabilityRow, imp: &str| row.outcomes[imp];
        let tally = |value, sys_error, hang, out_of_domain, diverging| OutcomeTally {
            value,
            sys_error,
            hang,
            out_of_domain,
            diverging,
        };
        assert_eq!(t(zero, "ref-f316"), tally(0, 2, 0, 0, Some(0)));
        assert_eq!(t(zero, "jack"), tally(0, 1, 1, 0, Some(1)));
        assert_eq!(t(zero, "ref-f64"), tally(0, 0, 0, 2, None));
        assert_eq!(t(zero, "ref-f32"), tally(0, 0, 0, 2, None));
        assert_eq!(t(plain, "jack"), tally(3, 0, 0, 0, Some(1)));
        assert_eq!(t(plain, "ref-f32"), tally(3, 0, 0, 0, None));
        // No answer of the category is a value on both sides.
        assert_eq!(zero.worst, None);
        let worst = plain.worst.as_ref().unwrap();
        assert_eq!(worst.implementation, "jack");
        assert_eq!(worst.vector, "hand-made #4");
        assert_eq!(worst.abs, 2.0 / 8192.0);
        assert_eq!(worst.rel, 1.0 / 8192.0);
        assert_eq!(worst.repro.as_deref(), Some("repro jack"));
        assert!(
            worst.answers.ends_with("vs ref-f64 2e0"),
            "{}",
            worst.answers
        );
        assert_eq!(
            reproduced,
            [("jack".to_string(), set.vectors[4].to_string())]
        );
    }
}
