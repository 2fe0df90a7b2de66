//! The generated bindings.toml opens the generated program through the
//! `jack` crate's bindings machinery (the harness's path for a user's
//! program), and its operations, SDF and pixels agree with ref-f316.

mod support;

use common::{Op, Outcome, F316};
use reference::Arith;
use support::*;

#[test]
fn seed_through_its_bindings() {
    let j = emitted("seed");
    let b = bound(&j);
    let d = reference("seed");
    for (x, y) in [
        (0, 0),
        (100, 140),
        (256, 128),
        (330, 150),
        (400, 200),
        (511, 255),
    ] {
        let ours = b.pixel(x, y).expect("pixel runs").outcome;
        let Outcome::Value(p) = ours else {
            panic!("({x},{y}): {ours:?}")
        };
        let Outcome::Value(want) = d.pixel(x as u32, y as u32) else {
            panic!("the reference answers")
        };
        assert_eq!(Some(p.shade), want.value.triple, "({x},{y}) shade");
        assert_eq!(p.white, Some(want.level == 1), "({x},{y}) white");
    }
    for p in grid(3) {
        let ours = b.sdf(p).expect("sdf runs").outcome;
        let Outcome::Value(v) = d.sdf(p) else {
            panic!("the reference answers")
        };
        assert_eq!(
            ours,
            Outcome::Value((v.sd.triple.unwrap(), v.col.triple.unwrap()))
        );
    }
}

#[test]
fn the_bound_operations_are_the_reference_operations() {
    let b = bound(&emitted("seed"));
    let values = [
        F316::new(0, 127, 8192),
        F316::new(1, 128, 10240),
        F316::new(0, 131, 16383),
        F316::new(0, 120, 10485),
        F316::ZERO,
    ];
    for op in Op::ALL {
        assert!(b.has_op(op), "{op:?} is bound");
        for &a in &values {
            for &c in &values[..op.arity().max(1)] {
                let args = &[a, c][..op.arity()];
                let ours = b.op(op, args).expect("op runs").outcome;
                let want = reference::op(op, args, Arith::SPEC).expect("a reference op");
                assert_eq!(ours, want, "{op:?}{args:?}");
            }
        }
    }
}

#[test]
fn other_scenes_open_through_their_bindings() {
    for name in ["rtdemo", "sdf-engine", "toon", "tests/carved"] {
        let j = emitted(name);
        let b = bound(&j);
        assert_eq!(
            b.has_pixel(),
            name != "rtdemo",
            "{name}: four levels have no pixel binding"
        );
        let d = reference(name);
        for p in grid(2) {
            let ours = b.sdf(p).expect("sdf runs").outcome;
            let Outcome::Value(v) = d.sdf(p) else {
                panic!("the reference answers")
            };
            assert_eq!(
                ours,
                Outcome::Value((v.sd.triple.unwrap(), v.col.triple.unwrap())),
                "{name}"
            );
        }
    }
}
