//! The scene-derived generators: every generated set validates, is the same
//! on every run, and each vector lies where its category says, checked with
//! an oracle of the scene's distances written from the format's rules
//! (`support`), which is itself checked against ref-f64 on every node of
//! every scene.

mod support;

use common::{Outcome, F316};
use reference::{Described, RefImpl, Settings};
use scene::desc::{Camera, Node};
use std::path::PathBuf;
use support::Oracle;
use vectors::gen::scene_derived::{edge, facts, pixels, sdf_points};
use vectors::{Level, Vector, VectorSet};

/// The claims of docs/scenes.md ("Vectors from a scene"), restated here:
/// a near-surface point's distance, a seam point's distance to both
/// children, a cell-edge point's distance to the boundary plane.
const NEAR: f64 = 1e-3;
const SEAM: f64 = 4e-3;
const CELL: f64 = 1e-3;

/// How far the oracle and ref-f64 may part on a distance or a colour: both
/// compute in f64 from the same numbers, by formulas that differ only in
/// the order of their roundings, at points within a few units of the
/// origin.
const AGREE: f64 = 1e-9;

fn scene(name: &str) -> scene::Checked {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("scenes/{name}.json"));
    scene::load(&path).unwrap_or_else(|e| panic!("{e}"))
}

const SCENES: [&str; 5] = ["seed", "rtdemo", "sdf-engine", "toon", "tests/carved"];

/// A set of `vectors` survives its file format's validation.
fn validates(name: &str, level: Level, vectors: Vec<Vector>) {
    let set = VectorSet::new(name, level, "scene-derived", Some(1), vectors);
    let back = VectorSet::parse(name, &set.to_json()).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(back, set);
}

#[test]
fn sdf_points_lie_where_their_category_says() {
    for name in SCENES {
        let s = scene(name);
        let points = sdf_points(&s, 7, 6).unwrap();
        assert_eq!(
            points,
            sdf_points(&s, 7, 6).unwrap(),
            "{name}: deterministic"
        );
        let nodes = &s.description.nodes;
        let oracle = Oracle::new(&s.description);
        let mut near = 0;
        for v in &points {
            let Vector::Sdf(p) = v else { panic!() };
            let (kind, node) = p.category.split_once(':').unwrap();
            let q = p.p.map(F316::to_f64);
            let sd = |n: &str| oracle.at(n, q).sd;
            let close = |n: &String| sd(n).abs() < SEAM;
            match (kind, &nodes[node]) {
                ("near", _) => {
                    near += 1;
                    assert!(sd(node).abs() < NEAR, "{name}: {v}: distance {}", sd(node));
                }
                ("seam", Node::Union(c) | Node::Subtraction(c) | Node::Intersection(c)) => {
                    assert!(
                        c.children.windows(2).any(|w| close(&w[0]) && close(&w[1])),
                        "{name}: {v}"
                    );
                }
                ("seam", Node::SmoothUnion(c)) => {
                    assert!(
                        c.children.windows(2).any(|w| close(&w[0]) && close(&w[1])),
                        "{name}: {v}"
                    );
                }
                ("blend", Node::SmoothUnion(c)) => {
                    let [a, b] = [&c.children[0], &c.children[1]].map(|n| sd(n));
                    assert!((a - b).abs() < c.k, "{name}: {v}: {a} {b}");
                    assert!(sd(node).abs() < NEAR, "{name}: {v}");
                }
                ("cell-edge", Node::Repeat(r)) => {
                    // Within CELL of a plane x_i = (m + 1/2) c_i.
                    let on_edge = (0..3).any(|i| {
                        let c = r.period[i];
                        let m = (q[i] / c - 0.5).round();
                        c != 0.0 && (q[i] - (m + 0.5) * c).abs() < CELL
                    });
                    assert!(on_edge, "{name}: {v}");
                }
                _ => panic!("{name}: unexpected category {}", p.category),
            }
        }
        assert!(
            near >= nodes.len(),
            "{name}: {near} near-surface points for {} nodes",
            nodes.len()
        );
        validates(name, Level::Sdf, points);
    }
}

/// A node of `scene` as the root, on ref-f64.
fn ref_f64_of(scene: &scene::Checked, node: &str) -> Described {
    let mut d = scene.description.clone();
    d.root = node.to_string();
    let checked = scene::check::check(d).unwrap_or_else(|e| panic!("{node}: {e}"));
    Described::new(RefImpl::F64, &checked, Settings::default()).unwrap()
}

/// 256 points in the cube of half side 5 around the camera's target (the
/// origin for the direct camera), by SplitMix64.
fn points_around(scene: &scene::Checked) -> Vec<[F316; 3]> {
    let centre = match &scene.description.image.camera {
        Camera::LookAt { target, .. } => *target,
        Camera::Direct { .. } => [0.0; 3],
    };
    let mut rng = common::SplitMix64::new(316);
    (0..256)
        .map(|_| {
            centre
                .map(|c| F316::from_f64_truncating(c + rng.unit() * 10.0 - 5.0).expect("in range"))
        })
        .collect()
}

/// The oracle and ref-f64 agree within [`AGREE`] on every node's distance,
/// and on its colour wherever the oracle's colour is certain, at points
/// around every scene and at its derived points (near every surface, seam,
/// blend and cell edge). This is the independent check of the lowering of
/// `sdf-engine` and `toon` (and of every other scene): ref-f316 and the
/// Float316 kernel are checked bit for bit against each other, ref-f64 by
/// its error against them, but all three interpret the same lowered
/// program.
#[test]
fn the_oracle_agrees_with_ref_f64_on_every_node_of_every_scene() {
    for name in SCENES {
        let s = scene(name);
        let oracle = Oracle::new(&s.description);
        let mut points = points_around(&s);
        points.extend(
            sdf_points(&s, 11, 4)
                .unwrap()
                .iter()
                .filter_map(|v| match v {
                    Vector::Sdf(p) => Some(p.p),
                    _ => None,
                }),
        );
        let mut colours = 0;
        for node in s.description.nodes.keys() {
            let reference = ref_f64_of(&s, node);
            for q in &points {
                let Outcome::Value(r) = reference.sdf(*q) else {
                    panic!("{name}: {node} at {q:?}: a trap")
                };
                let o = oracle.at(node, q.map(F316::to_f64));
                assert!(
                    (o.sd - r.sd.value).abs() <= AGREE,
                    "{name}: {node} at {q:?}: the oracle's distance {}, ref-f64's {}",
                    o.sd,
                    r.sd.value
                );
                if let (Some(col), true) = (o.col, o.col_certain) {
                    colours += 1;
                    assert!(
                        (col - r.col.value).abs() <= AGREE,
                        "{name}: {node} at {q:?}: the oracle's colour {col}, ref-f64's {}",
                        r.col.value
                    );
                }
            }
        }
        if name != "rtdemo" {
            assert!(colours > points.len(), "{name}: {colours} colours compared");
        }
    }
}

#[test]
fn the_combinations_get_seams_blends_and_cell_edges() {
    let points = sdf_points(&scene("sdf-engine"), 7, 6).unwrap();
    for kind in ["seam:", "blend:", "cell-edge:"] {
        assert!(
            points.iter().any(|v| v.category().starts_with(kind)),
            "sdf-engine has no {kind} point"
        );
    }
}

#[test]
fn pixels_lie_on_the_edges_their_category_names() {
    for (name, wanted) in [
        (
            "seed",
            &["silhouette", "shadow-edge", "surface-edge", "horizon"][..],
        ),
        ("rtdemo", &["silhouette", "reflection-edge"][..]),
        ("toon", &["silhouette"][..]),
    ] {
        let s = scene(name);
        let set = pixels(&s, 40).unwrap();
        assert_eq!(set, pixels(&s, 40).unwrap(), "{name}: deterministic");
        let all = facts(&s).unwrap();
        let w = s.description.image.size[0] as usize;
        let max_distance = match s.description.method {
            scene::desc::Method::SphereTrace { max_distance, .. } => max_distance,
            _ => f64::INFINITY,
        };
        for v in &set {
            let Vector::Pixel(p) = v else { panic!() };
            let (x, y) = (usize::from(p.x), usize::from(p.y));
            let a = &all[y * w + x];
            let ok = [
                all.get(y * w + x + 1).filter(|_| x + 1 < w),
                all.get((y + 1) * w + x),
            ]
            .into_iter()
            .flatten()
            .any(|b| edge(a, b, max_distance) == Some(p.category.as_str()));
            assert!(ok, "{name}: {v} is not a {}", p.category);
        }
        for c in wanted {
            assert!(
                set.iter().any(|v| v.category() == *c),
                "{name}: no {c} pixel"
            );
        }
        validates(name, Level::Pixels, set);
    }
}

/// A scene with tuned call sites (whose names only its whole program has)
/// derives the points its untuned scene derives: they are found in f64,
/// where no site has a variant.
#[test]
fn a_tuned_scene_derives_the_untuned_scenes_points() {
    let tuned = scene("tests/seed-tuned");
    assert!(!tuned.description.variants.is_empty());
    let plain = scene("seed");
    assert_eq!(
        sdf_points(&tuned, 5, 4).unwrap(),
        sdf_points(&plain, 5, 4).unwrap()
    );
}
