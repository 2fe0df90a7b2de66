//! The report model: everything a nightly run found, as plain serialisable
//! data. `report.json` is this structure; the HTML page and the history line
//! are views of it. Field names are part of the JSON contract: bump
//! [`SCHEMA_VERSION`] when one changes meaning or disappears.

use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Version of the `report.json` layout.
pub const SCHEMA_VERSION: u32 = 1;

/// A whole nightly report.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Report {
    /// Always [`SCHEMA_VERSION`] when written by this build.
    pub schema_version: u32,
    /// When, where and how long.
    pub meta: RunMeta,
    /// Every implementation the harness knows, available here or not.
    pub implementations: Vec<ImplStatus>,
    /// Level comparisons (ops, sdf, pixels, image, exhaustive unary checks).
    pub comparisons: Vec<Comparison>,
    /// The harness self-test, when it ran.
    pub selftest: Option<SelfTest>,
    /// One full render per available implementation (and precision variant).
    pub renders: Vec<Render>,
    /// Every pair of image renders, with its diff images.
    pub image_pairs: Vec<ImagePair>,
    /// The Jack program's per-pixel VM instruction cost, when it ran.
    pub cost_map: Option<CostMap>,
    /// Speed against error, one point per implementation and variant.
    pub speed_error: SpeedError,
    /// Hard-case categories and their outcome on every implementation.
    pub stability: Vec<StabilityRow>,
    /// Benchmark table.
    pub bench: Vec<BenchRow>,
    /// The described scenes of the scene step (docs/scenes.md).
    #[serde(default)]
    pub scenes: Vec<SceneRow>,
    /// The TestFloat-style cases of each operation at each level, and
    /// where they ran (docs/coverage.md).
    #[serde(default)]
    pub testfloat: Vec<CaseCount>,
    /// Steps that could not run or failed, with the reason; the report is
    /// still written, these are listed at its top.
    pub problems: Vec<String>,
    /// The night's verdict: every comparison and whether it diverged
    /// beyond its policy, and everything that could not be compared.
    #[serde(default)]
    pub verdict: harness::verdict::Verdict,
}

/// When, where and how long a run took.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct RunMeta {
    /// Start time, UTC, `YYYY-MM-DDTHH:MM:SSZ`.
    pub started_at: String,
    /// `git rev-parse HEAD` of the source tree, or `unknown`.
    pub git_commit: String,
    /// Whether the tree had uncommitted changes.
    pub git_dirty: bool,
    /// Wall-clock duration of the whole run, seconds.
    pub duration_s: f64,
    /// Logical CPUs of the machine.
    pub cpus: usize,
    /// The harness version (crate version).
    pub harness_version: String,
    /// Seconds spent in each step, in order.
    pub steps: Vec<StepTiming>,
}

/// Time spent in one step of the run.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct StepTiming {
    /// Step name (`ops`, `image`, `bench`, ...).
    pub step: String,
    /// Seconds.
    pub seconds: f64,
}

/// Whether an implementation could run here.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ImplStatus {
    /// Command-line name (`ref-f64`, `jack`, ...).
    pub name: String,
    /// Whether it ran on this machine.
    pub available: bool,
    /// Why not, or a note on the device it ran on.
    pub note: Option<String>,
    /// Seconds spent opening it (compiling kernels or the Jack program,
    /// initialising), whether or not it opened.
    #[serde(default)]
    pub open_s: f64,
}

/// The comparison of two implementations at one level.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Comparison {
    /// `ops`, `sdf`, `pixels`, `image`, `unary-exhaustive`.
    pub level: String,
    /// What was compared within the level (vector set, op name, ...).
    pub scope: String,
    /// First implementation.
    pub a: String,
    /// Second implementation.
    pub b: String,
    /// The policy that judged the pair (`bit-exact`, `error figures`).
    pub policy: String,
    /// Cases compared.
    pub cases: u64,
    /// Cases that diverge under the policy.
    pub divergences: u64,
    /// Whether the pair diverges beyond its policy: a divergent case, or a
    /// finding over the whole set (the flip fraction, an oracle that is not
    /// f64). Any such row fails the night, whatever its policy.
    #[serde(default)]
    pub beyond_policy: bool,
    /// The set-level findings beyond policy, one line each.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub findings: Vec<String>,
    /// Error figures, for float policies.
    pub error: Option<ErrorFigures>,
    /// A few divergent cases, in order.
    pub examples: Vec<DivergenceExample>,
}

/// The TestFloat-style cases of one operation at one level, run through
/// the Float316 implementations and compared bit for bit with the first.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct CaseCount {
    /// The operation (`add`, `inv_sqrt`, ...).
    pub op: String,
    /// The TestFloat level (1 or 2).
    pub level: u8,
    /// Cases of the operation at this level.
    pub cases: u64,
    /// The implementations that answered them, the first the one the
    /// others are compared with.
    pub implementations: Vec<String>,
    /// Bit-exact divergences from the first, summed over the others.
    pub divergences: u64,
}

/// One described scene: what it uses, what it never reaches, its cost.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SceneRow {
    /// The description's name.
    pub name: String,
    /// The description file.
    pub file: String,
    /// The shape and combination kinds of its nodes (`sphere`, `union`, ...).
    pub shapes: Vec<String>,
    /// The Float316 operations its program calls, read from the statements.
    pub operations: Vec<String>,
    /// Float316 operations reached over the traced pixels, with call counts.
    pub reached: BTreeMap<String, u64>,
    /// Pixels traced on ref-f316 for `reached` and the domains.
    pub traced_pixels: u64,
    /// Float316 operations the traced pixels never call.
    pub never_reached: Vec<String>,
    /// Operand classes (`sqrt(zero)`, `div(negative,positive)`) and traps
    /// (`div -> trap`) of the reached operations that no traced call hits.
    pub domains_never_reached: Vec<String>,
    /// Whole-image cost on each implementation that renders it.
    pub costs: Vec<SceneCost>,
    /// Implementations that do not render it, and why.
    pub unsupported: Vec<String>,
    /// What the Jack program generated from it costs, when it was made.
    #[serde(default)]
    pub jack: Option<SceneJackCost>,
    /// Its pictures: each leg's render, difference overlays, the Jack
    /// program's cost map.
    #[serde(default)]
    pub pictures: Vec<ScenePicture>,
    /// How each implementation's answers ended, per level: out of the
    /// modelled domain, `Sys.error`, hang.
    #[serde(default)]
    pub outcomes: Vec<SceneOutcomes>,
    /// CPU seconds the step spent on the scene (every thread), where the
    /// system tells.
    #[serde(default)]
    pub cpu_s: Option<f64>,
    /// For a description `harness tune` wrote: the name of the untuned
    /// scene it was tuned from, whose row its saving is measured against.
    #[serde(default)]
    pub tuned_from: Option<String>,
}

/// How one implementation's answers for a described scene ended at one
/// level.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SceneOutcomes {
    pub implementation: String,
    /// `pixels` (every pixel it rendered) or `sdf` (the step's query
    /// points).
    pub level: String,
    pub cases: u64,
    /// Answers out of the modelled domain: each stopped at the one Float316
    /// operation that left it.
    pub out_of_domain: u64,
    pub sys_error: u64,
    pub hang: u64,
}

/// The cost of the Jack program generated from a described scene, measured
/// on every `step`-th pixel of every `step`-th row (the nightly: every
/// pixel).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SceneJackCost {
    pub step: u32,
    pub pixels_measured: u64,
    /// VM instructions per pixel (desktop clock): mean and max.
    pub mean: f64,
    pub max: u64,
    /// `Main.init` and the estimated whole image, VM instructions.
    pub init_instructions: u64,
    pub whole_image_instructions: u64,
    /// The whole image on the official desktop VM emulator at 1.4 M VM
    /// instructions per second, and by the hand-written seed program's
    /// 9 h 45 min there; on our emulator at the rate measured; seconds.
    pub desktop_s: f64,
    pub desktop_seed_scale_s: f64,
    pub ours_s: f64,
    /// Size in VM commands, Hack ROM words estimated with every command in
    /// line and with shared call/return/compare routines, the ROM's words.
    pub vm_commands: u64,
    pub rom_textbook: u64,
    pub rom_shared: u64,
    pub rom_words: u64,
    /// `Main.main` drawing the whole image on our emulator, one thread,
    /// measured (seconds), when it finished.
    #[serde(default)]
    pub main_s: Option<f64>,
}

/// One picture of a described scene.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ScenePicture {
    /// The image, relative path.
    pub image: String,
    pub caption: String,
}

/// The cost of one whole-image render of a described scene.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SceneCost {
    pub implementation: String,
    /// Seconds to make it from the description (lowering; for the GPU,
    /// generating and compiling the kernels).
    pub setup_s: f64,
    /// Seconds for the whole image (kernels compiled beforehand).
    pub render_s: f64,
    pub pixels: u64,
    /// `render_s / pixels`.
    pub per_pixel_s: f64,
}

/// Error against an oracle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ErrorFigures {
    /// Mean absolute error.
    pub mean_abs: f64,
    /// Maximum absolute error.
    pub max_abs: f64,
}

/// One divergent case of a level comparison.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct DivergenceExample {
    /// The input, as text (`add((0,127,8192), (1,126,8192))`, `pixel(3,4)`).
    pub case: String,
    /// What A produced.
    pub a: String,
    /// What B produced.
    pub b: String,
    /// The first divergent Float316 operation, when localized.
    pub first_op: Option<String>,
    /// A command that reproduces the divergence.
    pub repro: Option<String>,
}

/// The harness self-test.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SelfTest {
    /// Whether every check passed.
    pub passed: bool,
    /// One line per check.
    pub lines: Vec<String>,
}

/// One full-image render.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Render {
    /// `impl` or `impl/variant`.
    pub label: String,
    /// Implementation name.
    pub implementation: String,
    /// Precision variant of the reference, if any.
    pub variant: Option<String>,
    /// The dithered image, relative to the report directory.
    pub image: String,
    /// Set-up time (compile, device creation), seconds.
    pub setup_s: f64,
    /// Render time of the whole image, seconds.
    pub render_s: f64,
    /// Pixels rendered.
    pub pixels: u64,
    /// Hack VM instructions executed, for the Jack program.
    pub vm_instructions: Option<u64>,
    /// Whether the dithered image equals the spec's image bit for bit.
    pub identical_to_spec: Option<bool>,
    /// Whether shades (values before dithering) are available.
    pub has_shades: bool,
    /// Pixels whose computation trapped (drawn in the trap colour).
    #[serde(default)]
    pub trapped: u64,
}

/// The comparison of two renders.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ImagePair {
    /// Label of the first render.
    pub a: String,
    /// Label of the second render.
    pub b: String,
    /// Image width, pixels.
    pub width: u32,
    /// Image height, pixels.
    pub height: u32,
    /// Pixels compared.
    pub pixels: u64,
    /// Pixels whose dithered bit differs.
    pub differing_pixels: u64,
    /// Pixels whose shade differs (bit-exact for Float316 pairs).
    pub differing_shades: Option<u64>,
    /// The difference overlay image, relative path.
    pub overlay: String,
    /// Shade error heat map, when both renders have shades.
    pub heat: Option<HeatMap>,
    /// Divergent pixels (dithered bit differs), at most a bounded number.
    pub divergences: Vec<PixelDivergence>,
    /// How the listed pixels' first divergent operations were found, or
    /// why this pair cannot be localized (a float side has no Float316
    /// operations; a screen has no per-pixel trace).
    #[serde(default)]
    pub localization: String,
    /// How many divergent pixels are not listed.
    pub unlisted: u64,
    /// Why a lower precision differs from the oracle, for pairs of one
    /// with the oracle (`harness explain`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub explanation: Option<PairExplanation>,
    /// Both renders come from implementations that must agree bit for
    /// bit: a differing pixel or shade is a divergence.
    #[serde(default)]
    pub bit_exact: bool,
    /// Why the pair diverges beyond its policy (a bit-exact pair that
    /// differs, a float render flipping more pixels than its policy allows
    /// against the oracle), if it does.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub beyond_policy: Option<String>,
}

/// A heat map image and its colour bar.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct HeatMap {
    /// The heat map image, relative path.
    pub image: String,
    /// The colour bar (SVG), relative path.
    pub legend: String,
    /// Mean absolute shade difference over all pixels.
    pub mean_abs: f64,
    /// Maximum absolute shade difference.
    pub max_abs: f64,
    /// Absolute shade difference that 50 %, 95 % and 99 % of the pixels do
    /// not exceed (what a percentile threshold would have to allow).
    #[serde(default)]
    pub percentiles_abs: [f64; 3],
}

/// One pixel whose dithered bit differs between two renders.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PixelDivergence {
    /// Column.
    pub x: u32,
    /// Row.
    pub y: u32,
    /// A's bit (true = white).
    pub a_white: bool,
    /// B's bit.
    pub b_white: bool,
    /// A's shade before dithering, when known.
    pub a_shade: Option<f64>,
    /// B's shade before dithering, when known.
    pub b_shade: Option<f64>,
    /// The first divergent Float316 operation (Float316 pairs, localized;
    /// `None` when the pair cannot be localized, see
    /// [`ImagePair::localization`]).
    pub first_op: Option<String>,
    /// The command that reproduces it.
    pub repro: String,
    /// Its class and root cause against the oracle, when explained.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub explained: Option<String>,
}

/// Why the pixels of a lower-precision render differ from the oracle's.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PairExplanation {
    /// The reference implementation whose pipeline explained them.
    pub explained_by: String,
    /// Whether the explanation holds for the render's implementation (it
    /// agrees with `explained_by` bit for bit), or why not.
    pub holds: String,
    /// Which pixels were explained.
    pub inputs: String,
    /// Pixels per class (threshold flip, control-flow divergence, ...).
    pub classes: Vec<NamedCount>,
    /// Control-flow divergences per decision.
    pub decisions: Vec<NamedCount>,
    /// Top root causes: pixels whose largest contributor a site is.
    pub causes: Vec<CauseRow>,
    /// The pixels coloured by class, relative path (empty: none).
    pub class_map: String,
    /// Colour of each class in the map (`count` is `0xRRGGBB`).
    pub colours: Vec<NamedCount>,
    /// One line per explained pixel when they are few (the largest shade
    /// differences of a pair without flips).
    pub examples: Vec<String>,
    /// Seconds spent explaining.
    pub seconds: f64,
}

/// A name and a number.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct NamedCount {
    pub name: String,
    pub count: u64,
}

/// One root-cause site across many pixels.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct CauseRow {
    /// `op in call path`.
    pub site: String,
    /// Pixels whose largest contributor it is.
    pub pixels: u64,
    /// Their mean share of the error.
    pub mean_share: f64,
}

/// The Jack program's cost per pixel.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct CostMap {
    /// The cost map image, relative path.
    pub image: String,
    /// Its colour bar (SVG), relative path.
    pub legend: String,
    /// Fewest VM instructions for one pixel.
    pub min: u64,
    /// Most VM instructions for one pixel.
    pub max: u64,
    /// Mean VM instructions per pixel.
    pub mean: f64,
}

/// Speed against error.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SpeedError {
    /// One point per implementation and precision variant.
    pub points: Vec<SpeedPoint>,
    /// The plot (SVG), relative path; empty when there was nothing to plot.
    pub plot: String,
    /// The cheapest precision variant whose dithered image equals the
    /// spec's, with its cost, e.g. `ref-f316+newton-3 (1.9 µs per pixel)`.
    pub cheapest_spec_identical: Option<String>,
}

/// Cost and error of one implementation or variant against `ref-f64`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SpeedPoint {
    /// `impl` or `impl/variant`.
    pub label: String,
    /// Seconds per pixel.
    pub time_per_pixel_s: f64,
    /// Hack VM instructions per pixel (Jack program only).
    pub vm_instructions_per_pixel: Option<f64>,
    /// Mean absolute shade error against `ref-f64`.
    pub mean_shade_error: Option<f64>,
    /// Maximum absolute shade error against `ref-f64`.
    pub max_shade_error: Option<f64>,
    /// Dithered pixels that differ from `ref-f64`.
    pub pixel_flips: u64,
    /// Whether the dithered image equals the spec's image.
    pub identical_to_spec: Option<bool>,
}

/// One category of a vector set: the hard-case catalogue of the op
/// vectors, the scene's hard places for SDF queries and pixels.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct StabilityRow {
    /// The vector set (`ops-nightly`, `sdf-nightly`, ...).
    #[serde(default)]
    pub set: String,
    /// Category tag from the vectors crate.
    pub category: String,
    /// Vectors in the category.
    pub vectors: u64,
    /// Outcomes per implementation.
    pub outcomes: BTreeMap<String, OutcomeTally>,
    /// The worst error against f64 found in the category.
    pub worst: Option<WorstError>,
}

/// How many vectors ended in each outcome kind.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct OutcomeTally {
    /// Normal values.
    pub value: u64,
    /// `Sys.error` codes.
    pub sys_error: u64,
    /// Hangs (budget ran out).
    pub hang: u64,
    /// Out of domain.
    pub out_of_domain: u64,
    /// Float316 implementations: vectors whose answer differs from
    /// `ref-f316`'s bit for bit. `None` for float implementations (their
    /// difference is an error, see [`StabilityRow::worst`]) or when
    /// `ref-f316` gave no answers.
    pub diverging: Option<u64>,
}

/// The worst error against f64 of a category (largest relative error
/// over the numbers of every answer that is a value on both sides).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct WorstError {
    /// Which implementation.
    pub implementation: String,
    /// The input.
    pub case: String,
    /// Where it is in its set (`ops-nightly #1234`).
    #[serde(default)]
    pub vector: String,
    /// What it answered, and what `ref-f64` answered.
    #[serde(default)]
    pub answers: String,
    /// A command that reproduces it (paths relative to the report).
    #[serde(default)]
    pub repro: Option<String>,
    /// Absolute error.
    pub abs: f64,
    /// Relative error.
    pub rel: f64,
}

/// One row of `harness bench`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct BenchRow {
    /// Implementation (or `impl/variant`).
    pub implementation: String,
    /// Set-up time, seconds.
    pub setup_s: f64,
    /// Full image time, seconds.
    pub image_s: f64,
    /// Pixels rendered.
    pub pixels: u64,
    /// Seconds per pixel.
    pub per_pixel_s: f64,
    /// Hack VM instructions per pixel (Jack program only).
    pub vm_instructions_per_pixel: Option<f64>,
    /// Mean absolute shade error against `ref-f64`.
    pub mean_shade_error: Option<f64>,
    /// Maximum absolute shade error against `ref-f64`.
    pub max_shade_error: Option<f64>,
    /// Dithered pixels that differ from `ref-f64` (a trap on one side
    /// only counts as one).
    pub pixel_flips: u64,
    /// Pixels that trapped where `ref-f64` answered.
    #[serde(default)]
    pub trapped: u64,
}

impl BenchRow {
    /// Pixels per second.
    pub fn pixels_per_s(&self) -> f64 {
        if self.per_pixel_s > 0.0 {
            1.0 / self.per_pixel_s
        } else {
            0.0
        }
    }
}

impl Report {
    /// An empty report of the current schema.
    pub fn new(meta: RunMeta) -> Self {
        Report {
            schema_version: SCHEMA_VERSION,
            meta,
            ..Report::default()
        }
    }

    /// Divergences over every level comparison whose policy is bit-exact
    /// (the history's trend line).
    pub fn bit_exact_divergences(&self) -> u64 {
        self.comparisons
            .iter()
            .filter(|c| c.policy == crate::BIT_EXACT)
            .map(|c| c.divergences)
            .sum()
    }

    /// Record in `verdict` every comparison of the report (level rows,
    /// image pairs, the self-test; the described scenes' rows are level
    /// rows) with whether it
    /// diverged beyond its policy.
    pub fn add_comparisons_to(&self, verdict: &mut harness::verdict::Verdict) {
        for c in &self.comparisons {
            let beyond = c.beyond_policy.then(|| {
                let mut why = vec![format!("{} divergences ({})", c.divergences, c.policy)];
                why.extend(c.findings.iter().cloned());
                why.join("; ")
            });
            verdict.compared(
                format!("{} vs {} on {} ({})", c.a, c.b, c.scope, c.level),
                c.cases,
                beyond,
            );
        }
        for p in &self.image_pairs {
            verdict.compared(
                format!("{} vs {} image", p.a, p.b),
                p.pixels,
                p.beyond_policy.clone(),
            );
        }
        if let Some(s) = &self.selftest {
            let failed: Vec<&str> = s
                .lines
                .iter()
                .filter(|l| l.contains("FAIL"))
                .map(String::as_str)
                .collect();
            let beyond =
                (!s.passed).then(|| format!("the self-test failed: {}", failed.join("; ")));
            verdict.compared("self-test", s.lines.len() as u64, beyond);
        }
    }

    /// Serialise as pretty JSON.
    pub fn to_json(&self) -> serde_json::Result<String> {
        serde_json::to_string_pretty(self)
    }

    /// Parse `report.json`, refusing another schema version.
    pub fn from_json(text: &str) -> anyhow::Result<Self> {
        let value: serde_json::Value = serde_json::from_str(text)?;
        let version = value.get("schema_version").and_then(|v| v.as_u64());
        anyhow::ensure!(
            version == Some(SCHEMA_VERSION as u64),
            "report schema_version {version:?}, this harness reads {SCHEMA_VERSION}"
        );
        Ok(serde_json::from_value(value)?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use harness::verdict::{Status, Verdict};

    #[test]
    fn a_bench_rows_speed_is_the_inverse_of_its_time_per_pixel_and_0_without_one() {
        let row = |per_pixel_s| BenchRow {
            per_pixel_s,
            ..BenchRow::default()
        };
        assert_eq!(row(0.25).pixels_per_s(), 4.0);
        assert_eq!(row(0.0).pixels_per_s(), 0.0);
    }

    /// The self-test joins the verdict: a failed one is beyond policy,
    /// naming its failing checks; a passed one is within.
    #[test]
    fn a_failed_self_test_fails_the_verdict_with_its_failing_checks() {
        for (passed, lines) in [
            (true, vec!["ok add", "ok mul"]),
            (false, vec!["ok add", "FAIL mul: 3 of 9"]),
        ] {
            let mut report = Report::new(RunMeta::default());
            report.selftest = Some(SelfTest {
                passed,
                lines: lines.iter().map(|l| l.to_string()).collect(),
            });
            let mut verdict = Verdict::new(false);
            report.add_comparisons_to(&mut verdict);
            assert_eq!(verdict.cases(), 2);
            if passed {
                assert_eq!(verdict.status(), Status::Agreed);
            } else {
                assert_eq!(verdict.status(), Status::Diverged);
                let why = verdict.compared[0].beyond_policy.clone().unwrap();
                assert_eq!(why, "the self-test failed: FAIL mul: 3 of 9");
            }
        }
    }
}
