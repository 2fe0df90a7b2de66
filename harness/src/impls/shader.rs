//! The `shader` kind: a user's WGSL or Shadertoy-style GLSL file, run
//! unmodified on any wgpu adapter through `gpu::shader` (conventions in
//! docs/shaders.md). A shader that does not compile, loops for ever or
//! outruns its time limit fails like a real component: the front end's
//! diagnostic (file, line, column) or the timeout is the implementation's
//! error, an endless loop's pixels are hangs, and the harness goes on.

use crate::cast::file::{FieldError, Fields};
use crate::cast::{Entry, Kind, Opener, Request};
use crate::implementation::{Answer, Bitmap, ImplError, Implementation, Num, Numbers};
use common::image_consts::{HEIGHT, WIDTH};
use common::{Outcome, F316};
use gpu::shader::{
    Language, Shade, ShaderNum, ShaderNumbers, ShaderOptions, ShaderSource, UserShader,
};
use gpu::GpuError;
use std::path::PathBuf;
use std::time::Duration;
use toml::de::DeValue;
use vectors::{Level, Vector};

/// The `shader` kind (no built-in entries).
pub struct ShaderKind;

impl Kind for ShaderKind {
    fn name(&self) -> &'static str {
        "shader"
    }

    fn declare(&self, name: &str, fields: &mut Fields<'_>) -> Result<Entry, FieldError> {
        let path = fields
            .path("path")?
            .ok_or_else(|| fields.error("path", "missing (required): the shader's file"))?;
        let numbers = fields
            .parsed::<ShaderNumbers>("numbers")?
            .unwrap_or(ShaderNumbers::F32);
        let language = fields.parsed::<Language>("language")?;
        if language.is_none() && Language::from_extension(&path).is_none() {
            return Err(fields.error(
                "path",
                "the extension does not say the language (.wgsl; .glsl, .frag, .fs): \
                 declare language = \"glsl\" or \"wgsl\"",
            ));
        }
        let mut options = ShaderOptions {
            numbers,
            ..ShaderOptions::default()
        };
        if let Some(shade) = fields.parsed::<Shade>("shade")? {
            options.shade = shade;
        }
        if let Some(limit) = positive(fields, "loop_limit")? {
            options.loop_limit = u32::try_from(limit)
                .map_err(|_| fields.error("loop_limit", "at most 4294967295"))?;
        }
        if let Some(seconds) = positive(fields, "timeout_s")? {
            options.time_limit = Duration::from_secs(seconds);
        }
        // The front end alone (no device) decides the levels; a shader that
        // does not compile is still an entry, whose opening fails with the
        // diagnostic, like any component that does not start.
        let levels = match ShaderSource::read(&path, language)
            .and_then(|source| UserShader::check(&source, &options))
        {
            Ok(provides) => {
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
                path: path.clone(),
                language,
                options,
            },
        )
        .about(format!("the shader {}, wgpu", path.display()))
        .levels(&levels))
    }
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

/// Compiles the shader on the preferred adapter.
struct ShaderOpener {
    path: PathBuf,
    language: Option<Language>,
    options: ShaderOptions,
}

impl Opener for ShaderOpener {
    fn open(&self, request: &Request<'_>) -> Result<Box<dyn Implementation>, ImplError> {
        request.seed_scene_only()?;
        let source = ShaderSource::read(&self.path, self.language).map_err(failed)?;
        let shader = UserShader::open(&source, &self.options).map_err(|e| match e {
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

    fn eval(&self, batch: &[Vector]) -> Result<Vec<Outcome<Answer>>, ImplError> {
        Ok(match batch.first() {
            None => Vec::new(),
            Some(Vector::Op(_)) => {
                let out = self.shader.ops(&super::op_cases(batch)).map_err(failed)?;
                out.into_iter().map(|o| o.map(Answer::from)).collect()
            }
            Some(Vector::Sdf(_)) => {
                let points: Vec<[F316; 3]> = batch
                    .iter()
                    .filter_map(|v| match v {
                        Vector::Sdf(s) => Some(s.p),
                        _ => None,
                    })
                    .collect();
                let out = self.shader.sdf(&points).map_err(failed)?;
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
                let pixels: Vec<(u16, u16)> = batch
                    .iter()
                    .filter_map(|v| match v {
                        Vector::Pixel(p) => Some((p.x, p.y)),
                        _ => None,
                    })
                    .collect();
                let out = self.shader.pixels(&pixels).map_err(failed)?;
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

#[cfg(test)]
mod tests {
    use crate::cast::Cast;
    use crate::implementation::Numbers;
    use std::path::{Path, PathBuf};
    use vectors::Level;

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
}
