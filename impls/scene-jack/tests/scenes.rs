//! Every scene's generated program compiles under both profiles, and its
//! pixels and SDF agree with ref-f316 bit for bit on samples.

mod support;

use support::*;

#[test]
fn compiles_under_both_profiles() {
    for name in SCENES {
        let j = emitted(name);
        for profile in [jack::Profile::Desktop, jack::Profile::Web] {
            if let Err(e) = scene_jack::cost::compile(&j, profile) {
                panic!("{name} under {profile:?}: {e}");
            }
        }
    }
}

/// Rows `rows` sampled every `step` pixels, compared with the reference.
fn check_pixels(name: &str, rows: &[u32], step: u32) {
    let r = runner(name);
    let d = reference(name);
    let w = d.program().pixels.width;
    let bad: Vec<String> = rows
        .iter()
        .flat_map(|&y| (0..w).step_by(step as usize).map(move |x| (x, y)))
        .filter_map(|(x, y)| pixel_mismatch(&r, &d, x, y))
        .collect();
    assert!(
        bad.is_empty(),
        "{name}: {} pixels differ: {:?}",
        bad.len(),
        &bad[..bad.len().min(5)]
    );
}

fn check_sdf(name: &str) {
    let r = runner(name);
    let d = reference(name);
    let bad: Vec<String> = grid(6)
        .into_iter()
        .filter_map(|p| sdf_mismatch(&r, &d, p))
        .collect();
    assert!(
        bad.is_empty(),
        "{name}: {} SDF answers differ: {:?}",
        bad.len(),
        &bad[..bad.len().min(5)]
    );
}

#[test]
fn seed_pixels_equal_the_reference() {
    check_pixels("seed", &[0, 60, 100, 128, 150, 180, 255], 3);
}

#[test]
fn seed_sdf_equals_the_reference() {
    check_sdf("seed");
}

#[test]
fn rtdemo_pixels_and_sdf_equal_the_reference() {
    // Rows 0..8 are outside the BBC's drawn rows (level 0).
    check_pixels("rtdemo", &[0, 9, 60, 120, 200, 239], 4);
    check_sdf("rtdemo");
}

#[test]
fn sdf_engine_pixels_and_sdf_equal_the_reference() {
    check_pixels("sdf-engine", &[40, 128, 200], 8);
    check_sdf("sdf-engine");
}

#[test]
fn toon_pixels_and_sdf_equal_the_reference() {
    check_pixels("toon", &[40, 128, 200], 8);
    check_sdf("toon");
}

#[test]
fn carved_pixels_and_sdf_equal_the_reference() {
    check_pixels("tests/carved", &[10, 48, 80], 3);
    check_sdf("tests/carved");
}
