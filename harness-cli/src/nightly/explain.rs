//! The nightly's `explain` step: for each image pair of a lower-precision
//! implementation with the oracle, why their pixels differ (see
//! [`harness::explain`]): classes, changed decisions, top root causes, a
//! class map, and each listed pixel's class and root cause.

use super::step::Step;
use super::Night;
use anyhow::Result;
use harness::explain::{self, Class, Explainer, Explanation, Summary};
use harness_report::model::{CauseRow, NamedCount, PairExplanation};
use harness_report::{RenderImages, LISTED_PIXELS};
use std::collections::BTreeMap;
use std::time::Instant;

/// Shade differences explained for a pair whose dithered bits all agree.
const LARGEST: usize = 10;

/// Root-cause rows kept per pair.
const CAUSES: usize = 10;

/// The class map's colours.
fn colour(class: Class) -> [u8; 3] {
    match class {
        Class::ThresholdFlip => [255, 210, 0],
        Class::ControlFlow => [230, 40, 40],
        Class::Accumulated => [60, 140, 255],
        Class::Agree => [120, 120, 120],
        Class::Unexplained => [255, 0, 255],
    }
}

/// A reference label and the pixels it explained.
type Explained = (String, Vec<(usize, usize)>);

/// The step.
pub struct Explain;

impl Step for Explain {
    fn key(&self) -> &'static str {
        "explain"
    }

    fn name(&self) -> String {
        "explain".into()
    }

    fn run(&self, night: &mut Night<'_>) -> Result<()> {
        let oracle = night.cast.oracle().name.clone();
        let pairs: Vec<(String, String)> = night
            .builder
            .report()
            .image_pairs
            .iter()
            .filter(|p| p.a == oracle || p.b == oracle)
            .map(|p| (p.a.clone(), p.b.clone()))
            .collect();
        // Explanations by reference label and pixels, shared by the
        // implementations that agree with that reference.
        let mut done: BTreeMap<Explained, (Vec<Explanation>, f64)> = BTreeMap::new();
        for (a, b) in pairs {
            let other = if a == oracle { &b } else { &a };
            let Some(imp) = super::lookup(&night.opened, &night.variants, other) else {
                continue; // a program's screen, or not open here
            };
            let Ok(label) = explain::reference_label(imp) else {
                continue; // computes with f64
            };
            let (Some(mine), Some(theirs)) = (
                night.builder.render_images(other),
                night.builder.render_images(&oracle),
            ) else {
                continue;
            };
            let (pixels, inputs) = chosen_pixels(mine, theirs, label.contains('+'));
            let key = (label.clone(), pixels.clone());
            if !done.contains_key(&key) {
                let start = Instant::now();
                let explained = Explainer::new(&label)?.pixels(&pixels);
                done.insert(key.clone(), (explained, start.elapsed().as_secs_f64()));
            }
            let (explanations, seconds) = &done[&key];
            let holds = holds(night, other, &label);
            let summary = Summary::of(explanations);
            let named = |pairs: Vec<(String, u64)>| {
                pairs
                    .into_iter()
                    .map(|(name, count)| NamedCount { name, count })
                    .collect()
            };
            let few = !pixels.is_empty() && pixels.len() <= LARGEST;
            let explanation = PairExplanation {
                explained_by: label,
                holds,
                inputs,
                classes: named(
                    summary
                        .classes
                        .iter()
                        .map(|(c, n)| (c.to_string(), *n))
                        .collect(),
                ),
                decisions: named(
                    summary
                        .decisions
                        .iter()
                        .map(|(d, n)| (d.to_string(), *n))
                        .collect(),
                ),
                causes: summary
                    .causes
                    .iter()
                    .take(CAUSES)
                    .map(|c| CauseRow {
                        site: c.site.to_string(),
                        pixels: c.pixels,
                        mean_share: c.mean_share,
                    })
                    .collect(),
                colours: named(
                    summary
                        .classes
                        .iter()
                        .map(|(c, _)| {
                            let [r, g, b] = colour(*c);
                            (c.to_string(), u64::from_be_bytes([0, 0, 0, 0, 0, r, g, b]))
                        })
                        .collect(),
                ),
                examples: if few {
                    explanations
                        .iter()
                        .map(|e| format!("{}: {}", e.input, e.one_line()))
                        .collect()
                } else {
                    Vec::new()
                },
                seconds: *seconds,
                class_map: String::new(),
            };
            let classes: Vec<(usize, usize, [u8; 3])> = pixels
                .iter()
                .zip(explanations)
                .map(|(&(x, y), e)| (x, y, colour(e.class)))
                .collect();
            let lines: BTreeMap<(usize, usize), String> = pixels
                .iter()
                .zip(explanations)
                .map(|(&p, e)| (p, e.one_line()))
                .collect();
            night
                .builder
                .add_explanation((&a, &b), explanation, &classes, |x, y| {
                    lines.get(&(x, y)).cloned()
                })?;
        }
        Ok(())
    }
}

/// The pixels to explain: every one whose dithered bit differs (the
/// listed ones only for a variant, `listed_only`), else the largest shade
/// differences; and what they are, in words.
fn chosen_pixels(
    mine: &RenderImages,
    oracle: &RenderImages,
    listed_only: bool,
) -> (Vec<(usize, usize)>, String) {
    let differing = mine
        .bits
        .positions_where(&oracle.bits, |p, q| p != q)
        .unwrap_or_default();
    if !differing.is_empty() {
        let n = differing.len();
        if listed_only && n > LISTED_PIXELS {
            let listed = differing.into_iter().take(LISTED_PIXELS).collect();
            return (
                listed,
                format!("the {LISTED_PIXELS} listed of the {n} pixels whose dithered bit differs"),
            );
        }
        return (
            differing,
            format!("every pixel whose dithered bit differs ({n})"),
        );
    }
    let (Some(a), Some(b)) = (&mine.shades, &oracle.shades) else {
        return (
            Vec::new(),
            "no dithered bit differs and no shades to compare".into(),
        );
    };
    let mut diffs: Vec<(f64, usize)> = a
        .data()
        .iter()
        .zip(b.data())
        .map(|(p, q)| (p - q).abs())
        .enumerate()
        .filter(|(_, d)| *d > 0.0)
        .map(|(i, d)| (d, i))
        .collect();
    diffs.sort_by(|p, q| q.0.total_cmp(&p.0).then(p.1.cmp(&q.1)));
    let w = a.width();
    let largest: Vec<(usize, usize)> = diffs
        .into_iter()
        .take(LARGEST)
        .map(|(_, i)| (i % w, i / w))
        .collect();
    let text = format!(
        "no dithered bit differs; the {} pixels whose shades differ most",
        largest.len()
    );
    (largest, text)
}

/// Whether the explanations of `label` hold for the render `other`.
fn holds(night: &Night<'_>, other: &str, label: &str) -> String {
    if other == label {
        return format!("{other} is the explained implementation");
    }
    let same = match (
        night.builder.render_images(other),
        night.builder.render_images(label),
    ) {
        (Some(m), Some(r)) => m.bits == r.bits && m.shades == r.shades,
        _ => return format!("{label} was not rendered: {other} not compared with it"),
    };
    if same {
        format!("they hold for {other}: its render equals {label}'s bit for bit (dithered bits and shades)")
    } else {
        format!("{other}'s render differs from {label}'s: the explanations are {label}'s, not {other}'s")
    }
}
