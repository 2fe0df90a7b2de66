//! The Jack raymarcher on the emulator agrees bit for bit with ref-f316 on
//! the committed small sets, and a pixel trace of both lines up record for
//! record so localization has nothing to report.

mod support;

use harness::cast::Cast;
use harness::localize::localize;
use vectors::{PixelVector, Vector};

#[test]
fn jack_agrees_with_ref_f316_on_the_small_sets() {
    let jack = Cast::builtin().open("jack").unwrap();
    support::assert_agrees_with_ref_f316_on_the_small_sets(jack.as_ref());
}

#[test]
fn web_divide_profile_is_a_divergence_of_the_jack_program() {
    let reference = Cast::builtin().open("ref-f316").unwrap();
    let web = Cast::builtin().open("jack+web-divide").unwrap();
    support::assert_diverges_on_the_small_ops_set(reference.as_ref(), web.as_ref());
}

#[test]
fn pixel_traces_of_jack_and_ref_f316_line_up() {
    let reference = Cast::builtin().open("ref-f316").unwrap();
    let jack = Cast::builtin().open("jack").unwrap();
    let input = Vector::Pixel(PixelVector {
        category: "t".into(),
        x: 312,
        y: 87,
    });
    let l = localize(
        reference.as_ref(),
        jack.as_ref(),
        reference.as_ref(),
        &input,
    )
    .unwrap();
    assert!(!l.differs(), "{l:?}");
}
