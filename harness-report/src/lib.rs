//! Reports: the model of what a run found ([`model`]), its images
//! ([`images`]) and charts ([`plot`]), the HTML page ([`html`]), the run history ([`history`])
//! and atomic writing ([`atomic`]). [`ReportBuilder`]
//! ties them together: it writes image files into a staging directory as
//! results arrive and swaps the finished report into place.

pub mod atomic;
pub mod history;
pub mod html;
pub mod images;
pub mod measure;
pub mod meta;
pub mod model;
pub mod plot;
pub mod stability;

use anyhow::{ensure, Context, Result};
use harness::cast::RoleNames;
use images::{Grid, Palette, Scale};
use model::*;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Policy name of comparisons that require bit-exact agreement.
pub const BIT_EXACT: &str = "bit-exact";
/// Policy name of comparisons judged by error figures against an oracle.
pub const ERROR_FIGURES: &str = "error figures";
/// Divergent pixels listed (and marked) per image pair.
pub const LISTED_PIXELS: usize = 200;
/// Decades below the largest error that a heat map shows.
const HEAT_DECADES: f64 = 5.0;

/// The images of one render, kept to compare it with later ones.
#[derive(Clone, Debug)]
pub struct RenderImages {
    /// Dithered bits, `true` = white.
    pub bits: Grid<bool>,
    /// Shades before dithering, when the implementation exposes them.
    pub shades: Option<Grid<f64>>,
    /// The pixels whose computation trapped (`Sys.error`, hang, out of
    /// domain); `None` when none did. A trap is an answer, never a colour:
    /// its bit and shade mean nothing, and it differs from every value.
    pub traps: Option<Grid<bool>>,
}

impl RenderImages {
    /// Whether the pixel at `(x, y)` trapped.
    pub fn trapped(&self, x: usize, y: usize) -> bool {
        self.traps.as_ref().is_some_and(|t| *t.get(x, y))
    }

    /// How many pixels trapped.
    pub fn trap_count(&self) -> u64 {
        self.traps
            .as_ref()
            .map_or(0, |t| t.data().iter().filter(|x| **x).count() as u64)
    }

    /// The pixels where two renders differ, row by row: a trap on one side
    /// only, or (neither trapped) a different dithered bit.
    pub fn differing(&self, other: &RenderImages) -> Result<Vec<(usize, usize)>> {
        let bits = self.bits.positions_where(&other.bits, |p, q| p != q)?;
        if self.traps.is_none() && other.traps.is_none() {
            return Ok(bits);
        }
        let width = self.bits.width();
        Ok((0..self.bits.data().len())
            .map(|i| (i % width, i / width))
            .filter(|&(x, y)| match (self.trapped(x, y), other.trapped(x, y)) {
                (false, false) => self.bits.get(x, y) != other.bits.get(x, y),
                (a, b) => a != b,
            })
            .collect())
    }

    /// Pixels trapped on one side and answered on the other.
    pub fn trap_mismatches(&self, other: &RenderImages) -> u64 {
        if self.traps.is_none() && other.traps.is_none() {
            return 0;
        }
        let width = self.bits.width();
        (0..self.bits.data().len())
            .filter(|i| self.trapped(i % width, i / width) != other.trapped(i % width, i / width))
            .count() as u64
    }

    /// Mean and max absolute shade difference over the pixels where
    /// neither side trapped (`None` without shades on both sides).
    pub fn shade_error(&self, other: &RenderImages) -> Result<Option<(f64, f64)>> {
        let (Some(s), Some(o)) = (&self.shades, &other.shades) else {
            return Ok(None);
        };
        let diff = images::abs_diff(s, o)?;
        let width = diff.width();
        let answered: Vec<f64> = diff
            .data()
            .iter()
            .enumerate()
            .filter(|(i, _)| {
                !self.trapped(i % width, i / width) && !other.trapped(i % width, i / width)
            })
            .map(|(_, d)| *d)
            .collect();
        Ok(Some(mean_max(&answered)))
    }
}

/// What makes an image pair diverge beyond its policy.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PairGate {
    /// Both renders must agree bit for bit: any differing pixel or shade.
    pub bit_exact: bool,
    /// The most dithered pixels that may flip, as a fraction, for a render
    /// against the oracle (its number type's policy); a trap against a
    /// value always diverges. `None`: the pair is measured, not judged (a
    /// precision variant).
    pub flip_limit: Option<f64>,
}

impl PairGate {
    /// Why a pair with these counts diverges beyond the gate, if it does.
    pub fn judge(
        self,
        pixels: u64,
        differing: u64,
        differing_shades: Option<u64>,
        trap_mismatches: u64,
    ) -> Option<String> {
        if self.bit_exact {
            let n = differing.max(differing_shades.unwrap_or(0));
            return (n > 0).then(|| format!("{n} pixels differ between two bit-exact renders"));
        }
        let limit = self.flip_limit?;
        let fraction = differing as f64 / pixels.max(1) as f64;
        if trap_mismatches > 0 {
            Some(format!(
                "{trap_mismatches} pixels trapped on one side and answered on the other"
            ))
        } else if fraction > limit {
            Some(format!(
                "{differing} of {pixels} dithered pixels flip ({:.3}%), over the policy's {:.3}%",
                100.0 * fraction,
                100.0 * limit
            ))
        } else {
            None
        }
    }
}

/// How the listed divergent pixels of an image pair are localized.
pub enum PixelLocalizer<'a> {
    /// Both sides compute with Float316 and can be traced: `method` says
    /// how, `first_op(x, y)` describes a listed pixel's first divergent
    /// operation in one line.
    Traced {
        method: String,
        first_op: Box<dyn FnMut(usize, usize) -> String + 'a>,
    },
    /// The pair cannot be localized, for this reason.
    Impossible(String),
}

/// Builds a report directory: images are written as they are added, the
/// JSON, HTML and plot on [`ReportBuilder::finish`], which swaps the whole
/// directory into place and appends the history line.
pub struct ReportBuilder {
    stage: atomic::StagingDir,
    report: Report,
    renders: BTreeMap<String, RenderImages>,
    /// Who the error figures are taken against, and whose variants the
    /// speed plot's cheapest spec-identical render is looked for among.
    roles: RoleNames,
}

/// File-name-safe form of a label (`ref-f316+newton-1` -> `ref-f316_newton-1`).
fn file_stem(label: &str) -> String {
    label
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

impl ReportBuilder {
    /// Start a report that will replace `target` when finished.
    pub fn new(target: &Path, meta: RunMeta, roles: RoleNames) -> Result<Self> {
        let stage = atomic::StagingDir::new(target)?;
        std::fs::create_dir(stage.path().join("images")).context("creating images/")?;
        Ok(ReportBuilder {
            stage,
            report: Report::new(meta),
            renders: BTreeMap::new(),
            roles,
        })
    }

    /// The report being built, to fill in the parts that are plain data.
    pub fn report_mut(&mut self) -> &mut Report {
        &mut self.report
    }

    /// The report being built.
    pub fn report(&self) -> &Report {
        &self.report
    }

    fn write_png(&self, name: &str, img: &image::RgbImage) -> Result<String> {
        let rel = format!("images/{name}");
        images::save_png(img, &self.stage.path().join(&rel))?;
        Ok(rel)
    }

    /// Write a picture of a described scene into the report's images as
    /// `scene-NAME.png` (`name` is made a file name); its relative path.
    pub fn write_scene_picture(&self, name: &str, img: &image::RgbImage) -> Result<String> {
        self.write_png(&format!("scene-{}.png", file_stem(name)), img)
    }

    fn write_text(&self, name: &str, text: &str) -> Result<String> {
        let rel = format!("images/{name}");
        let path = self.stage.path().join(&rel);
        std::fs::write(&path, text).with_context(|| format!("writing {}", path.display()))?;
        Ok(rel)
    }

    /// Add a render: its dithered image is written and it joins the
    /// renders that pairs and speed points are computed from. `render.image`
    /// and `render.has_shades` are filled in here.
    pub fn add_render(&mut self, mut render: Render, images: RenderImages) -> Result<()> {
        ensure!(
            !self.renders.contains_key(&render.label),
            "render {} added twice",
            render.label
        );
        if let Some(s) = &images.shades {
            images.bits.same_size(s)?;
        }
        if let Some(t) = &images.traps {
            images.bits.same_size(t)?;
        }
        render.image = self.write_png(
            &format!("render-{}.png", file_stem(&render.label)),
            &images::dithered(&images.bits, images.traps.as_ref()),
        )?;
        render.trapped = images.trap_count();
        render.has_shades = images.shades.is_some();
        self.renders.insert(render.label.clone(), images);
        self.report.renders.push(render);
        Ok(())
    }

    /// The images of a render added earlier.
    pub fn render_images(&self, label: &str) -> Option<&RenderImages> {
        self.renders.get(label)
    }

    fn render_of(&self, label: &str) -> Result<&RenderImages> {
        self.renders
            .get(label)
            .with_context(|| format!("no render named {label}"))
    }

    /// Write a one-vector set that reproduces a finding into `repro/`;
    /// returns its path relative to the report directory.
    pub fn write_repro(&self, vector: &vectors::Vector) -> Result<String> {
        let rel = format!("repro/{}.json", vector.slug());
        let path = self.stage.path().join(&rel);
        std::fs::create_dir_all(path.parent().expect("repro/ has a parent"))
            .context("creating repro/")?;
        vectors::VectorSet::repro(vector.clone()).save(&path)?;
        Ok(rel)
    }

    /// Compare two renders added earlier: overlay, heat map (when both have
    /// shades) and the list of divergent pixels; `localizer` names the
    /// first divergent operation of each listed pixel or says why it
    /// cannot, `repro(x, y)` gives the command that reproduces a pixel.
    /// `gate` says what makes the pair diverge beyond its policy (recorded
    /// in [`ImagePair::beyond_policy`]; such a pair fails the run).
    pub fn add_pair(
        &mut self,
        a: &str,
        b: &str,
        gate: PairGate,
        localizer: PixelLocalizer<'_>,
        repro: impl Fn(usize, usize) -> String,
    ) -> Result<&ImagePair> {
        let (ra, rb) = (self.render_of(a)?, self.render_of(b)?);
        let differing = ra.differing(rb)?;
        let stem = format!("{}-vs-{}", file_stem(a), file_stem(b));
        let mut overlay = images::overlay(&ra.bits, &rb.bits)?;
        for traps in [&ra.traps, &rb.traps].into_iter().flatten() {
            images::mark_traps(&mut overlay, traps)?;
        }
        let overlay = self.write_png(&format!("overlay-{stem}.png"), &overlay)?;
        let mut differing_shades = None;
        let mut heat = None;
        if let (Some(sa), Some(sb)) = (&ra.shades, &rb.shades) {
            let diff = images::abs_diff(sa, sb)?;
            differing_shades = Some(diff.data().iter().filter(|d| **d != 0.0).count() as u64);
            let (mean_abs, max_abs) = mean_max(diff.data());
            if let Some(scale) = Scale::log_for(diff.data().iter().copied(), HEAT_DECADES) {
                let img = self.write_png(
                    &format!("heat-{stem}.png"),
                    &images::heat_map(&diff, scale, Palette::Hot),
                )?;
                let bar = plot::colour_bar(
                    "|shade A − shade B| (log scale; black = 0)",
                    scale,
                    Palette::Hot,
                )?;
                let legend = self.write_text(&format!("heat-{stem}-legend.svg"), &bar)?;
                heat = Some(HeatMap {
                    image: img,
                    legend,
                    mean_abs,
                    max_abs,
                    percentiles_abs: percentiles(diff.data(), HEAT_PERCENTILES),
                });
            }
        }
        let pixels = ra.bits.data().len() as u64;
        let beyond_policy = gate.judge(
            pixels,
            differing.len() as u64,
            differing_shades,
            ra.trap_mismatches(rb),
        );
        let shade = |r: &RenderImages, x: usize, y: usize| r.shades.as_ref().map(|s| *s.get(x, y));
        let listed = differing.len().min(LISTED_PIXELS);
        let (localization, mut localize) = match localizer {
            PixelLocalizer::Traced { method, first_op } => (
                format!("{method}; {listed} listed pixels localized"),
                Some(first_op),
            ),
            PixelLocalizer::Impossible(why) => (format!("not localizable: {why}"), None),
        };
        let divergences = differing
            .iter()
            .take(LISTED_PIXELS)
            .map(|&(x, y)| PixelDivergence {
                x: x as u32,
                y: y as u32,
                a_white: *ra.bits.get(x, y),
                b_white: *rb.bits.get(x, y),
                a_shade: shade(ra, x, y),
                b_shade: shade(rb, x, y),
                first_op: localize.as_mut().map(|f| f(x, y)),
                repro: repro(x, y),
                explained: None,
            })
            .collect();
        self.report.image_pairs.push(ImagePair {
            a: a.into(),
            b: b.into(),
            width: ra.bits.width() as u32,
            height: ra.bits.height() as u32,
            pixels,
            differing_pixels: differing.len() as u64,
            differing_shades,
            overlay,
            heat,
            divergences,
            localization,
            unlisted: differing.len().saturating_sub(LISTED_PIXELS) as u64,
            bit_exact: gate.bit_exact,
            explanation: None,
            beyond_policy,
        });
        Ok(self.report.image_pairs.last().expect("just pushed"))
    }

    /// Attach an explanation to the pair `a`, `b` added earlier: `classes`
    /// colours each explained pixel in the class map written here, and
    /// `explained(x, y)` gives a listed pixel its class and root cause.
    pub fn add_explanation(
        &mut self,
        (a, b): (&str, &str),
        mut explanation: PairExplanation,
        classes: &[(usize, usize, [u8; 3])],
        explained: impl Fn(usize, usize) -> Option<String>,
    ) -> Result<()> {
        let index = self
            .report
            .image_pairs
            .iter()
            .position(|p| p.a == a && p.b == b)
            .with_context(|| format!("no image pair {a} vs {b}"))?;
        let (w, h) = {
            let p = &self.report.image_pairs[index];
            (p.width, p.height)
        };
        if !classes.is_empty() {
            let mut img = image::RgbImage::from_pixel(w, h, image::Rgb([40, 40, 40]));
            for &(x, y, c) in classes {
                if x < w as usize && y < h as usize {
                    img.put_pixel(x as u32, y as u32, image::Rgb(c));
                }
            }
            let stem = format!("{}-vs-{}", file_stem(a), file_stem(b));
            explanation.class_map = self.write_png(&format!("classes-{stem}.png"), &img)?;
        }
        let pair = &mut self.report.image_pairs[index];
        for d in &mut pair.divergences {
            d.explained = explained(d.x as usize, d.y as usize);
        }
        pair.explanation = Some(explanation);
        Ok(())
    }

    /// The speed point of a render against the oracle's render (which
    /// must have been added, with shades): time per pixel, VM instructions
    /// per pixel, shade errors and dithered flips.
    pub fn speed_point(&self, label: &str) -> Result<SpeedPoint> {
        let render = self
            .report
            .renders
            .iter()
            .find(|r| r.label == label)
            .with_context(|| format!("no render named {label}"))?;
        let oracle_label = self.roles.oracle.as_str();
        let (r, oracle) = (self.render_of(label)?, self.render_of(oracle_label)?);
        let flips = r.differing(oracle)?.len() as u64;
        let errors = if label == oracle_label {
            None
        } else {
            r.shade_error(oracle)?
        };
        let pixels = render.pixels.max(1) as f64;
        Ok(SpeedPoint {
            label: label.into(),
            time_per_pixel_s: render.render_s / pixels,
            vm_instructions_per_pixel: render.vm_instructions.map(|n| n as f64 / pixels),
            mean_shade_error: errors.map(|e| e.0),
            max_shade_error: errors.map(|e| e.1),
            pixel_flips: flips,
            identical_to_spec: render.identical_to_spec,
        })
    }

    /// The per-pixel VM instruction cost of the Jack program.
    pub fn set_cost_map(&mut self, costs: &Grid<u64>) -> Result<()> {
        let values: Vec<f64> = costs.data().iter().map(|c| *c as f64).collect();
        let (min, max) = (
            costs.data().iter().copied().min().unwrap_or(0),
            costs.data().iter().copied().max().unwrap_or(0),
        );
        let scale = Scale::Linear {
            lo: min as f64,
            hi: max as f64,
        };
        let grid = Grid::new(costs.width(), costs.height(), values)?;
        let image = self.write_png(
            "cost-jack.png",
            &images::heat_map(&grid, scale, Palette::Viridis),
        )?;
        let bar = plot::colour_bar("Hack VM instructions per pixel", scale, Palette::Viridis)?;
        let legend = self.write_text("cost-jack-legend.svg", &bar)?;
        let mean = grid.data().iter().sum::<f64>() / grid.data().len().max(1) as f64;
        self.report.cost_map = Some(CostMap {
            image,
            legend,
            min,
            max,
            mean,
        });
        Ok(())
    }

    /// Write the speed plot, `report.json` and `index.html`, swap the
    /// directory into place, then append this run's line to `history_path`.
    /// Returns the report directory.
    pub fn finish(mut self, history_path: &Path) -> Result<PathBuf> {
        let se = &mut self.report.speed_error;
        se.cheapest_spec_identical = cheapest_spec_identical(&se.points, &self.roles.tracer);
        if let Some(svg) = plot::speed_error(&self.report.speed_error.points)? {
            self.report.speed_error.plot = self.write_text("speed-error.svg", &svg)?;
        }
        let entry = history::HistoryEntry::from_report(&self.report);
        let mut past = history::read(history_path)?;
        // A run killed after its report was swapped in and before its line
        // was appended left a report the history lacks: its line first.
        let previous = std::fs::read_to_string(self.stage.target().join("report.json"))
            .ok()
            .and_then(|text| Report::from_json(&text).ok());
        if let Some(previous) = previous {
            let line = history::HistoryEntry::from_report(&previous);
            let known = past
                .entries
                .iter()
                .any(|e| (&e.date, &e.commit) == (&line.date, &line.commit));
            if !known {
                history::append(history_path, &line)?;
                past.entries.push(line);
            }
        }
        past.entries.push(entry.clone());
        let dir = self.stage.path();
        std::fs::write(dir.join("report.json"), self.report.to_json()?)
            .context("writing report.json")?;
        std::fs::write(dir.join("index.html"), html::render(&self.report, &past))
            .context("writing index.html")?;
        let target = self.stage.commit()?;
        history::append(history_path, &entry)?;
        Ok(target)
    }
}

/// Mean and maximum of non-negative values (0, 0 when empty).
fn mean_max(values: &[f64]) -> (f64, f64) {
    let max = values.iter().copied().fold(0f64, f64::max);
    let mean = values.iter().sum::<f64>() / values.len().max(1) as f64;
    (mean, max)
}

/// The percentiles of the heat map's summary.
const HEAT_PERCENTILES: [f64; 3] = [0.50, 0.95, 0.99];

/// The smallest value that the fraction `q` of `values` does not exceed,
/// for each `q` (nearest rank; 0 for no values).
fn percentiles<const N: usize>(values: &[f64], qs: [f64; N]) -> [f64; N] {
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    qs.map(|q| {
        let rank = (q * sorted.len() as f64).ceil() as usize;
        sorted.get(rank.max(1) - 1).copied().unwrap_or(0.0)
    })
}

/// The cheapest of the tracer and its variants (label `TRACER` or
/// `TRACER+VARIANT`, as the cast labels them) whose dithered image equals
/// the spec's, with its cost.
pub fn cheapest_spec_identical(points: &[SpeedPoint], tracer: &str) -> Option<String> {
    let variant_prefix = format!("{tracer}+");
    points
        .iter()
        .filter(|p| p.identical_to_spec == Some(true))
        .filter(|p| p.label == tracer || p.label.starts_with(&variant_prefix))
        .min_by(|a, b| a.time_per_pixel_s.total_cmp(&b.time_per_pixel_s))
        .map(|p| {
            format!(
                "{} ({} per pixel)",
                p.label,
                html::seconds(p.time_per_pixel_s)
            )
        })
}

#[cfg(test)]
mod tests;
