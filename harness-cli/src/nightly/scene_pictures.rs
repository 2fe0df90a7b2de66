//! The pictures of a described scene in the report, as the seed scene's
//! renders section has them: each leg's render (the generated Jack
//! program's among them), each leg's difference overlay against the render
//! it is judged by (a Float316 leg against ref-f316, a float leg against
//! ref-f64), and the generated Jack program's cost map and the screen its
//! `Main.main` drew.

use super::scene_jack::{self, JackLeg};
use crate::commands::jack::cost;
use anyhow::Result;
use common::image_consts::{HEIGHT, WIDTH};
use common::Outcome;
use harness_report::images::{A_WHITE_COLOUR, B_WHITE_COLOUR, TRAP_COLOUR};
use harness_report::model::ScenePicture;
use harness_report::ReportBuilder;
use image::{Rgb, RgbImage};
use reference::{SceneImage, ScenePixel};

/// The grey of a pixel (level 0 black, the top level white), or `None`
/// for a trap.
fn grey(p: &Outcome<ScenePixel>, levels: u8) -> Option<u8> {
    let top = u16::from(levels.max(2) - 1);
    match p {
        Outcome::Value(p) => Some((u16::from(p.level) * 255 / top) as u8),
        _ => None,
    }
}

/// `image` in greys, traps in [`TRAP_COLOUR`].
fn render(image: &SceneImage) -> RgbImage {
    RgbImage::from_fn(image.width as u32, image.height as u32, |x, y| {
        match grey(
            &image.pixels[y as usize * image.width + x as usize],
            image.levels,
        ) {
            Some(g) => Rgb([g, g, g]),
            None => Rgb(TRAP_COLOUR),
        }
    })
}

/// A 512x256 screen, `true` = white.
fn screen(white: &[bool]) -> RgbImage {
    let (w, h) = (WIDTH as u32, HEIGHT as u32);
    RgbImage::from_fn(w, h, |x, y| {
        Rgb([if white[(y * w + x) as usize] { 255 } else { 0 }; 3])
    })
}

/// `b` over `a`: `a` dimmed where their levels agree, [`B_WHITE_COLOUR`]
/// where `b` is lighter, [`A_WHITE_COLOUR`] where `a` is, [`TRAP_COLOUR`]
/// where one traps and the other does not; and the number of pixels that
/// differ. `None` when the sizes differ.
fn overlay(a: &SceneImage, b: &SceneImage) -> Option<(RgbImage, usize)> {
    if (a.width, a.height) != (b.width, b.height) || a.pixels.len() != b.pixels.len() {
        return None;
    }
    let colour = |i: usize| -> (Rgb<u8>, bool) {
        match (grey(&a.pixels[i], a.levels), grey(&b.pixels[i], b.levels)) {
            (Some(x), Some(y)) if x == y => (Rgb([x / 3 + 40; 3]), false),
            (Some(x), Some(y)) if y > x => (Rgb(B_WHITE_COLOUR), true),
            (Some(_), Some(_)) => (Rgb(A_WHITE_COLOUR), true),
            (None, None) => (Rgb([40; 3]), false),
            _ => (Rgb(TRAP_COLOUR), true),
        }
    };
    let differing = (0..a.pixels.len()).filter(|&i| colour(i).1).count();
    let img = RgbImage::from_fn(a.width as u32, a.height as u32, |x, y| {
        colour(y as usize * a.width + x as usize).0
    });
    Some((img, differing))
}

/// The render a leg is drawn over, among `images`: another Float316 leg
/// over ref-f316, which it must equal; ref-f316 and the float legs over
/// ref-f64, where their precision shows.
fn judged_by(label: &str, images: &[(String, SceneImage)]) -> Option<&'static str> {
    let float316 = label.ends_with("f316") || label == scene_jack::LABEL;
    let base = if float316 && label != "ref-f316" {
        "ref-f316"
    } else {
        "ref-f64"
    };
    (label != base && images.iter().any(|(l, _)| l == base)).then_some(base)
}

/// Write the pictures of scene `name` into the report's images.
pub fn pictures(
    builder: &ReportBuilder,
    name: &str,
    images: &[(String, SceneImage)],
    jack: Option<&JackLeg>,
) -> Result<Vec<ScenePicture>> {
    let mut out = Vec::new();
    let mut add = |file: String, img: &RgbImage, caption: String| -> Result<()> {
        out.push(ScenePicture {
            image: builder.write_scene_picture(&file, img)?,
            caption,
        });
        Ok(())
    };
    let find = |label: &str| images.iter().find(|(l, _)| l == label).map(|(_, i)| i);
    for (label, image) in images {
        add(format!("{name}-{label}"), &render(image), label.clone())?;
        if let Some(base) = judged_by(label, images).and_then(|b| find(b).map(|i| (b, i))) {
            if let Some((img, n)) = overlay(base.1, image) {
                let caption = format!("{label} over {}: {n} pixels differ", base.0);
                add(format!("{name}-{label}-vs-{}", base.0), &img, caption)?;
            }
        }
    }
    if let Some(leg) = jack {
        let label = scene_jack::LABEL;
        let map = image::DynamicImage::ImageLuma8(cost::cost_map(&leg.measured)).to_rgb8();
        let c = &leg.measured.cost;
        add(
            format!("{name}-{label}-cost"),
            &map,
            format!(
                "{label}: VM instructions per pixel, black 0, white {} (the most); mean {:.0}",
                c.max, c.mean
            ),
        )?;
        if let Ok(main) = &leg.screen {
            let label = scene_jack::screen_label();
            add(
                format!("{name}-{label}"),
                &screen(&main.white),
                format!("{label}: the Hack screen Main.main drew"),
            )?;
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use reference::Scalar;

    fn image(levels: u8, ls: &[Option<u8>]) -> SceneImage {
        SceneImage {
            width: ls.len(),
            height: 1,
            levels,
            pixels: ls
                .iter()
                .map(|l| match l {
                    Some(level) => Outcome::Value(ScenePixel {
                        value: Scalar {
                            value: 0.0,
                            triple: None,
                        },
                        level: *level,
                    }),
                    None => Outcome::SysError(3),
                })
                .collect(),
        }
    }

    #[test]
    fn the_overlay_marks_each_kind_of_difference() {
        let a = image(4, &[Some(0), Some(3), Some(1), None, Some(2)]);
        let b = image(4, &[Some(0), Some(1), Some(2), Some(2), Some(2)]);
        let (img, n) = overlay(&a, &b).unwrap();
        assert_eq!(n, 3);
        assert_eq!(img.dimensions(), (5, 1));
        assert_eq!(img.get_pixel(1, 0), &Rgb(A_WHITE_COLOUR), "b darker");
        assert_eq!(img.get_pixel(2, 0), &Rgb(B_WHITE_COLOUR), "b lighter");
        assert_eq!(
            img.get_pixel(3, 0),
            &Rgb(TRAP_COLOUR),
            "a trap against a value"
        );
        assert_eq!(
            img.get_pixel(4, 0),
            &Rgb([2 * 85 / 3 + 40; 3]),
            "same: dimmed"
        );
        assert!(overlay(&a, &image(4, &[Some(0)])).is_none());
    }

    #[test]
    fn a_screen_is_drawn_white_and_black() {
        let mut white = vec![true; WIDTH * HEIGHT];
        white[WIDTH + 3] = false;
        let img = screen(&white);
        assert_eq!(img.dimensions(), (512, 256));
        assert_eq!(img.get_pixel(3, 1), &Rgb([0; 3]));
        assert_eq!(img.get_pixel(4, 1), &Rgb([255; 3]));
    }

    #[test]
    fn legs_are_judged_by_their_number_types_reference() {
        let some = image(2, &[Some(0)]);
        let images: Vec<(String, SceneImage)> = ["ref-f64", "ref-f32", "ref-f316", "gpu-f316"]
            .map(|l| (l.to_string(), some.clone()))
            .into();
        assert_eq!(judged_by("gpu-f316", &images), Some("ref-f316"));
        assert_eq!(judged_by("ref-f32", &images), Some("ref-f64"));
        assert_eq!(judged_by(scene_jack::LABEL, &images), Some("ref-f316"));
        assert_eq!(judged_by("ref-f316", &images), Some("ref-f64"));
        assert_eq!(judged_by("ref-f64", &images), None);
    }
}
