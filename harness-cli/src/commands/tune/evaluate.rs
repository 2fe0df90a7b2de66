//! One configuration judged on the Rust reference: the description with its
//! variants, rendered whole by ref-f316 (rows in parallel) with the Float316
//! operations counted, against the untuned image and against ref-f64.

use super::space::{self, Config};
use anyhow::Context;
use common::Outcome;
use reference::{Described, OpCounts, RefImpl, SceneImage, ScenePixel, Settings};
use serde::{Deserialize, Serialize};

/// What a configuration's image is, against the untuned one and ref-f64.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Evaluation {
    /// Pixels whose output level (the dithered image the user sees) differs
    /// from the untuned image's, a trap against a value counted.
    pub flips: u64,
    /// Pixels whose shade differs from the untuned image's (bit for bit).
    pub shades: u64,
    /// The first pixel, in row order, whose level differs.
    pub first_flip: Option<(u32, u32)>,
    /// The largest `|shade - ref-f64 shade|`; `None` when a pixel trapped
    /// where ref-f64 answered (or the other way round).
    pub max_error: Option<f64>,
    /// The pixel of `max_error` (the first trapped one when `None`).
    pub worst_error: Option<(u32, u32)>,
    /// The Float316 operations of the whole image.
    pub counts: OpCounts,
}

/// What a configuration must keep.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum Constraint {
    /// At most this many pixels whose output level differs from the
    /// untuned image's.
    Flips(u64),
    /// The largest shade error against ref-f64 at most this.
    MaxError(f64),
}

impl Constraint {
    /// Whether `e` keeps it.
    pub fn holds(&self, e: &Evaluation) -> bool {
        match *self {
            Constraint::Flips(n) => e.flips <= n,
            Constraint::MaxError(max) => e.max_error.is_some_and(|m| m <= max),
        }
    }

    /// The pixel that breaks it in `e`: the first differing one, or the one
    /// with the largest error.
    pub fn forbidding_pixel(&self, e: &Evaluation) -> Option<(u32, u32)> {
        match self {
            Constraint::Flips(_) => e.first_flip,
            Constraint::MaxError(_) => e.worst_error,
        }
    }

    /// In words.
    pub fn describe(&self) -> String {
        match self {
            Constraint::Flips(0) => {
                "0 pixels whose output level differs from the untuned image".into()
            }
            Constraint::Flips(n) => {
                format!("at most {n} pixels whose output level differs from the untuned image")
            }
            Constraint::MaxError(e) => format!("|shade - ref-f64| at most {e} at every pixel"),
        }
    }
}

/// Judges configurations of one description.
pub struct Evaluator {
    /// The description without `variants`.
    description: serde_json::Value,
    /// The untuned ref-f316 image, its operations and ref-f64's image.
    base: SceneImage,
    base_counts: OpCounts,
    oracle: SceneImage,
    /// ref-f316 of the untuned description.
    base_reference: Described,
}

impl Evaluator {
    /// Render the untuned `description` (without `variants`), checked as
    /// `checked`, on ref-f316 and ref-f64.
    pub fn new(
        description: serde_json::Value,
        checked: &scene::Checked,
    ) -> anyhow::Result<Evaluator> {
        let base_reference = Described::new(RefImpl::F316, checked, Settings::default())?;
        let (base, base_counts) = base_reference.render_counted()?;
        let oracle = Described::new(RefImpl::F64, checked, Settings::default())?.render();
        Ok(Evaluator {
            description,
            base,
            base_counts,
            oracle,
            base_reference,
        })
    }

    /// The description with `c`'s variants, checked.
    pub fn checked(&self, c: &Config) -> anyhow::Result<scene::Checked> {
        scene::parse(&self.description(c).to_string())
            .with_context(|| format!("the configuration {}", space::key(c)))
    }

    /// The description with `c`'s variants, as JSON.
    pub fn description(&self, c: &Config) -> serde_json::Value {
        let mut d = self.description.clone();
        if !c.is_empty() {
            d["variants"] = space::variants_field(c);
        }
        d
    }

    /// ref-f316 of the description with `c`'s variants.
    pub fn reference(&self, c: &Config) -> anyhow::Result<Described> {
        Ok(Described::new(
            RefImpl::F316,
            &self.checked(c)?,
            Settings::default(),
        )?)
    }

    /// The untuned ref-f316, its image and its operations.
    pub fn base(&self) -> (&Described, &SceneImage, &OpCounts) {
        (&self.base_reference, &self.base, &self.base_counts)
    }

    /// The untuned configuration's evaluation (no flip by definition).
    pub fn base_evaluation(&self) -> Evaluation {
        judge(&self.base, &self.oracle, &self.base, self.base_counts)
    }

    /// Render `c` and judge it.
    pub fn evaluate(&self, c: &Config) -> anyhow::Result<Evaluation> {
        let (image, counts) = self.reference(c)?.render_counted()?;
        Ok(judge(&self.base, &self.oracle, &image, counts))
    }

    /// `c`'s image (for the final check).
    pub fn image(&self, c: &Config) -> anyhow::Result<(Described, SceneImage)> {
        let d = self.reference(c)?;
        let image = d.render();
        Ok((d, image))
    }
}

/// The level of a pixel, or how it stopped.
fn level(p: &Outcome<ScenePixel>) -> Outcome<u8> {
    (*p).map(|p| p.level)
}

/// `image` against the untuned `base` and the `oracle` (same size).
fn judge(
    base: &SceneImage,
    oracle: &SceneImage,
    image: &SceneImage,
    counts: OpCounts,
) -> Evaluation {
    let w = image.width;
    let at = |i: usize| ((i % w) as u32, (i / w) as u32);
    let mut e = Evaluation {
        flips: 0,
        shades: 0,
        first_flip: None,
        max_error: Some(0.0),
        worst_error: None,
        counts,
    };
    for (i, ((p, b), o)) in image
        .pixels
        .iter()
        .zip(&base.pixels)
        .zip(&oracle.pixels)
        .enumerate()
    {
        if level(p) != level(b) {
            e.flips += 1;
            e.first_flip.get_or_insert(at(i));
        }
        let shade = |p: &Outcome<ScenePixel>| (*p).map(|p| p.value.triple);
        if shade(p) != shade(b) {
            e.shades += 1;
        }
        match (p, o) {
            (Outcome::Value(p), Outcome::Value(o)) => {
                let err = (p.value.value - o.value.value).abs();
                if e.max_error.is_some_and(|m| err > m) {
                    e.max_error = Some(err);
                    e.worst_error = Some(at(i));
                }
            }
            // A trap where the other side answered: the first one is the
            // worst pixel.
            (Outcome::Value(_), _) | (_, Outcome::Value(_)) if e.max_error.is_some() => {
                e.max_error = None;
                e.worst_error = Some(at(i));
            }
            _ => {}
        }
    }
    e
}

#[cfg(test)]
mod tests {
    use super::*;
    use reference::Scalar;

    fn image(levels: &[u8], shades: &[f64]) -> SceneImage {
        SceneImage {
            width: 2,
            height: levels.len() / 2,
            levels: 2,
            pixels: levels
                .iter()
                .zip(shades)
                .map(|(&level, &value)| {
                    Outcome::Value(ScenePixel {
                        value: Scalar {
                            value,
                            triple: common::F316::from_f64_truncating(value),
                        },
                        level,
                    })
                })
                .collect(),
        }
    }

    #[test]
    fn flips_shades_and_the_largest_error_are_counted_with_their_pixels() {
        let base = image(&[0, 1, 1, 0], &[0.25, 0.75, 0.75, 0.25]);
        let oracle = image(&[0, 1, 1, 0], &[0.25, 0.75, 0.5, 0.25]);
        let tuned = image(&[0, 1, 0, 0], &[0.25, 0.5, 0.5, 0.125]);
        let e = judge(&base, &oracle, &tuned, OpCounts::default());
        assert_eq!(e.flips, 1);
        assert_eq!(e.first_flip, Some((0, 1)));
        assert_eq!(e.shades, 3);
        assert_eq!(e.max_error, Some(0.25));
        assert_eq!(e.worst_error, Some((1, 0)));
        assert!(Constraint::Flips(1).holds(&e));
        assert!(!Constraint::Flips(0).holds(&e));
        assert_eq!(Constraint::Flips(0).forbidding_pixel(&e), Some((0, 1)));
        assert!(Constraint::MaxError(0.25).holds(&e));
        assert!(!Constraint::MaxError(0.2).holds(&e));
        let mut trapped = tuned.clone();
        trapped.pixels[3] = Outcome::Hang;
        let e = judge(&base, &oracle, &trapped, OpCounts::default());
        assert_eq!(
            (e.flips, e.max_error, e.worst_error),
            (2, None, Some((1, 1)))
        );
        assert!(!Constraint::MaxError(100.0).holds(&e));
    }
}
