//! `gpu-f316` against `ref-f316`, bit for bit: generated operand tables
//! (random values and a catalogue of hard cases) for every operation, and
//! scene queries at generated points.

use crate::support::{gpu, paired};
use common::{Op, SplitMix64, F316};
use reference::{Arith, RefImpl, Reference};

/// Values that exercise the edges of every algorithm: signed zeros,
/// non-canonical zeros, mantissa bounds, exponent bounds and words that are
/// not normalised at all.
fn hard_values() -> Vec<F316> {
    let mut v = Vec::new();
    for s in [0, 1] {
        for (e, m) in [
            (0, 0),
            (61, 0),
            (200, 0),
            (127, 8192),
            (127, 8193),
            (127, 12288),
            (127, 16383),
            (126, 16383),
            (128, 8192),
            (140, 8192),
            (141, 8192),
            (140, 16383),
            (120, 10485),
            (0, 8192),
            (1, 8192),
            (255, 16383),
            (32767, 8192),
            (-32768, 8192),
            (-5, 9000),
            (127, 16384),
            (127, -1),
            (127, 4096),
            (127, 1),
        ] {
            v.push(F316::new(s, e, m));
        }
    }
    v
}

fn random_value(rng: &mut SplitMix64) -> F316 {
    F316::new(
        rng.below(2) as i16,
        100 + rng.below(61) as i16,
        8192 + rng.below(8192) as i16,
    )
}

/// Operand pairs for a binary op: every pair of hard values, random pairs,
/// and near-cancelling pairs (same magnitude give or take a few units).
fn pairs(rng: &mut SplitMix64, random: usize) -> Vec<(F316, F316)> {
    let hard = hard_values();
    let mut out: Vec<(F316, F316)> = hard
        .iter()
        .flat_map(|&a| hard.iter().map(move |&b| (a, b)))
        .collect();
    for _ in 0..random {
        let a = random_value(rng);
        out.push((a, random_value(rng)));
        let near = F316::new(
            1 - a.s,
            a.e - rng.below(2) as i16,
            (a.m as i32 + rng.below(5) as i32 - 2).clamp(8192, 16383) as i16,
        );
        out.push((a, near));
    }
    out
}

#[test]
fn every_op_matches_the_reference_bit_for_bit() {
    let Some(gpu) = gpu() else { return };
    let mut rng = SplitMix64::new(316);
    let mut cases = Vec::new();
    for op in Op::ALL {
        for (a, b) in pairs(&mut rng, 1500) {
            cases.push((op, a, b));
        }
    }
    let got = gpu.f316_ops(&cases).expect("ops kernel runs");
    let mut mismatches = Vec::new();
    for (&(op, a, b), got) in paired("ops", &cases, &got) {
        let args: &[F316] = if op.arity() == 2 { &[a, b] } else { &[a] };
        let want = reference::op(op, args, Arith::default()).expect("arity");
        if *got != want {
            mismatches.push(format!("{op}{args:?}: gpu {got:?}, ref {want:?}"));
        }
    }
    assert!(
        mismatches.is_empty(),
        "{} of {} cases differ:\n{}",
        mismatches.len(),
        cases.len(),
        mismatches[..mismatches.len().min(20)].join("\n")
    );
}

/// Points near and away from the objects, and far enough out that floor
/// leaves its domain.
fn points(rng: &mut SplitMix64, n: usize) -> Vec<[F316; 3]> {
    let coord = |rng: &mut SplitMix64, scale: f64| {
        let x = (rng.unit() * 2.0 - 1.0) * scale;
        F316::from_f64_truncating(x).expect("encodable")
    };
    let mut out: Vec<[F316; 3]> = (0..n)
        .map(|i| {
            let scale = [0.5, 2.0, 4.0, 12.0][i % 4];
            [coord(rng, scale), coord(rng, scale), coord(rng, scale)]
        })
        .collect();
    let big = F316::new(0, 141, 8192);
    out.extend([
        [F316::ZERO; 3],
        [F316::NEG_ZERO; 3],
        [big, F316::ZERO, F316::ZERO],
        [F316::ZERO, F316::ZERO, big.negated()],
        [F316::new(1, 127, 12288), F316::ZERO, F316::ZERO],
        [F316::new(0, 127, 12288), F316::ZERO, F316::ZERO],
    ]);
    out
}

#[test]
fn scene_matches_the_reference_bit_for_bit() {
    let Some(gpu) = gpu() else { return };
    let points = points(&mut SplitMix64::new(1316), 3000);
    let got = gpu.f316_sdf(&points).expect("sdf kernel runs");
    let reference = Reference::seed(RefImpl::F316);
    let mut mismatches = Vec::new();
    for (p, got) in paired("sdf", &points, &got) {
        let want = reference
            .sdf(*p)
            .map(|s| (s.sd.triple.expect("triple"), s.col.triple.expect("triple")));
        if *got != want {
            mismatches.push(format!("{p:?}: gpu {got:?}, ref {want:?}"));
        }
    }
    assert!(
        mismatches.is_empty(),
        "{} of {} points differ:\n{}",
        mismatches.len(),
        points.len(),
        mismatches[..mismatches.len().min(20)].join("\n")
    );
}
