//! The `fma` variant: the float formulation with its multiply-adds
//! contracted, as a GPU driver may compile `a * b + c`.

use common::F316;
use reference::{RefImpl, Reference, Scene, Settings, Variant};

fn fused(implementation: RefImpl) -> Reference {
    Reference::new(
        implementation,
        &Scene::default(),
        Variant::Fma.apply(Settings::default()),
    )
    .expect("the seed scene is valid")
}

/// The seed sphere's distance at `p` by hand in f32: `length(p - centre) -
/// 1`, its dot product either rounded at each step (the spec) or with each
/// product after the first fused into the sum before it.
fn sphere_by_hand(p: [f32; 3], contracted: bool) -> f32 {
    let q = [p[0] - (-1.5), p[1], p[2]];
    let d = if contracted {
        q[2].mul_add(q[2], q[1].mul_add(q[1], q[0] * q[0]))
    } else {
        (q[0] * q[0] + q[1] * q[1]) + q[2] * q[2]
    };
    d.sqrt() - 1.0
}

/// Points where the seed scene's nearest surface is the sphere (left of
/// the torus, above the floor, within 0.4 of the surface).
fn sphere_points() -> Vec<[F316; 3]> {
    let mut points = Vec::new();
    for i in 0..23 {
        for j in 0..9 {
            for k in 0..23 {
                let p = [
                    -2.9 + 0.061 * f64::from(i),
                    -0.4 + 0.097 * f64::from(j),
                    -1.1 + 0.1003 * f64::from(k),
                ];
                let q = [p[0] + 1.5, p[1], p[2]];
                let r = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2]).sqrt();
                if (0.7..1.35).contains(&r) && p[0] < -1.0 {
                    points.push(p.map(|x| F316::from_f64_truncating(x).expect("in range")));
                }
            }
        }
    }
    points
}

#[test]
fn the_fma_variant_computes_the_sphere_with_fused_multiply_adds() {
    let spec = Reference::seed(RefImpl::F32);
    let contracted = fused(RefImpl::F32);
    let points = sphere_points();
    assert!(points.len() > 500, "{} points", points.len());
    let mut differing = 0;
    for p in points {
        let p32 = p.map(|c| c.to_f64() as f32);
        let sd = |r: &Reference| r.sdf(p).value().expect("a value").sd.value;
        assert_eq!(
            sd(&spec),
            f64::from(sphere_by_hand(p32, false)),
            "the spec at {p32:?}"
        );
        assert_eq!(
            sd(&contracted),
            f64::from(sphere_by_hand(p32, true)),
            "fused at {p32:?}"
        );
        differing += usize::from(sd(&spec) != sd(&contracted));
    }
    assert!(differing > 0, "fusing changed no distance");
}

#[test]
fn the_fma_variant_changes_shades_of_the_image() {
    for implementation in [RefImpl::F32, RefImpl::F64] {
        let spec = Reference::seed(implementation).render();
        let contracted = fused(implementation).render();
        let changed = spec
            .pixels
            .iter()
            .zip(&contracted.pixels)
            .filter(|(a, b)| a != b)
            .count();
        eprintln!("{implementation}: {changed} shades changed");
        assert!(changed > 0, "{implementation}: no shade changed");
    }
}

#[test]
fn the_fma_variant_applies_to_the_float_formulations_only() {
    assert!(Variant::Fma.applies_to(RefImpl::F32));
    assert!(Variant::Fma.applies_to(RefImpl::F64));
    assert!(!Variant::Fma.applies_to(RefImpl::F316));
    assert_eq!("fma".parse::<Variant>().unwrap(), Variant::Fma);
}
