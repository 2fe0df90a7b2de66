//! The entry conventions of a user's shader (docs/shaders.md): which
//! functions each language and number type must or may define, how a parsed
//! module is checked against them, and the wrapper code that calls them
//! from the harness's compute kernels.

use crate::error::GpuError;
use common::image_consts::{HEIGHT, WIDTH};
use naga::{Module, TypeInner};
use std::fmt;
use std::str::FromStr;

/// The language a shader is written in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Language {
    /// Shadertoy-style GLSL: `void mainImage(out vec4 fragColor, in vec2 fragCoord)`.
    Glsl,
    /// WGSL: `fn pixel(coord: vec2<f32>, resolution: vec2<f32>) -> f32`.
    Wgsl,
}

impl Language {
    /// The language a file name's extension says: `.wgsl` is WGSL;
    /// `.glsl`, `.frag`, `.fs` are GLSL.
    pub fn from_extension(path: &std::path::Path) -> Option<Language> {
        match path.extension()?.to_str()? {
            "wgsl" => Some(Language::Wgsl),
            "glsl" | "frag" | "fs" => Some(Language::Glsl),
            _ => None,
        }
    }
}

impl FromStr for Language {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "glsl" => Ok(Language::Glsl),
            "wgsl" => Ok(Language::Wgsl),
            _ => Err(format!(
                "unknown shader language `{s}` (expected glsl or wgsl)"
            )),
        }
    }
}

/// The numbers a shader computes with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ShaderNumbers {
    /// IEEE f32 (the shade and distances are f32).
    F32,
    /// Float316 as integer triples `vec3<i32>(s, e, m)` (WGSL only).
    Float316,
}

impl FromStr for ShaderNumbers {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "f32" => Ok(ShaderNumbers::F32),
            "float316" => Ok(ShaderNumbers::Float316),
            _ => Err(format!(
                "unknown number type `{s}` (expected f32 or float316)"
            )),
        }
    }
}

/// Where the shade of a GLSL shader's `fragColor` comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shade {
    /// Rec. 709 luminance `0.2126 r + 0.7152 g + 0.0722 b`, in f32, left to right.
    Luminance,
    /// One channel.
    Red,
    /// One channel.
    Green,
    /// One channel.
    Blue,
    /// One channel.
    Alpha,
}

impl Shade {
    /// The shade of one `fragColor`.
    pub fn of(self, [r, g, b, a]: [f32; 4]) -> f32 {
        match self {
            Shade::Luminance => 0.2126 * r + 0.7152 * g + 0.0722 * b,
            Shade::Red => r,
            Shade::Green => g,
            Shade::Blue => b,
            Shade::Alpha => a,
        }
    }
}

impl FromStr for Shade {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "luminance" => Ok(Shade::Luminance),
            "red" | "r" => Ok(Shade::Red),
            "green" | "g" => Ok(Shade::Green),
            "blue" | "b" => Ok(Shade::Blue),
            "alpha" | "a" => Ok(Shade::Alpha),
            _ => Err(format!(
                "unknown shade `{s}` (expected luminance, red, green, blue or alpha)"
            )),
        }
    }
}

/// One kernel the harness wraps around a shader.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Entry {
    /// The pixel shade (the pixels and image levels).
    Pixels,
    /// The scene's distance and colour at a point (the sdf level).
    Sdf,
    /// One Float316 operation (the ops level).
    Ops,
}

impl Entry {
    /// A short name for kernel labels.
    pub(crate) fn name(self) -> &'static str {
        match self {
            Entry::Pixels => "pixels",
            Entry::Sdf => "sdf",
            Entry::Ops => "ops",
        }
    }

    /// The entry point's name in the wrapped module.
    pub(crate) fn entry_point(self, language: Language) -> &'static str {
        match (language, self) {
            (Language::Glsl, _) => "main",
            (Language::Wgsl, Entry::Pixels) => "harness_pixels",
            (Language::Wgsl, Entry::Sdf) => "harness_sdf",
            (Language::Wgsl, Entry::Ops) => "harness_ops",
        }
    }

    /// Input and output words per item, as the wrappers in `wrappers/`
    /// read and write them.
    pub(crate) fn words(self, language: Language, numbers: ShaderNumbers) -> (usize, usize) {
        match (numbers, self, language) {
            (ShaderNumbers::F32, Entry::Pixels, Language::Glsl) => (2, 5),
            (ShaderNumbers::F32, Entry::Pixels, Language::Wgsl) => (2, 2),
            (ShaderNumbers::F32, _, _) => (3, 3),
            (ShaderNumbers::Float316, Entry::Pixels, _) => (2, 5),
            (ShaderNumbers::Float316, Entry::Sdf, _) => (9, 7),
            (ShaderNumbers::Float316, Entry::Ops, _) => (7, 4),
        }
    }
}

/// A function a convention asks for: its name and its type, as naga sees it.
struct Expected {
    entry: Entry,
    name: &'static str,
    /// Argument types in the notation of [`describe`].
    args: &'static [&'static str],
    result: Option<&'static str>,
    /// The declaration as the user writes it, for messages.
    declaration: &'static str,
}

const GLSL_F32: [Expected; 2] = [
    Expected {
        entry: Entry::Pixels,
        name: "mainImage",
        args: &["ptr<vec4<f32>>", "vec2<f32>"],
        result: None,
        declaration: "void mainImage(out vec4 fragColor, in vec2 fragCoord)",
    },
    Expected {
        entry: Entry::Sdf,
        name: "sdf",
        args: &["vec3<f32>"],
        result: Some("vec2<f32>"),
        declaration: "vec2 sdf(vec3 p)",
    },
];

const WGSL_F32: [Expected; 2] = [
    Expected {
        entry: Entry::Pixels,
        name: "pixel",
        args: &["vec2<f32>", "vec2<f32>"],
        result: Some("f32"),
        declaration: "fn pixel(coord: vec2<f32>, resolution: vec2<f32>) -> f32",
    },
    Expected {
        entry: Entry::Sdf,
        name: "sdf",
        args: &["vec3<f32>"],
        result: Some("vec2<f32>"),
        declaration: "fn sdf(p: vec3<f32>) -> vec2<f32>",
    },
];

const WGSL_F316: [Expected; 3] = [
    Expected {
        entry: Entry::Pixels,
        name: "pixel",
        args: &["vec2<i32>"],
        result: Some("vec4<i32>"),
        declaration: "fn pixel(coord: vec2<i32>) -> vec4<i32>",
    },
    Expected {
        entry: Entry::Sdf,
        name: "sdf",
        args: &["array<vec3<i32>, 3>"],
        result: Some("array<vec3<i32>, 2>"),
        declaration: "fn sdf(p: array<vec3<i32>, 3>) -> array<vec3<i32>, 2>",
    },
    Expected {
        entry: Entry::Ops,
        name: "op",
        args: &["u32", "vec3<i32>", "vec3<i32>"],
        result: Some("vec3<i32>"),
        declaration: "fn op(code: u32, a: vec3<i32>, b: vec3<i32>) -> vec3<i32>",
    },
];

/// What a checked shader provides: its entries (pixels first) and, for a
/// Float316 shader, whether it declares `var<private> status: i32`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Provides {
    pub(crate) entries: Vec<Entry>,
    pub(crate) status: bool,
}

impl Provides {
    /// Whether the shader answers the sdf level (it defines `sdf`).
    pub fn sdf(&self) -> bool {
        self.entries.contains(&Entry::Sdf)
    }

    /// Whether the shader answers the ops level (it defines `op`).
    pub fn ops(&self) -> bool {
        self.entries.contains(&Entry::Ops)
    }
}

fn expected(language: Language, numbers: ShaderNumbers) -> Result<&'static [Expected], String> {
    match (language, numbers) {
        (Language::Glsl, ShaderNumbers::F32) => Ok(&GLSL_F32),
        (Language::Wgsl, ShaderNumbers::F32) => Ok(&WGSL_F32),
        (Language::Wgsl, ShaderNumbers::Float316) => Ok(&WGSL_F316),
        (Language::Glsl, ShaderNumbers::Float316) => Err(
            "a Float316 shader is written in WGSL (integer triples); GLSL shaders compute in f32"
                .into(),
        ),
    }
}

/// A type in a WGSL-like notation: `f32`, `vec2<f32>`, `array<vec3<i32>, 3>`,
/// `ptr<vec4<f32>>` (a GLSL `out` or `inout` parameter).
fn describe(module: &Module, ty: naga::Handle<naga::Type>) -> String {
    let scalar = |s: naga::Scalar| match (s.kind, s.width) {
        (naga::ScalarKind::Float, 4) => "f32".to_string(),
        (naga::ScalarKind::Sint, 4) => "i32".to_string(),
        (naga::ScalarKind::Uint, 4) => "u32".to_string(),
        (naga::ScalarKind::Bool, _) => "bool".to_string(),
        (kind, width) => format!("{kind:?}{}", 8 * width),
    };
    match &module.types[ty].inner {
        TypeInner::Scalar(s) => scalar(*s),
        TypeInner::Vector { size, scalar: s } => format!("vec{}<{}>", *size as u8, scalar(*s)),
        TypeInner::Array {
            base,
            size: naga::ArraySize::Constant(n),
            ..
        } => format!("array<{}, {n}>", describe(module, *base)),
        TypeInner::Pointer { base, .. } => format!("ptr<{}>", describe(module, *base)),
        other => module.types[ty]
            .name
            .clone()
            .unwrap_or_else(|| format!("{other:?}")),
    }
}

/// The signature of a function in [`describe`]'s notation.
fn signature(module: &Module, f: &naga::Function) -> (Vec<String>, Option<String>) {
    let args = f.arguments.iter().map(|a| describe(module, a.ty)).collect();
    let result = f.result.as_ref().map(|r| describe(module, r.ty));
    (args, result)
}

impl Expected {
    fn matches(&self, (args, result): &(Vec<String>, Option<String>)) -> bool {
        args.len() == self.args.len()
            && args.iter().zip(self.args).all(|(a, b)| a == b)
            && result.as_deref() == self.result
    }
}

impl fmt::Display for Expected {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "`{}`", self.declaration)
    }
}

/// Check a parsed shader (`module`, from the file `name`) against its
/// convention: the pixel function must be there, optional functions are
/// used when present; a function of a convention's name with another type
/// is an error, never ignored.
pub(crate) fn check(
    module: &Module,
    name: &str,
    language: Language,
    numbers: ShaderNumbers,
) -> Result<Provides, GpuError> {
    let fail = |text: String| GpuError::Shader {
        diagnostic: format!("{name}: error: {text} (docs/shaders.md)"),
    };
    let table = expected(language, numbers).map_err(fail)?;
    if language == Language::Wgsl {
        wgsl_own_names(module, numbers).map_err(fail)?;
    }
    let mut entries = Vec::new();
    for want in table {
        let found: Vec<_> = module
            .functions
            .iter()
            .filter(|(_, f)| f.name.as_deref() == Some(want.name))
            .map(|(_, f)| signature(module, f))
            .collect();
        if found.iter().any(|s| want.matches(s)) {
            entries.push(want.entry);
        } else if let Some((args, result)) = found.first() {
            return Err(fail(format!(
                "`{}` has the type ({}) -> {}, but the harness calls {want}",
                want.name,
                args.join(", "),
                result.as_deref().unwrap_or("void")
            )));
        } else if want.entry == Entry::Pixels {
            let what = match language {
                Language::Glsl => "a Shadertoy shader defines it",
                Language::Wgsl => "the harness calls it for every pixel",
            };
            return Err(fail(format!("no function {want}: {what}")));
        }
    }
    let status = module.global_variables.iter().any(|(_, g)| {
        g.name.as_deref() == Some("status")
            && g.space == naga::AddressSpace::Private
            && describe(module, g.ty) == "i32"
    });
    Ok(Provides {
        entries,
        status: numbers == ShaderNumbers::Float316 && status,
    })
}

/// What a WGSL shader may not declare (docs/shaders.md): an entry point
/// (the wrapper has them: a `@compute fn main` of its own would never be
/// called), a resource binding (the wrapper's `@group(0)` bindings are the
/// kernel's only ones), or a name starting with `harness_` (the wrapper's),
/// besides those [`wgsl_provided`] gives it to call. `module` is the user's
/// code followed by [`wgsl_provided`]. The message names what is refused.
fn wgsl_own_names(module: &Module, numbers: ShaderNumbers) -> Result<(), String> {
    if let Some(entry) = module.entry_points.first() {
        let stage = format!("{:?}", entry.stage).to_lowercase();
        return Err(format!(
            "the shader declares the entry point `{}` (@{}): the harness's wrapper has \
             the entry points, and calls the shader's `pixel` (and `sdf`, `op`); remove \
             the entry point",
            entry.name, stage
        ));
    }
    if let Some(name) = module
        .global_variables
        .iter()
        .find(|(_, g)| g.binding.is_some())
        .map(|(_, g)| g.name.as_deref().unwrap_or("an unnamed variable"))
    {
        return Err(format!(
            "the shader declares the binding `{name}` (@group/@binding): the harness's \
             wrapper has the kernel's bindings; a shader's globals are `var<private>` or \
             `const`"
        ));
    }
    let provided = provided_names(numbers);
    let functions = module
        .functions
        .iter()
        .map(|(_, f)| ("function", f.name.as_deref()));
    let globals = module
        .global_variables
        .iter()
        .map(|(_, g)| ("variable", g.name.as_deref()));
    let constants = module
        .constants
        .iter()
        .map(|(_, c)| ("constant", c.name.as_deref()));
    let overrides = module
        .overrides
        .iter()
        .map(|(_, o)| ("override", o.name.as_deref()));
    let types = module
        .types
        .iter()
        .map(|(_, t)| ("type", t.name.as_deref()));
    let reserved = functions
        .chain(globals)
        .chain(constants)
        .chain(overrides)
        .chain(types)
        .filter_map(|(what, name)| Some((what, name?)))
        .find(|(_, name)| name.starts_with(RESERVED_PREFIX) && !provided.iter().any(|p| p == name));
    match reserved {
        Some((what, name)) => Err(format!(
            "the shader declares the {what} `{name}`: names starting with \
             `{RESERVED_PREFIX}` are the harness's wrapper's{}; rename it",
            if provided.is_empty() {
                String::new()
            } else {
                format!(" (a shader may call {})", provided.join(", "))
            }
        )),
        None => Ok(()),
    }
}

/// The prefix of the wrapper's names, which a shader may not declare.
pub const RESERVED_PREFIX: &str = "harness_";

/// The names [`wgsl_provided`] declares for a shader computing with
/// `numbers`: the only `harness_` names a shader's module may hold.
fn provided_names(numbers: ShaderNumbers) -> Vec<String> {
    let text = wgsl_provided(numbers);
    let module = naga::front::wgsl::parse_str(&text).expect("the provided WGSL parses alone");
    let functions = module.functions.iter().map(|(_, f)| f.name.clone());
    let globals = module.global_variables.iter().map(|(_, g)| g.name.clone());
    functions.chain(globals).flatten().collect()
}

const IO_WGSL: &str = include_str!("wrappers/io.wgsl");
const F32_PIXELS_WGSL: &str = include_str!("wrappers/f32_pixels.wgsl");
const F32_SDF_WGSL: &str = include_str!("wrappers/f32_sdf.wgsl");
const F316_IO_WGSL: &str = include_str!("wrappers/f316_io.wgsl");
const F316_PIXELS_WGSL: &str = include_str!("wrappers/f316_pixels.wgsl");
const F316_SDF_WGSL: &str = include_str!("wrappers/f316_sdf.wgsl");
const F316_OPS_WGSL: &str = include_str!("wrappers/f316_ops.wgsl");
const IO_GLSL: &str = include_str!("wrappers/io.glsl");
const PIXELS_GLSL: &str = include_str!("wrappers/pixels.glsl");
const SDF_GLSL: &str = include_str!("wrappers/sdf.glsl");

/// The image size as the wrappers' float literals.
fn sized(text: &str) -> String {
    text.replace("HARNESS_WIDTH", &format!("{WIDTH}.0"))
        .replace("HARNESS_HEIGHT", &format!("{HEIGHT}.0"))
}

/// What a WGSL shader may call besides its own code: for Float316 the
/// spec's dither matrix, `harness_bayer(x, y)` (a Float316 shader dithers
/// itself); nothing for f32.
pub(crate) fn wgsl_provided(numbers: ShaderNumbers) -> String {
    match numbers {
        ShaderNumbers::F32 => String::new(),
        ShaderNumbers::Float316 => {
            crate::image::bayer_wgsl("harness_bayer_matrix", "harness_bayer")
        }
    }
}

/// The WGSL that follows the user's code: bindings, loop-guard state,
/// [`wgsl_provided`], and one entry point per provided entry.
pub(crate) fn wgsl_wrapper(numbers: ShaderNumbers, provides: &Provides) -> String {
    let status = if provides.status { "status" } else { "0" };
    let mut text = IO_WGSL.replace("HARNESS_USER_STATUS", status);
    if numbers == ShaderNumbers::Float316 {
        text.push_str(F316_IO_WGSL);
    }
    text.push_str(&wgsl_provided(numbers));
    for entry in &provides.entries {
        text.push_str(match (numbers, entry) {
            (ShaderNumbers::F32, Entry::Pixels) => F32_PIXELS_WGSL,
            (ShaderNumbers::F32, _) => F32_SDF_WGSL,
            (ShaderNumbers::Float316, Entry::Pixels) => F316_PIXELS_WGSL,
            (ShaderNumbers::Float316, Entry::Sdf) => F316_SDF_WGSL,
            (ShaderNumbers::Float316, Entry::Ops) => F316_OPS_WGSL,
        });
    }
    sized(&text)
}

/// The GLSL that follows the user's code for one entry: bindings,
/// loop-guard state and `main` (`None`: just the bindings and an empty
/// `main`, to parse the user's code alone).
pub(crate) fn glsl_wrapper(entry: Option<Entry>) -> String {
    let main = match entry {
        None => "\nvoid main() {}\n",
        Some(Entry::Pixels) => PIXELS_GLSL,
        Some(_) => SDF_GLSL,
    };
    sized(&format!("{IO_GLSL}{main}"))
}

/// Shadertoy's uniforms as the GLSL preprocessor's macros, for a still
/// image: `iResolution` the image size, `iTime` 0 and the other inputs at
/// rest (no mouse, frame 0). Textures (`iChannel0..3`) are not provided.
pub(crate) fn shadertoy_defines() -> Vec<(&'static str, String)> {
    vec![
        ("iResolution", format!("vec3({WIDTH}.0, {HEIGHT}.0, 1.0)")),
        ("iTime", "0.0".into()),
        ("iTimeDelta", "0.0".into()),
        ("iFrameRate", "60.0".into()),
        ("iFrame", "0".into()),
        ("iMouse", "vec4(0.0)".into()),
        ("iDate", "vec4(0.0)".into()),
        ("iSampleRate", "44100.0".into()),
    ]
}
