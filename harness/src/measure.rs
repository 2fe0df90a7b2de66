//! The one whole-image render: every pixel of the image through the
//! [`Implementation`] trait at the `pixels` level (so that shades, the
//! values before dithering, come with the dithered bits), timed, as
//! `harness render`, `harness bench`, `harness check` and the nightly
//! need it; and the error figures of one render against another.

use crate::cast::Cast;
use crate::implementation::{Answer, Implementation};
use crate::report::images::Grid;
use crate::report::RenderImages;
use crate::runner::{self, RunOptions};
use anyhow::{anyhow, Context, Result};
use common::image_consts::{HEIGHT, WIDTH};
use common::Outcome;
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
    /// Bits and shades.
    pub images: RenderImages,
    /// Pixels whose computation trapped (drawn white, shade NaN).
    pub trapped: u64,
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
    /// `None` for a pixel whose computation trapped, which is never drawn:
    /// white, as the Hack screen starts.
    pub fn from_pixels(
        label: &str,
        setup_s: f64,
        render_s: f64,
        pixels: impl IntoIterator<Item = Option<(bool, f64)>>,
    ) -> Result<FullRender> {
        let mut trapped = 0;
        let (bits, shades): (Vec<bool>, Vec<f64>) = pixels
            .into_iter()
            .map(|p| {
                p.unwrap_or_else(|| {
                    trapped += 1;
                    (true, f64::NAN)
                })
            })
            .unzip();
        Ok(FullRender {
            label: label.into(),
            setup_s,
            render_s,
            images: RenderImages {
                bits: Grid::new(WIDTH, HEIGHT, bits)?,
                shades: Some(Grid::new(WIDTH, HEIGHT, shades)?),
            },
            trapped,
            costs: None,
        })
    }
}

/// Open `label` from the cast and render every pixel. Fails when the
/// implementation cannot be opened (unknown, unavailable) or gives no
/// answers.
pub fn render(cast: &Cast, label: &str, progress: bool) -> Result<FullRender> {
    let start = Instant::now();
    let imp = cast
        .open(label)
        .with_context(|| format!("implementation `{label}`"))?;
    let setup_s = start.elapsed().as_secs_f64();
    Ok(render_with(imp.as_ref(), setup_s, progress)?.0)
}

/// Every pixel through `imp`, opened in `setup_s` seconds: the render and
/// each pixel's answer in row order.
pub fn render_with(
    imp: &dyn Implementation,
    setup_s: f64,
    progress: bool,
) -> Result<(FullRender, Vec<Outcome<Answer>>)> {
    let label = imp.label();
    let start = Instant::now();
    let (answers, costs) = match imp.render_image(progress) {
        Some(image) => {
            let image = image.map_err(|e| anyhow!("{label}: {e}"))?;
            (image.pixels, image.costs)
        }
        None => {
            let run = runner::run(&[imp], &full_image_set(), RunOptions { progress })
                .into_iter()
                .next()
                .context("the runner returned no run")?;
            (run.answers.map_err(|e| anyhow!("{label}: {e}"))?, None)
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

/// Mean and max absolute shade error of `subject` against `oracle` (pixels
/// that trapped on either side are left out) and dithered flips.
pub fn error_against(
    subject: &RenderImages,
    oracle: &RenderImages,
) -> Result<(Option<(f64, f64)>, u64)> {
    let flips = subject
        .bits
        .positions_where(&oracle.bits, |a, b| a != b)?
        .len() as u64;
    let errors = match (&subject.shades, &oracle.shades) {
        (Some(s), Some(o)) => {
            s.same_size(o)?;
            let diffs: Vec<f64> = s
                .data()
                .iter()
                .zip(o.data())
                .map(|(a, b)| (a - b).abs())
                .filter(|d| d.is_finite())
                .collect();
            let max = diffs.iter().copied().fold(0f64, f64::max);
            Some((diffs.iter().sum::<f64>() / diffs.len().max(1) as f64, max))
        }
        _ => None,
    };
    Ok((errors, flips))
}
