//! Users' shaders (`gpu::shader`): the seed scene's Shadertoy port and WGSL
//! port from `examples/shaders/` against the references and our gpu-f32
//! kernel, and shaders that fail like real components.

use crate::support::{float_pixels, gpu};
use common::Outcome;
use gpu::shader::{Language, Shade, ShaderNum, ShaderOptions, ShaderSource, UserShader};
use gpu::GpuError;
use reference::{RefImpl, Reference};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

fn file(relative: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(relative)
}

/// Open a shader file, or `None` when the GPU leg is skipped.
fn open(relative: &str, options: ShaderOptions) -> Option<UserShader> {
    let source = ShaderSource::read(&file(relative), None).expect("readable");
    match UserShader::open(&source, &options) {
        Ok(shader) => Some(shader),
        Err(e @ GpuError::NoAdapter { .. }) if std::env::var_os(gpu::SKIP_ENV).is_some() => {
            eprintln!("GPU leg skipped: {e}");
            None
        }
        Err(e) => panic!("{e}"),
    }
}

fn red() -> ShaderOptions {
    ShaderOptions {
        shade: Shade::Red,
        ..ShaderOptions::default()
    }
}

/// Shades and dithered bits of a whole f32 render.
fn f32_image(pixels: Vec<Outcome<(ShaderNum, bool)>>) -> (Vec<f32>, Vec<bool>) {
    pixels
        .into_iter()
        .map(|p| match p {
            Outcome::Value((ShaderNum::F32(v), white)) => (v, white),
            other => panic!("expected an f32 shade, got {other:?}"),
        })
        .unzip()
}

/// Max and mean absolute difference, and dithered-pixel flips.
fn compare(a: &[f32], a_white: &[bool], b: &[f64], b_white: &[bool]) -> (f64, f64, usize) {
    let errs: Vec<f64> = a
        .iter()
        .zip(b)
        .map(|(&x, &y)| (x as f64 - y).abs())
        .collect();
    let flips = a_white.iter().zip(b_white).filter(|(x, y)| x != y).count();
    (
        errs.iter().cloned().fold(0.0, f64::max),
        errs.iter().sum::<f64>() / errs.len() as f64,
        flips,
    )
}

/// The Shadertoy port of the seed scene runs unmodified, and is the seed
/// scene: against ref-f64 its shades differ by f32 rounding and the
/// built-ins' formulas only, and at most 0.1% of the pixels flip.
#[test]
fn the_shadertoy_port_renders_the_seed_scene() {
    let Some(shader) = open("../../examples/shaders/seed.glsl", red()) else {
        return;
    };
    assert!(shader.provides().sdf());
    let (shade, white) = f32_image(shader.render().expect("render"));
    let (want, want_white) = float_pixels(&Reference::seed(RefImpl::F64));
    let (max, mean, flips) = compare(&shade, &white, &want, &want_white);
    eprintln!("seed.glsl against ref-f64: max {max:e}, mean {mean:e}, {flips} flips");
    assert!(max < 1e-3 && mean < 1e-5, "max {max:e}, mean {mean:e}");
    assert!(flips <= 131, "{flips} flips");
}

/// The seed scene as a user's WGSL file against our gpu-f32 kernel: the
/// same figures within the stated tolerance (shades within 1e-4 of each
/// other, at most 0.05% of the pixels dithered differently).
#[test]
fn the_wgsl_port_agrees_with_the_gpu_f32_kernel() {
    let Some(ours) = gpu() else { return };
    let Some(shader) = open("../../examples/shaders/seed.wgsl", ShaderOptions::default()) else {
        return;
    };
    let (shade, white) = f32_image(shader.render().expect("render"));
    let (kernel, kernel_white): (Vec<f32>, Vec<bool>) =
        ours.render_f32().expect("render").into_iter().unzip();
    let kernel_f64: Vec<f64> = kernel.iter().map(|&v| v as f64).collect();
    let (max, mean, flips) = compare(&shade, &white, &kernel_f64, &kernel_white);
    eprintln!("seed.wgsl against gpu-f32: max {max:e}, mean {mean:e}, {flips} flips");
    assert!(max < 1e-4, "max {max:e}");
    assert!(flips <= 65, "{flips} flips");

    // Its sdf level is the kernel's scene too.
    let points = [[common::F316::ONE; 3], [common::F316::ZERO; 3]];
    let user = shader.sdf(&points).expect("sdf");
    let kernel = ours
        .f32_sdf(&points.map(|p| p.map(|c| c.to_f64() as f32)))
        .expect("sdf");
    for (u, (sd, col)) in user.iter().zip(kernel) {
        let Outcome::Value((ShaderNum::F32(usd), ShaderNum::F32(ucol))) = *u else {
            panic!("{u:?}")
        };
        assert!(
            (usd - sd).abs() < 1e-5 && ucol == col,
            "{u:?} vs {sd} {col}"
        );
    }
}

/// A syntax error names the user's file, line and column (naga's
/// diagnostic), not the wrapper's.
#[test]
fn a_syntax_error_points_into_the_users_file() {
    let path = file("tests/shaders/syntax_error.glsl");
    let source = ShaderSource::read(&path, None).expect("readable");
    let message = UserShader::check(&source, &ShaderOptions::default())
        .expect_err("does not parse")
        .to_string();
    eprintln!("{message}");
    let at = format!("{}:5:5: error: ", path.display());
    assert!(message.starts_with(&at), "{message}");
    assert!(
        message.contains("fragColor = vec4(vec3(d), 1.0);"),
        "{message}"
    );
}

#[test]
fn a_missing_main_image_is_named() {
    let source =
        ShaderSource::read(&file("tests/shaders/no_main_image.glsl"), None).expect("readable");
    let message = UserShader::check(&source, &ShaderOptions::default())
        .expect_err("no mainImage")
        .to_string();
    assert!(
        message.contains("no function `void mainImage(out vec4 fragColor, in vec2 fragCoord)`"),
        "{message}"
    );
}

/// A shader that loops for ever answers a hang for every pixel, in
/// bounded time (the loop guard), and the device goes on working.
#[test]
fn an_endless_loop_is_a_hang() {
    let Some(shader) = open("tests/shaders/endless.glsl", ShaderOptions::default()) else {
        return;
    };
    let pixels: Vec<(u16, u16)> = (0..512).map(|x| (x, 7)).collect();
    let answers = shader.pixels(&pixels).expect("answers");
    assert!(answers.iter().all(|a| matches!(a, Outcome::Hang)));
    let again = shader.pixels(&[(0, 0)]).expect("the device still works");
    assert!(matches!(again[0], Outcome::Hang));
}

/// A dispatch that outruns its time limit is a timeout; the shader is
/// abandoned (later calls fail at once, nothing waits for the dispatch)
/// and the harness goes on.
#[test]
fn a_dispatch_past_its_time_limit_is_a_timeout() {
    let options = ShaderOptions {
        loop_limit: Some(20_000),
        time_limit: Some(Duration::from_millis(200)),
        ..ShaderOptions::default()
    };
    // Opening dispatches one pixel: well within the limit.
    let Some(shader) = open("tests/shaders/slow.wgsl", options) else {
        return;
    };
    let started = Instant::now();
    match shader.render() {
        Err(GpuError::Timeout { kernel, seconds }) => {
            assert!(kernel.ends_with("slow.wgsl pixels"), "{kernel}");
            assert_eq!(seconds, 0.2);
        }
        other => panic!("expected a timeout, got {other:?}"),
    }
    assert!(started.elapsed() < Duration::from_secs(10));
    assert!(matches!(
        shader.pixels(&[(0, 0)]),
        Err(GpuError::Timeout { .. })
    ));
    drop(shader);
    // Our own kernels, on their own device, are unaffected.
    if let Some(ours) = gpu() {
        ours.f32_pixels(&[(1, 1)])
            .expect("another device still works");
    }
}

#[test]
fn the_language_comes_from_the_extension() {
    assert_eq!(
        Language::from_extension(Path::new("a/b.frag")),
        Some(Language::Glsl)
    );
    assert_eq!(
        Language::from_extension(Path::new("x.wgsl")),
        Some(Language::Wgsl)
    );
    assert_eq!(Language::from_extension(Path::new("x.txt")), None);
}

/// Shadertoy's usual idioms (a version line, precision, macros with
/// arguments, structs, inout, while/continue, matrices) run unmodified.
#[test]
fn shadertoy_idioms_run_unmodified() {
    let Some(shader) = open("tests/shaders/idioms.glsl", ShaderOptions::default()) else {
        return;
    };
    let (shade, _) = f32_image(shader.render().expect("render"));
    let sky = shade[0];
    assert!(shade.iter().all(|v| (0.0..=1.0).contains(v)));
    assert!(
        shade.iter().any(|&v| (v - sky).abs() > 0.1),
        "not a flat image"
    );
}

/// A Shadertoy shader of another scene, written as an outsider would and
/// declared by following docs/shaders.md alone (tests/shaders/two_shapes.glsl:
/// `#define`, a `mat2` rotation of a swizzle, an int `for` loop with
/// `break`, integer literals in float constructors), runs unmodified: every
/// pixel answers, the sky is Shadertoy's sky colour by luminance, the
/// box's face in its own shadow is dark.
#[test]
fn an_outsiders_shadertoy_shader_runs_unmodified() {
    let Some(shader) = open("tests/shaders/two_shapes.glsl", ShaderOptions::default()) else {
        return;
    };
    assert!(!shader.provides().sdf());
    let (shade, _) = f32_image(shader.render().expect("render"));
    // The top left pixel sees only sky: pow(vec3(.6, .7, .9), vec3(.4545)).
    let sky: f64 = [(0.2126, 0.6), (0.7152, 0.7), (0.0722, 0.9)]
        .iter()
        .map(|(w, c): &(f64, f64)| w * c.powf(0.4545))
        .sum();
    assert!(
        (f64::from(shade[0]) - sky).abs() < 1e-4,
        "{} vs {sky}",
        shade[0]
    );
    let box_face = shade[140 * 512 + 190];
    assert!(box_face < 0.5, "{box_face}");
}
