//! The `jack` kind: a Jack program on the Hack VM emulator, reached through
//! its bindings (`docs/bindings.md`). The built-in `jack` is the seed
//! raymarcher with `impls/jack/raymarcher/bindings.toml`; a declared
//! `[impl.NAME]` names a program folder and binds it, inline or in a
//! bindings file. Every query runs on a clone of the program's ready
//! snapshot; op traces come from the emulator watching the bound operation
//! functions. The image level renders through the pixel statements, pixels
//! in parallel, when they give the white bit; else it runs the whole
//! program where `capture` is bound. A shade the pixel statements give
//! alone (or before the program's clamp) is clamped and dithered with
//! ref-f316's own operations, as the reference's pipeline does.
//!
//! The fault `web-divide` runs a program with the web IDE's flooring
//! `Math.divide` in place of its profile's; everything else (the compiler's
//! checks, the OS, the memory layout) stays its profile's.

use crate::cast::entry::{Entry, Kind, Opener, Request, VariantInfo, VariantRole};
use crate::cast::file::{FieldError, Fields};
use crate::implementation::{
    Answer, Bitmap, Failure, FailureKind, ImageAnswers, ImplError, Implementation, Num, Numbers,
};
use common::image_consts::{HEIGHT, WIDTH};
use common::{Op, Outcome, TraceRecord};
pub use jack::Profile;
use jack::{
    Bindings, BoundPixel, BoundProgram, Budgets, DivideRule, JackError, JackProgram, WholeRun,
};
use serde::de::IntoDeserializer;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use vectors::{Level, Vector};

/// The `jack` kind.
pub struct JackKind;

/// The fault that gives the program the web IDE's flooring `Math.divide`.
const WEB_DIVIDE: &str = "web-divide";

/// Instructions a whole-program run may take (the seed program takes 21 G).
const WHOLE_BUDGET: u64 = 100_000_000_000;

/// Where a program's sources come from.
#[derive(Clone, Debug)]
enum Source {
    /// The seed raymarcher, embedded in the `jack` crate.
    Seed,
    /// A folder of .jack or .vm files.
    Folder(PathBuf),
    /// The cache folder of a program generated from a scene description.
    Generated(PathBuf),
}

/// The levels `bindings` can answer.
fn levels(b: &Bindings) -> Vec<Level> {
    let mut levels = Vec::new();
    if !b.ops.is_empty() {
        levels.push(Level::Ops);
    }
    if b.sdf.is_some() {
        levels.push(Level::Sdf);
    }
    if b.pixel.is_some() {
        levels.push(Level::Pixels);
    }
    if b.pixel.is_some() || b.capture.is_some() {
        levels.push(Level::Image);
    }
    levels
}

fn entry(
    name: &str,
    source: Source,
    profile: Profile,
    bindings: Bindings,
    places: Places,
) -> Entry {
    let levels = levels(&bindings);
    Entry::new(
        name,
        "jack",
        Numbers::Float316,
        JackOpener {
            source,
            profile,
            bindings,
            places,
        },
    )
    .levels(&levels)
    .traces()
    .slow()
    .variants(vec![VariantInfo {
        name: WEB_DIVIDE.into(),
        role: VariantRole::Fault,
    }])
}

/// The seed raymarcher's bindings.
fn seed_bindings() -> Bindings {
    toml::from_str(jack::sources::BINDINGS).expect("the raymarcher's bindings parse")
}

/// The binding fields of an `[impl.NAME]` table.
const BINDING_FIELDS: [&str; 11] = [
    "ready",
    "float",
    "vec3",
    "sdf_result",
    "ops",
    "sdf",
    "pixel",
    "pixel_shade",
    "capture",
    "out_of_domain",
    "budget",
];

/// Read field `key` of `fields` as a `T`; errors located in the file.
fn part<T: serde::de::DeserializeOwned>(
    fields: &mut Fields<'_>,
    key: &str,
) -> Result<Option<T>, FieldError> {
    let Some(value) = fields.raw(key) else {
        return Ok(None);
    };
    T::deserialize(value.clone().into_deserializer())
        .map(Some)
        .map_err(|e| {
            let at = e.span().map_or(value.span().start, |s| s.start);
            fields.error_at(key, at, e.message().trim_end().to_string())
        })
}

/// Where each binding field was written, by its path in the bindings
/// (`ops.add`, `pixel[1]`, `ready.until_call`): a binding error found when
/// the program is opened is located as a TOML error is.
#[derive(Clone, Debug, Default)]
struct Places(Vec<(String, FieldError)>);

impl Places {
    /// Every value under `value`, at `path`; `at` locates a value's offset.
    fn walk(
        &mut self,
        value: &toml::Spanned<toml::de::DeValue<'_>>,
        path: String,
        at: &dyn Fn(&str, usize) -> FieldError,
    ) {
        use toml::de::DeValue;
        self.0.push((path.clone(), at(&path, value.span().start)));
        match value.get_ref() {
            DeValue::Table(t) => {
                for (k, v) in t.iter() {
                    self.walk(v, format!("{path}.{}", k.get_ref()), at);
                }
            }
            DeValue::Array(items) => {
                for (i, v) in items.iter().enumerate() {
                    self.walk(v, format!("{path}[{i}]"), at);
                }
            }
            _ => {}
        }
    }

    /// `e` located at its field's value (or the nearest enclosing one
    /// written): `FILE:LINE:COL: FIELD: message`.
    fn locate(&self, e: &jack::BindError) -> String {
        let mut path = e.field.as_str();
        loop {
            if let Some((_, place)) = self.0.iter().find(|(p, _)| p == path) {
                let mut place = place.clone();
                place.field = format!("{}{}", place.field, &e.field[path.len()..]);
                place.message = format!("bad binding: {}", e.message);
                return place.to_string();
            }
            match path.rfind(['.', '[']) {
                Some(i) => path = &path[..i],
                None => return format!("bad binding {e}"),
            }
        }
    }
}

/// The bindings file `path` with its text: the bindings, and where each
/// field was written.
fn bindings_file(path: &Path, text: &str) -> Result<(Bindings, Places), FieldError> {
    let mut places = Places::default();
    let source = crate::cast::file::Source { file: path, text };
    let bindings = toml::from_str(text).map_err(|e| {
        let at = e.span().map_or(0, |s| s.start);
        source.error(at, "", e.message().trim_end().to_string())
    })?;
    let table = crate::cast::file::parse(source)?;
    for (k, v) in table.get_ref().iter() {
        places.walk(v, k.get_ref().to_string(), &|p, at| source.error(at, p, ""));
    }
    Ok((bindings, places))
}

/// The bindings of a declared entry: inline fields, or a bindings file.
fn declared_bindings(fields: &mut Fields<'_>) -> Result<(Bindings, Places), FieldError> {
    let mut places = Places::default();
    if let Some(path) = fields.path("bindings")? {
        let text =
            common::input::read_text(&path).map_err(|e| fields.error("bindings", e.to_string()))?;
        return bindings_file(&path, &text);
    }
    for key in BINDING_FIELDS {
        if let Some(value) = fields.raw(key) {
            let at = |p: &str, at: usize| {
                let mut e = fields.error_at(key, at, "");
                e.field.push_str(&p[key.len()..]);
                e
            };
            places.walk(value, key.to_string(), &at);
        }
    }
    let mut b = Bindings {
        ready: part(fields, "ready")?.ok_or_else(|| {
            fields.error(
                "ready",
                "missing (required: where the program is ready to be queried, \
                 `ready = { init = [\"Main.init()\"] }` or \
                 `ready = { run = \"Main.main\", until_call = \"Class.function\" }`; \
                 `ready = { init = [] }` when nothing needs setting up)",
            )
        })?,
        float: part(fields, "float")?
            .ok_or_else(|| fields.error("float", "missing (required: the float's layout)"))?,
        vec3: part(fields, "vec3")?,
        sdf_result: part(fields, "sdf_result")?,
        ops: part(fields, "ops")?.unwrap_or_default(),
        sdf: part(fields, "sdf")?,
        pixel: part(fields, "pixel")?,
        pixel_shade: part(fields, "pixel_shade")?.unwrap_or_default(),
        capture: part(fields, "capture")?,
        out_of_domain: part(fields, "out_of_domain")?,
        budget: part(fields, "budget")?.unwrap_or_default(),
    };
    b.ops.retain(|_, v| !v.trim().is_empty());
    Ok((b, places))
}

impl Kind for JackKind {
    fn name(&self) -> &'static str {
        "jack"
    }

    fn builtins(&self) -> Vec<Entry> {
        vec![entry(
            "jack",
            Source::Seed,
            Profile::Desktop,
            seed_bindings(),
            Places::default(),
        )
        .about("the seed Jack raymarcher on the Hack VM emulator, through its bindings")]
    }

    fn declare(&self, _name: &str, fields: &mut Fields<'_>) -> Result<Entry, FieldError> {
        let profile = fields
            .parsed::<Profile>("profile")?
            .unwrap_or(Profile::Desktop);
        if let Some(scene) = fields.path("scene")? {
            return generated(fields, &scene, profile);
        }
        let Some(dir) = fields.path("program")? else {
            for key in BINDING_FIELDS.iter().chain(&["bindings"]) {
                if fields.raw(key).is_some() {
                    return Err(fields.error(key, "bindings need a `program` folder"));
                }
            }
            return Ok(entry(
                "jack",
                Source::Seed,
                profile,
                seed_bindings(),
                Places::default(),
            )
            .about(format!(
                "the seed Jack raymarcher under the {} OS profile",
                profile.name()
            )));
        };
        let (bindings, places) = declared_bindings(fields)?;
        let about = format!(
            "the Jack program {} under the {} OS profile, through bindings",
            dir.display(),
            profile.name()
        );
        Ok(entry("jack", Source::Folder(dir), profile, bindings, places).about(about))
    }
}

/// The entry `scene = FILE` declares: the Jack program generated from the
/// description (crate `scene-jack`), written with its `bindings.toml` into
/// the cache folder [`generated_dir`] names, then opened from there as a
/// user's program is.
fn generated(fields: &mut Fields<'_>, scene: &Path, profile: Profile) -> Result<Entry, FieldError> {
    for key in BINDING_FIELDS.iter().chain(&["bindings", "program"]) {
        if fields.raw(key).is_some() {
            return Err(fields.error(
                key,
                "`scene` generates the program and its bindings; leave this field out",
            ));
        }
    }
    let sources = scene_jack::emit_file(scene)
        .map_err(|e| fields.error("scene", e.to_string()))?
        .sources;
    let dir = generated_dir(scene, &sources);
    write_generated(&dir, &sources).map_err(|e| {
        fields.error(
            "scene",
            format!(
                "cannot write the generated program into {}: {e}",
                dir.display()
            ),
        )
    })?;
    let (bindings, places) = bindings_file(&dir.join("bindings.toml"), &sources.bindings)?;
    let about = format!(
        "the Jack program generated from {} (in {}) under the {} OS profile, through its bindings",
        scene.display(),
        dir.display(),
        profile.name()
    );
    Ok(entry("jack", Source::Generated(dir), profile, bindings, places).about(about))
}

/// The cache folder of a generated program: under the system's temporary
/// directory, named by the scene file's stem and a hash of everything
/// generated, so that a changed scene or back end never reuses stale files.
fn generated_dir(scene: &Path, sources: &scene_jack::JackSources) -> PathBuf {
    let files = sources
        .classes
        .iter()
        .map(|c| (c.name.as_str(), c.text.as_str()))
        .chain([("bindings.toml", sources.bindings.as_str())]);
    let hash = common::hash::fnv1a(
        files.flat_map(|(name, text)| name.bytes().chain([0]).chain(text.bytes()).chain([0])),
    );
    let stem = scene
        .file_stem()
        .map_or("scene".into(), |s| s.to_string_lossy().into_owned());
    std::env::temp_dir()
        .join("f316-harness-jack")
        .join(format!("{stem}-{hash:016x}"))
}

/// Write `sources` into `dir` unless it is there already: into a fresh
/// sibling first, renamed into place, so that a folder of that name is
/// always whole.
fn write_generated(dir: &Path, sources: &scene_jack::JackSources) -> std::io::Result<()> {
    if dir.is_dir() {
        return Ok(());
    }
    let parent = dir.parent().expect("the cache folder has a parent");
    std::fs::create_dir_all(parent)?;
    let tmp = fresh_dir(parent)?;
    sources.write_to(&tmp)?;
    match std::fs::rename(&tmp, dir) {
        Ok(()) => Ok(()),
        // Another process wrote the same folder first.
        Err(_) if dir.is_dir() => std::fs::remove_dir_all(&tmp),
        Err(e) => {
            let _ = std::fs::remove_dir_all(&tmp);
            Err(e)
        }
    }
}

/// A new empty folder in `parent`, named by this process and a counter.
fn fresh_dir(parent: &Path) -> std::io::Result<PathBuf> {
    static NEXT: std::sync::atomic::AtomicU32 = std::sync::atomic::AtomicU32::new(0);
    loop {
        let n = NEXT.fetch_add(1, Ordering::Relaxed);
        let tmp = parent.join(format!(".tmp-{}-{n}", std::process::id()));
        match std::fs::create_dir(&tmp) {
            Ok(()) => return Ok(tmp),
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {}
            Err(e) => return Err(e),
        }
    }
}

/// Opens a bound program under its profile (`web-divide`: with a flooring
/// `Math.divide`).
struct JackOpener {
    source: Source,
    profile: Profile,
    bindings: Bindings,
    /// Where the bindings were written, to locate their errors.
    places: Places,
}

impl Opener for JackOpener {
    fn open(&self, request: &Request<'_>) -> Result<Box<dyn Implementation>, ImplError> {
        request.seed_scene_only()?;
        let mut program = match &self.source {
            Source::Seed => JackProgram::from_jack(&jack::sources::SOURCES, self.profile),
            Source::Folder(dir) | Source::Generated(dir) => {
                JackProgram::from_dir(dir, self.profile)
            }
        }
        .map_err(|e| ImplError::Failed(e.to_string()))?;
        if request.label.variants.iter().any(|v| v == WEB_DIVIDE) {
            // The web IDE's Math.divide, and nothing else of the web
            // profile: the program compiles, lays out and runs as before.
            program = program.with_divide(DivideRule::Floor);
        }
        // A program that does not compile, or never reaches its bindings'
        // ready point, is a failure of the port, not of this machine.
        // A generated program answers its own scene, where the probes'
        // seed answers do not apply; its bindings give each role its own
        // argument by construction.
        let probe = !matches!(self.source, Source::Generated(_));
        let bound = BoundProgram::open(&program, &self.bindings, Budgets::default())
            .and_then(|bound| {
                if probe {
                    check_sdf_roles(&bound, &self.bindings)?;
                }
                Ok(bound)
            })
            .map_err(|e| match e {
                JackError::Bind(e) => ImplError::Failed(self.places.locate(&e)),
                e => ImplError::Failed(e.to_string()),
            })?;
        Ok(Box::new(JackAdapter {
            bound,
            label: request.label.to_string(),
            hang_told: AtomicBool::new(false),
        }))
    }
}

/// Points of the seed scene where ref-f316's distance and colour differ.
const ROLE_PROBES: [[f64; 3]; 3] = [[0.0, 0.0, 0.0], [2.0, 0.5, 3.0], [-1.0, 2.0, 1.0]];

/// Refuse SDF bindings whose distance and colour come back in each other's
/// roles, which no round trip sees when the program never makes the result
/// object from its parts (`new = "alloc"`, an argument-less `new`, getters
/// swapped): the program's answers at a few points against ref-f316's.
/// Answers that differ otherwise are findings, left to the comparison.
fn check_sdf_roles(bound: &BoundProgram, bindings: &Bindings) -> Result<(), JackError> {
    if !bound.has_sdf() {
        return Ok(());
    }
    let reference = reference::Reference::seed(reference::RefImpl::F316);
    let mut swapped = None;
    for p in ROLE_PROBES {
        let p = p.map(|v| common::F316::from_f64_truncating(v).expect("a probe fits"));
        let (Outcome::Value(want), Ok(got)) = (reference.sdf(p), bound.sdf(p)) else {
            continue;
        };
        let (Some(d), Some(c), Outcome::Value(got)) =
            (want.sd.triple, want.col.triple, got.outcome)
        else {
            continue;
        };
        if d == c {
            continue;
        }
        if got == (d, c) {
            return Ok(());
        }
        if got == (c, d) {
            swapped.get_or_insert((p, d, c));
        }
    }
    let Some((p, d, c)) = swapped else {
        return Ok(());
    };
    let (field, how) = match &bindings.sdf_result {
        Some(l) => (
            "sdf_result.fields",
            format!(
                "list the fields of {} in the order the class declares them",
                l.class
            ),
        ),
        None => ("sdf", "give each of `distance` and `colour` its own".into()),
    };
    Err(jack::BindError::new(
        field,
        format!(
            "distance and colour come back in each other's roles: at p = ({}, {}, {}) the \
             program gives distance {c:?} and colour {d:?}, where ref-f316 gives distance \
             {d:?} and colour {c:?}; {how}",
            p[0].to_f64(),
            p[1].to_f64(),
            p[2].to_f64()
        ),
    )
    .into())
}

/// A bound Jack program as an implementation.
pub struct JackAdapter {
    bound: BoundProgram,
    label: String,
    /// Whether a hang's budget was told on stderr (once per adapter).
    hang_told: AtomicBool,
}

/// The answer of pixel (x, y) from what its statements gave: the shade
/// clamped and the white bit computed as ref-f316 computes them
/// ([`crate::dither::float316`]) where the program gives the shade before its
/// clamp, or the shade alone.
fn finish_pixel(p: Outcome<BoundPixel>, x: usize, y: usize) -> Outcome<Answer> {
    let pixel = match p {
        Outcome::Value(p) => p,
        trap => return trap.map(|_| Answer::Unsupported),
    };
    let finished = match pixel.white {
        Some(white) if pixel.clamped => Outcome::Value((pixel.shade, white)),
        Some(white) => crate::dither::float316(pixel.shade, false, x, y).map(|(v, _)| (v, white)),
        None => crate::dither::float316(pixel.shade, pixel.clamped, x, y),
    };
    finished.map(|(shade, white)| Answer::Pixel {
        shade: Num::F316(shade),
        white,
    })
}

/// The whole image through the pixel statements, pixels in parallel,
/// with a bar of pixels done when `shown` (on a terminal).
fn render_with_bar(
    bound: &BoundProgram,
    shown: bool,
) -> Result<Vec<jack::Counted<BoundPixel>>, JackError> {
    let bar = crate::progress::show(
        crate::progress::items((WIDTH * HEIGHT) as u64, "jack", "pixels"),
        shown,
    );
    let render = bound.render_rows_observed(0..HEIGHT, &|| bar.inc(1));
    bar.finish_and_clear();
    render
}

fn failed(e: JackError) -> ImplError {
    match e {
        JackError::Unsupported(what) => ImplError::Unsupported(what),
        e => ImplError::Failed(e.to_string()),
    }
}

impl JackAdapter {
    /// Say once, on stderr, which budget a hang ran out of: a program whose
    /// operation really finishes, only later, needs a larger one (the
    /// other side of a comparison may hang on the same case too, so the
    /// note says where a larger budget is the fix).
    fn tell_hang(&self, v: &Vector) {
        let budgets = self.bound.budgets();
        let (field, budget) = match v {
            Vector::Op(_) => ("op", budgets.op),
            Vector::Sdf(_) => ("sdf", budgets.sdf),
            Vector::Pixel(_) | Vector::Image(_) => ("pixel", budgets.pixel),
        };
        if !self.hang_told.swap(true, Ordering::Relaxed) {
            eprintln!(
                "note: `{}` ran out of its instruction budget `budget.{field}` ({budget} \
                 instructions) on at least one case, reported as a hang; where the other side \
                 finishes such a case, the program may only need longer: set a larger budget \
                 in its bindings, `budget = {{ {field} = N }}` (docs/bindings.md)",
                self.label
            );
        }
    }

    /// The image: through the pixel statements when they give the white
    /// bit, else by running the whole program where `capture` says how,
    /// else through the pixel statements with the white bits computed from
    /// their shades.
    fn image(&self) -> Result<Vec<bool>, ImplError> {
        let through_pixels = self.bound.pixel_gives_white()
            || self.bound.has_pixel() && !self.bound.captures_pixels();
        if through_pixels {
            let render = render_with_bar(&self.bound, crate::progress::wanted()).map_err(failed)?;
            // A pixel whose computation trapped is never drawn: the Hack
            // screen starts white.
            return Ok(render
                .iter()
                .enumerate()
                .map(
                    |(i, p)| match finish_pixel(p.outcome, i % WIDTH, i / WIDTH) {
                        Outcome::Value(Answer::Pixel { white, .. }) => white,
                        _ => true,
                    },
                )
                .collect());
        }
        let run = self
            .bound
            .run_whole(&[], WHOLE_BUDGET, &mut |_| {})
            .map_err(failed)?;
        match run.outcome {
            Outcome::Value(()) => Ok(run.image()),
            other => Err(ImplError::Failed(format!(
                "the whole program did not finish: {}",
                other.map(|_| "halted")
            ))),
        }
    }

    fn answer(&self, v: &Vector) -> Result<Outcome<Answer>, ImplError> {
        Ok(match v {
            // An operation the bindings leave out (the program writes it
            // inline): counted as unsupported, never guessed.
            Vector::Op(o) if !self.bound.has_op(o.op) => Outcome::Value(Answer::Unsupported),
            Vector::Op(o) => self
                .bound
                .op(o.op, &o.args())
                .map_err(failed)?
                .outcome
                .map(Answer::from),
            Vector::Sdf(s) => self
                .bound
                .sdf(s.p)
                .map_err(failed)?
                .outcome
                .map(|(sd, col)| Answer::Sdf {
                    sd: Num::F316(sd),
                    col: Num::F316(col),
                }),
            Vector::Pixel(p) => {
                let (x, y) = (usize::from(p.x), usize::from(p.y));
                finish_pixel(self.bound.pixel(x, y).map_err(failed)?.outcome, x, y)
            }
            Vector::Image(_) => Outcome::Value(Answer::Image {
                bitmap: Bitmap {
                    width: WIDTH,
                    height: HEIGHT,
                    white: self.image()?,
                },
            }),
        })
    }
}

impl Implementation for JackAdapter {
    fn label(&self) -> String {
        self.label.clone()
    }

    fn numbers(&self) -> Numbers {
        Numbers::Float316
    }

    fn supports(&self, level: Level) -> bool {
        match level {
            Level::Ops => Op::ALL.into_iter().any(|op| self.bound.has_op(op)),
            Level::Sdf => self.bound.has_sdf(),
            Level::Pixels => self.bound.has_pixel(),
            Level::Image => self.bound.has_pixel() || self.bound.captures_pixels(),
        }
    }

    fn checks_domain(&self) -> bool {
        self.bound.checks_domain()
    }

    fn batch_size(&self, level: Level) -> usize {
        // Each vector runs on its own clone of the snapshot: small batches
        // spread over the cores.
        match level {
            Level::Ops => 256,
            Level::Sdf => 16,
            Level::Pixels | Level::Image => 1,
        }
    }

    /// Each input in turn. A run that ends where an answer was due (the
    /// program halts, overflows its stack, or the VM stops it with an error)
    /// is the port crashing on that input: contained, naming it, with the
    /// answers before it kept.
    fn eval(&self, batch: &[Vector]) -> Result<Vec<Outcome<Answer>>, ImplError> {
        let mut answers = Vec::with_capacity(batch.len());
        for v in batch {
            match self.answer(v) {
                Ok(Outcome::Hang) => {
                    self.tell_hang(v);
                    answers.push(Outcome::Hang)
                }
                Ok(a) => answers.push(a),
                Err(ImplError::Failed(why)) => {
                    return Err(Failure::new(&self.label, FailureKind::Crash, why, batch)
                        .after(answers, batch)
                        .into())
                }
                Err(e) => return Err(e),
            }
        }
        Ok(answers)
    }

    /// Every pixel through the pixel statements, with the VM instructions
    /// each took; `None` when only the whole program is bound.
    fn render_image(&self, progress: bool) -> Option<Result<ImageAnswers, ImplError>> {
        if !self.bound.has_pixel() {
            return None;
        }
        Some(
            render_with_bar(&self.bound, progress)
                .map_err(failed)
                .map(|render| ImageAnswers {
                    costs: Some(render.iter().map(|p| p.instructions).collect()),
                    pixels: render
                        .into_iter()
                        .enumerate()
                        .map(|(i, p)| finish_pixel(p.outcome, i % WIDTH, i / WIDTH))
                        .collect(),
                }),
        )
    }

    /// The Hack screen after the whole program ran from its entry with the
    /// bound keys; `None` when the bindings do not say how to run it.
    fn program_screen(
        &self,
        expected_cost: Option<u64>,
        progress: bool,
    ) -> Option<Result<Bitmap, ImplError>> {
        if !self.bound.captures_pixels() {
            return None;
        }
        let bar = crate::progress::show(
            crate::progress::instructions(expected_cost, "Main.main"),
            progress,
        );
        let run = self
            .bound
            .run_whole(&[], WHOLE_BUDGET, &mut |n| bar.set_position(n));
        bar.finish_and_clear();
        Some(match run {
            Ok(WholeRun {
                outcome: Outcome::Value(()),
                screen,
                ..
            }) => Ok(Bitmap {
                width: WIDTH,
                height: HEIGHT,
                white: screen,
            }),
            Ok(other) => Err(ImplError::Failed(format!(
                "the whole program did not finish: {}",
                other.outcome.map(|_| "screen")
            ))),
            Err(e) => Err(failed(e)),
        })
    }

    fn trace(&self, input: &Vector) -> Result<Vec<TraceRecord>, ImplError> {
        match input {
            Vector::Op(o) => self.bound.trace_op(o.op, &o.args()),
            Vector::Sdf(s) => self.bound.trace_sdf(s.p),
            Vector::Pixel(p) => {
                let (x, y) = (usize::from(p.x), usize::from(p.y));
                if self.bound.has_pixel() {
                    self.bound.trace_pixel(x, y)
                } else {
                    // The whole program, watching the pixel's operations.
                    self.bound
                        .run_whole(&[(x, y)], WHOLE_BUDGET, &mut |_| {})
                        .and_then(|run| {
                            run.traces.get(&(x, y)).cloned().ok_or_else(|| {
                                JackError::Unsupported(format!(
                                    "the whole program never computed pixel ({x},{y})"
                                ))
                            })
                        })
                }
            }
            Vector::Image(_) => {
                return Err(ImplError::Unsupported("a trace of the whole image".into()))
            }
        }
        .map_err(failed)
    }
}
