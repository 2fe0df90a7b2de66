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

#[test]
fn the_example_still_lifes_pixels_and_sdf_equal_the_reference() {
    check_pixels(STILL_LIFE, &[20, 96, 150, 191], 5);
    check_sdf(STILL_LIFE);
}

/// rtdemo's `Main.main` draws its four levels by the documented 2x2 rule
/// (`scene_jack::expected_screen` from the reference's levels).
#[test]
fn rtdemo_main_draws_its_four_levels_by_the_documented_rule() {
    let screen =
        scene_jack::cost::run_main(&emitted("rtdemo"), jack::Profile::Desktop, 5_000_000_000)
            .expect("Main.main ends");
    let image = reference("rtdemo").render();
    let want = scene_jack::expected_screen(&program("rtdemo"), |x, y| {
        image.pixels[y as usize * image.width + x as usize]
            .value()
            .map(|p| p.level)
    })
    .expect("no trap");
    let differing: Vec<(usize, usize)> = (0..want.len())
        .filter(|&i| screen.white[i] != want[i])
        .map(|i| (i % 512, i / 512))
        .collect();
    assert!(
        differing.is_empty(),
        "{} screen pixels differ: {:?}",
        differing.len(),
        &differing[..differing.len().min(5)]
    );
    // Not all one colour: every level shows.
    assert!(want.iter().any(|&w| w) && want.iter().any(|&w| !w));
}

/// The library classes keep what the scene calls, each subroutine exactly
/// as the hand-written Float316 class writes it.
#[test]
fn libraries_keep_only_what_the_scene_calls() {
    let hand = include_str!("../../jack/raymarcher/Float316.jack");
    let seed = emitted("seed");
    let rtdemo = emitted("rtdemo");
    let f_seed = seed.class("Float316.jack").unwrap();
    let f_rtdemo = rtdemo.class("Float316.jack").unwrap();
    assert!(f_seed.contains("method void invSqrt("));
    assert!(!f_rtdemo.contains("method void invSqrt(") && !f_rtdemo.contains("isX2"));
    assert!(!rtdemo.class("Ops.jack").unwrap().contains("normalize3"));
    for sub in f_rtdemo.split("\n\n").filter(|s| s.contains("method ")) {
        assert!(hand.contains(sub.trim_end_matches("}\n")), "changed: {sub}");
    }
}
