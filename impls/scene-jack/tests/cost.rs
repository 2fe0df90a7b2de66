//! The cost figures of the generated seed program against the hand-written
//! raymarcher, and its whole image on the Hack screen against the committed
//! render (ignored: about 22 G VM instructions).

mod support;

use scene_jack::cost;
use support::*;

#[test]
fn seed_costs_about_what_the_hand_written_program_costs() {
    let j = emitted("seed");
    let size = cost::size(&cost::compile(&j, jack::Profile::Desktop).unwrap());
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../jack/raymarcher");
    let hand_vm: Vec<(String, String)> =
        jack_compiler::compile_dir(std::path::Path::new(dir), jack::Profile::Desktop)
            .unwrap()
            .into_iter()
            .map(jack_compiler::VmClass::into_file)
            .collect();
    let hand_size = cost::size(&hand_vm);
    println!("seed: {size:?}; hand-written: {hand_size:?}");
    assert!(size.rom_shared <= cost::ROM_WORDS, "{size:?}");
    let r = runner("seed");
    let pixels: Vec<(u32, u32)> = (0..256)
        .step_by(16)
        .flat_map(|y| (0..512).step_by(32).map(move |x| (x, y)))
        .collect();
    let ours = cost::pixel_cost(&r, &pixels);
    let hand = jack::Raymarcher::new(jack::Profile::Desktop, jack::Budgets::default()).unwrap();
    let theirs: u64 = pixels
        .iter()
        .map(|&(x, y)| hand.pixel(x as usize, y as usize).unwrap().instructions)
        .sum();
    let theirs = theirs as f64 / pixels.len() as f64;
    println!(
        "seed: per pixel mean {:.0} (hand-written {theirs:.0}), max {}",
        ours.mean, ours.max
    );
    assert!(ours.mean < 1.5 * theirs, "{} against {theirs}", ours.mean);
}

/// The generated seed program's `Main.main`, unmodified, draws the
/// committed render of the original program
/// (`vectors/images/seed-float316-512x256.png`, 255 = white) with 0
/// differing pixels. Ignored by `cargo test` (about 22 G VM instructions on
/// one thread); scripts/nightly.sh runs it.
#[test]
#[ignore = "the whole image: about 22 G VM instructions"]
fn seed_main_draws_the_committed_render() {
    let j = emitted("seed");
    let screen =
        cost::run_main(&j, jack::Profile::Desktop, 60_000_000_000).expect("Main.main ends");
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../vectors/images/seed-float316-512x256.png"
    );
    let committed = image::open(path).expect("the committed render").to_luma8();
    assert_eq!(committed.dimensions(), (512, 256));
    let differing: Vec<(u32, u32)> = committed
        .enumerate_pixels()
        .filter(|(x, y, p)| screen.white[(y * 512 + x) as usize] != (p.0[0] == 255))
        .map(|(x, y, _)| (x, y))
        .collect();
    println!("seed Main.main: {} VM instructions", screen.instructions);
    assert!(
        differing.is_empty(),
        "{} pixels differ, first {:?}",
        differing.len(),
        differing.first()
    );
}
