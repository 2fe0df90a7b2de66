//! The `shader` kind: a user's WGSL or Shadertoy-style GLSL file, run
//! unmodified on any wgpu adapter through `gpu::shader` (conventions in
//! docs/shaders.md). A shader that does not compile, loops for ever or
//! outruns its time limit fails like a real component: the front end's
//! diagnostic (file, line, column) or the timeout is the implementation's
//! error, an endless loop's pixels are hangs, and the harness goes on.
//!
//! Its built-in entries are our own kernels, `gpu-f32` and `gpu-f316`:
//! our WGSL (compiled into the binary), written to the same convention,
//! run without the loop guard and time limit (their loops have constant
//! bounds). Without an adapter they are unavailable, with the reason.

use crate::cast::entry::{Entry, Kind, Opener, Request};
use crate::cast::file::{FieldError, Fields};
use crate::implementation::{Answer, Bitmap, ImplError, Implementation, Num, Numbers};
use common::image_consts::{HEIGHT, WIDTH};
use common::Outcome;
use gpu::shader::{
    Language, Provides, Shade, ShaderNum, ShaderNumbers, ShaderOptions, ShaderSource, UserShader,
};
use gpu::GpuError;
use std::path::PathBuf;
use std::time::Duration;
use toml::de::DeValue;
use vectors::{Level, Vector};

/// The `shader` kind: our two kernels are its built-in entries.
pub struct ShaderKind;

/// The built-in entry of our own kernel computing with `numbers`.
fn ours(numbers: ShaderNumbers) -> Entry {
    let opener = ShaderOpener {
        source: Source::Embedded(ShaderSource::ours(numbers)),
        options: ShaderOptions::ours(numbers),
    };
    match numbers {
        ShaderNumbers::Float316 => Entry::new("gpu-f316", "shader", Numbers::Float316, opener)
            .about("the Float316 kernels (Float316 as i32 arithmetic), wgpu"),
        ShaderNumbers::F32 => Entry::new("gpu-f32", "shader", Numbers::F32, opener)
            .about("the f32 scene kernels, wgpu")
            .levels(&[Level::Sdf, Level::Pixels, Level::Image]),
    }
}

impl Kind for ShaderKind {
    fn name(&self) -> &'static str {
        "shader"
    }

    fn builtins(&self) -> Vec<Entry> {
        vec![ours(ShaderNumbers::F32), ours(ShaderNumbers::Float316)]
    }

    fn declare(&self, name: &str, fields: &mut Fields<'_>) -> Result<Entry, FieldError> {
        let path = fields
            .path("path")?
            .ok_or_else(|| fields.error("path", "missing (required): the shader's file"))?;
        let numbers = fields
            .parsed::<ShaderNumbers>("numbers")?
            .unwrap_or(ShaderNumbers::F32);
        let language = fields.parsed::<Language>("language")?;
        let Some(resolved) = language.or_else(|| Language::from_extension(&path)) else {
            return Err(fields.error(
                "path",
                "the extension does not say the language (.wgsl; .glsl, .frag, .fs): \
                 declare language = \"glsl\" or \"wgsl\"",
            ));
        };
        let mut options = ShaderOptions {
            numbers,
            ..ShaderOptions::default()
        };
        if let Some(shade) = fields.parsed::<Shade>("shade")? {
            if resolved == Language::Wgsl {
                return Err(fields.error(
                    "shade",
                    format!(
                        "{} is WGSL, whose `pixel` returns the shade itself: `shade` picks a \
                         channel of a GLSL shader's `fragColor` (docs/shaders.md)",
                        path.display()
                    ),
                ));
            }
            options.shade = shade;
        }
        if let Some(limit) = positive(fields, "loop_limit")? {
            options.loop_limit = Some(
                u32::try_from(limit)
                    .map_err(|_| fields.error("loop_limit", "at most 4294967295"))?,
            );
        }
        if let Some(seconds) = positive(fields, "timeout_s")? {
            if seconds > crate::contain::MAX_DURATION_S {
                return Err(fields.error(
                    "timeout_s",
                    format!(
                        "at most {} seconds (one day), is {seconds}",
                        crate::contain::MAX_DURATION_S
                    ),
                ));
            }
            options.time_limit = Some(Duration::from_secs(seconds));
        }
        // The front end alone (no device) decides the levels; a shader that
        // does not compile is still an entry, whose opening fails with the
        // diagnostic, like any component that does not start.
        let levels = match ShaderSource::read(&path, language)
            .and_then(|source| UserShader::check(&source, &options))
        {
            Ok(provides) => levels_of(&provides),
            Err(_) => vec![Level::Pixels, Level::Image],
        };
        let kind_numbers = match numbers {
            ShaderNumbers::F32 => Numbers::F32,
            ShaderNumbers::Float316 => Numbers::Float316,
        };
        Ok(Entry::new(
            name,
            "shader",
            kind_numbers,
            ShaderOpener {
                source: Source::File {
                    path: path.clone(),
                    language,
                },
                options,
            },
        )
        .about(format!("the shader {}, wgpu", path.display()))
        .levels(&levels))
    }
}

/// The levels a shader answers: ops and sdf when it defines `op` and
/// `sdf`, pixels and image always.
fn levels_of(provides: &Provides) -> Vec<Level> {
    let mut levels = Vec::new();
    if provides.ops() {
        levels.push(Level::Ops);
    }
    if provides.sdf() {
        levels.push(Level::Sdf);
    }
    levels.extend([Level::Pixels, Level::Image]);
    levels
}

/// A positive integer field, if present.
fn positive(fields: &mut Fields<'_>, key: &str) -> Result<Option<u64>, FieldError> {
    let Some(value) = fields.raw(key) else {
        return Ok(None);
    };
    let parsed = match value.get_ref() {
        DeValue::Integer(i) => u64::from_str_radix(&i.as_str().replace('_', ""), i.radix())
            .ok()
            .filter(|&n| n > 0),
        _ => None,
    };
    parsed
        .map(Some)
        .ok_or_else(|| fields.error(key, "expected a positive integer"))
}

/// The name of the seed scene's Shadertoy port in the nightly's cast.
pub const SEED_SHADERTOY: &str = "seed-shadertoy";

/// The seed scene's Shadertoy port (examples/shaders/seed.glsl, compiled
/// into the binary; grey, so its shade is `fragColor.r`) as the entry
/// [`SEED_SHADERTOY`]: the nightly's cast has it by default, so that a
/// user's shader runs every night, compared with ref-f64 by error figures
/// and dithered-pixel flips like any f32 implementation.
pub fn seed_shadertoy() -> Entry {
    let source = ShaderSource::from_text(
        "examples/shaders/seed.glsl",
        include_str!("../../../examples/shaders/seed.glsl"),
        Language::Glsl,
    );
    let options = ShaderOptions {
        shade: Shade::Red,
        ..ShaderOptions::default()
    };
    let levels = UserShader::check(&source, &options)
        .map(|provides| levels_of(&provides))
        .unwrap_or_else(|_| vec![Level::Pixels, Level::Image]);
    Entry::new(
        SEED_SHADERTOY,
        "shader",
        Numbers::F32,
        ShaderOpener {
            source: Source::Embedded(source),
            options,
        },
    )
    .about("the seed scene's Shadertoy port (examples/shaders/seed.glsl), wgpu")
    .levels(&levels)
}

/// Where an entry's shader comes from.
enum Source {
    /// Compiled into the binary: our own kernels, the seed's Shadertoy port.
    Embedded(ShaderSource),
    /// A user's file.
    File {
        path: PathBuf,
        language: Option<Language>,
    },
}

/// How long a shader with a time limit (a user's, the seed's Shadertoy
/// port) may take to compile by default: its pipelines and each kernel's
/// first dispatch, where a driver may compile machine code. An entry's
/// `timeout_s` above it is its limit instead.
pub const COMPILE_LIMIT: Duration = Duration::from_secs(120);

/// The environment variable that sets every such shader's compile limit
/// instead, in seconds (in (0, 86400], as `HARNESS_WATCHDOG_S`).
pub const COMPILE_LIMIT_VAR: &str = "HARNESS_SHADER_COMPILE_S";

/// The compile limit of a shader whose dispatches have `time_limit`: none
/// for our own kernels, which have no time limit either (their loops and
/// their compilation are known); else `from_env` (the value of
/// [`COMPILE_LIMIT_VAR`]) when it is a valid duration; else the larger of
/// [`COMPILE_LIMIT`] and the time limit.
fn compile_limit(time_limit: Option<Duration>, from_env: Option<&str>) -> Option<Duration> {
    let time_limit = time_limit?;
    if let Some(text) = from_env {
        match text
            .parse::<f64>()
            .ok()
            .and_then(crate::contain::user_seconds)
        {
            Some(limit) => return Some(limit),
            None => eprintln!(
                "warning: {COMPILE_LIMIT_VAR}: `{text}` is not a number of seconds in \
                 (0, {}]: not used, the default compile limit applies",
                crate::contain::MAX_DURATION_S
            ),
        }
    }
    Some(COMPILE_LIMIT.max(time_limit))
}

/// Compiles the shader on the preferred adapter, a shader with a time limit
/// on a contained worker under [`compile_limit`]: one whose compilation
/// never ends fails its entry, and `harness cast` lists the others.
struct ShaderOpener {
    source: Source,
    options: ShaderOptions,
}

impl Opener for ShaderOpener {
    fn open(&self, request: &Request<'_>) -> Result<Box<dyn Implementation>, ImplError> {
        request.seed_scene_only()?;
        let source = match &self.source {
            Source::Embedded(source) => source.clone(),
            Source::File { path, language } => {
                ShaderSource::read(path, *language).map_err(failed)?
            }
        };
        let options = self.options;
        let limit = compile_limit(
            options.time_limit,
            std::env::var(COMPILE_LIMIT_VAR).ok().as_deref(),
        );
        let opened = match limit {
            None => UserShader::open(&source, &options),
            Some(limit) => {
                let name = source.name().to_string();
                let label = request.label.to_string();
                match crate::contain::within(&label, limit, move || {
                    UserShader::open(&source, &options)
                })? {
                    Some(opened) => opened,
                    None => {
                        return Err(ImplError::Failed(format!(
                            "{name}: the shader did not compile within its limit of {} s \
                             (its pipelines and each kernel's first dispatch; the limit is \
                             the larger of {} s and its timeout_s, {COMPILE_LIMIT_VAR} sets \
                             another): the driver is left compiling, the entry is not used",
                            common::shown(limit.as_secs_f64()),
                            COMPILE_LIMIT.as_secs()
                        )))
                    }
                }
            }
        };
        let shader = opened.map_err(|e| match e {
            GpuError::NoAdapter { .. } => {
                ImplError::Unavailable(format!("no usable wgpu adapter: {e}"))
            }
            e => failed(e),
        })?;
        Ok(Box::new(ShaderAdapter {
            shader,
            label: request.label.to_string(),
        }))
    }
}

fn failed(e: GpuError) -> ImplError {
    ImplError::Failed(e.to_string())
}

/// A user's shader as an [`Implementation`].
struct ShaderAdapter {
    shader: UserShader,
    label: String,
}

fn num(n: ShaderNum) -> Num {
    match n {
        ShaderNum::F32(v) => Num::F32(v),
        ShaderNum::F316(t) => Num::F316(t),
    }
}

impl Implementation for ShaderAdapter {
    fn label(&self) -> String {
        self.label.clone()
    }

    fn numbers(&self) -> Numbers {
        match self.shader.numbers() {
            ShaderNumbers::F32 => Numbers::F32,
            ShaderNumbers::Float316 => Numbers::Float316,
        }
    }

    fn supports(&self, level: Level) -> bool {
        match level {
            Level::Ops => self.shader.provides().ops(),
            Level::Sdf => self.shader.provides().sdf(),
            Level::Pixels | Level::Image => true,
        }
    }

    fn batch_size(&self, _level: Level) -> usize {
        // The kernels batch to the device's limits themselves: one call.
        usize::MAX
    }

    fn adapter(&self) -> Option<common::AdapterDescription> {
        Some(self.shader.adapter_info().clone())
    }

    fn eval(&self, batch: &[Vector]) -> Result<Vec<Outcome<Answer>>, ImplError> {
        Ok(match batch.first() {
            None => Vec::new(),
            Some(Vector::Op(_)) => {
                let out = self.shader.ops(&op_cases(batch)).map_err(failed)?;
                out.into_iter().map(|o| o.map(Answer::from)).collect()
            }
            Some(Vector::Sdf(_)) => {
                let out = self.shader.sdf(&sdf_points(batch)).map_err(failed)?;
                out.into_iter()
                    .map(|o| {
                        o.map(|(sd, col)| Answer::Sdf {
                            sd: num(sd),
                            col: num(col),
                        })
                    })
                    .collect()
            }
            Some(Vector::Pixel(_)) => {
                let out = self.shader.pixels(&pixel_coords(batch)).map_err(failed)?;
                out.into_iter()
                    .map(|o| {
                        o.map(|(shade, white)| Answer::Pixel {
                            shade: num(shade),
                            white,
                        })
                    })
                    .collect()
            }
            Some(Vector::Image(_)) => {
                let pixels = self.shader.render().map_err(failed)?;
                let bitmap = Bitmap {
                    width: WIDTH,
                    height: HEIGHT,
                    white: pixels
                        .iter()
                        .map(|p| p.value().is_none_or(|(_, w)| w))
                        .collect(),
                };
                vec![Outcome::Value(Answer::Image { bitmap }); batch.len()]
            }
        })
    }
}

/// The operation cases of an ops-level batch, as the GPU kernels take them
/// (a unary operation's second operand is zero).
fn op_cases(batch: &[vectors::Vector]) -> Vec<(common::Op, common::F316, common::F316)> {
    batch
        .iter()
        .filter_map(|v| match v {
            vectors::Vector::Op(o) => Some((o.op, o.a, o.b.unwrap_or(common::F316::ZERO))),
            _ => None,
        })
        .collect()
}

/// The points of an sdf-level batch.
fn sdf_points(batch: &[vectors::Vector]) -> Vec<[common::F316; 3]> {
    batch
        .iter()
        .filter_map(|v| match v {
            vectors::Vector::Sdf(s) => Some(s.p),
            _ => None,
        })
        .collect()
}

/// The pixels `(x, y)` of a pixel-level batch.
fn pixel_coords(batch: &[vectors::Vector]) -> Vec<(u16, u16)> {
    batch
        .iter()
        .filter_map(|v| match v {
            vectors::Vector::Pixel(p) => Some((p.x, p.y)),
            _ => None,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use crate::cast::Cast;
    use crate::implementation::Numbers;
    use gpu::shader::{ShaderNumbers, ShaderOptions, ShaderSource, UserShader};
    use std::path::{Path, PathBuf};
    use vectors::Level;

    /// gpu-f32 and gpu-f316 are shader entries over our own WGSL, and the
    /// levels they list are what the front end finds in it.
    #[test]
    fn our_kernels_are_shader_entries_of_the_levels_their_wgsl_provides() {
        let cast = Cast::builtin();
        for (name, numbers) in [
            ("gpu-f32", ShaderNumbers::F32),
            ("gpu-f316", ShaderNumbers::Float316),
        ] {
            let entry = cast.get(name).expect("built-in");
            assert_eq!(entry.kind, "shader");
            let provides =
                UserShader::check(&ShaderSource::ours(numbers), &ShaderOptions::ours(numbers))
                    .expect("our WGSL follows the convention");
            assert_eq!(entry.levels, super::levels_of(&provides), "{name}");
        }
        assert_eq!(cast.get("gpu-f316").unwrap().levels, Level::ALL);
    }

    /// A shader's compilation is bounded by the larger of 120 s and its
    /// `timeout_s`, or by HARNESS_SHADER_COMPILE_S; ours are not (issue 35
    /// item 5).
    #[test]
    fn the_compile_limit_is_the_larger_of_120_s_and_the_time_limit() {
        use super::compile_limit;
        use std::time::Duration;
        let s = Duration::from_secs;
        assert_eq!(compile_limit(Some(s(10)), None), Some(s(120)));
        assert_eq!(compile_limit(Some(s(600)), None), Some(s(600)));
        assert_eq!(compile_limit(None, None), None);
        assert_eq!(compile_limit(None, Some("5")), None);
        assert_eq!(
            compile_limit(Some(s(600)), Some("0.5")),
            Some(Duration::from_millis(500))
        );
        for bad in ["0", "-1", "1e300", "soon"] {
            assert_eq!(compile_limit(Some(s(10)), Some(bad)), Some(s(120)), "{bad}");
        }
    }

    /// A project file at the repository's root, so that paths are the
    /// repository's.
    fn project(text: &str) -> Result<Cast, crate::cast::file::FieldError> {
        let root: PathBuf = Path::new(env!("CARGO_MANIFEST_DIR")).join("../harness.toml");
        Cast::with_project(&root, text)
    }

    #[test]
    fn a_shadertoy_shader_is_declared() {
        let cast = project(
            "[impl.seed-shadertoy]\nkind = \"shader\"\npath = \"examples/shaders/seed.glsl\"\nshade = \"red\"\n",
        )
        .expect("valid");
        let entry = cast.get("seed-shadertoy").expect("declared");
        assert_eq!(entry.kind, "shader");
        assert_eq!(entry.numbers, Numbers::F32);
        assert_eq!(entry.levels, [Level::Sdf, Level::Pixels, Level::Image]);
    }

    #[test]
    fn a_shader_that_does_not_compile_fails_with_its_diagnostic() {
        let cast = project(
            "[impl.broken]\nkind = \"shader\"\npath = \"impls/gpu/tests/shaders/syntax_error.glsl\"\n",
        )
        .expect("a broken shader is still an entry");
        match cast.open("broken") {
            Err(e) => {
                let message = e.to_string();
                assert!(
                    message.contains("syntax_error.glsl:5:5: error: "),
                    "{message}"
                );
            }
            Ok(_) => panic!("opened a shader that does not parse"),
        }
    }

    #[test]
    fn a_shader_entry_names_its_bad_fields() {
        let missing = project("[impl.s]\nkind = \"shader\"\n")
            .err()
            .expect("no path");
        assert!(missing.to_string().contains("path"), "{missing}");
        let bad = project(
            "[impl.s]\nkind = \"shader\"\npath = \"examples/shaders/seed.glsl\"\nloop_limit = -3\n",
        )
        .err()
        .expect("negative limit");
        assert!(bad.to_string().contains("loop_limit"), "{bad}");
    }

    /// `shade` picks a channel of GLSL's `fragColor`; a WGSL shader returns
    /// its shade, so the field is refused there, by its line and name.
    #[test]
    fn shade_on_a_wgsl_shader_is_refused() {
        let wgsl = project(
            "[impl.s]\nkind = \"shader\"\npath = \"examples/shaders/seed.wgsl\"\nshade = \"red\"\n",
        )
        .err()
        .expect("shade on WGSL");
        let text = wgsl.to_string();
        assert!(
            text.contains("harness.toml:4:")
                && text.contains("impl.s.shade")
                && text.contains("seed.wgsl is WGSL"),
            "{text}"
        );
        let declared = project(
            "[impl.s]\nkind = \"shader\"\npath = \"examples/shaders/seed.glsl\"\nlanguage = \"wgsl\"\nshade = \"red\"\n",
        )
        .err()
        .expect("shade on a file declared WGSL");
        assert!(declared.to_string().contains("impl.s.shade"), "{declared}");
        assert!(
            project("[impl.s]\nkind = \"shader\"\npath = \"examples/shaders/seed.wgsl\"\n").is_ok()
        );
    }

    /// A WGSL shader with an entry point of its own is an entry whose
    /// opening fails (no device needed), naming the file and the entry point.
    #[test]
    fn a_wgsl_shader_with_its_own_entry_point_fails_naming_it() {
        let cast = project(
            "[impl.own]\nkind = \"shader\"\npath = \"impls/gpu/tests/shaders/own_entry.wgsl\"\n",
        )
        .expect("a shader that does not pass the front end is still an entry");
        match cast.open("own") {
            Err(e) => {
                let message = e.to_string();
                assert!(
                    message.contains(
                        "own_entry.wgsl: error: the shader declares the entry point `main`"
                    ),
                    "{message}"
                );
            }
            Ok(_) => panic!("opened a shader with its own entry point"),
        }
    }
}
