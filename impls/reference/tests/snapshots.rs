//! Snapshots: Float316 operation results on a fixed operand table, and a
//! digest of each implementation's image of the seed scene.

use common::{Op, F316};
use reference::{op, Arith, RefImpl, Reference};
use std::fmt::Write;

/// Operands that exercise signs, zeros, the non-canonical sqrt(0), carries,
/// cancellation and the domain limits.
fn operands() -> Vec<F316> {
    let mut v: Vec<F316> = [
        1.0, -1.0, 1.5, 0.5, 12.0, -25.75, 0.01, 0.835, 0.167, 124.0, 16383.5,
    ]
    .iter()
    .map(|&x| F316::from_f64_truncating(x).unwrap())
    .collect();
    v.extend([
        F316::ZERO,
        F316::NEG_ZERO,
        F316::new(0, 61, 0),
        F316::new(0, 127, 8193),
        F316::new(1, 127, 16383),
        F316::new(0, 141, 8192),
    ]);
    v
}

#[test]
fn op_table() {
    let xs = operands();
    let mut out = String::new();
    for o in Op::ALL {
        if o.arity() == 1 {
            for &a in &xs {
                let r = op(o, &[a], Arith::default()).unwrap();
                writeln!(out, "{o}({a:?}) = {r}").unwrap();
            }
        } else {
            for &a in &xs {
                for &b in &xs {
                    let r = op(o, &[a, b], Arith::default()).unwrap();
                    writeln!(out, "{o}({a:?}, {b:?}) = {r}").unwrap();
                }
            }
        }
    }
    insta::assert_snapshot!(out);
}

/// FNV-1a over the 8-bit samples.
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}

#[test]
fn image_digests() {
    let images = RefImpl::ALL.map(|imp| Reference::seed(imp).render().gray8());
    let f316 = &images[0];
    let mut out = String::new();
    for (imp, g) in RefImpl::ALL.iter().zip(&images) {
        let white = g.iter().filter(|&&s| s == 255).count();
        let differ = g.iter().zip(f316).filter(|(a, b)| a != b).count();
        writeln!(
            out,
            "{imp}: white {white}, fnv1a {:016x}, differs from ref-f316 in {differ} pixels",
            fnv1a(g)
        )
        .unwrap();
    }
    insta::assert_snapshot!(out);
}
