//! The seed scene from its description: ref-f316 reproduces the committed
//! Jack render exactly, and the float renders equal the hand-written ones.

use reference::{Described, RefImpl, Reference, Settings};
use std::path::PathBuf;

fn scene(name: &str) -> scene::Checked {
    let path =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("../../vectors/scenes/{name}.json"));
    scene::load(&path).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn seed_description_equals_the_hand_written_seed_on_every_reference() {
    let seed = scene("seed");
    for imp in RefImpl::ALL {
        let described = Described::new(imp, &seed, Settings::default())
            .unwrap()
            .render();
        let hand = Reference::seed(imp).render();
        let differ: Vec<usize> = described
            .gray8()
            .iter()
            .zip(hand.gray8())
            .enumerate()
            .filter(|(_, (a, b))| **a != *b)
            .map(|(i, _)| i)
            .collect();
        assert!(
            differ.is_empty(),
            "{imp}: {} pixels differ, first {:?}",
            differ.len(),
            &differ[..differ.len().min(10)]
        );
        for (d, h) in described.pixels.iter().zip(&hand.pixels) {
            assert_eq!((*d).map(|p| p.value), (*h).map(|p| p.value), "{imp}");
        }
    }
}

/// The decisions of a shadowed run, each scene evaluation's (its `union`s
/// and checker parity) in a canonical order: the description folds the
/// floor in last, the hand-written scene evaluates it first.
fn decisions(run: &reference::ShadowRun) -> Vec<(reference::Decision, bool, [u64; 2])> {
    use reference::Decision::{Checker, Union};
    let mut out = Vec::new();
    let mut scene = Vec::new();
    for d in &run.decisions {
        let item = (d.decision, d.taken, d.operands.map(f64::to_bits));
        if matches!(d.decision, Union | Checker) {
            scene.push(item);
        } else {
            scene.sort();
            out.append(&mut scene);
            out.push(item);
        }
    }
    scene.sort();
    out.extend(scene);
    out
}

#[test]
fn the_described_seed_decides_as_the_hand_written_one() {
    let seed = scene("seed");
    let options = reference::ShadowOptions::default();
    for imp in [RefImpl::F316, RefImpl::F32, RefImpl::F64] {
        let described = Described::new(imp, &seed, Settings::default()).unwrap();
        let hand = Reference::seed(imp);
        // Sky, sphere, torus, lit and shadowed floor, a silhouette.
        for (x, y) in [
            (10, 5),
            (128, 128),
            (384, 128),
            (60, 230),
            (300, 200),
            (106, 93),
        ] {
            let d = described.shadow_pixel(x, y, &options);
            let h = hand.shadow_pixel(x as usize, y as usize, &options);
            assert!(!d.decisions.is_empty(), "{imp} ({x},{y})");
            assert_eq!(decisions(&d), decisions(&h), "{imp} pixel ({x},{y})");
            assert_eq!(d.output("shade"), h.output("shade"), "{imp} ({x},{y})");
        }
    }
}

#[test]
fn a_reflection_reports_its_bounces() {
    let rtdemo = scene("rtdemo");
    let f64 = Described::new(RefImpl::F64, &rtdemo, Settings::default()).unwrap();
    let bounces = |x, y| {
        f64.decided_pixel(x, y)
            .1
            .iter()
            .filter(|d| d.decision == reference::Decision::Bounce && d.taken)
            .count()
    };
    let most = (0..240)
        .flat_map(|y| (0..320).map(move |x| (x, y)))
        .map(|(x, y)| bounces(x, y))
        .max();
    assert!(most >= Some(2), "some ray reflects twice: {most:?}");
    assert_eq!(bounces(0, 0), 0);
}
