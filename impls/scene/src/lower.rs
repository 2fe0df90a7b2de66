//! Lowering a checked [`Description`] to a [`Program`] in one formulation.
//! Every feature of the format is written here once; back ends only map
//! statements. Where the Float316 and IEEE formulations of the seed scene
//! differ (spec sections 3-7), the lowering emits each one's order.

use crate::build::{Builder, Surf};
use crate::check::Checked;
use crate::desc::{
    Axis, Background, Camera, Colour, Description, Handedness, Material, Method, Node, Output,
    Texture, Transform,
};
use crate::ir::{
    BReg, Binary, Decision, Dither, Formulation, FuncId, Logic, Pixels, Program, Reg, Stmt, TReg,
    Taken, Unary, VecOp,
};
use common::image_consts::BAYER;

/// The BBC demo's 4x4 ordered-dither matrix `A()`, row by row.
pub const BBC4: [u8; 16] = [0, 24, 6, 30, 36, 12, 42, 18, 9, 33, 3, 27, 45, 21, 39, 15];

/// The standard 4x4 Bayer matrix, row by row.
pub const BAYER4: [u8; 16] = [0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5];

struct Lower<'a> {
    d: &'a Description,
    checked: &'a Checked,
    form: Formulation,
    b: Builder,
    sdf: FuncId,
}

/// Lower `checked` to a program in formulation `form`, with the
/// description's per-site variants (Float316 only: they are variants of
/// Float316's operations).
pub fn lower(checked: &Checked, form: Formulation) -> Program {
    let mut p = lower_untuned(checked, form);
    if form == Formulation::Float316 {
        let chosen = checked
            .description
            .variants
            .iter()
            .map(|v| (v.site.clone(), v.variant))
            .collect();
        crate::sites::tune(&mut p, &chosen);
    }
    p
}

/// Lower `checked` with the spec's operations at every site.
pub fn lower_untuned(checked: &Checked, form: Formulation) -> Program {
    let d = &checked.description;
    let mut l = Lower {
        d,
        checked,
        form,
        b: Builder::default(),
        sdf: 0,
    };
    l.sdf = l.sdf_function();
    let setup = l.setup_function();
    let (pixel, pixels) = l.pixel_function();
    Program {
        formulation: form,
        consts: l.b.consts,
        tables: l.b.tables,
        functions: l.b.functions,
        setup,
        sdf: l.sdf,
        pixel,
        pixels,
    }
}

impl Lower<'_> {
    /// Emit `f`'s statements inside a trace frame `name`.
    fn frame<T>(&mut self, name: &str, f: impl FnOnce(&mut Self) -> T) -> T {
        self.b.open_block();
        let out = f(self);
        let body = self.b.close_block();
        self.b.push(Stmt::Frame {
            name: name.to_string(),
            body,
        });
        out
    }

    /// The statements `f` emits, as a block of their own.
    fn block(&mut self, f: impl FnOnce(&mut Self)) -> Vec<Stmt> {
        self.b.open_block();
        f(self);
        self.b.close_block()
    }

    /// `if cond { then } else { otherwise }`.
    fn if_else(
        &mut self,
        cond: BReg,
        then: impl FnOnce(&mut Self),
        otherwise: impl FnOnce(&mut Self),
    ) {
        let then = self.block(then);
        let otherwise = self.block(otherwise);
        self.b.push(Stmt::If {
            cond,
            then,
            otherwise,
        });
    }

    // ---- The signed distance ----

    fn sdf_function(&mut self) -> FuncId {
        let p = self.b.begin("sdf", 3);
        let root = &self.d.root;
        let s = self.frame("scene", |l| l.node(root, p[0]));
        self.b.end(vec![s.sd, s.col], vec![s.tag])
    }

    fn node(&mut self, name: &str, p: Reg) -> Surf {
        let origin = format!("nodes.{name}");
        match &self.d.nodes[name] {
            Node::Union(c) => self.fold(&c.children, p, |l, a, b| l.union(a, b)),
            Node::Intersection(c) => self.fold(&c.children, p, |l, a, b| {
                let c = l.b.gt(a.sd, b.sd);
                l.b.select_surf(c, a, b)
            }),
            Node::Subtraction(c) => self.fold(&c.children, p, |l, a, b| {
                let nb = l.b.un(Unary::Neg, b.sd);
                let keep = l.b.gt(a.sd, nb);
                let sd = l.b.select(keep, a.sd, nb);
                Surf { sd, ..a }
            }),
            Node::SmoothUnion(c) => {
                let k = c.k;
                self.fold(&c.children, p, |l, a, b| l.smooth_union(a, b, k, &origin))
            }
            Node::Repeat(r) => {
                let q = self.repeat(p, r.period, &origin);
                self.node(&r.child, q)
            }
            leaf => self.frame(name, |l| l.leaf(name, leaf, p)),
        }
    }

    /// Combine `children` left to right with `f`.
    fn fold(
        &mut self,
        children: &[String],
        p: Reg,
        f: impl Fn(&mut Self, Surf, Surf) -> Surf,
    ) -> Surf {
        let mut acc = self.node(&children[0], p);
        for c in &children[1..] {
            let s = self.node(c, p);
            acc = f(self, acc, s);
        }
        acc
    }

    /// `union(a, b)`: a if `gt(b.sd, a.sd)`, else b (spec section 4).
    fn union(&mut self, a: Surf, b: Surf) -> Surf {
        let c = self.b.gt(b.sd, a.sd);
        self.b.decide(Decision::Union, c, b.sd, a.sd);
        self.b.select_surf(c, a, b)
    }

    /// IQ's polynomial smooth minimum: `h = clamp01((b - a) / k * 0.5 +
    /// 0.5)`, `sd = (b + (a - b) * h) - (k * h) * (1 - h)`; the colour is
    /// blended by `h`, the tag is the nearer child's.
    fn smooth_union(&mut self, a: Surf, b: Surf, k: f64, origin: &str) -> Surf {
        let b_ = &mut self.b;
        let kk = b_.k(k, &format!("{origin}.smooth_union.k"));
        let half = b_.k(0.5, "smooth_union");
        let one = b_.k(1.0, "smooth_union");
        let t = b_.sub(b.sd, a.sd);
        let t = b_.div(t, kk);
        let t = b_.mul(t, half);
        let t = b_.add(t, half);
        let h = b_.un(Unary::Clamp01, t);
        let mix = |b_: &mut Builder, x: Reg, y: Reg| {
            let d = b_.sub(y, x);
            let d = b_.mul(d, h);
            b_.add(x, d)
        };
        let m = mix(b_, b.sd, a.sd);
        let kh = b_.mul(kk, h);
        let rest = b_.sub(one, h);
        let w = b_.mul(kh, rest);
        let sd = b_.sub(m, w);
        let col = mix(b_, b.col, a.col);
        let nearer = b_.gt(b.sd, a.sd);
        let tag = b_.treg();
        b_.push(Stmt::SelectTag {
            dst: tag,
            cond: nearer,
            a: a.tag,
            b: b.tag,
        });
        Surf { sd, col, tag }
    }

    /// Domain repetition: `(fract(p / c + 0.5) - 0.5) * c` on each axis
    /// with a non-zero period (the division and product are left out for
    /// a period of 1).
    fn repeat(&mut self, p: Reg, period: [f64; 3], origin: &str) -> Reg {
        let b = &mut self.b;
        let half = b.k(0.5, "repeat");
        let mut out = [p, p + 1, p + 2];
        for (i, &c) in period.iter().enumerate() {
            if c == 0.0 {
                continue;
            }
            let kc = b.k(c, &format!("{origin}.repeat.period[{i}]"));
            let mut t = p + i as u16;
            if c != 1.0 {
                t = b.div(t, kc);
            }
            let t = b.add(t, half);
            let t = b.un(Unary::Fract, t);
            let mut t = b.sub(t, half);
            if c != 1.0 {
                t = b.mul(t, kc);
            }
            out[i] = t;
        }
        b.v3(out[0], out[1], out[2])
    }

    /// A shape with its placement and colour.
    fn leaf(&mut self, name: &str, node: &Node, p: Reg) -> Surf {
        let origin = format!("nodes.{name}");
        let (transform, material) = node.shape_parts().expect("a leaf is a shape");
        let (q, scale) = self.place(p, transform, &origin);
        let sd = self.shape(node, q, &origin);
        let sd = match scale {
            Some(s) => {
                let ks = self.b.k(s, &format!("{origin}.transform"));
                self.b.mul(sd, ks)
            }
            None => sd,
        };
        let index = self.checked.material_index(material);
        let col = self.colour(
            &self.d.materials[material],
            q,
            &format!("materials.{material}"),
        );
        let tag = self.b.treg();
        self.b.push(Stmt::SetTag {
            dst: tag,
            value: index,
        });
        Surf { sd, col, tag }
    }

    /// The query point in the shape's own space: the transforms undone, the
    /// last first. Returns it and the total scale, if any.
    fn place(&mut self, p: Reg, transform: &[Transform], origin: &str) -> (Reg, Option<f64>) {
        let mut q = p;
        let mut scale = None::<f64>;
        for t in transform.iter().rev() {
            let o = format!("{origin}.transform");
            match *t {
                Transform::Translate(v) => {
                    let kv = self.b.kv(v, &o);
                    q = self.b.vec(VecOp::Sub, q, kv);
                }
                Transform::Scale(s) => {
                    let inv = self.b.k(1.0 / s, &o);
                    q = self.b.vec(VecOp::Scale, q, inv);
                    scale = Some(scale.unwrap_or(1.0) * s);
                }
                Transform::Rotate { axis, degrees } => {
                    q = self.rotate(q, axis, -degrees.to_radians(), &o);
                }
            }
        }
        (q, scale)
    }

    /// `p` rotated by `angle` about `axis`: (c*u - s*w, c*w + s*u) in the
    /// plane (u, w) of the other two axes.
    fn rotate(&mut self, p: Reg, axis: Axis, angle: f64, origin: &str) -> Reg {
        let (iu, iw) = match axis {
            Axis::X => (1, 2),
            Axis::Y => (2, 0),
            Axis::Z => (0, 1),
        };
        let b = &mut self.b;
        let c = b.k(angle.cos(), origin);
        let s = b.k(angle.sin(), origin);
        let (u, w) = (p + iu, p + iw);
        let cu = b.mul(c, u);
        let sw = b.mul(s, w);
        let nu = b.sub(cu, sw);
        let cw = b.mul(c, w);
        let su = b.mul(s, u);
        let nw = b.add(cw, su);
        let mut comps = [p, p + 1, p + 2];
        comps[iu as usize] = nu;
        comps[iw as usize] = nw;
        b.v3(comps[0], comps[1], comps[2])
    }

    fn shape(&mut self, node: &Node, q: Reg, origin: &str) -> Reg {
        let b = &mut self.b;
        let (x, y, z) = (q, q + 1, q + 2);
        match node {
            Node::Plane(s) => {
                let k = b.k(-s.height, &format!("{origin}.plane.height"));
                b.add(y, k)
            }
            Node::Sphere(s) => {
                let r = b.k(s.radius, &format!("{origin}.sphere.radius"));
                let l = b.length(q);
                b.sub(l, r)
            }
            Node::Torus(s) => {
                let ring = b.k(s.ring, &format!("{origin}.torus.ring"));
                let tube = b.k(s.tube, &format!("{origin}.torus.tube"));
                let xx = b.mul(x, x);
                let zz = b.mul(z, z);
                let r2 = b.add(xx, zz);
                let r = b.un(Unary::Sqrt, r2);
                let d1 = b.sub(r, ring);
                let dd = b.mul(d1, d1);
                let yy = b.mul(y, y);
                let t2 = b.add(dd, yy);
                let t = b.un(Unary::Sqrt, t2);
                b.sub(t, tube)
            }
            Node::Box(s) => {
                let size = b.kv(s.size, &format!("{origin}.box.size"));
                box_distance(b, q, size)
            }
            Node::RoundBox(s) => {
                let inner = s.size.map(|c| c - s.radius);
                let size = b.kv(inner, &format!("{origin}.round_box.size"));
                let r = b.k(s.radius, &format!("{origin}.round_box.radius"));
                let d = box_distance(b, q, size);
                b.sub(d, r)
            }
            Node::Capsule(s) => {
                let a = b.kv(s.a, &format!("{origin}.capsule.a"));
                let ba = b.kv(
                    [s.b[0] - s.a[0], s.b[1] - s.a[1], s.b[2] - s.a[2]],
                    &format!("{origin}.capsule.b"),
                );
                let r = b.k(s.radius, &format!("{origin}.capsule.radius"));
                let pa = b.vec(VecOp::Sub, q, a);
                let t = b.dot(pa, ba);
                let bb = b.dot(ba, ba);
                let t = b.div(t, bb);
                let h = b.un(Unary::Clamp01, t);
                let along = b.vec(VecOp::Scale, ba, h);
                let d = b.vec(VecOp::Sub, pa, along);
                let l = b.length(d);
                b.sub(l, r)
            }
            Node::Cylinder(s) => {
                let r = b.k(s.radius, &format!("{origin}.cylinder.radius"));
                let h = b.k(s.height, &format!("{origin}.cylinder.height"));
                let zero = b.k(0.0, "cylinder");
                let xx = b.mul(x, x);
                let zz = b.mul(z, z);
                let r2 = b.add(xx, zz);
                let rl = b.un(Unary::Sqrt, r2);
                let dx = b.sub(rl, r);
                let ay = b.un(Unary::Abs, y);
                let dy = b.sub(ay, h);
                let m = b.bin(Binary::Max, dx, dy);
                let inside = b.bin(Binary::Min, m, zero);
                let mx = b.bin(Binary::Max, dx, zero);
                let my = b.bin(Binary::Max, dy, zero);
                let mxx = b.mul(mx, mx);
                let myy = b.mul(my, my);
                let o2 = b.add(mxx, myy);
                let outside = b.un(Unary::Sqrt, o2);
                b.add(inside, outside)
            }
            _ => unreachable!("combinations are not leaves"),
        }
    }

    /// The material's colour at `q` (a constant, or a texture).
    fn colour(&mut self, m: &Material, q: Reg, origin: &str) -> Reg {
        let c = match m {
            Material::Phong { colour, .. }
            | Material::BlinnPhong { colour, .. }
            | Material::Diffuse { colour, .. }
            | Material::Toon { colour, .. } => colour,
            Material::Mirror {} => return self.b.k(0.0, origin),
        };
        match c {
            Colour::Plain(v) => self.b.k(*v, &format!("{origin}.colour")),
            Colour::Textured(Texture::Checker { even, odd_add }) => {
                let b = &mut self.b;
                let fx = b.un(Unary::Floor, q);
                let fz = b.un(Unary::Floor, q + 2);
                let sum = b.add(fx, fz);
                let parity = b.un(Unary::Mod2, sum);
                b.push(Stmt::Decide {
                    decision: Decision::Checker,
                    taken: Taken::Parity(parity),
                    a: q,
                    b: q + 2,
                });
                let odd = b.k(*odd_add, &format!("{origin}.colour.checker.odd_add"));
                let checker = b.mul(parity, odd);
                let even = b.k(*even, &format!("{origin}.colour.checker.even"));
                b.add(checker, even)
            }
        }
    }

    // ---- Camera set-up ----

    fn setup_function(&mut self) -> FuncId {
        self.b.begin("setup", 0);
        let results = match &self.d.image.camera {
            Camera::LookAt {
                position,
                target,
                up,
                handedness,
                ..
            } => self.b.frame("camera", |b| {
                let cam = b.kv(*position, "image.camera.look_at.position");
                let at = b.kv(*target, "image.camera.look_at.target");
                let up = b.kv(*up, "image.camera.look_at.up");
                // The basis's third vector: back for right-handed, forward
                // for left-handed (the image's x is mirrored between them).
                let f = match handedness {
                    Handedness::Right => b.vec(VecOp::Sub, cam, at),
                    Handedness::Left => b.vec(VecOp::Sub, at, cam),
                };
                let f = b.normalize(f);
                let r = b.vec(VecOp::Cross, up, f);
                let r = b.normalize(r);
                let u = b.vec(VecOp::Cross, f, r);
                // Rows r1 = (right.x, up'.x, f.x), r2, r3.
                (0..3).flat_map(|i| [r + i, u + i, f + i]).collect()
            }),
            Camera::Direct { .. } => Vec::new(),
        };
        self.b.end(results, Vec::new())
    }

    // ---- The pixel ----

    fn pixel_function(&mut self) -> (FuncId, Pixels) {
        let d = self.d;
        let [width, height] = d.image.size;
        let params = self.b.begin("pixel", 2);
        let (x, n) = (params[0], params[1]);
        let value = match (&d.method, &d.image.camera) {
            (Method::SphereTrace { .. }, Camera::LookAt { .. }) => {
                let (ro, rd) = self.look_at_ray(x, n);
                self.trace(ro, rd)
            }
            (Method::SphereTrace { .. }, Camera::Direct { .. }) => {
                let (ro, rd) = self.direct_ray(x, n);
                self.trace(ro, rd)
            }
            (Method::AnalyticSpheres { bounces }, camera) => {
                let (ro, rd) = match camera {
                    Camera::LookAt { .. } => self.look_at_ray(x, n),
                    Camera::Direct { .. } => self.direct_ray(x, n),
                };
                self.spheres(ro, rd, *bounces)
            }
        };
        let (value, level, dither) = self.output(value);
        let id = self.b.end(vec![value, level], Vec::new());
        let (row_origin, rows) = match &d.image.camera {
            Camera::Direct {
                row_origin, rows, ..
            } => (Some(*row_origin), *rows),
            Camera::LookAt { .. } => (None, [0, height - 1]),
        };
        let levels = if matches!(d.image.output, Output::Levels4 { .. }) {
            4
        } else {
            2
        };
        let pixels = Pixels {
            width,
            height,
            row_origin,
            rows,
            dither,
            levels,
        };
        (id, pixels)
    }

    /// The look-at camera's ray: (origin, direction).
    fn look_at_ray(&mut self, x: Reg, n: Reg) -> (Reg, Reg) {
        let Camera::LookAt {
            position,
            scale,
            handedness,
            ..
        } = &self.d.image.camera
        else {
            unreachable!("called for the look-at camera")
        };
        let [w, h] = self.d.image.size;
        let scale = scale.unwrap_or(f64::from(h));
        let b = &mut self.b;
        let hw = b.k(f64::from(w) / 2.0, "image.size");
        let hh = b.k(f64::from(h) / 2.0, "image.size");
        let s = b.k(scale, "image.camera.look_at.scale");
        let u = b.sub(x, hw);
        let u = b.div(u, s);
        let v = b.sub(n, hh);
        let v = b.div(v, s);
        let v = b.un(Unary::Neg, v);
        // The image plane is at -1 along back, +1 along forward.
        let depth = match handedness {
            Handedness::Right => b.k(-1.0, "image.camera"),
            Handedness::Left => b.k(1.0, "image.camera.look_at.handedness"),
        };
        let d = b.v3(u, v, depth);
        let d = b.normalize(d);
        let rd = b.frame("ray", |b| {
            let rows: Vec<Reg> = (0..3)
                .map(|i| {
                    let r = b.vreg();
                    for j in 0..3 {
                        b.push(Stmt::Uniform {
                            dst: r + j,
                            index: 3 * i + j,
                        });
                    }
                    r
                })
                .collect();
            let c: Vec<Reg> = rows.iter().map(|&r| b.dot(r, d)).collect();
            b.v3(c[0], c[1], c[2])
        });
        let ro = b.kv(*position, "image.camera.look_at.position");
        (ro, rd)
    }

    /// The BBC demo's ray: u = (x - cx) / s, v = (n - cy) / s, w = 1 /
    /// sqrt(u*u + v*v + 1), direction (u*w, v*w, -w).
    fn direct_ray(&mut self, x: Reg, n: Reg) -> (Reg, Reg) {
        let Camera::Direct {
            position,
            centre,
            scale,
            ..
        } = &self.d.image.camera
        else {
            unreachable!("called for the direct camera")
        };
        let b = &mut self.b;
        let cx = b.k(centre[0], "image.camera.direct.centre[0]");
        let cy = b.k(centre[1], "image.camera.direct.centre[1]");
        let s = b.k(*scale, "image.camera.direct.scale");
        let one = b.k(1.0, "image.camera.direct");
        let u = b.sub(x, cx);
        let u = b.div(u, s);
        let v = b.sub(n, cy);
        let v = b.div(v, s);
        let uu = b.mul(u, u);
        let vv = b.mul(v, v);
        let t = b.add(uu, vv);
        let t = b.add(t, one);
        let t = b.un(Unary::Sqrt, t);
        let w = b.div(one, t);
        let u = b.mul(u, w);
        let v = b.mul(v, w);
        let mw = b.un(Unary::Neg, w);
        let rd = b.v3(u, v, mw);
        let ro = b.kv(*position, "image.camera.direct.position");
        (ro, rd)
    }

    /// Sphere tracing of a view ray, shading and shadow: the shade.
    fn trace(&mut self, ro: Reg, rd: Reg) -> Reg {
        let Method::SphereTrace {
            steps,
            max_distance,
            ..
        } = self.d.method
        else {
            unreachable!("called for sphere tracing")
        };
        let (depth, col, tag) = self.march(ro, rd, steps, "march step");
        let maxd = self.b.k(max_distance, "method.sphere_trace.max_distance");
        let miss = self.b.gt(depth, maxd);
        self.b.decide(Decision::Miss, miss, depth, maxd);
        let value = self.b.reg();
        self.if_else(
            miss,
            |l| {
                let v = l.background(ro, rd);
                l.b.copy(value, v);
            },
            |l| {
                let along = l.b.vec(VecOp::Scale, rd, depth);
                let p = l.b.vec(VecOp::Add, ro, along);
                let n = l.normal(p);
                let v = l.shade(tag, p, n, col, rd);
                let v = l.shadow(p, n, v);
                l.b.copy(value, v);
            },
        );
        value
    }

    /// March from `ro` along `rd` for up to `steps` steps: (depth, colour
    /// and tag of the last evaluation). Stops on a hit or past the maximum
    /// distance (both tested every step, as Jack's `|`).
    fn march(&mut self, ro: Reg, rd: Reg, steps: u32, name: &str) -> (Reg, Reg, TReg) {
        let Method::SphereTrace {
            hit_distance,
            max_distance,
            ..
        } = self.d.method
        else {
            unreachable!("called for sphere tracing")
        };
        let sdf = self.sdf;
        let b = &mut self.b;
        let depth = b.k(0.0, "march");
        let col = b.k(0.0, "march");
        let tag = b.treg();
        b.push(Stmt::SetTag { dst: tag, value: 0 });
        let prec = b.k(hit_distance, "method.sphere_trace.hit_distance");
        let maxd = b.k(max_distance, "method.sphere_trace.max_distance");
        let body = b.block(|b| {
            let along = b.vec(VecOp::Scale, rd, depth);
            let p = b.vec(VecOp::Add, ro, along);
            let sd = b.reg();
            b.push(Stmt::Call {
                func: sdf,
                args: vec![p, p + 1, p + 2],
                results: vec![sd, col],
                tags: vec![tag],
            });
            b.push(Stmt::Binary {
                dst: depth,
                op: Binary::Add,
                a: depth,
                b: sd,
            });
            let hit = b.gt(prec, sd);
            b.decide(Decision::MarchHit, hit, prec, sd);
            let far = b.gt(depth, maxd);
            b.decide(Decision::MarchFar, far, depth, maxd);
            let stop = b.logic(Logic::Or, hit, far);
            b.push(Stmt::Break { cond: stop });
        });
        b.push(Stmt::Loop {
            count: steps,
            name: Some(name.to_string()),
            body,
        });
        (depth, col, tag)
    }

    /// The scene's distance at `p` (colour and tag dropped).
    fn distance(&mut self, p: Reg) -> Reg {
        let b = &mut self.b;
        let sd = b.reg();
        let col = b.reg();
        let tag = b.treg();
        b.push(Stmt::Call {
            func: self.sdf,
            args: vec![p, p + 1, p + 2],
            results: vec![sd, col],
            tags: vec![tag],
        });
        sd
    }

    /// The tetrahedral normal estimate (spec section 5).
    fn normal(&mut self, p: Reg) -> Reg {
        let Method::SphereTrace { normal_offset, .. } = self.d.method else {
            unreachable!("called for sphere tracing")
        };
        let h = normal_offset;
        let ks = [[h, -h, -h], [-h, -h, h], [-h, h, -h], [h, h, h]];
        self.frame("normal", |l| {
            let ks: Vec<Reg> = ks
                .iter()
                .map(|k| l.b.kv(*k, "method.sphere_trace.normal_offset"))
                .collect();
            let ds: Vec<Reg> = ks
                .iter()
                .map(|&k| {
                    let q = l.b.vec(VecOp::Add, p, k);
                    l.distance(q)
                })
                .collect();
            let mut n = l.b.vec(VecOp::Scale, ks[0], ds[0]);
            for i in 1..4 {
                let t = l.b.vec(VecOp::Scale, ks[i], ds[i]);
                n = l.b.vec(VecOp::Add, n, t);
            }
            l.b.normalize(n)
        })
    }

    /// The light's position (checked present for sphere tracing).
    fn light(&mut self) -> Reg {
        let pos = self
            .d
            .light
            .as_ref()
            .expect("checked: sphere tracing has a light")
            .position;
        self.b.kv(pos, "light.position")
    }

    /// The view ray's origin.
    fn camera(&mut self) -> Reg {
        let pos = match &self.d.image.camera {
            Camera::LookAt { position, .. } | Camera::Direct { position, .. } => *position,
        };
        self.b.kv(pos, "image.camera.position")
    }

    /// The shade at the hit `p` with normal `n` and colour `col`, by the
    /// material of `tag`.
    fn shade(&mut self, tag: TReg, p: Reg, n: Reg, col: Reg, rd: Reg) -> Reg {
        let materials = self.checked.materials.clone();
        let value = self.b.reg();
        let d = self.d;
        let cases: Vec<Vec<Stmt>> = materials
            .iter()
            .map(|name| {
                let origin = format!("materials.{name}");
                self.block(|l| {
                    let v = l.material(&d.materials[name], &origin, p, n, col, rd);
                    l.b.copy(value, v);
                })
            })
            .collect();
        if cases.len() == 1 {
            for s in cases.into_iter().next().expect("one case") {
                self.b.push(s);
            }
        } else {
            self.b.push(Stmt::Switch { tag, cases });
        }
        value
    }

    /// `x` to the integer power `e`: `pow` in IEEE, square-and-multiply
    /// from the top bit in Float316 (4 is two squarings, as the seed).
    fn power(&mut self, x: Reg, e: u32, origin: &str) -> Reg {
        match self.form {
            Formulation::Ieee => {
                let k = self.b.k(f64::from(e), origin);
                self.b.bin(Binary::Pow, x, k)
            }
            Formulation::Float316 => {
                let mut r = x;
                for bit in (0..31 - e.leading_zeros()).rev() {
                    r = self.b.mul(r, r);
                    if e >> bit & 1 == 1 {
                        r = self.b.mul(r, x);
                    }
                }
                r
            }
        }
    }

    /// `k[0] * k[1]` applied to `x`: `(k0 * x) * k1` in IEEE, the product
    /// truncated once and `mul(k0k1, x)` in Float316.
    fn factor_pair(&mut self, k: [f64; 2], x: Reg, origin: &str) -> Reg {
        match self.form {
            Formulation::Ieee => {
                let k0 = self.b.k(k[0], origin);
                let k1 = self.b.k(k[1], origin);
                let t = self.b.mul(k0, x);
                self.b.mul(t, k1)
            }
            Formulation::Float316 => {
                let kk = self.b.k(k[0] * k[1], origin);
                self.b.mul(kk, x)
            }
        }
    }

    fn material(&mut self, m: &Material, origin: &str, p: Reg, n: Reg, col: Reg, rd: Reg) -> Reg {
        match m {
            Material::Phong {
                diffuse,
                specular,
                exponent,
                ambient,
                ..
            } => {
                let lit = self.frame("light", |l| {
                    l.phong(origin, p, n, *diffuse, *specular, *exponent)
                });
                let v = self.b.mul(col, lit);
                let a = match self.form {
                    Formulation::Ieee => {
                        let a0 = self.b.k(ambient[0], &format!("{origin}.phong.ambient"));
                        let a1 = self.b.k(ambient[1], &format!("{origin}.phong.ambient"));
                        self.b.mul(a0, a1)
                    }
                    Formulation::Float316 => self
                        .b
                        .k(ambient[0] * ambient[1], &format!("{origin}.phong.ambient")),
                };
                self.b.add(v, a)
            }
            Material::BlinnPhong {
                diffuse,
                specular,
                exponent,
                fresnel,
                fresnel_exponent,
                ambient,
                occlusion,
                ..
            } => {
                let o = format!("{origin}.blinn_phong");
                let ao = occlusion.then(|| self.occlusion(p, n));
                let light = self.light();
                let b = &mut self.b;
                let l = b.vec(VecOp::Sub, light, p);
                let l = b.normalize(l);
                let dif = b.angle(n, l);
                let h = b.vec(VecOp::Sub, l, rd);
                let h = b.normalize(h);
                let sh = b.angle(n, h);
                let one = b.k(1.0, &o);
                let nd = b.dot(n, rd);
                let f = b.add(one, nd);
                let f = b.un(Unary::Clamp01, f);
                let spe = self.power(sh, *exponent, &o);
                let fre = self.power(f, *fresnel_exponent, &o);
                let b = &mut self.b;
                let kd = b.k(*diffuse, &o);
                let ka = b.k(*ambient, &o);
                let ks = b.k(*specular, &o);
                let kf = b.k(*fresnel, &o);
                let t = b.mul(kd, dif);
                let mut amb = ka;
                if let Some(ao) = ao {
                    amb = b.mul(ka, ao);
                }
                let t = b.add(t, amb);
                let t = b.mul(col, t);
                let s = b.mul(ks, spe);
                let t = b.add(t, s);
                let f = b.mul(kf, fre);
                b.add(t, f)
            }
            Material::Diffuse {
                diffuse, ambient, ..
            } => {
                let o = format!("{origin}.diffuse");
                let light = self.light();
                let b = &mut self.b;
                let l = b.vec(VecOp::Sub, light, p);
                let l = b.normalize(l);
                let a = b.angle(l, n);
                let kd = b.k(*diffuse, &o);
                let t = b.mul(kd, a);
                let t = b.mul(col, t);
                let ka = b.k(*ambient, &o);
                b.add(t, ka)
            }
            Material::Toon { bands, ambient, .. } => {
                let o = format!("{origin}.toon");
                let light = self.light();
                let b = &mut self.b;
                let l = b.vec(VecOp::Sub, light, p);
                let l = b.normalize(l);
                let a = b.angle(l, n);
                let kb = b.k(f64::from(*bands), &o);
                let t = b.mul(a, kb);
                let t = b.un(Unary::Floor, t);
                let t = b.div(t, kb);
                let t = b.mul(col, t);
                let ka = b.k(*ambient, &o);
                b.add(t, ka)
            }
            Material::Mirror {} => unreachable!("checked: mirrors need analytic spheres"),
        }
    }

    /// The seed's light term (spec sections 5 and 7), in frame `light`.
    fn phong(
        &mut self,
        origin: &str,
        p: Reg,
        n: Reg,
        diffuse: [f64; 2],
        specular: [f64; 2],
        exponent: u32,
    ) -> Reg {
        let light = self.light();
        let cam = self.camera();
        let b = &mut self.b;
        let l = b.vec(VecOp::Sub, light, p);
        let l = b.normalize(l);
        let c = b.vec(VecOp::Sub, cam, p);
        let c = b.normalize(c);
        let a = b.angle(l, n);
        let a = b.un(Unary::Double, a);
        let na = b.vec(VecOp::Scale, n, a);
        let r = b.vec(VecOp::Sub, na, l);
        let a = b.angle(l, n);
        let dif = self.factor_pair(diffuse, a, &format!("{origin}.phong.diffuse"));
        let s = self.b.angle(r, c);
        let s = self.power(s, exponent, &format!("{origin}.phong.exponent"));
        let spe = match self.form {
            Formulation::Ieee => {
                let k0 = self.b.k(specular[0], origin);
                let k1 = self.b.k(specular[1], origin);
                let t = self.b.mul(k0, s);
                self.b.mul(t, k1)
            }
            Formulation::Float316 => {
                let kk = self.b.k(
                    specular[0] * specular[1],
                    &format!("{origin}.phong.specular"),
                );
                self.b.mul(s, kk)
            }
        };
        self.b.add(dif, spe)
    }

    /// The C99 engine's ambient occlusion: five samples at `0.01 + 0.12 *
    /// i / 4` along the normal, weights falling by 0.95, `clamp01(1 - 3o)`.
    fn occlusion(&mut self, p: Reg, n: Reg) -> Reg {
        self.frame("occlusion", |m| {
            let mut o = m.b.k(0.0, "occlusion");
            let mut s = m.b.k(1.0, "occlusion");
            let decay = m.b.k(0.95, "occlusion");
            for i in 0..5 {
                let h = m.b.k(0.01 + 0.12 * f64::from(i) / 4.0, "occlusion");
                let off = m.b.vec(VecOp::Scale, n, h);
                let q = m.b.vec(VecOp::Add, p, off);
                let d = m.distance(q);
                let t = m.b.sub(h, d);
                let t = m.b.mul(s, t);
                o = m.b.add(o, t);
                s = m.b.mul(s, decay);
            }
            let one = m.b.k(1.0, "occlusion");
            let three = m.b.k(3.0, "occlusion");
            let t = m.b.mul(three, o);
            let t = m.b.sub(one, t);
            m.b.un(Unary::Clamp01, t)
        })
    }

    /// The hard shadow (spec section 5): the value times the shadow factor
    /// when the light is farther than the shadow ray's depth.
    fn shadow(&mut self, p: Reg, n: Reg, value: Reg) -> Reg {
        let Some(shadow) = self.d.shadow.clone() else {
            return value;
        };
        let out = self.b.reg();
        self.b.copy(out, value);
        self.frame("shadow", |m| {
            let light = m.light();
            let ld = m.b.vec(VecOp::Sub, light, p);
            let ld = m.b.normalize(ld);
            let k = m.b.k(shadow.offset, "shadow.offset");
            let off = m.b.vec(VecOp::Scale, n, k);
            let o = m.b.vec(VecOp::Add, off, p);
            let (sdepth, _, _) = m.march(o, ld, shadow.steps, "shadow march step");
            let light = m.light();
            let to = m.b.vec(VecOp::Sub, light, o);
            let dist = m.b.length(to);
            let dark = m.b.gt(dist, sdepth);
            m.b.decide(Decision::Shadow, dark, dist, sdepth);
            m.b.if_else(
                dark,
                |b| {
                    let v = if shadow.factor == 0.25 {
                        b.un(Unary::Quarter, out)
                    } else {
                        let f = b.k(shadow.factor, "shadow.factor");
                        b.mul(out, f)
                    };
                    b.copy(out, v);
                },
                |_| {},
            );
        });
        out
    }

    /// What a ray from `ro` along `rd` that hits nothing sees.
    fn background(&mut self, ro: Reg, rd: Reg) -> Reg {
        let b = &mut self.b;
        match self.d.background {
            Background::Constant(v) => b.k(v, "background.constant"),
            Background::Sky { base, slope } => {
                let kb = b.k(base, "background.sky.base");
                let ks = b.k(slope, "background.sky.slope");
                let t = b.mul(ks, rd + 1);
                b.add(kb, t)
            }
            Background::SkyFloor {
                height,
                step,
                base,
                fog,
            } => {
                let value = b.reg();
                let zero = b.k(0.0, "background.sky_floor");
                let below = b.gt(zero, rd + 1);
                b.if_else(
                    below,
                    |b| {
                        // BBC: P = (Y + 2) / V; -V * ((INT(X - U*P) + INT(Z - W*P)
                        // AND 1) / 2 + .3) + .2, with W = -d.z.
                        let kh = b.k(height, "background.sky_floor.height");
                        let t = b.sub(ro + 1, kh);
                        let pp = b.div(t, rd + 1);
                        let ux = b.mul(rd, pp);
                        let x = b.sub(ro, ux);
                        let w = b.un(Unary::Neg, rd + 2);
                        let wz = b.mul(w, pp);
                        let z = b.sub(ro + 2, wz);
                        let fx = b.un(Unary::Floor, x);
                        let fz = b.un(Unary::Floor, z);
                        let sum = b.add(fx, fz);
                        let parity = b.un(Unary::Mod2, sum);
                        let ks = b.k(step, "background.sky_floor.step");
                        let t = b.mul(parity, ks);
                        let kb = b.k(base, "background.sky_floor.base");
                        let t = b.add(t, kb);
                        let mv = b.un(Unary::Neg, rd + 1);
                        let t = b.mul(mv, t);
                        let kf = b.k(fog, "background.sky_floor.fog");
                        let v = b.add(t, kf);
                        b.copy(value, v);
                    },
                    |b| b.copy(value, rd + 1),
                );
                value
            }
        }
    }

    /// Analytic mirrored spheres: up to `bounces` reflections, then the
    /// background along the last ray. The sphere just left is not tested
    /// again.
    fn spheres(&mut self, ro: Reg, rd: Reg, bounces: u32) -> Reg {
        let spheres = self.checked.spheres.clone();
        let b = &mut self.b;
        let o = b.vreg();
        b.copy3(o, ro);
        let d = b.vreg();
        b.copy3(d, rd);
        let last = b.treg();
        b.push(Stmt::SetTag {
            dst: last,
            value: u16::MAX,
        });
        let body = b.block(|b| {
            let found = b.breg();
            let best_t = b.reg();
            let best_c = b.vreg();
            let hit = b.treg();
            b.push(Stmt::Bool {
                dst: found,
                value: false,
            });
            let zero = b.k(0.0, "method.analytic_spheres");
            b.copy(best_t, zero);
            for (i, (centre, radius, origin)) in spheres.iter().enumerate() {
                let i = i as u16;
                let c = b.kv(*centre, origin);
                let oc = b.vec(VecOp::Sub, o, c);
                let pp = b.dot(d, oc);
                let p2 = b.mul(pp, pp);
                let ee = b.mul(oc, oc);
                let ff = b.mul(oc + 1, oc + 1);
                let gg = b.mul(oc + 2, oc + 2);
                let t = b.sub(p2, ee);
                let t = b.sub(t, ff);
                let t = b.sub(t, gg);
                let r2 = b.k(radius * radius, origin);
                let disc = b.add(t, r2);
                let is_last = b.breg();
                b.push(Stmt::TagIs {
                    dst: is_last,
                    tag: last,
                    value: i,
                });
                let other = b.not(is_last);
                let positive = b.gt(disc, zero);
                let test = b.logic(Logic::And, other, positive);
                b.if_else(
                    test,
                    |b| {
                        let np = b.un(Unary::Neg, pp);
                        let sq = b.un(Unary::Sqrt, disc);
                        let t = b.sub(np, sq);
                        let ahead = b.gt(t, zero);
                        let nearer = b.gt(best_t, t);
                        let first = b.not(found);
                        let better = b.logic(Logic::Or, first, nearer);
                        let take = b.logic(Logic::And, ahead, better);
                        b.if_else(
                            take,
                            |b| {
                                b.copy(best_t, t);
                                b.copy3(best_c, c);
                                b.push(Stmt::SetTag { dst: hit, value: i });
                                b.push(Stmt::Bool {
                                    dst: found,
                                    value: true,
                                });
                            },
                            |_| {},
                        );
                    },
                    |_| {},
                );
            }
            b.decide(Decision::Bounce, found, best_t, zero);
            let miss = b.not(found);
            b.push(Stmt::Break { cond: miss });
            // X = X + T*U (and so on), then the reflection about the
            // normal o - c: d = d - (2 * dot(d, o - c)) * (o - c).
            let along_t = b.vreg();
            for j in 0..3 {
                b.push(Stmt::Binary {
                    dst: along_t + j,
                    op: Binary::Mul,
                    a: best_t,
                    b: d + j,
                });
            }
            let no2 = b.vec(VecOp::Add, o, along_t);
            b.copy3(o, no2);
            let oc = b.vec(VecOp::Sub, o, best_c);
            let two = b.k(2.0, "method.analytic_spheres");
            let pd = b.dot(d, oc);
            let p2 = b.mul(two, pd);
            let r = b.vreg();
            for j in 0..3 {
                let t = b.mul(p2, oc + j);
                b.push(Stmt::Binary {
                    dst: r + j,
                    op: Binary::Sub,
                    a: d + j,
                    b: t,
                });
            }
            b.copy3(d, r);
            b.push(Stmt::SelectTag {
                dst: last,
                cond: found,
                a: hit,
                b: last,
            });
        });
        b.push(Stmt::Loop {
            count: bounces + 1,
            name: Some("bounce".into()),
            body,
        });
        self.background(o, d)
    }

    /// Clamp and output: (value, level, the matrix index kind).
    fn output(&mut self, value: Reg) -> (Reg, Reg, Dither) {
        let out = self.d.image.output.clone();
        let b = &mut self.b;
        if let Output::Levels4 { gain } = out {
            // BBC: GCOL 3 - (48 * SQR C + A(M MOD 4 + N MOD 4 * 4) / 3) DIV 16.
            let table = b.table(BBC4.iter().map(|&a| f64::from(a)).collect());
            let kg = b.k(gain, "image.output.levels4.gain");
            let s = b.un(Unary::Sqrt, value);
            let s = b.mul(kg, s);
            let a = b.reg();
            b.push(Stmt::Table { dst: a, table });
            let three = b.k(3.0, "image.output.levels4");
            let a = b.div(a, three);
            let t = b.add(s, a);
            let sixteen = b.k(16.0, "image.output.levels4");
            let t = b.div(t, sixteen);
            let q = b.un(Unary::Floor, t);
            let level = b.sub(three, q);
            return (value, level, Dither::Bayer4);
        }
        // Clamp to [0, 1] (spec section 6): 1 when above 1, 0 when the sign
        // bit is set.
        let one = b.k(1.0, "image.output");
        let zero = b.k(0.0, "image.output");
        let half = b.k(0.5, "image.output");
        let above = b.gt(value, one);
        b.decide(Decision::ClampHigh, above, value, one);
        let neg = b.sign_bit(value);
        b.if_else(
            above,
            |_| {},
            |b| b.decide(Decision::ClampLow, neg, value, zero),
        );
        let low = b.select(neg, zero, value);
        let v = b.select(above, one, low);
        let (matrix, size): (Vec<u8>, f64) = match out {
            Output::Bayer8 => (BAYER.to_vec(), 64.0),
            Output::Bayer4 => (BAYER4.to_vec(), 16.0),
            Output::Threshold => (Vec::new(), 1.0),
            Output::Levels4 { .. } => unreachable!("handled above"),
        };
        let form = self.form;
        let (white, dither) = b.frame("dither", |b| {
            if matrix.is_empty() {
                let white = b.gt(v, half);
                b.decide(Decision::Dither, white, v, half);
                return (white, Dither::None);
            }
            let centre = size / 2.0;
            let dithered = match form {
                Formulation::Float316 => {
                    let t = b.table(
                        matrix
                            .iter()
                            .map(|&m| (f64::from(m) - centre) / size)
                            .collect(),
                    );
                    let e = b.reg();
                    b.push(Stmt::Table { dst: e, table: t });
                    b.add(v, e)
                }
                Formulation::Ieee => {
                    let t = b.table(matrix.iter().map(|&m| f64::from(m) / size).collect());
                    let e = b.reg();
                    b.push(Stmt::Table { dst: e, table: t });
                    let s = b.add(v, e);
                    b.sub(s, half)
                }
            };
            let kind = if size == 64.0 {
                Dither::Bayer8
            } else {
                Dither::Bayer4
            };
            let white = b.gt(dithered, half);
            b.decide(Decision::Dither, white, dithered, half);
            (white, kind)
        });
        let level = b.select(white, one, zero);
        (v, level, dither)
    }
}

/// IQ's box: `length(max(q, 0)) + min(max(q.x, max(q.y, q.z)), 0)` with
/// `q = abs(p) - size`.
fn box_distance(b: &mut Builder, p: Reg, size: Reg) -> Reg {
    let zero = b.k(0.0, "box");
    let ax = b.un(Unary::Abs, p);
    let ay = b.un(Unary::Abs, p + 1);
    let az = b.un(Unary::Abs, p + 2);
    let a = b.v3(ax, ay, az);
    let q = b.vec(VecOp::Sub, a, size);
    let mx = b.bin(Binary::Max, q, zero);
    let my = b.bin(Binary::Max, q + 1, zero);
    let mz = b.bin(Binary::Max, q + 2, zero);
    let m = b.v3(mx, my, mz);
    let outside = b.length(m);
    let yz = b.bin(Binary::Max, q + 1, q + 2);
    let xyz = b.bin(Binary::Max, q, yz);
    let inside = b.bin(Binary::Min, xyz, zero);
    b.add(outside, inside)
}
