//! Vectors derived from a scene description (docs/scenes.md, "Vectors from
//! a scene"), found with the scene's own f64 reference (`ref-f64` made from
//! the description):
//! - SDF query points ([`sdf_points`]): at small signed distances from the
//!   surface of every node (each shape and each combination, evaluated as
//!   the scene's root: a node below a repetition is its copy in the cell at
//!   the origin), on the seams where two children of a combination meet,
//!   in a smooth union's blend region, and on repetition cell boundaries;
//! - pixels ([`pixels`]): where the f64 render's hit or miss, the surface
//!   hit, the shadow decision or the bounce count changes between a pixel
//!   and its right or lower neighbour, and the horizon.
//!
//! Everything is deterministic: the same scene and seed give the same set.

use super::Draw;
use crate::set::{Level, PixelVector, SdfVector, Vector, VectorSet};
use common::{Outcome, F316};
use rayon::prelude::*;
use reference::{Decided, Decision, Described, RefImpl, Settings};
use scene::desc::{Camera, Node};
use scene::Checked;

/// Near-surface points lie within this distance of their node's surface
/// (in f64, after encoding as Float316).
pub const BAND: f64 = 1e-3;

/// Seam points lie within this distance of both children's surfaces.
pub const SEAM_BAND: f64 = 4e-3;

/// Cell-boundary points lie within this distance of a boundary plane.
pub const CELL_BAND: f64 = 1e-3;

/// Half the side of the cube, around the camera's target, that starting
/// points are drawn from.
pub const REACH: f64 = 4.0;

/// Projection steps toward a surface.
const STEPS: usize = 12;

/// Starting points tried per wanted point before a node is given up.
const TRIES: usize = 8;

/// Why vectors could not be derived from a scene.
#[derive(Debug, thiserror::Error)]
pub enum SceneVectorsError {
    #[error("node {node} as the root: {message}")]
    Node { node: String, message: String },
    #[error("{0}")]
    Reference(String),
    #[error(
        "the image is {0}x{1}: pixel vectors hold coordinates of at most 512x256 (the set format's image)"
    )]
    TooLarge(u32, u32),
}

/// The scene's f64 reference with `root` as its root.
fn as_root(scene: &Checked, root: &str) -> Result<Described, SceneVectorsError> {
    let mut d = scene.description.clone();
    d.root = root.to_string();
    // Sites are named from the whole scene's root, and the float
    // references these fields run on ignore variants anyway.
    d.variants.clear();
    let bad = |message: String| SceneVectorsError::Node {
        node: root.to_string(),
        message,
    };
    let checked = scene::check::check(d).map_err(|e| bad(e.to_string()))?;
    Described::new(RefImpl::F64, &checked, Settings::default()).map_err(|e| bad(e.to_string()))
}

fn encode(p: [f64; 3]) -> Option<[F316; 3]> {
    let t = p.map(F316::from_f64_truncating);
    Some([t[0]?, t[1]?, t[2]?])
}

/// A node's signed distance at `p` (after encoding), in f64.
pub struct Field(Described);

impl Field {
    /// The distance of `scene`'s node `root`.
    pub fn new(scene: &Checked, root: &str) -> Result<Self, SceneVectorsError> {
        as_root(scene, root).map(Field)
    }

    /// The distance at the encoded point `q`.
    pub fn at(&self, q: [F316; 3]) -> Option<f64> {
        match self.0.sdf(q) {
            Outcome::Value(v) if v.sd.value.is_finite() => Some(v.sd.value),
            _ => None,
        }
    }

    /// The distance at `p` once encoded.
    fn eval(&self, p: [f64; 3]) -> Option<f64> {
        self.at(encode(p)?)
    }

    /// The gradient at `p` (central differences), normalized.
    fn normal(&self, p: [f64; 3]) -> Option<[f64; 3]> {
        const H: f64 = 1.0 / 64.0;
        let mut g = [0.0; 3];
        for (i, gi) in g.iter_mut().enumerate() {
            let (mut a, mut b) = (p, p);
            a[i] += H;
            b[i] -= H;
            *gi = (self.eval(a)? - self.eval(b)?) / (2.0 * H);
        }
        let l = g.iter().map(|v| v * v).sum::<f64>().sqrt();
        (l > 1e-6).then(|| g.map(|v| v / l))
    }

    /// `p` moved toward the surface by Newton steps along the gradient.
    fn project(&self, mut p: [f64; 3]) -> Option<[f64; 3]> {
        for _ in 0..STEPS {
            let d = self.eval(p)?;
            if d.abs() < BAND / 8.0 {
                break;
            }
            let n = self.normal(p)?;
            // Steps are bounded so a far point does not jump across the
            // scene on a flat gradient.
            let step = d.clamp(-1.0, 1.0);
            p = [0, 1, 2].map(|i| p[i] - step * n[i]);
        }
        Some(p)
    }
}

/// The centre of the cube starting points are drawn from: the camera's
/// target, or the origin for the direct camera.
fn centre(scene: &Checked) -> [f64; 3] {
    match &scene.description.image.camera {
        Camera::LookAt { target, .. } => *target,
        Camera::Direct { .. } => [0.0; 3],
    }
}

fn start(d: &mut Draw, c: [f64; 3]) -> [f64; 3] {
    c.map(|ci| ci + d.one(&(-REACH..REACH)))
}

fn sdf(category: String, q: [F316; 3]) -> Vector {
    Vector::Sdf(SdfVector { category, p: q })
}

/// Up to `n` points within [`BAND`] of `field`'s surface, at signed
/// distances drawn from `(-BAND / 2, BAND / 2)` along the normal.
fn near_surface(d: &mut Draw, field: &Field, c: [f64; 3], n: usize) -> Vec<[F316; 3]> {
    let mut out = Vec::new();
    for _ in 0..n * TRIES {
        if out.len() == n {
            break;
        }
        let Some(p) = field.project(start(d, c)) else {
            continue;
        };
        let Some(normal) = field.normal(p) else {
            continue;
        };
        let off = d.one(&(-BAND / 2.0..BAND / 2.0));
        let Some(q) = encode([0, 1, 2].map(|i| p[i] + off * normal[i])) else {
            continue;
        };
        if field.at(q).is_some_and(|v| v.abs() < BAND) {
            out.push(q);
        }
    }
    out
}

/// Up to `n` points within [`SEAM_BAND`] of both `a`'s and `b`'s surfaces
/// (alternating projections).
fn seam(d: &mut Draw, a: &Field, b: &Field, c: [f64; 3], n: usize) -> Vec<[F316; 3]> {
    let mut out = Vec::new();
    for _ in 0..n * TRIES {
        if out.len() == n {
            break;
        }
        let mut p = Some(start(d, c));
        for _ in 0..6 {
            p = p.and_then(|p| a.project(p)).and_then(|p| b.project(p));
        }
        let Some(q) = p.and_then(encode) else {
            continue;
        };
        let close = |f: &Field| f.at(q).is_some_and(|v| v.abs() < SEAM_BAND);
        if close(a) && close(b) {
            out.push(q);
        }
    }
    out
}

/// The children of a combination node.
fn children(node: &Node) -> Option<&[String]> {
    match node {
        Node::Union(c) | Node::Subtraction(c) | Node::Intersection(c) => Some(&c.children),
        Node::SmoothUnion(c) => Some(&c.children),
        _ => None,
    }
}

/// `per_kind` points of each kind for every node of `scene`, by node name:
/// `near:NODE` (within [`BAND`] of the node's surface), `seam:NODE`
/// (within [`SEAM_BAND`] of two consecutive children's surfaces), `blend:NODE`
/// (a smooth union's surface where its children's distances differ by less
/// than `k`), `cell-edge:NODE` (within [`CELL_BAND`] of a repetition's
/// cell boundary, on the repeated child's surface).
pub fn sdf_points(
    scene: &Checked,
    seed: u64,
    per_kind: usize,
) -> Result<Vec<Vector>, SceneVectorsError> {
    let c = centre(scene);
    let nodes = &scene.description.nodes;
    let fields = nodes
        .keys()
        .map(|name| Ok((name.as_str(), Field::new(scene, name)?)))
        .collect::<Result<std::collections::BTreeMap<_, _>, SceneVectorsError>>()?;
    let mut d = Draw::new(seed);
    let mut out = Vec::new();
    for (name, node) in nodes {
        let field = &fields[name.as_str()];
        let near = near_surface(&mut d, field, c, per_kind);
        out.extend(near.iter().map(|&q| sdf(format!("near:{name}"), q)));
        if let Some(kids) = children(node) {
            for pair in kids.windows(2) {
                let (a, b) = (&fields[pair[0].as_str()], &fields[pair[1].as_str()]);
                let per_pair = per_kind.div_ceil(kids.len() - 1);
                out.extend(
                    seam(&mut d, a, b, c, per_pair)
                        .into_iter()
                        .map(|q| sdf(format!("seam:{name}"), q)),
                );
            }
        }
        if let Node::SmoothUnion(s) = node {
            let (a, b) = (
                &fields[s.children[0].as_str()],
                &fields[s.children[1].as_str()],
            );
            let wide = near_surface(&mut d, field, c, per_kind * TRIES);
            out.extend(
                wide.into_iter()
                    .filter(|&q| match (a.at(q), b.at(q)) {
                        (Some(x), Some(y)) => (x - y).abs() < s.k,
                        _ => false,
                    })
                    .take(per_kind)
                    .map(|q| sdf(format!("blend:{name}"), q)),
            );
        }
        if let Node::Repeat(r) = node {
            out.extend(
                cell_edges(&mut d, field, r.period, &near, per_kind)
                    .into_iter()
                    .map(|q| sdf(format!("cell-edge:{name}"), q)),
            );
        }
    }
    Ok(out)
}

/// Near-surface points of a repetition moved onto the nearest cell
/// boundary `(m + 1/2) c` of one axis with a non-zero period `c`.
fn cell_edges(
    d: &mut Draw,
    field: &Field,
    period: [f64; 3],
    near: &[[F316; 3]],
    n: usize,
) -> Vec<[F316; 3]> {
    let axes: Vec<usize> = (0..3).filter(|&i| period[i] != 0.0).collect();
    let mut out = Vec::new();
    if axes.is_empty() {
        return out;
    }
    for q in near.iter().cycle().take(n * TRIES) {
        if out.len() == n {
            break;
        }
        let axis = axes[d.one(&(0..axes.len()))];
        let mut p = q.map(F316::to_f64);
        let c = period[axis];
        p[axis] = ((p[axis] / c + 0.5).round() - 0.5) * c;
        let Some(e) = encode(p) else { continue };
        if on_cell_edge(e, period) && field.at(e).is_some() {
            out.push(e);
        }
    }
    out
}

/// Whether `q` lies within [`CELL_BAND`] of a cell boundary of `period`.
pub fn on_cell_edge(q: [F316; 3], period: [f64; 3]) -> bool {
    (0..3).any(|i| {
        let c = period[i];
        c != 0.0 && {
            let t = q[i].to_f64() / c + 0.5;
            ((t - t.round()) * c.abs()).abs() < CELL_BAND
        }
    })
}

/// What the f64 render's run of one pixel decided.
#[derive(Clone, Debug, PartialEq)]
pub struct RayFacts {
    /// Whether the view ray met a surface.
    pub hit: bool,
    /// The depth of the view ray's march (sphere tracing).
    pub depth: Option<f64>,
    /// The `union` decisions of the march step that hit: which surface.
    pub surface: Vec<bool>,
    /// The shadow decision, when one was made.
    pub shadow: Option<bool>,
    /// Reflections (analytic spheres).
    pub bounces: usize,
}

impl RayFacts {
    /// The facts of one run's decisions.
    pub fn of(decisions: &[Decided]) -> Self {
        let miss = decisions.iter().position(|d| d.decision == Decision::Miss);
        let bounces = decisions
            .iter()
            .filter(|d| d.decision == Decision::Bounce && d.taken)
            .count();
        let hit = match miss {
            Some(i) => !decisions[i].taken,
            None => bounces > 0,
        };
        let view = &decisions[..miss.unwrap_or(0)];
        let last_step = view
            .iter()
            .rposition(|d| d.decision == Decision::MarchHit)
            .unwrap_or(0);
        let step_start = view[..last_step]
            .iter()
            .rposition(|d| d.decision == Decision::MarchFar)
            .map_or(0, |i| i + 1);
        RayFacts {
            hit,
            depth: miss.map(|i| decisions[i].operands[0]),
            surface: view[step_start..last_step]
                .iter()
                .filter(|d| d.decision == Decision::Union)
                .map(|d| d.taken)
                .collect(),
            shadow: decisions
                .iter()
                .find(|d| d.decision == Decision::Shadow)
                .map(|d| d.taken),
            bounces,
        }
    }
}

/// The categories of scene-derived pixels, in the order a pixel is given
/// the first that applies.
pub const PIXEL_CATEGORIES: [&str; 5] = [
    "horizon",
    "silhouette",
    "reflection-edge",
    "shadow-edge",
    "surface-edge",
];

/// The category of pixel `a` against its neighbour `b`: `horizon` (hit
/// against miss, the hit one's depth beyond half of `max_distance`),
/// `silhouette` (hit against miss), `reflection-edge` (bounce counts
/// differ), `shadow-edge`, `surface-edge` (another surface hit).
pub fn edge(a: &RayFacts, b: &RayFacts, max_distance: f64) -> Option<&'static str> {
    if a.hit != b.hit {
        let depth = if a.hit { a.depth } else { b.depth };
        return Some(if depth.is_some_and(|d| d > max_distance / 2.0) {
            "horizon"
        } else {
            "silhouette"
        });
    }
    if a.bounces != b.bounces {
        return Some("reflection-edge");
    }
    if !a.hit {
        return None;
    }
    if a.shadow != b.shadow {
        return Some("shadow-edge");
    }
    (a.surface != b.surface).then_some("surface-edge")
}

/// The facts of every pixel of `scene`'s f64 render, row by row.
pub fn facts(scene: &Checked) -> Result<Vec<RayFacts>, SceneVectorsError> {
    let f64 = Described::new(RefImpl::F64, scene, Settings::default())
        .map_err(|e| SceneVectorsError::Reference(e.to_string()))?;
    let [w, h] = scene.description.image.size;
    Ok((0..h)
        .into_par_iter()
        .flat_map_iter(|y| {
            let f64 = &f64;
            (0..w).map(move |x| RayFacts::of(&f64.decided_pixel(x, y).1))
        })
        .collect())
}

/// Up to `per_category` pixels of each category of [`PIXEL_CATEGORIES`]
/// (evenly spaced among those found, in row order), each pixel once.
pub fn pixels(scene: &Checked, per_category: usize) -> Result<Vec<Vector>, SceneVectorsError> {
    let [w, h] = scene.description.image.size;
    if w > 512 || h > 256 {
        return Err(SceneVectorsError::TooLarge(w, h));
    }
    let max_distance = match scene.description.method {
        scene::desc::Method::SphereTrace { max_distance, .. } => max_distance,
        scene::desc::Method::AnalyticSpheres { .. } => f64::INFINITY,
    };
    let facts = facts(scene)?;
    let (w, h) = (w as usize, h as usize);
    let mut found: Vec<Vec<(u16, u16)>> = vec![Vec::new(); PIXEL_CATEGORIES.len()];
    for y in 0..h {
        for x in 0..w {
            let a = &facts[y * w + x];
            let neighbours = [
                (x + 1 < w).then(|| y * w + x + 1),
                (y + 1 < h).then(|| (y + 1) * w + x),
            ];
            let category = neighbours
                .into_iter()
                .flatten()
                .filter_map(|j| edge(a, &facts[j], max_distance))
                .min_by_key(|c| PIXEL_CATEGORIES.iter().position(|k| k == c));
            if let Some(c) = category {
                let k = PIXEL_CATEGORIES
                    .iter()
                    .position(|k| *k == c)
                    .expect("a category");
                found[k].push((x as u16, y as u16));
            }
        }
    }
    Ok(PIXEL_CATEGORIES
        .iter()
        .zip(found)
        .flat_map(|(category, all)| {
            let stride = all.len().div_ceil(per_category.max(1)).max(1);
            all.into_iter()
                .step_by(stride)
                .map(|(x, y)| {
                    Vector::Pixel(PixelVector {
                        category: category.to_string(),
                        x,
                        y,
                    })
                })
                .collect::<Vec<_>>()
        })
        .collect())
}

/// Points per kind and node of [`sdf_set`].
pub const PER_KIND: usize = 16;

/// Pixels per category of [`pixel_set`].
pub const PER_CATEGORY: usize = 64;

/// The SDF set of `scene` ([`sdf_points`], [`PER_KIND`] of each kind),
/// named `NAME-sdf`.
pub fn sdf_set(scene: &Checked, seed: u64) -> Result<VectorSet, SceneVectorsError> {
    let name = &scene.description.name;
    Ok(VectorSet::new(
        &format!("{name}-sdf"),
        Level::Sdf,
        &format!(
            "points near every surface, seam, blend region and cell boundary of scene {name} \
             (vectors::gen::scene_derived, docs/scenes.md)"
        ),
        Some(seed),
        sdf_points(scene, seed, PER_KIND)?,
    ))
}

/// The pixel set of `scene` ([`pixels`], [`PER_CATEGORY`] of each
/// category), named `NAME-pixels`.
pub fn pixel_set(scene: &Checked) -> Result<VectorSet, SceneVectorsError> {
    let name = &scene.description.name;
    Ok(VectorSet::new(
        &format!("{name}-pixels"),
        Level::Pixels,
        &format!(
            "pixels on the silhouettes, horizon, reflection, shadow and surface edges of \
             scene {name}'s f64 render (vectors::gen::scene_derived, docs/scenes.md)"
        ),
        None,
        pixels(scene, PER_CATEGORY)?,
    ))
}
