//! Scene query points: uniform in the scene box, within 1e-3 of each
//! surface, on the torus axis, at the sphere centre, on floor tile edges
//! (integer x or z) and far away. Points are Float316 triples (encoded by
//! truncation); float implementations use their exact f64 values.

use super::Draw;
use crate::set::{SdfVector, Vector};
use common::F316;
use proptest::prelude::*;
use std::f64::consts::TAU;

/// The categories of query points.
pub const CATEGORIES: [&str; 8] = [
    "uniform",
    "near-floor",
    "near-sphere",
    "near-torus",
    "torus-axis",
    "sphere-centre",
    "tile-edge",
    "far",
];

const SPHERE_CENTRE: [f64; 3] = [-1.5, 0.0, 0.0];
const TORUS_CENTRE: [f64; 3] = [1.5, 0.0, 0.0];
/// Offsets from a surface before encoding; truncating each coordinate to
/// 13 fraction bits moves a point by less than 5e-4 more (|coords| < 4), so
/// every point lies within 1e-3 of its surface.
const NEAR: f64 = 5e-4;

fn encode(p: [f64; 3]) -> [F316; 3] {
    p.map(|c| F316::from_f64_truncating(c).expect("scene coordinates are finite and in range"))
}

/// One point of `category` (as f64 coordinates, before encoding).
fn point(d: &mut Draw, category: &str) -> [f64; 3] {
    let unit = |d: &mut Draw| d.one(&(0.0..1.0f64));
    let near = |d: &mut Draw| d.one(&(-NEAR..=NEAR));
    match category {
        "uniform" => [
            d.one(&(-4.0..4.0f64)),
            d.one(&(-1.2..2.5f64)),
            d.one(&(-6.0..4.0f64)),
        ],
        "near-floor" => [
            d.one(&(-4.0..4.0f64)),
            -1.0 + near(d),
            d.one(&(-6.0..4.0f64)),
        ],
        "near-sphere" => {
            let (theta, z) = (unit(d) * TAU, unit(d) * 2.0 - 1.0);
            let r = 1.0 + near(d);
            let rho = (1.0 - z * z).sqrt();
            [
                SPHERE_CENTRE[0] + r * rho * theta.cos(),
                SPHERE_CENTRE[1] + r * z,
                SPHERE_CENTRE[2] + r * rho * theta.sin(),
            ]
        }
        "near-torus" => {
            let (theta, phi) = (unit(d) * TAU, unit(d) * TAU);
            let tube = 0.25 + near(d);
            let ring = 1.0 + tube * phi.cos();
            [
                TORUS_CENTRE[0] + ring * theta.cos(),
                TORUS_CENTRE[1] + tube * phi.sin(),
                TORUS_CENTRE[2] + ring * theta.sin(),
            ]
        }
        "torus-axis" => {
            let y = if d.one(&(0..4u8)) == 0 {
                0.0
            } else {
                d.one(&(-2.0..2.0f64))
            };
            [TORUS_CENTRE[0], y, 0.0]
        }
        "sphere-centre" => {
            let off = |d: &mut Draw| {
                if d.one(&any::<bool>()) {
                    0.0
                } else {
                    near(d) * 1e-2
                }
            };
            [SPHERE_CENTRE[0] + off(d), off(d), off(d)]
        }
        "tile-edge" => {
            let int = |d: &mut Draw| f64::from(d.one(&(-5..=5i32)));
            let free = |d: &mut Draw| d.one(&(-5.0..5.0f64));
            let y = d.one(&(-1.001..0.5f64));
            match d.one(&(0..3u8)) {
                0 => [int(d), y, free(d)],
                1 => [free(d), y, int(d)],
                _ => [int(d), y, int(d)],
            }
        }
        "far" => {
            let far = |d: &mut Draw| {
                let mag = 10f64.powf(d.one(&(1.0..3.0f64)));
                if d.one(&any::<bool>()) {
                    mag
                } else {
                    -mag
                }
            };
            [far(d), far(d), far(d)]
        }
        other => unreachable!("unknown sdf category {other}"),
    }
}

/// `per_category` points of every category, in category order.
pub fn generate(seed: u64, per_category: usize) -> Vec<Vector> {
    let mut d = Draw::new(seed);
    CATEGORIES
        .iter()
        .flat_map(|&category| {
            (0..per_category)
                .map(|_| {
                    Vector::Sdf(SdfVector {
                        category: category.to_string(),
                        p: encode(point(&mut d, category)),
                    })
                })
                .collect::<Vec<_>>()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn points_lie_where_their_category_says() {
        let all = generate(316, 20);
        assert_eq!(all, generate(316, 20));
        for v in &all {
            let Vector::Sdf(s) = v else { panic!() };
            let [x, y, z] = s.p_f64();
            let ok = match s.category.as_str() {
                "near-floor" => (y + 1.0).abs() <= 1e-3,
                "near-sphere" => (((x + 1.5).powi(2) + y * y + z * z).sqrt() - 1.0).abs() <= 1e-3,
                "near-torus" => {
                    let q = (((x - 1.5).powi(2) + z * z).sqrt() - 1.0).hypot(y);
                    (q - 0.25).abs() <= 1e-3
                }
                "torus-axis" => x == 1.5 && z == 0.0,
                "tile-edge" => x.fract() == 0.0 || z.fract() == 0.0,
                "far" => x.abs() >= 9.99 && y.abs() >= 9.99,
                _ => true,
            };
            assert!(ok, "{v} ({x},{y},{z})");
        }
    }
}
