//! Out of domain the same way as the reference: the generated program of a
//! scene that drives `floor` and `mod2` outside their modelled domain
//! (`vectors/scenes/tests/domain.json`) calls `Sys.error(316)` there, which
//! its bindings declare as `out_of_domain`: opened as the harness opens a
//! Jack program, it answers out of domain on exactly the pixels and SDF
//! points where ref-f316 does, and its op trace ends in the same failing
//! operation.

mod support;

use common::{Op, Outcome, F316};
use support::*;

const SCENE: &str = "tests/domain";

#[test]
fn the_bindings_declare_the_domain_check() {
    let j = emitted(SCENE);
    assert!(
        j.bindings
            .contains(&format!("out_of_domain = {}", scene_jack::OUT_OF_DOMAIN)),
        "{}",
        j.bindings
    );
    let float = j.class("Float316.jack").unwrap();
    assert!(float.contains(&format!("do Sys.error({});", scene_jack::OUT_OF_DOMAIN)));
    assert!(bound(&j).checks_domain());
}

#[test]
fn every_pixel_has_the_reference_outcome() {
    let b = bound(&emitted(SCENE));
    let d = reference(SCENE);
    let (w, h) = (d.program().pixels.width, d.program().pixels.height);
    let mut ood = 0;
    let mut bad = Vec::new();
    for y in 0..h {
        for x in 0..w {
            let ours = b.pixel(x as usize, y as usize).expect("pixel runs").outcome;
            let theirs = d.pixel(x, y);
            ood += usize::from(theirs == Outcome::OutOfDomain);
            let same = ours.same_as(&theirs, |p, v| {
                Some(p.shade) == v.value.triple && p.white == Some(v.level == 1)
            });
            if !same {
                bad.push(format!("({x},{y}): jack {ours:?}, reference {theirs:?}"));
            }
        }
    }
    assert!(
        bad.is_empty(),
        "{} differ: {:?}",
        bad.len(),
        &bad[..bad.len().min(5)]
    );
    assert!(ood > 300, "{ood} pixels out of domain");
}

fn p(x: f64, y: f64, z: f64) -> [F316; 3] {
    [x, y, z].map(|c| F316::from_f64_truncating(c).unwrap())
}

#[test]
fn every_sdf_point_has_the_reference_outcome() {
    let b = bound(&emitted(SCENE));
    let d = reference(SCENE);
    let mut points = grid(6);
    // Beyond 16.384 on x or z, and floors summing past 2^14.
    let far = |q: [F316; 3]| q.map(|c| F316::from_f64_truncating(c.to_f64() * 6.0).unwrap());
    points.extend(grid(5).into_iter().map(far));
    let mut ood = 0;
    for q in points {
        let ours = b.sdf(q).expect("sdf runs").outcome;
        let theirs = d.sdf(q);
        ood += usize::from(theirs == Outcome::OutOfDomain);
        let same = ours.same_as(&theirs, |(sd, col), v| {
            Some(*sd) == v.sd.triple && Some(*col) == v.col.triple
        });
        assert!(same, "{q:?}: jack {ours:?}, reference {theirs:?}");
    }
    assert!(ood > 10, "{ood} points out of domain");
}

/// The last record of both traces is the failing operation, out of
/// domain, with the same operands: `floor` of 16500 and 20000, `mod2` of
/// 10000 + 10000.
#[test]
fn the_traces_end_in_the_same_failing_operation() {
    let b = bound(&emitted(SCENE));
    let d = reference(SCENE);
    for (q, op) in [
        (p(16.5, 0.0, 0.0), Op::Floor),
        (p(-20.0, 0.0, 0.0), Op::Floor),
        (p(10.0, -1.0, 10.0), Op::Mod2),
    ] {
        let ours = b.trace_sdf(q).expect("traced");
        let theirs = d.trace_sdf(q).expect("traced").records;
        let (a, r) = (ours.last().unwrap(), theirs.last().unwrap());
        assert_eq!((a.op, &a.result), (op, &Outcome::OutOfDomain), "{a:?}");
        assert!(a.same_computation(r), "jack {a:?}, reference {r:?}");
        assert!(
            a.path.iter().any(|f| f == "Scene.sdf"),
            "a Jack call path: {:?}",
            a.path
        );
    }
}
