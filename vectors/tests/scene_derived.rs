//! The scene-derived generators: every generated set validates, is the same
//! on every run, and each vector lies where its category says (checked
//! again here with the scene's f64 reference).

use scene::desc::Node;
use std::path::PathBuf;
use vectors::gen::scene_derived::{
    edge, facts, on_cell_edge, pixels, sdf_points, Field, BAND, SEAM_BAND,
};
use vectors::{Level, Vector, VectorSet};

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
        let field = |n: &str| Field::new(&s, n).unwrap();
        let mut near = 0;
        for v in &points {
            let Vector::Sdf(p) = v else { panic!() };
            let (kind, node) = p.category.split_once(':').unwrap();
            let q = p.p;
            match (kind, &nodes[node]) {
                ("near", _) => {
                    near += 1;
                    let d = field(node).at(q).unwrap();
                    assert!(d.abs() < BAND, "{name}: {v}: distance {d}");
                }
                ("seam", Node::Union(c) | Node::Subtraction(c) | Node::Intersection(c)) => {
                    let close = |n: &String| field(n).at(q).is_some_and(|d| d.abs() < SEAM_BAND);
                    assert!(
                        c.children.windows(2).any(|w| close(&w[0]) && close(&w[1])),
                        "{name}: {v}"
                    );
                }
                ("seam", Node::SmoothUnion(c)) => {
                    let close = |n: &String| field(n).at(q).is_some_and(|d| d.abs() < SEAM_BAND);
                    assert!(
                        c.children.windows(2).any(|w| close(&w[0]) && close(&w[1])),
                        "{name}: {v}"
                    );
                }
                ("blend", Node::SmoothUnion(c)) => {
                    let [a, b] = [&c.children[0], &c.children[1]].map(|n| field(n).at(q).unwrap());
                    assert!((a - b).abs() < c.k, "{name}: {v}: {a} {b}");
                    assert!(field(node).at(q).unwrap().abs() < BAND, "{name}: {v}");
                }
                ("cell-edge", Node::Repeat(r)) => assert!(on_cell_edge(q, r.period), "{name}: {v}"),
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
