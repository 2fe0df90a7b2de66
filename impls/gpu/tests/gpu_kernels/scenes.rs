//! Kernels generated from scene descriptions: on every shipped scene the
//! Float316 kernel agrees with ref-f316 (made from the same description)
//! bit for bit on the whole image and on SDF queries, uniform ones and
//! those derived from the scene (`vectors::gen::scene_derived`);
//! the f32 kernel renders and is compared with ref-f64 by its error.

use crate::support::{gpu, paired};
use common::{Outcome, SplitMix64, F316};
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

/// Points around the scene (512 in [-4, 4]^3, 64 farther out in
/// [-32, 32]^3), and those derived from it: near every surface, seam,
/// blend region and repetition cell boundary.
fn points(scene: &scene::Checked) -> Vec<[F316; 3]> {
    let mut rng = SplitMix64::new(17);
    let mut points: Vec<[F316; 3]> = [(512, 4.0), (64, 32.0)]
        .into_iter()
        .flat_map(|(n, half)| vec![half; n])
        .map(|half| {
            [(); 3].map(|_| {
                F316::from_f64_truncating((rng.unit() * 2.0 - 1.0) * half).expect("a small value")
            })
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

/// What [`check`] saw besides agreement.
#[derive(Default)]
struct Seen {
    /// gpu-f32's level flips against ref-f64.
    flips: usize,
    /// Pixels and SDF points both Float316 sides answered out of domain.
    out_of_domain: [usize; 2],
}

/// ref-f316 and gpu-f316 from `path` agree on every pixel and SDF point
/// (a trap or out of domain is an outcome like a value); gpu-f32 renders.
fn check(path: &str) -> Seen {
    let Some(gpu) = gpu() else {
        return Seen::default();
    };
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
    let ood = |o: &Outcome<GpuPixel>| matches!(o, Outcome::OutOfDomain);
    let ood_pixels = theirs.iter().filter(|o| ood(o)).count();
    let pts = points(&c);
    let g = kernel.sdf(gpu, &pts).unwrap();
    let ood_sdf = g
        .iter()
        .filter(|o| matches!(o, Outcome::OutOfDomain))
        .count();
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
    let flips = paired(path, &f64_image.pixels, &f32_image)
        .filter(|(b, a)| !a.same_as(b, |a, b| a.level == b.level))
        .count();
    Seen {
        flips,
        out_of_domain: [ood_pixels, ood_sdf],
    }
}

#[test]
fn seed_scene_generated() {
    let flips = check("seed.json").flips;
    assert!(flips < 2000, "{flips}");
}

#[test]
fn rtdemo_generated() {
    let flips = check("rtdemo.json").flips;
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

/// The seed with three call sites at one Newton step (`variants`): the
/// kernel computes those sites' variants as ref-f316 does, on every pixel
/// and SDF point (scene-jack's and reference's tests show the variants
/// change the answers of their sites).
#[test]
fn seed_with_tuned_sites_generated() {
    check("tests/seed-tuned.json");
}

/// The seed with both floors at `floor-direct` and four products truncated
/// (two in the torus's distance): the kernel computes them as ref-f316
/// does, on every pixel and SDF point (scene-jack's tests show the
/// products change answers and each variant is cheaper on the Jack VM).
#[test]
fn seed_with_tuned_operations_generated() {
    check("tests/seed-tuned-ops.json");
}

/// A scene written for this test, with combinations and shapes no other
/// scene or test uses (intersection, subtraction, cylinder, round box,
/// scale), renders on every implementation with no code written for it.
#[test]
fn a_new_combination_renders_everywhere() {
    check("tests/carved.json");
}

/// A scene that drives `floor` and `mod2` outside their modelled domain
/// (a checker plane scaled by 0.001): gpu-f316 answers out of domain on
/// exactly the pixels and SDF points where ref-f316 does (the sky and far
/// floor; points beyond |x| or |z| of 16.384, or whose floors sum past
/// 2^14), and the same values elsewhere.
#[test]
fn out_of_domain_as_the_reference() {
    let Some(_) = gpu() else { return };
    let [pixels, sdf] = check("tests/domain.json").out_of_domain;
    assert!(pixels > 300, "{pixels} pixels out of domain");
    assert!(sdf > 10, "{sdf} SDF points out of domain");
}
