//! Whether the per-operation instruction budget ([`Budgets::op`]) is exact:
//! every case that ends must end well inside it, so that running out of it
//! means a loop that never ends (a hang on every implementation), and a
//! hang costs the whole budget, so it should be no larger than that needs.
//!
//! Runs the nightly's operation sets (TestFloat level 2 of every operation,
//! every normalised input of each unary operation) and the costliest
//! finishing cases of any triple (the alignment shift of `add` and `sub`
//! at the largest exponent difference) with the default budget, and
//! prints per operation the hangs and the longest finishing case (the
//! nightly checks that every hang here is a hang of ref-f316, whose loops
//! are bounded).
//!
//! `cargo run --release -p jack --example op_budget`

use common::{Op, Outcome, F316};
use jack::{Budgets, Profile, Raymarcher};
use rayon::prelude::*;
use vectors::gen::ops::all_normalised;
use vectors::gen::testfloat::{cases, CaseLevel, DEFAULT_SEED};
use vectors::Vector;

/// The operands of a case of an operation set.
fn operands(v: &Vector) -> Vec<F316> {
    match v {
        Vector::Op(o) => std::iter::once(o.a).chain(o.b).collect(),
        _ => unreachable!("an operation set holds operation vectors"),
    }
}

/// (cases, hangs, longest finishing case and its operands) of `op` over
/// `inputs`.
fn costs(jack: &Raymarcher, op: Op, inputs: &[Vec<F316>]) -> (usize, usize, u64, Vec<F316>) {
    inputs
        .par_iter()
        .map(|args| {
            let c = jack.op(op, args).expect("the operation runs");
            match c.outcome {
                Outcome::Hang => (1, 1, 0, Vec::new()),
                _ => (1, 0, c.instructions, args.clone()),
            }
        })
        .reduce(
            || (0, 0, 0, Vec::new()),
            |a, b| {
                let longest = if a.2 >= b.2 { (a.2, a.3) } else { (b.2, b.3) };
                (a.0 + b.0, a.1 + b.1, longest.0, longest.1)
            },
        )
}

fn report(jack: &Raymarcher, what: &str, op: Op, inputs: &[Vec<F316>], budget: u64) {
    let (n, hangs, longest, args) = costs(jack, op, inputs);
    let args: Vec<String> = args.iter().map(|a| a.to_string()).collect();
    println!(
        "{what:<22} {op:<9} {n:>9} cases {hangs:>7} hangs  longest finishing {longest:>6} instructions ({:.1}% of the default budget {budget}) at {}",
        100.0 * longest as f64 / budget as f64,
        args.join(", ")
    );
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let budget = Budgets::default().op;
    let jack = Raymarcher::new(Profile::Desktop, Budgets::default())?;
    // The costliest cases first.
    for op in [Op::Add, Op::Sub] {
        let inputs: Vec<Vec<F316>> = gaps();
        report(&jack, "largest exponent gap", op, &inputs, budget);
    }
    for op in Op::ALL {
        let inputs: Vec<Vec<F316>> = cases(op, CaseLevel::Two, DEFAULT_SEED)
            .iter()
            .map(operands)
            .collect();
        report(&jack, "testfloat level 2", op, &inputs, budget);
    }
    for op in Op::UNARY {
        let inputs: Vec<Vec<F316>> = all_normalised(1).map(|a| vec![a]).collect();
        report(&jack, "every normalised input", op, &inputs, budget);
        report(&jack, "every exponent", op, &every_exponent(), budget);
    }
    Ok(())
}

/// Mantissa words: normalised ends, carry and detector bits, small and
/// negative words.
const MANTISSAS: [i16; 8] = [8192, 16383, 16384, 32767, 0, 1, -1, i16::MIN];

/// Every exponent a word holds, of both signs, with each of [`MANTISSAS`].
fn every_exponent() -> Vec<Vec<F316>> {
    (0..=1)
        .flat_map(|s| {
            (i16::MIN..=i16::MAX)
                .flat_map(move |e| MANTISSAS.into_iter().map(move |m| vec![F316::new(s, e, m)]))
        })
        .collect()
}

/// The alignment shift runs (e_big - e_small) / 14 times: the largest
/// differences a 16-bit exponent allows, on the mantissa patterns that
/// matter (normalised, carry and detector bits, negative words).
fn gaps() -> Vec<Vec<F316>> {
    [(i16::MAX, 0), (0, -i16::MAX), (i16::MAX, 1), (-1, i16::MIN)]
        .into_iter()
        .flat_map(|(big, small)| {
            MANTISSAS.into_iter().flat_map(move |mb| {
                MANTISSAS.into_iter().flat_map(move |ms| {
                    [(0, 0), (0, 1), (1, 0)]
                        .into_iter()
                        .map(move |(sa, sb)| vec![F316::new(sa, big, mb), F316::new(sb, small, ms)])
                })
            })
        })
        .collect()
}
