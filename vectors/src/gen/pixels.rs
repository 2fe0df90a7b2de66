//! Pixel coordinates: random subsets, the image border, the horizon, and,
//! from facts about a render supplied by the caller ([`PixelFacts`]), the
//! silhouettes, the shadow edges and the pixels whose dithered value lies
//! exactly on the threshold.

use super::Draw;
use crate::set::{PixelVector, Vector};
use common::image_consts::{HEIGHT, WIDTH};

/// The categories of pixels.
pub const CATEGORIES: [&str; 6] = [
    "random",
    "border",
    "horizon",
    "silhouette",
    "shadow-edge",
    "dither-tie",
];

/// Facts about a render of the whole image.
pub struct PixelFacts {
    /// Pre-dither shades, row by row (`WIDTH * HEIGHT`).
    pub shades: Vec<f64>,
    /// The background's shade, which marks a miss.
    pub background: f64,
    /// Pixels whose dithered value is exactly the threshold 0.5.
    pub dither_ties: Vec<(u16, u16)>,
}

impl PixelFacts {
    fn at(&self, x: usize, y: usize) -> f64 {
        self.shades[y * WIDTH + x]
    }

    /// Pixels with a right or lower neighbour across an edge: `silhouette`
    /// when one side is background, `shadow-edge` when the brighter side is
    /// about four times the darker one (a shadow quarters the value).
    fn edges(&self, category: &str) -> Vec<(u16, u16)> {
        let is_bg = |v: f64| v == self.background;
        let mut out = Vec::new();
        for y in 0..HEIGHT - 1 {
            for x in 0..WIDTH - 1 {
                let a = self.at(x, y);
                let hit = [self.at(x + 1, y), self.at(x, y + 1)].into_iter().any(|b| {
                    if category == "silhouette" {
                        is_bg(a) != is_bg(b)
                    } else {
                        let (lo, hi) = (a.min(b), a.max(b));
                        !is_bg(a) && !is_bg(b) && lo > 0.0 && (3.0..5.0).contains(&(hi / lo))
                    }
                });
                if hit {
                    out.push((x as u16, y as u16));
                }
            }
        }
        out
    }
}

/// The first row, per column, whose ray meets the floor within the
/// maximum distance 12: the horizon of the floor (camera of the spec).
fn horizon_row(x: usize) -> usize {
    // Camera basis for eye (0, 1.5, 4) looking at the origin.
    let f = normalize([0.0, 1.5, 4.0]);
    let r = normalize(cross([0.0, 1.0, 0.0], f));
    let up = cross(f, r);
    let u = (x as f64 - 256.0) / 256.0;
    (0..HEIGHT)
        .find(|&y| {
            let v = -((y as f64 - 128.0) / 256.0);
            let d = normalize([u, v, -1.0]);
            let ry = r[1] * d[0] + up[1] * d[1] + f[1] * d[2];
            // Distance along the ray to the plane y = -1 from height 1.5.
            ry < 0.0 && -2.5 / ry <= 12.0
        })
        .unwrap_or(HEIGHT - 1)
}

fn normalize(v: [f64; 3]) -> [f64; 3] {
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    v.map(|c| c / l)
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - b[1] * a[2],
        a[2] * b[0] - b[2] * a[0],
        a[0] * b[1] - b[0] * a[1],
    ]
}

/// `per_category` pixels of every category, in category order. The
/// categories that need facts about a render are left out without them.
pub fn generate(seed: u64, per_category: usize, facts: Option<&PixelFacts>) -> Vec<Vector> {
    let mut d = Draw::new(seed);
    let mut out = Vec::new();
    for category in CATEGORIES {
        let pool: Vec<(u16, u16)> = match category {
            "random" => Vec::new(),
            "border" => (0..WIDTH)
                .flat_map(|x| [(x, 0), (x, HEIGHT - 1)])
                .chain((1..HEIGHT - 1).flat_map(|y| [(0, y), (WIDTH - 1, y)]))
                .map(|(x, y)| (x as u16, y as u16))
                .collect(),
            "horizon" => (0..WIDTH)
                .map(|x| (x as u16, horizon_row(x) as u16))
                .collect(),
            "dither-tie" => match facts {
                Some(f) => f.dither_ties.clone(),
                None => continue,
            },
            edge => match facts {
                Some(f) => f.edges(edge),
                None => continue,
            },
        };
        for _ in 0..per_category {
            let (x, y) = if category == "random" {
                (d.one(&(0..WIDTH as u16)), d.one(&(0..HEIGHT as u16)))
            } else if pool.is_empty() {
                break;
            } else {
                pool[d.one(&(0..pool.len()))]
            };
            out.push(Vector::Pixel(PixelVector {
                category: category.to_string(),
                x,
                y,
            }));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn border_and_horizon_pixels() {
        let all = generate(9, 10, None);
        assert_eq!(all, generate(9, 10, None));
        assert_eq!(all.len(), 30);
        for v in &all {
            let Vector::Pixel(p) = v else { panic!() };
            match p.category.as_str() {
                "border" => assert!(p.x == 0 || p.y == 0 || p.x == 511 || p.y == 255),
                "horizon" => assert!((60..160).contains(&p.y), "{v}"),
                _ => {}
            }
        }
    }

    #[test]
    fn edges_come_from_the_shade_map() {
        // Background above row 100, a lit floor below, a shadow in a box.
        let mut shades = vec![0.835; WIDTH * HEIGHT];
        for y in 100..HEIGHT {
            for x in 0..WIDTH {
                let shadow = (200..300).contains(&x) && (150..200).contains(&y);
                shades[y * WIDTH + x] = if shadow { 0.2 } else { 0.8 };
            }
        }
        let facts = PixelFacts {
            shades,
            background: 0.835,
            dither_ties: vec![(7, 9)],
        };
        let all = generate(3, 5, Some(&facts));
        assert!(all
            .iter()
            .filter(|v| v.category() == "dither-tie")
            .all(|v| v.slug() == "pixel-7-9"));
        for v in &all {
            let Vector::Pixel(p) = v else { panic!() };
            match p.category.as_str() {
                "silhouette" => assert_eq!(p.y, 99),
                "shadow-edge" => assert!(
                    [199, 299].contains(&p.x) || [149, 199].contains(&p.y),
                    "{v}"
                ),
                _ => {}
            }
        }
        assert_eq!(
            all.iter().filter(|v| v.category() == "silhouette").count(),
            5
        );
    }
}
