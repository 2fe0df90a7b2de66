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
