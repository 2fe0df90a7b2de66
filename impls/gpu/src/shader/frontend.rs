//! From a user's source to validated naga modules, one per kernel: parse
//! the user's code alone, with only the helpers it may call (its errors
//! point into its file), check it against
//! the convention, parse it again followed by the wrapper, install the loop
//! guard, validate. No device is needed.

use super::convention::{self, Entry, Language, Provides, ShaderNumbers};
use super::diagnostic::Wrapped;
use super::{guard, ShaderSource};
use crate::error::GpuError;
use naga::front::glsl;
use naga::valid::{Capabilities, ValidationFlags, Validator};
use naga::{Module, ShaderStage};

/// A validated module and the entry point of one kernel.
pub(crate) struct KernelModule {
    pub entry: Entry,
    pub module: Module,
}

/// The front end's result: what the shader provides and its kernels.
pub(crate) struct Front {
    pub provides: Provides,
    pub kernels: Vec<KernelModule>,
}

/// Parse, check, wrap, guard (`loop_limit` iterations per invocation;
/// `None`: no guard) and validate `source` computing with `numbers`.
pub(crate) fn front(
    source: &ShaderSource,
    numbers: ShaderNumbers,
    loop_limit: Option<u32>,
) -> Result<Front, GpuError> {
    match source.language {
        Language::Wgsl => wgsl(source, numbers, loop_limit),
        Language::Glsl => glsl(source, numbers, loop_limit),
    }
}

fn wgsl(
    source: &ShaderSource,
    numbers: ShaderNumbers,
    limit: Option<u32>,
) -> Result<Front, GpuError> {
    let user = &source.text;
    // The user's code with only what it may call (after it, so that its
    // offsets stay its own).
    let alone_text = format!("{user}\n{}", convention::wgsl_provided(numbers));
    let alone = Wrapped {
        name: &source.name,
        source: &alone_text,
        user_len: user.len(),
    };
    let parsed = naga::front::wgsl::parse_str(&alone_text).map_err(|e| alone.wgsl(&e))?;
    let provides = convention::check(&parsed, &source.name, Language::Wgsl, numbers)?;
    let text = format!("{user}\n{}", convention::wgsl_wrapper(numbers, &provides));
    let wrapped = Wrapped {
        name: &source.name,
        source: &text,
        user_len: user.len(),
    };
    let module = naga::front::wgsl::parse_str(&text).map_err(|e| wrapped.wgsl(&e))?;
    let module = finish(module, limit, &wrapped)?;
    let kernels = provides
        .entries
        .iter()
        .map(|&entry| KernelModule {
            entry,
            module: module.clone(),
        })
        .collect();
    Ok(Front { provides, kernels })
}

fn glsl(
    source: &ShaderSource,
    numbers: ShaderNumbers,
    limit: Option<u32>,
) -> Result<Front, GpuError> {
    let user = blank_version(&source.text);
    let name = source.name.as_str();
    let parse =
        |text: &str| parse_glsl(text).map_err(|e| Wrapped::new(name, text, user.len()).glsl(&e));
    let provides = match parse_glsl(&user) {
        // The user's code alone parses only with an entry point of its own;
        // without one its own errors still point into it.
        Err(errors) if !is_missing_entry_point(&errors) => {
            return Err(Wrapped::new(name, &user, user.len()).glsl(&errors))
        }
        Err(_) => {
            let probe = parse(&format!("{user}\n{}", convention::glsl_wrapper(None)))?;
            convention::check(&probe, &source.name, Language::Glsl, numbers)?
        }
        Ok(own_main) => {
            convention::check(&own_main, &source.name, Language::Glsl, numbers)?;
            return Err(GpuError::Shader {
                diagnostic: format!(
                    "{}: error: the shader defines `main`: a Shadertoy shader defines only \
                     `mainImage`, the harness's wrapper has the entry point (docs/shaders.md)",
                    source.name
                ),
            });
        }
    };
    let mut kernels = Vec::new();
    for &entry in &provides.entries {
        let text = format!("{user}\n{}", convention::glsl_wrapper(Some(entry)));
        let module = finish(parse(&text)?, limit, &Wrapped::new(name, &text, user.len()))?;
        kernels.push(KernelModule { entry, module });
    }
    Ok(Front { provides, kernels })
}

/// Parse GLSL as a compute shader with Shadertoy's uniforms defined.
fn parse_glsl(text: &str) -> Result<Module, glsl::ParseErrors> {
    let mut options = glsl::Options::from(ShaderStage::Compute);
    for (name, value) in convention::shadertoy_defines() {
        options.defines.insert(name.to_string(), value);
    }
    glsl::Frontend::default().parse(&options, text)
}

/// naga's only complaint about GLSL without `main`, which the user's code
/// alone rightly is.
fn is_missing_entry_point(errors: &glsl::ParseErrors) -> bool {
    matches!(errors.errors.as_slice(), [only] if only.to_string() == "Missing entry point")
}

/// The most variable memory (private, function and workgroup) a user's
/// shader may declare for one invocation. A driver compiles an array into
/// code of its size: a GLSL `float big[100000]` kept lavapipe compiling for
/// minutes, through gigabytes, before the shader's first dispatch.
pub const MAX_VARIABLE_BYTES: u64 = 64 << 10;

/// Refuse a module whose variables pass [`MAX_VARIABLE_BYTES`], naming the
/// largest.
fn check_variables(module: &Module, name: &str) -> Result<(), GpuError> {
    let gctx = module.to_ctx();
    let bytes = |ty: naga::Handle<naga::Type>| match module.types[ty].inner {
        naga::TypeInner::Array {
            size: naga::ArraySize::Constant(n),
            stride,
            ..
        } => u64::from(n.get()) * u64::from(stride),
        ref other => u64::from(other.size(gctx)),
    };
    let globals = module
        .global_variables
        .iter()
        .filter(|(_, v)| {
            matches!(
                v.space,
                naga::AddressSpace::Private
                    | naga::AddressSpace::Function
                    | naga::AddressSpace::WorkGroup
            )
        })
        .map(|(_, v)| (v.name.as_deref(), bytes(v.ty)));
    let functions = module
        .functions
        .iter()
        .map(|(_, f)| f)
        .chain(module.entry_points.iter().map(|e| &e.function));
    let locals = functions.flat_map(|f| {
        f.local_variables
            .iter()
            .map(|(_, v)| (v.name.as_deref(), bytes(v.ty)))
    });
    let vars: Vec<(Option<&str>, u64)> = globals.chain(locals).collect();
    let total: u64 = vars.iter().map(|(_, b)| b).sum();
    match vars.iter().max_by_key(|(_, b)| *b) {
        Some((largest, size)) if total > MAX_VARIABLE_BYTES => Err(GpuError::Shader {
            diagnostic: format!(
                "{name}: error: the shader's variables take {total} bytes per invocation                  (`{}` {size}), more than the harness's bound of {MAX_VARIABLE_BYTES}: a                  driver compiles such an array into code of its size (docs/bounds.md)",
                largest.unwrap_or("an unnamed variable")
            ),
        }),
        _ => Ok(()),
    }
}

/// Install the loop guard (unless `limit` is `None`) and validate.
fn finish(mut module: Module, limit: Option<u32>, wrapped: &Wrapped) -> Result<Module, GpuError> {
    check_variables(&module, wrapped.name)?;
    if let Some(limit) = limit {
        let guarded = guard::install(&mut module, limit);
        debug_assert!(guarded, "the wrappers declare the loop guard's variables");
    }
    Validator::new(ValidationFlags::all(), Capabilities::all())
        .validate(&module)
        .map_err(|e| wrapped.validation(&e))?;
    Ok(module)
}

/// The user's GLSL with a `#version` line replaced by spaces: naga reads
/// GLSL 4.40 to 4.60 core, Shadertoy writes GLSL ES 3.00 without the line;
/// the harness compiles every shader as its own version, and blanking (not
/// removing) keeps every offset, so diagnostics keep the user's lines and
/// columns.
fn blank_version(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for line in text.split_inclusive('\n') {
        if line.trim_start().starts_with("#version") {
            out.extend(line.chars().map(|c| if c == '\n' { c } else { ' ' }));
        } else {
            out.push_str(line);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn glsl_with(declaration: &str) -> Result<Front, GpuError> {
        let text = format!(
            "{declaration}\nvoid mainImage(out vec4 c, in vec2 p) {{ big[0] = p.x; c = vec4(big[0]); }}\n"
        );
        let source = ShaderSource::from_text("big.glsl", &text, Language::Glsl);
        front(&source, ShaderNumbers::F32, Some(1000))
    }

    /// A large array is refused before any driver compiles it, naming the
    /// variable; a Shadertoy-sized one is not.
    #[test]
    fn a_shader_declaring_a_huge_array_is_refused_naming_it() {
        assert!(glsl_with("float big[1000];").is_ok());
        let Err(e) = glsl_with("float big[1000000];") else {
            panic!("accepted")
        };
        let text = e.to_string();
        assert!(
            text.contains("big.glsl: error: the shader's variables take 4000")
                && text.contains("`big`"),
            "{text}"
        );
    }

    fn glsl_source(text: &str) -> ShaderSource {
        ShaderSource::from_text("user.glsl", text, Language::Glsl)
    }

    #[test]
    fn a_version_line_is_blanked_in_place() {
        let text = "#version 300 es\nvoid f() {}\n";
        let blanked = blank_version(text);
        assert_eq!(blanked.len(), text.len());
        assert_eq!(blanked, format!("{}\nvoid f() {{}}\n", " ".repeat(15)));
    }

    #[test]
    fn a_shadertoy_shader_parses_with_its_uniforms() {
        let text = "#version 300 es\nprecision highp float;\n\
            void mainImage(out vec4 fragColor, in vec2 fragCoord) {\n\
            vec2 uv = fragCoord / iResolution.xy;\n\
            fragColor = vec4(uv, 0.5 + 0.5 * cos(iTime), 1.0);\n}\n";
        let front = front(&glsl_source(text), ShaderNumbers::F32, Some(100)).expect("parses");
        assert_eq!(front.kernels.len(), 1);
        assert!(!front.provides.sdf());
    }

    #[test]
    fn a_syntax_error_points_into_the_users_file() {
        let text = "void mainImage(out vec4 fragColor, in vec2 fragCoord) {\n\
            fragColor = vec4(1.0)\n}\n";
        let error = front(&glsl_source(text), ShaderNumbers::F32, Some(100))
            .err()
            .expect("a syntax error");
        let message = error.to_string();
        assert!(message.starts_with("user.glsl:3:1: error: "), "{message}");
        assert!(message.contains("user.glsl:3:1"), "{message}");
    }

    #[test]
    fn a_missing_main_image_is_named() {
        let text = "void mainimage(out vec4 c, in vec2 p) { c = vec4(1.0); }\n";
        let error = front(&glsl_source(text), ShaderNumbers::F32, Some(100))
            .err()
            .expect("no mainImage");
        let message = error.to_string();
        assert!(
            message.contains("no function `void mainImage(out vec4 fragColor, in vec2 fragCoord)`"),
            "{message}"
        );
    }

    #[test]
    fn a_wgsl_type_error_points_into_the_users_file() {
        let text = "fn pixel(coord: vec2<f32>, resolution: vec2<f32>) -> f32 {\n    \
            let a: f32 = 1u;\n    return a;\n}\n";
        let source = ShaderSource::from_text("user.wgsl", text, Language::Wgsl);
        let message = front(&source, ShaderNumbers::F32, Some(100))
            .err()
            .expect("a type error")
            .to_string();
        assert!(message.starts_with("user.wgsl:2:"), "{message}");
    }

    #[test]
    fn a_convention_function_of_another_type_is_an_error() {
        let text = "fn pixel(coord: vec2<f32>) -> f32 { return coord.x; }\n";
        let source = ShaderSource::from_text("user.wgsl", text, Language::Wgsl);
        let message = front(&source, ShaderNumbers::F32, Some(100))
            .err()
            .expect("wrong type")
            .to_string();
        assert!(
            message.contains("`pixel` has the type (vec2<f32>) -> f32"),
            "{message}"
        );
    }

    fn wgsl_front(text: &str, numbers: ShaderNumbers) -> Result<Front, GpuError> {
        let source = ShaderSource::from_text("user.wgsl", text, Language::Wgsl);
        front(&source, numbers, Some(100))
    }

    const PIXEL: &str =
        "fn pixel(coord: vec2<f32>, resolution: vec2<f32>) -> f32 { return 0.5; }\n";

    /// An entry point of the shader's own, a binding or a `harness_` name
    /// is refused, naming the file and what it declares (docs/shaders.md).
    #[test]
    fn a_wgsl_entry_point_binding_or_harness_name_is_refused() {
        assert!(wgsl_front(PIXEL, ShaderNumbers::F32).is_ok());
        for (extra, named) in [
            (
                "@compute @workgroup_size(1)\nfn main() {}\n",
                "the entry point `main` (@compute)",
            ),
            (
                "@compute @workgroup_size(8)\nfn other(@builtin(global_invocation_id) id: vec3<u32>) {}\n",
                "the entry point `other` (@compute)",
            ),
            (
                "@group(1) @binding(0) var<storage, read> extra: array<u32>;\n",
                "the binding `extra`",
            ),
            (
                "fn harness_helper() -> f32 { return 1.0; }\n",
                "the function `harness_helper`",
            ),
            (
                "var<private> harness_state: f32 = 0.0;\n",
                "the variable `harness_state`",
            ),
            (
                "const harness_k: f32 = 2.0;\n",
                "the constant `harness_k`",
            ),
            (
                "struct harness_pair { a: f32, b: f32 }\nfn f(p: harness_pair) -> f32 { return p.a; }\n",
                "the type `harness_pair`",
            ),
        ] {
            let text = format!("{PIXEL}{extra}");
            let Err(e) = wgsl_front(&text, ShaderNumbers::F32) else {
                panic!("accepted: {extra}")
            };
            let message = e.to_string();
            assert!(
                message.starts_with("user.wgsl: error: the shader declares ")
                    && message.contains(named),
                "{extra}: {message}"
            );
        }
    }

    /// A Float316 shader may call the provided `harness_bayer` (and our own
    /// gpu-f316 does), but not declare a `harness_` name of its own.
    #[test]
    fn a_float316_shader_calls_harness_bayer_but_declares_no_harness_name() {
        let pixel = "fn pixel(coord: vec2<i32>) -> vec4<i32> {\n    \
            return vec4<i32>(0, 0, 0, harness_bayer(u32(coord.x), u32(coord.y)));\n}\n";
        assert!(wgsl_front(pixel, ShaderNumbers::Float316).is_ok());
        let ours = ShaderSource::ours(ShaderNumbers::Float316);
        assert!(front(&ours, ShaderNumbers::Float316, None).is_ok());
        let text = format!("{pixel}fn harness_dither(x: i32) -> i32 {{ return x; }}\n");
        let message = wgsl_front(&text, ShaderNumbers::Float316)
            .err()
            .expect("a harness_ name")
            .to_string();
        assert!(
            message.contains("the function `harness_dither`")
                && message.contains("may call harness_bayer"),
            "{message}"
        );
    }

    #[test]
    fn every_loop_is_guarded() {
        let text = "fn pixel(coord: vec2<f32>, resolution: vec2<f32>) -> f32 {\n\
            var s = 0.0;\n\
            for (var i = 0; i < 4; i++) { for (var j = 0; j < 4; j++) { s += 1.0; } }\n\
            loop { s += 1.0; if (s > 100.0) { break; } }\n\
            return s;\n}\n";
        let source = ShaderSource::from_text("user.wgsl", text, Language::Wgsl);
        let front = front(&source, ShaderNumbers::F32, Some(100)).expect("valid");
        let module = &front.kernels[0].module;
        let (_, pixel) = module
            .functions
            .iter()
            .find(|(_, f)| f.name.as_deref() == Some("pixel"))
            .expect("pixel");
        let mut loops = 0;
        count_guarded_loops(&pixel.body, &mut loops);
        assert_eq!(loops, 3);
    }

    /// Count loops whose body starts with the guard's emit, store and if.
    fn count_guarded_loops(block: &naga::Block, loops: &mut usize) {
        for statement in block.iter() {
            match statement {
                naga::Statement::Loop { body, .. } => {
                    let head: Vec<_> = body.iter().take(3).collect();
                    if matches!(
                        head.as_slice(),
                        [
                            naga::Statement::Emit(_),
                            naga::Statement::Store { .. },
                            naga::Statement::If { .. }
                        ]
                    ) {
                        *loops += 1;
                    }
                    count_guarded_loops(body, loops);
                }
                naga::Statement::Block(b) => count_guarded_loops(b, loops),
                naga::Statement::If { accept, reject, .. } => {
                    count_guarded_loops(accept, loops);
                    count_guarded_loops(reject, loops);
                }
                _ => {}
            }
        }
    }
}
