//! Kernels generated from scene descriptions: on every shipped scene the
//! Float316 kernel agrees with ref-f316 (made from the same description)
//! bit for bit on the whole image and on SDF queries, uniform ones and
//! those derived from the scene (`vectors::gen::scene_derived`);
//! the f32 kernel renders and is compared with ref-f64 by its error.

use crate::support::{gpu, paired, Rng};
use common::{Outcome, F316};
use gpu::GpuPixel;
use reference::{Described, RefImpl, ScenePixel, Settings};

fn load(path: &str) -> scene::Checked {
    let path = format!("{}/../../vectors/scenes/{path}", env!("CARGO_MANIFEST_DIR"));
    scene::load(std::path::Path::new(&path)).unwrap_or_else(|e| panic!("{e}"))
}

fn same(g: &Outcome<GpuPixel>, r: &Outcome<ScenePixel>) -> bool {
    g.same_as(r, |g, r| {
        g.level == r.level && g.value.triple == r.value.triple
    })
}

/// Points around the scene, and those derived from it: near every
/// surface, seam, blend region and repetition cell boundary.
fn points(scene: &scene::Checked) -> Vec<[F316; 3]> {
    let mut rng = Rng::new(17);
    let mut points: Vec<[F316; 3]> = (0..512)
        .map(|_| {
            [(); 3]
                .map(|_| F316::from_f64_truncating(rng.unit() * 8.0 - 4.0).expect("a small value"))
        })
        .collect();
    let derived = vectors::gen::scene_derived::sdf_points(scene, 17, 8).unwrap();
    assert!(!derived.is_empty());
    points.extend(derived.iter().filter_map(|v| match v {
        vectors::Vector::Sdf(s) => Some(s.p),
        _ => None,
    }));
    points
}

/// ref-f316 and gpu-f316 from `path` agree on every pixel and SDF point;
/// gpu-f32 renders (returns its level flips against ref-f64).
fn check(path: &str) -> usize {
    let Some(gpu) = gpu() else { return 0 };
    let c = load(path);
    let f316 = Described::new(RefImpl::F316, &c, Settings::default()).unwrap();
    let kernel = gpu
        .scene_kernel(f316.program())
        .expect("the generated kernel compiles");
    let theirs = kernel.render(gpu).unwrap();
    let ours = f316.render();
    let bad: Vec<usize> = paired(path, &ours.pixels, &theirs)
        .enumerate()
        .filter(|(_, (r, g))| !same(g, r))
        .map(|(i, _)| i)
        .collect();
    assert!(
        bad.is_empty(),
        "{path}: {} of {} pixels differ, first {:?}: gpu {:?} ref {:?}",
        bad.len(),
        ours.pixels.len(),
        bad.first(),
        bad.first().map(|&i| theirs[i]),
        bad.first().map(|&i| ours.pixels[i])
    );
    let pts = points(&c);
    let g = kernel.sdf(gpu, &pts).unwrap();
    for (p, g) in paired(path, &pts, &g) {
        let r = f316.sdf(*p);
        let agree = g.same_as(&r, |(sd, col), v| {
            sd.triple == v.sd.triple && col.triple == v.col.triple
        });
        assert!(agree, "{path}: sdf{p:?}: gpu {g:?} ref {r:?}");
    }
    let f64_image = Described::new(RefImpl::F64, &c, Settings::default())
        .unwrap()
        .render();
    let f32_kernel = gpu
        .scene_kernel(
            Described::new(RefImpl::F32, &c, Settings::default())
                .unwrap()
                .program(),
        )
        .expect("the f32 kernel compiles");
    let f32_image = f32_kernel.render(gpu).unwrap();
    paired(path, &f64_image.pixels, &f32_image)
        .filter(|(b, a)| !a.same_as(b, |a, b| a.level == b.level))
        .count()
}

#[test]
fn seed_scene_generated() {
    let flips = check("seed.json");
    assert!(flips < 2000, "{flips}");
}

#[test]
fn rtdemo_generated() {
    let flips = check("rtdemo.json");
    assert!(flips < 2000, "{flips}");
}

#[test]
fn sdf_engine_generated() {
    check("sdf-engine.json");
}

#[test]
fn toon_generated() {
    check("toon.json");
}

/// A scene written for this test, with combinations and shapes no other
/// scene or test uses (intersection, subtraction, cylinder, round box,
/// scale), renders on every implementation with no code written for it.
#[test]
fn a_new_combination_renders_everywhere() {
    check("tests/carved.json");
}
