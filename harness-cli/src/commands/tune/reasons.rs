//! Why a site cannot be tuned: at the pixel that forbids it, the untuned
//! and tuned answers, the first branch decision where the two runs part,
//! and the tuned pixel explained against ref-f64 as `harness explain` does
//! (class, changed decision, root-cause operation).

use super::evaluate::Evaluator;
use super::space::Config;
use common::Outcome;
use harness::explain::Explainer;
use reference::{Decided, ScenePixel};
use serde::Serialize;

/// A pixel that forbids a configuration, explained.
#[derive(Clone, Debug, Serialize)]
pub struct Forbidding {
    pub x: u32,
    pub y: u32,
    /// The pixel untuned and tuned: level and shade, or how it stopped.
    pub untuned: String,
    pub tuned: String,
    /// The first decision where the tuned run parts from the untuned one.
    pub changed_decision: Option<String>,
    /// The tuned pixel against ref-f64, in one line.
    pub explanation: String,
}

fn answer(p: &Outcome<ScenePixel>) -> String {
    match p {
        Outcome::Value(p) => format!("level {}, shade {}", p.level, p.value.value),
        other => format!("{:?}", other.kind()),
    }
}

fn side(d: &Decided) -> String {
    let taken = if d.taken { "taken" } else { "not taken" };
    format!("{taken} on [{}, {}]", d.operands[0], d.operands[1])
}

/// The first decision where `tuned` parts from `base`, in words.
fn first_change(base: &[Decided], tuned: &[Decided]) -> Option<String> {
    for (i, (b, t)) in base.iter().zip(tuned).enumerate() {
        if b.decision != t.decision {
            return Some(format!(
                "decision {i}: the untuned run decides {} where the tuned one decides {}",
                b.decision.name(),
                t.decision.name()
            ));
        }
        if b.taken != t.taken {
            return Some(format!(
                "{} (decision {i}): untuned {}, tuned {}",
                b.decision.name(),
                side(b),
                side(t)
            ));
        }
    }
    let n = base.len().min(tuned.len());
    match base.len().cmp(&tuned.len()) {
        std::cmp::Ordering::Equal => None,
        std::cmp::Ordering::Greater => Some(format!(
            "the runs agree on {n} decisions, then the tuned run ends where the untuned one \
             goes on ({} first)",
            base[n].decision.name()
        )),
        std::cmp::Ordering::Less => Some(format!(
            "the runs agree on {n} decisions, then the tuned run goes on ({} first) where the \
             untuned one ends",
            tuned[n].decision.name()
        )),
    }
}

/// Pixel (x, y) of `config` against the untuned scene.
pub fn forbidding(
    evaluator: &Evaluator,
    config: &Config,
    (x, y): (u32, u32),
) -> anyhow::Result<Forbidding> {
    let untuned = evaluator.base().0.decided_pixel(x, y);
    let tuned = evaluator.reference(config)?.decided_pixel(x, y);
    let explainer = Explainer::for_scene("ref-f316", &evaluator.checked(config)?)?;
    Ok(Forbidding {
        x,
        y,
        untuned: answer(&untuned.0),
        tuned: answer(&tuned.0),
        changed_decision: first_change(&untuned.1, &tuned.1),
        explanation: explainer.pixel(x as usize, y as usize).one_line(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use reference::Decision;

    fn d(decision: Decision, taken: bool) -> Decided {
        Decided {
            decision,
            taken,
            operands: [0.5, 0.25],
        }
    }

    #[test]
    fn the_first_change_is_a_side_a_decision_or_an_end() {
        let base = [d(Decision::MarchHit, false), d(Decision::MarchHit, true)];
        assert_eq!(first_change(&base, &base), None);
        let flipped = [d(Decision::MarchHit, false), d(Decision::MarchHit, false)];
        assert_eq!(
            first_change(&base, &flipped).unwrap(),
            "march-hit (decision 1): untuned taken on [0.5, 0.25], tuned not taken on [0.5, 0.25]"
        );
        let other = [d(Decision::MarchHit, false), d(Decision::MarchFar, true)];
        assert!(first_change(&base, &other)
            .unwrap()
            .contains("decides march-far"));
        let short = [d(Decision::MarchHit, false)];
        assert!(first_change(&base, &short)
            .unwrap()
            .contains("tuned run ends where the untuned one goes on (march-hit first)"));
    }
}
