//! The one whole-image render: every pixel of the image through the
//! [`Implementation`] trait at the `pixels` level (so that shades, the
//! values before dithering, come with the dithered bits), timed, as
//! `harness render`, `harness bench`, `harness check` and the nightly
//! need it; and the error figures of one render against another.

use crate::images::Grid;
use crate::RenderImages;
use anyhow::{anyhow, Context, Result};
use common::image_consts::{HEIGHT, WIDTH};
use common::Outcome;
use harness::cast::Cast;
use harness::implementation::{Answer, Bitmap, ImplError, Implementation, Numbers};
use harness::runner::{self, RunOptions};
use std::time::Instant;
use vectors::{Level, PixelVector, Vector, VectorSet};

/// One implementation's whole image, timed.
#[derive(Clone, Debug)]
pub struct FullRender {
    /// The implementation label (`ref-f316+newton-1`, ...).
    pub label: String,
    /// Seconds to open the implementation (compile, device creation).
    pub setup_s: f64,
    /// Wall-clock seconds for every pixel.
    pub render_s: f64,
    /// Bits, shades and the pixels that trapped.
    pub images: RenderImages,
    /// Each pixel's cost, when the implementation counts one (the Jack
    /// program's VM instructions).
    pub costs: Option<Grid<u64>>,
}

impl FullRender {
    /// Pixels rendered.
    pub fn pixels(&self) -> u64 {
        self.images.bits.data().len() as u64
    }
}

/// Every pixel of the image, row by row, as a `pixels`-level set.
pub fn full_image_set() -> VectorSet {
    let vectors = (0..HEIGHT)
        .flat_map(|y| (0..WIDTH).map(move |x| (x, y)))
        .map(|(x, y)| {
            Vector::Pixel(PixelVector {
                category: "image".into(),
                x: x as u16,
                y: y as u16,
            })
        })
        .collect();
    VectorSet::new(
        "full-image",
        Level::Pixels,
        "every pixel of the image",
        None,
        vectors,
    )
}

impl FullRender {
    /// A full render from each pixel's `(white, shade)` in row order;
    /// `None` for a pixel whose computation trapped: a trap in the image,
    /// never a colour (its bit and shade are placeholders that
    /// [`RenderImages::traps`] marks).
    pub fn from_pixels(
        label: &str,
        setup_s: f64,
        render_s: f64,
        pixels: impl IntoIterator<Item = Option<(bool, f64)>>,
    ) -> Result<FullRender> {
        let mut traps = Vec::new();
        let (bits, shades): (Vec<bool>, Vec<f64>) = pixels
            .into_iter()
            .map(|p| {
                traps.push(p.is_none());
                p.unwrap_or((true, f64::NAN))
            })
            .unzip();
        let traps = if traps.contains(&true) {
            Some(Grid::new(WIDTH, HEIGHT, traps)?)
        } else {
            None
        };
        Ok(FullRender {
            label: label.into(),
            setup_s,
            render_s,
            images: RenderImages {
                bits: Grid::new(WIDTH, HEIGHT, bits)?,
                shades: Some(Grid::new(WIDTH, HEIGHT, shades)?),
                traps,
            },
            costs: None,
        })
    }
}

/// Open `label` from the cast and render every pixel: the render and the
/// implementation's number type. Fails when the implementation cannot be
/// opened (unknown, unavailable) or gives no answers.
pub fn render(cast: &Cast, label: &str, progress: bool) -> Result<(FullRender, Numbers)> {
    let start = Instant::now();
    let imp = cast
        .open(label)
        .with_context(|| format!("implementation `{label}`"))?;
    let setup_s = start.elapsed().as_secs_f64();
    Ok((
        render_with(imp.as_ref(), setup_s, progress)?.0,
        imp.numbers(),
    ))
}

/// Every pixel through `imp`, opened in `setup_s` seconds: the render and
/// each pixel's answer in row order. An implementation that answers the
/// image level but not the pixels level (a Jack program bound through its
/// whole-program capture alone) renders its image as that level gives it:
/// bits only, no shades, each pixel's answer an [`Answer::Dot`].
pub fn render_with(
    imp: &dyn Implementation,
    setup_s: f64,
    progress: bool,
) -> Result<(FullRender, Vec<Outcome<Answer>>)> {
    let label = imp.label();
    let start = Instant::now();
    if !imp.supports(Level::Pixels) && imp.supports(Level::Image) {
        let bitmap =
            image_bits(imp, progress).map_err(|e| anyhow::Error::new(e).context(label.clone()))?;
        let render_s = start.elapsed().as_secs_f64();
        let answers = bitmap
            .white
            .iter()
            .map(|&white| Outcome::Value(Answer::Dot { white }))
            .collect();
        let full = FullRender {
            label: label.clone(),
            setup_s,
            render_s,
            images: RenderImages {
                bits: Grid::new(bitmap.width, bitmap.height, bitmap.white)?,
                shades: None,
                traps: None,
            },
            costs: None,
        };
        return Ok((full, answers));
    }
    let (answers, costs) = match imp.render_image(progress) {
        Some(image) => {
            let image = image.map_err(|e| anyhow::Error::new(e).context(label.clone()))?;
            (image.pixels, image.costs)
        }
        None => {
            let run = runner::run(&[imp], &full_image_set(), RunOptions { progress })
                .into_iter()
                .next()
                .context("the runner returned no run")?;
            let answers = run
                .answers
                .map_err(|e| anyhow::Error::new(e).context(label.clone()))?;
            (answers, None)
        }
    };
    let render_s = start.elapsed().as_secs_f64();
    let pixels = answers
        .iter()
        .map(|a| match a {
            Outcome::Value(Answer::Pixel { shade, white }) => Ok(Some((*white, shade.to_f64()))),
            Outcome::Value(other) => Err(anyhow!("{label}: a pixel answered `{other}`")),
            _ => Ok(None),
        })
        .collect::<Result<Vec<_>>>()?;
    let mut full = FullRender::from_pixels(&label, setup_s, render_s, pixels)?;
    full.costs = costs.map(|c| Grid::new(WIDTH, HEIGHT, c)).transpose()?;
    Ok((full, answers))
}

/// The image level's bitmap of `imp`: the screen of its whole program where
/// it has one ([`Implementation::program_screen`]), else its answer to the
/// image level's one vector.
fn image_bits(imp: &dyn Implementation, progress: bool) -> Result<Bitmap, ImplError> {
    if let Some(screen) = imp.program_screen(None, progress) {
        return screen;
    }
    let set = VectorSet::new(
        "full-image",
        Level::Image,
        "the whole image",
        None,
        vec![Vector::Image(vectors::ImageVector {
            category: "image".into(),
        })],
    );
    let run = runner::run(&[imp], &set, RunOptions { progress })
        .into_iter()
        .next()
        .ok_or_else(|| ImplError::Failed("the runner returned no run".into()))?;
    match run.answers?.pop() {
        Some(Outcome::Value(Answer::Image { bitmap })) => Ok(bitmap),
        other => Err(ImplError::Failed(format!(
            "the image level answered {other:?}"
        ))),
    }
}

/// The spec's dithered image (`vectors/images/seed-float316-512x256.png`).
pub fn spec_image() -> Result<Grid<bool>> {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../vectors/images/seed-float316-512x256.png");
    let img = image::open(&path)
        .with_context(|| format!("reading {}", path.display()))?
        .to_luma8();
    let bits = img.pixels().map(|p| p.0[0] > 127).collect();
    Ok(Grid::new(
        img.width() as usize,
        img.height() as usize,
        bits,
    )?)
}

/// The error figures of one whole image against the oracle's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImageError {
    /// Mean and max absolute shade error over the pixels both answered
    /// (`None` without shades on both sides).
    pub shade: Option<(f64, f64)>,
    /// Pixels that differ: a different dithered bit, or a trap on one side
    /// only.
    pub flips: u64,
    /// Pixels the subject trapped on where the oracle answered (or the
    /// other way round), counted as such, never dropped.
    pub traps: u64,
    pub pixels: u64,
}

impl ImageError {
    /// The figures of `subject` against `oracle`.
    pub fn of(subject: &RenderImages, oracle: &RenderImages) -> Result<ImageError> {
        Ok(ImageError {
            shade: subject.shade_error(oracle)?,
            flips: subject.differing(oracle)?.len() as u64,
            traps: subject.trap_mismatches(oracle),
            pixels: subject.bits.data().len() as u64,
        })
    }

    /// Why these figures diverge beyond the policy of a subject computing
    /// with `numbers`, if they do: a trap against a value, or more flips
    /// than the policy's fraction.
    pub fn beyond_policy(&self, numbers: Numbers) -> Option<String> {
        crate::PairGate {
            bit_exact: false,
            flip_limit: Some(harness::compare::Thresholds::for_subject(numbers).max_flip_fraction),
        }
        .judge(self.pixels, self.flips, None, self.traps)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use harness::implementation::ImplError;

    /// The spec's image is the reference's render, pixel for pixel, and a
    /// whole render has every pixel of it.
    #[test]
    fn the_spec_image_is_the_reference_render_of_every_pixel() {
        let (render, _) = render(&Cast::builtin(), "ref-f316", false).unwrap();
        assert_eq!(render.pixels(), (WIDTH * HEIGHT) as u64);
        let spec = spec_image().unwrap();
        assert_eq!(spec, render.images.bits);
        // Black and white only, so where the grey threshold lies between
        // them does not matter.
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../vectors/images/seed-float316-512x256.png");
        let luma = image::open(path).unwrap().to_luma8();
        assert!(luma.pixels().all(|p| p.0[0] == 0 || p.0[0] == 255));
        assert!(spec.data().iter().any(|&w| w) && spec.data().iter().any(|&w| !w));
    }

    /// Answers every pixel with a boolean.
    struct NotPixels;

    impl Implementation for NotPixels {
        fn label(&self) -> String {
            "not-pixels".into()
        }
        fn numbers(&self) -> Numbers {
            Numbers::F64
        }
        fn supports(&self, level: Level) -> bool {
            level == Level::Pixels
        }
        fn eval(&self, batch: &[Vector]) -> Result<Vec<Outcome<Answer>>, ImplError> {
            Ok(batch
                .iter()
                .map(|_| Outcome::Value(Answer::Bool { value: true }))
                .collect())
        }
    }

    #[test]
    fn a_render_whose_pixels_are_not_pixels_is_an_error_naming_the_implementation() {
        let e = render_with(&NotPixels, 0.0, false).unwrap_err();
        assert!(
            format!("{e:#}").contains("not-pixels: a pixel answered"),
            "{e:#}"
        );
    }
}
