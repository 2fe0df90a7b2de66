//! The scene step: every described scene of the night (`--scene`, default
//! every shipped one in `vectors/scenes/`, the test scene and the examples
//! in `examples/scenes/`) rendered from its description on each opened
//! implementation that supports it: the Float316 ones compared bit for bit
//! (gpu-f316 and the generated Jack program against ref-f316 on every
//! pixel's shade and level, and on SDF queries: uniform ones and those
//! derived from the scene, near its surfaces, seams and cell boundaries;
//! the Jack program's own screen too, [`super::scene_jack`]), the float ones
//! by their error against ref-f64; and per scene what it uses (shapes,
//! Float316 operations), what it never reaches (operations, operand
//! classes, traps, over traced ref-f316 pixels), how each implementation's
//! answers end (out of domain, `Sys.error`, hang), its cost per pixel on
//! each implementation and the CPU time the step spent on it.

use super::step::Step;
use super::Night;
use super::{scene_jack, scene_pictures};
use crate::commands::render_scene::{compile_gpu, kernel_image};
use anyhow::{bail, Context, Result};
use common::{Op, Outcome, OutcomeKind, TraceRecord, F316};
use harness::compare::Thresholds;
use harness::implementation::Numbers;
use harness::verdict::Missing;
use harness_report::model::{
    Comparison, DivergenceExample, ErrorFigures, SceneCost, SceneJackCost, SceneOutcomes, SceneRow,
};
use harness_report::{BIT_EXACT, ERROR_FIGURES};
use reference::{Described, RefImpl, SceneImage, ScenePixel, SdfValue, Settings};
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The folder of the shipped scenes.
pub fn shipped_dir() -> PathBuf {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../vectors/scenes");
    dir.canonicalize().unwrap_or(dir)
}

/// Every shipped scene, by file name order.
pub fn shipped() -> Result<Vec<PathBuf>> {
    descriptions(&shipped_dir())
}

/// The scene no shipped description uses the shapes of: carved shapes
/// (`vectors/scenes/tests/carved.json`), a scene nobody ported by hand.
pub const TEST_SCENE: &str = "tests/carved.json";

/// The folder of the example scenes: descriptions written as a user
/// writes their own.
pub fn examples_dir() -> PathBuf {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/scenes");
    dir.canonicalize().unwrap_or(dir)
}

/// The `.json` files of `dir`, by file name order.
fn descriptions(dir: &Path) -> Result<Vec<PathBuf>> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .with_context(|| format!("cannot list {}", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    files.sort();
    Ok(files)
}

/// The scenes of a night without `--scene`: every shipped one,
/// [`TEST_SCENE`], then every example of [`examples_dir`].
pub fn nightly_default() -> Result<Vec<PathBuf>> {
    let mut files = shipped()?;
    files.push(shipped_dir().join(TEST_SCENE));
    files.extend(descriptions(&examples_dir())?);
    Ok(files)
}

/// The file of `--scene NAME`: a shipped scene's name, or a path to a
/// description.
pub fn resolve(name: &str) -> Result<PathBuf> {
    let shipped_file = shipped_dir().join(format!("{name}.json"));
    if !name.contains('/') && shipped_file.is_file() {
        return Ok(shipped_file);
    }
    let path = PathBuf::from(name);
    if path.is_file() {
        return Ok(path);
    }
    let names: Vec<String> = shipped()?
        .iter()
        .filter_map(|f| f.file_stem().map(|s| s.to_string_lossy().into_owned()))
        .collect();
    bail!(
        "--scene: `{name}` is neither a shipped scene ({}) nor a file",
        names.join(", ")
    )
}

/// Every `TRACE_STRIDE`-th pixel in x and in y is traced for coverage.
const TRACE_STRIDE: usize = 8;

/// SDF query points compared per scene.
const SDF_POINTS: usize = 512;

/// The seed of the scene-derived SDF points
/// (`vectors::gen::scene_derived`).
const DERIVED_SEED: u64 = 17;

/// Examples kept per comparison.
const EXAMPLES: usize = 5;

/// The scene step.
pub struct Scenes;

impl Step for Scenes {
    fn key(&self) -> &'static str {
        "scenes"
    }

    fn name(&self) -> String {
        "described scenes".into()
    }

    fn run(&self, night: &mut Night<'_>) -> Result<()> {
        let files = night.options.scenes.clone();
        each_scene(night, &files)
    }
}

/// Each of `files` through every opened implementation that supports it
/// (a scene that cannot be compared is counted as not compared).
pub(super) fn each_scene(night: &mut Night<'_>, files: &[PathBuf]) -> Result<()> {
    let wants_gpu = ["gpu-f316", "gpu-f32"]
        .iter()
        .any(|n| night.find(n).is_some());
    let gpu = if wants_gpu {
        match gpu::Gpu::new() {
            Ok(g) => Some(g),
            Err(e) => {
                night.not_compared(
                    "scenes on the GPU".into(),
                    Missing::Unavailable,
                    format!("no GPU for the generated kernels: {e}"),
                );
                None
            }
        }
    } else {
        None
    };
    for file in files {
        if let Err(e) = one_scene(night, gpu.as_ref(), file) {
            night.not_compared(
                format!("scene {}", file.display()),
                Missing::Failed,
                format!("{e:#}"),
            );
        }
    }
    Ok(())
}

/// One scene through every opened implementation that supports it.
fn one_scene(night: &mut Night<'_>, gpu: Option<&gpu::Gpu>, file: &Path) -> Result<()> {
    let cpu_start = crate::cpu::process_seconds();
    let checked = scene::load(file)?;
    let name = checked.description.name.clone();
    let scope = format!("scene {name}");
    let mut row = SceneRow {
        name: name.clone(),
        file: file.display().to_string(),
        shapes: shapes(&checked),
        ..SceneRow::default()
    };
    let mut images: Vec<(String, SceneImage)> = Vec::new();
    let mut f316 = None;
    for imp in [RefImpl::F64, RefImpl::F32, RefImpl::F316] {
        if night.find(imp.name()).is_none() {
            continue;
        }
        let start = Instant::now();
        let described = Described::new(imp, &checked, Settings::default())?;
        let setup_s = start.elapsed().as_secs_f64();
        let start = Instant::now();
        let image = described.render();
        row.costs.push(cost(
            imp.name(),
            setup_s,
            start.elapsed().as_secs_f64(),
            &image,
        ));
        images.push((imp.name().into(), image));
        if imp == RefImpl::F316 {
            f316 = Some(described);
        }
    }
    let mut f316_kernel = None;
    for (label, form) in [("gpu-f32", RefImpl::F32), ("gpu-f316", RefImpl::F316)] {
        let Some(gpu) = gpu.filter(|_| night.find(label).is_some()) else {
            continue;
        };
        // Compiled (and warmed up) apart from the timed render.
        let start = Instant::now();
        let (kernel, program) = compile_gpu(gpu, form, &checked)?;
        let setup_s = start.elapsed().as_secs_f64();
        let start = Instant::now();
        let image = kernel_image(gpu, &kernel, &program)?;
        row.costs
            .push(cost(label, setup_s, start.elapsed().as_secs_f64(), &image));
        images.push((label.into(), image));
        if form == RefImpl::F316 {
            f316_kernel = Some(kernel);
        }
    }
    if name == "seed" {
        row.unsupported.push(
            "jack: the hand-written program answers the seed scene (compared in the levels, renders and pairs steps)".into(),
        );
    }
    let mut comparisons = Vec::new();
    if let (Some(a), Some(b)) = (
        find_image(&images, "ref-f316"),
        find_image(&images, "gpu-f316"),
    ) {
        comparisons.push(bit_exact_pixels(&scope, "ref-f316", "gpu-f316", a, b));
    }
    let mut points = sdf_points();
    let derived = vectors::gen::scene_derived::sdf_set(&checked, DERIVED_SEED)?;
    points.extend(derived.vectors.iter().filter_map(|v| match v {
        vectors::Vector::Sdf(s) => Some(s.p),
        _ => None,
    }));
    let ref_sdf: Vec<Outcome<SdfValue>> = match &f316 {
        Some(d) => points.iter().map(|&p| d.sdf(p)).collect(),
        None => Vec::new(),
    };
    let mut sdf_outcomes = Vec::new();
    if !ref_sdf.is_empty() {
        sdf_outcomes.push(outcomes("ref-f316", "sdf", &ref_sdf));
    }
    if let (Some(gpu), Some(k)) = (gpu, f316_kernel.as_ref().filter(|_| f316.is_some())) {
        let theirs = gpu_sdf(gpu, k, &points)?;
        comparisons.push(compare_sdf(&scope, &points, &ref_sdf, &theirs));
        sdf_outcomes.push(outcomes("gpu-f316", "sdf", &theirs));
    }
    // The generated Jack program, where the night has the jack kind and
    // ref-f316 to compare it with.
    let jack = if f316.is_some() && night.find("jack").is_some() {
        let judges = scene_jack::Judges {
            file,
            scope: &scope,
            points: &points,
            ref_sdf: &ref_sdf,
            images: &images,
        };
        jack_leg(night, &judges, &mut row)
    } else {
        None
    };
    if let Some(leg) = &jack {
        sdf_outcomes.push(outcomes(scene_jack::LABEL, "sdf", &leg.sdf));
        comparisons.extend(leg.comparisons.iter().cloned());
        images.push((scene_jack::LABEL.into(), leg.image.clone()));
    }
    // Pixels first, in the legs' order, then the SDF answers.
    row.outcomes = images
        .iter()
        .map(|(label, image)| outcomes(label, "pixels", &image.pixels))
        .chain(sdf_outcomes)
        .collect();
    if let Some(oracle) = find_image(&images, "ref-f64") {
        for label in ["ref-f32", "gpu-f32"] {
            if let Some(image) = find_image(&images, label) {
                comparisons.push(float_pixels(&scope, oracle, label, image));
            }
        }
    }
    if let Some(d) = &f316 {
        coverage(&mut row, d)?;
    }
    row.pictures = scene_pictures::pictures(&night.builder, &name, &images, jack.as_ref())?;
    row.cpu_s = cpu_start
        .zip(crate::cpu::process_seconds())
        .map(|(a, b)| b - a);
    let report = night.builder.report_mut();
    report.comparisons.extend(comparisons);
    report.scenes.push(row);
    Ok(())
}

/// Run the generated Jack program's leg and put its costs into `row`; a
/// leg that fails is not compared (and fails the night).
fn jack_leg(
    night: &mut Night<'_>,
    judges: &scene_jack::Judges<'_>,
    row: &mut SceneRow,
) -> Option<scene_jack::JackLeg> {
    let leg = match scene_jack::run(night, judges) {
        Ok(leg) => leg,
        Err(e) => {
            night.not_compared(
                format!("{}: {}", judges.scope, scene_jack::LABEL),
                Missing::Failed,
                format!("{e:#}"),
            );
            return None;
        }
    };
    let drawn = leg.image.pixels.len() as u64;
    let timed = |implementation: String, seconds: f64| SceneCost {
        implementation,
        setup_s: 0.0,
        render_s: seconds,
        pixels: drawn,
        per_pixel_s: seconds / drawn.max(1) as f64,
    };
    row.costs
        .push(timed(scene_jack::LABEL.into(), leg.pixels_s));
    if let Ok(screen) = &leg.screen {
        row.costs
            .push(timed(scene_jack::screen_label(), screen.seconds));
    }
    row.jack = Some(jack_cost(&leg));
    Some(leg)
}

/// The render labelled `label` among `images`.
fn find_image<'a>(images: &'a [(String, SceneImage)], label: &str) -> Option<&'a SceneImage> {
    images.iter().find(|(l, _)| l == label).map(|(_, i)| i)
}

/// How `label`'s `answers` at `level` end: counted by kind.
fn outcomes<T>(label: &str, level: &str, answers: &[Outcome<T>]) -> SceneOutcomes {
    let count = |kind: OutcomeKind| answers.iter().filter(|a| a.kind() == kind).count() as u64;
    SceneOutcomes {
        implementation: label.into(),
        level: level.into(),
        cases: answers.len() as u64,
        out_of_domain: count(OutcomeKind::OutOfDomain),
        sys_error: count(OutcomeKind::SysError),
        hang: count(OutcomeKind::Hang),
    }
}

/// The report's figures of a generated program's cost: its pixels'
/// counts, and `Main.main`'s time on our emulator where it finished.
fn jack_cost(leg: &scene_jack::JackLeg) -> SceneJackCost {
    let c = &leg.measured.cost;
    SceneJackCost {
        step: c.step,
        pixels_measured: c.pixels_measured as u64,
        mean: c.mean,
        max: c.max,
        init_instructions: c.init_instructions,
        whole_image_instructions: c.whole_image_instructions,
        desktop_s: c.desktop_s,
        desktop_seed_scale_s: c.desktop_seed_scale_s,
        ours_s: c.ours_s,
        vm_commands: c.vm_commands as u64,
        rom_textbook: c.rom_textbook as u64,
        rom_shared: c.rom_shared as u64,
        rom_words: c.rom_words as u64,
        main_s: leg.screen.as_ref().ok().map(|s| s.seconds),
    }
}

fn cost(label: &str, setup_s: f64, render_s: f64, image: &SceneImage) -> SceneCost {
    let pixels = image.pixels.len() as u64;
    SceneCost {
        implementation: label.into(),
        setup_s,
        render_s,
        pixels,
        per_pixel_s: render_s / pixels.max(1) as f64,
    }
}

/// The kinds of the description's nodes.
fn shapes(checked: &scene::Checked) -> Vec<String> {
    let kinds: BTreeSet<&str> = checked
        .description
        .nodes
        .values()
        .map(scene::check::node_kind)
        .collect();
    kinds.into_iter().map(String::from).collect()
}

fn pixel_text(p: Option<&Outcome<ScenePixel>>) -> String {
    match p {
        Some(Outcome::Value(v)) => format!("{:?} level {}", v.value.triple, v.level),
        Some(o) => format!("{o:?}"),
        None => "no pixel".into(),
    }
}

pub(super) fn example(case: String, a: String, b: String) -> DivergenceExample {
    DivergenceExample {
        case,
        a,
        b,
        first_op: None,
        repro: None,
    }
}

/// Two answer lists side by side over the longer one: an answer only one
/// list has is paired with `None` (a divergence, never dropped).
fn side_by_side<'a, T, U>(
    a: &'a [T],
    b: &'a [U],
) -> impl Iterator<Item = (usize, Option<&'a T>, Option<&'a U>)> {
    (0..a.len().max(b.len())).map(move |i| (i, a.get(i), b.get(i)))
}

/// One divergence of `c`, kept as an example while there are few.
pub(super) fn diverged(c: &mut Comparison, case: impl FnOnce() -> DivergenceExample) {
    c.divergences += 1;
    c.beyond_policy = true;
    if c.examples.len() < EXAMPLES {
        c.examples.push(case());
    }
}

/// Two images of different sizes diverge once for their size (their
/// pixels are then compared in order, over the larger one).
fn compare_sizes(c: &mut Comparison, a: &SceneImage, b: &SceneImage) {
    if (a.width, a.height) != (b.width, b.height) {
        c.cases += 1;
        diverged(c, || {
            example(
                "image size".into(),
                format!("{}x{}", a.width, a.height),
                format!("{}x{}", b.width, b.height),
            )
        });
    }
}

/// The pixel at index `i` of an image `width` wide.
fn pixel_case(i: usize, width: usize) -> String {
    let width = width.max(1);
    format!("pixel({},{})", i % width, i / width)
}

/// Two Float316 renders `a` and `b` (labelled so) on every pixel they
/// hold: triple, level and outcome.
pub(super) fn bit_exact_pixels(
    scope: &str,
    a_label: &str,
    b_label: &str,
    a: &SceneImage,
    b: &SceneImage,
) -> Comparison {
    let mut c = comparison("pixels", scope, a_label, b_label, BIT_EXACT);
    compare_sizes(&mut c, a, b);
    for (i, pa, pb) in side_by_side(&a.pixels, &b.pixels) {
        c.cases += 1;
        let same = pa.zip(pb).is_some_and(|(pa, pb)| {
            pa.same_as(pb, |x, y| {
                x.level == y.level && x.value.triple == y.value.triple
            })
        });
        if !same {
            diverged(&mut c, || {
                example(pixel_case(i, a.width), pixel_text(pa), pixel_text(pb))
            });
        }
    }
    c
}

/// Deterministic query points over the box [-4, 4]^3 (SplitMix64).
fn sdf_points() -> Vec<[F316; 3]> {
    let mut rng = common::SplitMix64::new(0x5eed);
    (0..SDF_POINTS)
        .map(|_| {
            [(); 3].map(|_| {
                F316::from_f64_truncating(rng.unit() * 8.0 - 4.0).expect("|x| <= 4 is in range")
            })
        })
        .collect()
}

/// gpu-f316's SDF at `points`: distance and colour triples.
fn gpu_sdf(
    gpu: &gpu::Gpu,
    kernel: &gpu::SceneKernel,
    points: &[[F316; 3]],
) -> Result<Vec<SdfTriples>> {
    Ok(kernel
        .sdf(gpu, points)?
        .into_iter()
        .map(|o| o.map(|(sd, col)| (sd.triple, col.triple)))
        .collect())
}

/// Another Float316 implementation's SDF answer: distance and colour
/// triples (`None`: it gave no Float316 number).
pub(super) type SdfTriples = Outcome<(Option<F316>, Option<F316>)>;

/// ref-f316's answers `ours` at each of `points` against `theirs`,
/// another implementation's answers to them in order (gpu-f316's; a point
/// it did not answer diverges).
pub(super) fn compare_sdf(
    scope: &str,
    points: &[[F316; 3]],
    ours: &[Outcome<SdfValue>],
    theirs: &[SdfTriples],
) -> Comparison {
    let mut c = comparison("sdf", scope, "ref-f316", "gpu-f316", BIT_EXACT);
    for (i, p, g) in side_by_side(points, theirs) {
        c.cases += 1;
        let point = p.map_or_else(
            || "an answer to no point".into(),
            |p| format!("sdf({:?},{:?},{:?})", p[0], p[1], p[2]),
        );
        let r = p.and(ours.get(i));
        let same = r.zip(g).is_some_and(|(r, g)| {
            r.same_as(g, |v, &(sd, col)| v.sd.triple == sd && v.col.triple == col)
        });
        if !same {
            diverged(&mut c, || {
                example(
                    point,
                    r.map_or_else(|| "no point".into(), |r| format!("{r:?}")),
                    g.map_or_else(|| "no answer".into(), |g| format!("{g:?}")),
                )
            });
        }
    }
    c
}

/// A float implementation's shades against ref-f64's: error figures over
/// the pixels both answer. A pixel whose output level differs is a flip,
/// judged with the others by the policy's flip fraction (f32's: 1%); a
/// pixel whose outcome differs (a trap against a value, a `Sys.error`'s
/// code) or that one image lacks diverges by itself.
fn float_pixels(scope: &str, oracle: &SceneImage, label: &str, image: &SceneImage) -> Comparison {
    let mut c = comparison("pixels", scope, "ref-f64", label, ERROR_FIGURES);
    compare_sizes(&mut c, oracle, image);
    let (mut sum, mut max, mut n, mut flips) = (0.0f64, 0.0f64, 0u64, 0u64);
    for (i, o, p) in side_by_side(&oracle.pixels, &image.pixels) {
        c.cases += 1;
        match (o, p) {
            (Some(Outcome::Value(x)), Some(Outcome::Value(y))) => {
                let e = (x.value.value - y.value.value).abs();
                sum += e;
                max = max.max(e);
                n += 1;
                flips += u64::from(x.level != y.level);
            }
            _ if o.zip(p).is_some_and(|(o, p)| o.same_as(p, |_, _| true)) => {}
            _ => diverged(&mut c, || {
                let text = |q: Option<&Outcome<ScenePixel>>| {
                    q.map_or_else(|| "no pixel".into(), |q| format!("{q:?}"))
                };
                example(pixel_case(i, oracle.width), text(o), text(p))
            }),
        }
    }
    let limit = Thresholds::for_subject(Numbers::F32).max_flip_fraction;
    let fraction = flips as f64 / c.cases.max(1) as f64;
    if fraction > limit {
        c.beyond_policy = true;
        c.findings.push(format!(
            "{flips} of {} pixels change level ({:.3}%), over the policy's {:.3}%",
            c.cases,
            100.0 * fraction,
            100.0 * limit
        ));
    }
    c.error = Some(ErrorFigures {
        mean_abs: sum / n.max(1) as f64,
        max_abs: max,
    });
    c
}

pub(super) fn comparison(level: &str, scope: &str, a: &str, b: &str, policy: &str) -> Comparison {
    Comparison {
        level: level.into(),
        scope: scope.into(),
        a: a.into(),
        b: b.into(),
        policy: policy.into(),
        ..Comparison::default()
    }
}

/// The sign class of an operand.
fn class(v: F316) -> &'static str {
    let x = v.to_f64();
    if x < 0.0 {
        "negative"
    } else if x == 0.0 {
        "zero"
    } else {
        "positive"
    }
}

const CLASSES: [&str; 3] = ["negative", "zero", "positive"];

/// The domains of `op`: every operand class combination, and a trap.
fn domains(op: Op) -> Vec<String> {
    let mut out: Vec<String> = if op.arity() == 1 {
        CLASSES.iter().map(|a| format!("{op}({a})")).collect()
    } else {
        CLASSES
            .iter()
            .flat_map(|a| CLASSES.iter().map(move |b| format!("{op}({a},{b})")))
            .collect()
    };
    out.push(format!("{op} -> trap"));
    out
}

/// The domains one call hits.
fn hits(r: &TraceRecord) -> [Option<String>; 2] {
    let classes: Vec<&str> = r.args.iter().map(|&a| class(a)).collect();
    let trap = !matches!(r.result, Outcome::Value(_));
    [
        Some(format!("{}({})", r.op, classes.join(","))),
        trap.then(|| format!("{} -> trap", r.op)),
    ]
}

/// What ref-f316 reaches over every `TRACE_STRIDE`-th pixel in x and y,
/// and the operations of the program's statements.
fn coverage(row: &mut SceneRow, f316: &Described) -> Result<()> {
    let program = f316.program();
    row.operations = scene::stats::operations(program)
        .into_iter()
        .map(String::from)
        .collect();
    let (w, h) = (program.pixels.width, program.pixels.height);
    let mut reached: BTreeMap<Op, u64> = BTreeMap::new();
    let mut seen: BTreeSet<String> = BTreeSet::new();
    for y in (0..h).step_by(TRACE_STRIDE) {
        for x in (0..w).step_by(TRACE_STRIDE) {
            let trace = f316.trace_pixel(x, y)?;
            row.traced_pixels += 1;
            for r in &trace.records {
                *reached.entry(r.op).or_default() += 1;
                seen.extend(hits(r).into_iter().flatten());
            }
        }
    }
    row.never_reached = Op::ALL
        .iter()
        .filter(|op| !reached.contains_key(op))
        .map(|op| op.to_string())
        .collect();
    row.domains_never_reached = reached
        .keys()
        .flat_map(|&op| domains(op))
        .filter(|d| !seen.contains(d))
        .collect();
    row.reached = reached
        .into_iter()
        .map(|(op, n)| (op.to_string(), n))
        .collect();
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_shipped_scene_resolves_by_name() {
        let files = shipped().unwrap();
        let names: Vec<String> = files
            .iter()
            .map(|f| f.file_stem().unwrap().to_string_lossy().into_owned())
            .collect();
        assert_eq!(names, ["rtdemo", "sdf-engine", "seed", "toon"]);
        for (name, file) in names.iter().zip(&files) {
            assert_eq!(&resolve(name).unwrap(), file);
        }
        let err = resolve("no-such-scene").unwrap_err().to_string();
        assert!(err.contains("rtdemo, sdf-engine, seed, toon"), "{err}");
        let night = nightly_default().unwrap();
        assert_eq!(night[..4], files[..]);
        assert!(night[4].is_file() && night[4].ends_with(TEST_SCENE));
        assert!(
            night[5..]
                .iter()
                .any(|f| f.ends_with("examples/scenes/still-life.json")),
            "{night:?}"
        );
    }

    fn pixel(level: u8) -> Outcome<ScenePixel> {
        Outcome::Value(ScenePixel {
            value: reference::Scalar {
                value: 0.5,
                triple: Some(F316::new(0, 126, 8192)),
            },
            level,
        })
    }

    fn image(width: usize, pixels: Vec<Outcome<ScenePixel>>) -> SceneImage {
        SceneImage {
            width,
            height: pixels.len() / width,
            levels: 2,
            pixels,
        }
    }

    /// Both pixel comparisons, bit-exact and by error figures, of `a`
    /// against `b`: their (cases, divergences).
    fn both(a: &SceneImage, b: &SceneImage) -> [(u64, u64); 2] {
        [
            bit_exact_pixels("s", "a", "b", a, b),
            float_pixels("s", a, "x", b),
        ]
        .map(|c| (c.cases, c.divergences))
    }

    #[test]
    fn pixels_differing_only_in_their_sys_error_code_diverge() {
        let a = image(2, vec![pixel(1), Outcome::SysError(3)]);
        assert_eq!(both(&a, &a), [(2, 0); 2]);
        let b = image(2, vec![pixel(1), Outcome::SysError(4)]);
        assert_eq!(both(&a, &b), [(2, 1); 2]);
        let c = bit_exact_pixels("s", "a", "b", &a, &b);
        assert_eq!(c.examples[0].case, "pixel(1,0)");
        assert_eq!(
            (c.examples[0].a.as_str(), c.examples[0].b.as_str()),
            ("SysError(3)", "SysError(4)")
        );
        let hang = image(2, vec![pixel(1), Outcome::Hang]);
        assert_eq!(both(&a, &hang), [(2, 1); 2]);
    }

    /// A float image's level flips are judged together by f32's flip
    /// fraction (1%), not one by one.
    #[test]
    fn level_flips_of_a_float_image_are_judged_by_the_flip_fraction() {
        let oracle = image(200, vec![pixel(1); 200]);
        let mut pixels = vec![pixel(1); 200];
        pixels[7] = pixel(0);
        pixels[9] = pixel(0);
        let two = float_pixels("s", &oracle, "x", &image(200, pixels.clone()));
        assert_eq!((two.divergences, two.beyond_policy), (0, false), "1% flip");
        pixels[11] = pixel(0);
        let three = float_pixels("s", &oracle, "x", &image(200, pixels));
        assert_eq!((three.divergences, three.beyond_policy), (0, true));
        assert_eq!(
            three.findings,
            ["3 of 200 pixels change level (1.500%), over the policy's 1.000%"]
        );
    }

    #[test]
    fn a_missing_pixel_or_another_size_diverges() {
        let a = image(2, vec![pixel(1), pixel(0), pixel(1), pixel(0)]);
        let short = SceneImage {
            pixels: a.pixels[..3].to_vec(),
            ..a.clone()
        };
        assert_eq!(both(&a, &short), [(4, 1); 2]);
        assert_eq!(both(&short, &a), [(4, 1); 2]);
        let c = bit_exact_pixels("s", "a", "b", &a, &short);
        assert_eq!(
            (c.examples[0].case.as_str(), c.examples[0].b.as_str()),
            ("pixel(1,1)", "no pixel")
        );
        // The same pixels, four in a row: the size diverges.
        let row = image(4, a.pixels.clone());
        assert_eq!(both(&a, &row), [(5, 1); 2]);
        assert_eq!(
            bit_exact_pixels("s", "a", "b", &a, &row).examples[0].case,
            "image size"
        );
    }

    #[test]
    fn sdf_answers_compare_sys_error_codes_and_count_missing_answers() {
        let points = [[F316::ZERO; 3], [F316::ONE; 3]];
        let s = reference::Scalar {
            value: 1.0,
            triple: Some(F316::ONE),
        };
        let ours = [
            Outcome::SysError(3),
            Outcome::Value(SdfValue { sd: s, col: s }),
        ];
        let one = Some(F316::ONE);
        let count = |theirs: &[SdfTriples]| {
            let c = compare_sdf("s", &points, &ours, theirs);
            (c.cases, c.divergences)
        };
        assert_eq!(
            count(&[Outcome::SysError(3), Outcome::Value((one, one))]),
            (2, 0)
        );
        assert_eq!(
            count(&[Outcome::SysError(5), Outcome::Value((one, one))]),
            (2, 1)
        );
        assert_eq!(count(&[Outcome::SysError(3)]), (2, 1));
        assert_eq!(
            count(&[
                Outcome::SysError(3),
                Outcome::Value((one, one)),
                Outcome::Hang
            ]),
            (3, 1)
        );
    }

    #[test]
    fn a_call_hits_its_operand_classes_and_a_trap() {
        let r = TraceRecord {
            op: Op::Div,
            args: vec![F316::NEG_ZERO, F316::from_f64_truncating(-2.0).unwrap()],
            result: Outcome::SysError(3),
            path: Vec::new(),
        };
        let [classes, trap] = hits(&r);
        assert_eq!(classes.as_deref(), Some("div(zero,negative)"));
        assert_eq!(trap.as_deref(), Some("div -> trap"));
        assert!(domains(Op::Div).contains(&"div(zero,negative)".to_string()));
        assert_eq!(domains(Op::Sqrt).len(), 4);
    }
}
