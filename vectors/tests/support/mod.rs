//! An oracle of a described scene's signed distance and surface colour,
//! written in f64 straight from the scene format's rules (docs/scenes.md,
//! "Nodes" and "Lighting"), with the textbook formula of each shape. It
//! shares no code with `impls/scene`, whose lowered program ref-f64,
//! ref-f316 and the generated kernels all interpret, nor with the
//! generators of `vectors::gen::scene_derived`.

use scene::desc::{Axis, Colour, Description, Material, Node, Texture, Transform};

/// A node's signed distance at a point and the colour of its surface there
/// (`None` for a material without a colour: the mirror).
#[derive(Clone, Copy, Debug)]
pub struct Surface {
    pub sd: f64,
    pub col: Option<f64>,
    /// Whether the colour is the one of a clear winner: false where two
    /// children of a union, intersection or subtraction are within
    /// [`TIE`] of each other, or a checker is within [`TIE`] of a square's
    /// edge, so that a rounding may pick the other colour.
    pub col_certain: bool,
}

/// Distances closer than this make a combination's colour uncertain.
pub const TIE: f64 = 1e-9;

type V = [f64; 3];

fn sub(a: V, b: V) -> V {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: V, b: V) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn length(a: V) -> f64 {
    dot(a, a).sqrt()
}

fn clamp01(x: f64) -> f64 {
    x.clamp(0.0, 1.0)
}

/// `p` rotated by `radians` about `axis`, right-handed.
fn rotate(p: V, axis: Axis, radians: f64) -> V {
    let (c, s) = (radians.cos(), radians.sin());
    let [x, y, z] = p;
    match axis {
        Axis::X => [x, c * y - s * z, s * y + c * z],
        Axis::Y => [c * x + s * z, y, -s * x + c * z],
        Axis::Z => [c * x - s * y, s * x + c * y, z],
    }
}

/// The scene's nodes, each evaluated as the root.
pub struct Oracle<'a>(&'a Description);

impl<'a> Oracle<'a> {
    pub fn new(description: &'a Description) -> Self {
        Oracle(description)
    }

    /// `node`'s surface at `p`.
    pub fn at(&self, node: &str, p: V) -> Surface {
        match &self.0.nodes[node] {
            Node::Union(c) => self.fold(&c.children, p, |a, b| {
                // Left to right: the right child only when strictly nearer.
                let winner = if b.sd < a.sd { b } else { a };
                Surface {
                    col_certain: winner.col_certain && (a.sd - b.sd).abs() > TIE,
                    ..winner
                }
            }),
            Node::Intersection(c) => self.fold(&c.children, p, |a, b| {
                let winner = if a.sd > b.sd { a } else { b };
                Surface {
                    col_certain: winner.col_certain && (a.sd - b.sd).abs() > TIE,
                    ..winner
                }
            }),
            // The first child carved by the others: its colour throughout.
            Node::Subtraction(c) => self.fold(&c.children, p, |a, b| Surface {
                sd: a.sd.max(-b.sd),
                ..a
            }),
            // IQ's polynomial smooth minimum; colours blended by h.
            Node::SmoothUnion(c) => self.fold(&c.children, p, |a, b| {
                let h = clamp01((b.sd - a.sd) / c.k * 0.5 + 0.5);
                Surface {
                    sd: b.sd + (a.sd - b.sd) * h - c.k * h * (1.0 - h),
                    col: a.col.zip(b.col).map(|(ca, cb)| cb + (ca - cb) * h),
                    col_certain: a.col_certain && b.col_certain,
                }
            }),
            Node::Repeat(r) => {
                let mut q = p;
                for i in 0..3 {
                    let c = r.period[i];
                    if c != 0.0 {
                        let t = p[i] / c + 0.5;
                        q[i] = (t - t.floor() - 0.5) * c;
                    }
                }
                self.at(&r.child, q)
            }
            shape => self.shape(shape, p),
        }
    }

    fn fold(
        &self,
        children: &[String],
        p: V,
        combine: impl Fn(Surface, Surface) -> Surface,
    ) -> Surface {
        let mut surfaces = children.iter().map(|c| self.at(c, p));
        let first = surfaces.next().expect("a combination has children");
        surfaces.fold(first, combine)
    }

    /// A shape: the point taken into the shape's own space (its transforms
    /// undone, the last first), the distance scaled back.
    fn shape(&self, node: &Node, p: V) -> Surface {
        let (transform, material) = node
            .shape_parts()
            .expect("combinations are evaluated by `at`");
        let mut q = p;
        let mut scale = 1.0;
        for t in transform.iter().rev() {
            match *t {
                Transform::Translate(v) => q = sub(q, v),
                Transform::Scale(s) => {
                    q = q.map(|x| x / s);
                    scale *= s;
                }
                Transform::Rotate { axis, degrees } => q = rotate(q, axis, -degrees.to_radians()),
            }
        }
        let sd = scale * local_distance(node, q);
        let (col, col_certain) = match self.0.materials.get(material) {
            Some(m) => colour(m, q),
            None => (None, true),
        };
        Surface {
            sd,
            col,
            col_certain,
        }
    }
}

/// The distance of a shape in its own space.
fn local_distance(node: &Node, q: V) -> f64 {
    let [x, y, z] = q;
    let boxed = |b: V, q: V| {
        let d = [0, 1, 2].map(|i| q[i].abs() - b[i]);
        let outside = length(d.map(|v| v.max(0.0)));
        outside + d[0].max(d[1]).max(d[2]).min(0.0)
    };
    match node {
        Node::Plane(s) => y - s.height,
        Node::Sphere(s) => length(q) - s.radius,
        Node::Torus(s) => {
            let ring = (x * x + z * z).sqrt() - s.ring;
            (ring * ring + y * y).sqrt() - s.tube
        }
        Node::Box(s) => boxed(s.size, q),
        // Half extents `size`, the rounding inside them.
        Node::RoundBox(s) => boxed(s.size.map(|b| b - s.radius), q) - s.radius,
        Node::Capsule(s) => {
            let (pa, ba) = (sub(q, s.a), sub(s.b, s.a));
            let h = clamp01(dot(pa, ba) / dot(ba, ba));
            length(sub(pa, ba.map(|v| v * h))) - s.radius
        }
        Node::Cylinder(s) => {
            let d = [(x * x + z * z).sqrt() - s.radius, y.abs() - s.height];
            d[0].max(d[1]).min(0.0) + length([d[0].max(0.0), d[1].max(0.0), 0.0])
        }
        _ => unreachable!("a shape"),
    }
}

/// A material's colour at `q` in the shape's own space, and whether it is
/// clear of a checker square's edge.
fn colour(material: &Material, q: V) -> (Option<f64>, bool) {
    let colour = match material {
        Material::Phong { colour, .. }
        | Material::BlinnPhong { colour, .. }
        | Material::Diffuse { colour, .. }
        | Material::Toon { colour, .. } => colour,
        Material::Mirror {} => return (None, true),
    };
    match colour {
        Colour::Plain(c) => (Some(*c), true),
        Colour::Textured(Texture::Checker { even, odd_add }) => {
            let cells = q[0].floor() + q[2].floor();
            let odd = cells.rem_euclid(2.0);
            let near_edge = [q[0], q[2]].iter().any(|v| (v - v.round()).abs() < TIE);
            (Some(even + odd_add * odd), !near_edge)
        }
    }
}
