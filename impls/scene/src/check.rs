//! The checks a description passes before it is lowered: every reference
//! resolves, the graph has no cycle, every combination has its children,
//! every parameter is in range, and every run it asks for is bounded.
//! Each error names the field by its path (`nodes.ball.sphere.radius`).

use crate::desc::{
    Background, Camera, Colour, Description, Material, Method, Node, Output, Texture, Transform,
};
use crate::SceneError;
use common::shown;
use std::collections::BTreeSet;

/// The most steps a march may take.
pub const MAX_STEPS: u32 = 1024;
/// The most reflections of an analytic ray.
pub const MAX_BOUNCES: u32 = 16;
/// The largest width or height.
pub const MAX_SIZE: u32 = 4096;
/// The largest exponent or band count.
pub const MAX_EXPONENT: u32 = 64;
/// The most nodes a scene may have.
pub const MAX_NODES: usize = 256;
/// The most uses of nodes once shared nodes are expanded (a node listed
/// twice is lowered twice), which bounds the lowered program's size.
pub const MAX_USES: usize = 256;
/// The most transforms of one shape.
pub const MAX_TRANSFORMS: usize = 16;
/// The most children of one combination.
pub const MAX_CHILDREN: usize = 64;

/// A description that passed every check, with what the lowering needs.
#[derive(Clone, Debug)]
pub struct Checked {
    pub description: Description,
    /// The materials the scene uses, in tag order.
    pub materials: Vec<String>,
    /// For analytic spheres: centre, radius and field of each sphere.
    pub spheres: Vec<([f64; 3], f64, String)>,
    /// The shape kinds the scene uses.
    pub shapes: BTreeSet<&'static str>,
}

impl Checked {
    /// The tag of material `name`.
    pub fn material_index(&self, name: &str) -> u16 {
        self.materials
            .iter()
            .position(|m| m == name)
            .expect("checked: every used material is listed") as u16
    }
}

fn err(path: impl Into<String>, message: impl Into<String>) -> SceneError {
    SceneError::Field {
        path: path.into(),
        message: message.into(),
    }
}

fn positive(path: &str, v: f64) -> Result<(), SceneError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(err(path, format!("must be positive, is {}", shown(v))))
    }
}

fn finite(path: &str, v: &[f64]) -> Result<(), SceneError> {
    match v.iter().find(|x| !x.is_finite() || x.abs() > 1e6) {
        Some(x) => Err(err(
            path,
            format!("{} is not a finite number below 1e6", shown(*x)),
        )),
        None => Ok(()),
    }
}

fn in_range(path: &str, v: u32, lo: u32, hi: u32) -> Result<(), SceneError> {
    if (lo..=hi).contains(&v) {
        Ok(())
    } else {
        Err(err(path, format!("{v} is outside {lo}..={hi}")))
    }
}

/// Check `d`.
pub fn check(d: Description) -> Result<Checked, SceneError> {
    if d.version != 1 {
        return Err(err(
            "version",
            format!(
                "version {} is not supported (this build reads 1)",
                d.version
            ),
        ));
    }
    image(&d)?;
    method(&d)?;
    if d.nodes.len() > MAX_NODES {
        return Err(err(
            "nodes",
            format!("{} nodes, at most {MAX_NODES}", d.nodes.len()),
        ));
    }
    if !d.nodes.contains_key(&d.root) {
        return Err(err("root", format!("no node named `{}`", d.root)));
    }
    let mut walk = Walk {
        d: &d,
        stack: Vec::new(),
        materials: Vec::new(),
        spheres: Vec::new(),
        shapes: BTreeSet::new(),
        uses: 0,
    };
    walk.node(&d.root, "root")?;
    let (materials, spheres, shapes) = (walk.materials, walk.spheres, walk.shapes);
    for name in &materials {
        material(&d, name)?;
    }
    let checked = Checked {
        description: d,
        materials,
        spheres,
        shapes,
    };
    variants(&checked)?;
    Ok(checked)
}

/// Each `variants[i].site` names a site of the Float316 program, once,
/// and its variant fits the site: an operation its own variant
/// (`newton-1`, `truncated-product`, `floor-direct`), a loop `steps` (1 to
/// the loop's count).
fn variants(c: &Checked) -> Result<(), SceneError> {
    use crate::sites::{Choice, Kind};
    let chosen = &c.description.variants;
    if chosen.is_empty() {
        return Ok(());
    }
    let program = crate::lower::lower_untuned(c, crate::ir::Formulation::Float316);
    let sites = crate::sites::sites(&program);
    for (i, v) in chosen.iter().enumerate() {
        let field = format!("variants[{i}].site");
        let Some(&(_, kind)) = sites.iter().find(|(name, _)| *name == v.site) else {
            let names: Vec<&str> = sites.iter().map(|(n, _)| n.as_str()).collect();
            return Err(err(
                field,
                format!(
                    "no call site `{}` with a variant; the sites are: {}",
                    v.site,
                    names.join(", ")
                ),
            ));
        };
        if chosen[..i].iter().any(|w| w.site == v.site) {
            return Err(err(field, format!("site `{}` is listed twice", v.site)));
        }
        let field = format!("variants[{i}].variant");
        match (v.variant, kind) {
            (Choice::Steps(n), Kind::Loop(count)) => in_range(&field, n, 1, count)?,
            (Choice::Steps(_), Kind::Op(takes)) => {
                return Err(err(
                    field,
                    format!("`{}` is an operation: it takes `{takes}`", v.site),
                ))
            }
            (choice, Kind::Loop(_)) => {
                return Err(err(
                    field,
                    format!("`{}` is a loop: it takes `steps`, not `{choice}`", v.site),
                ))
            }
            (choice, Kind::Op(takes)) if choice.tuning() != Some(takes) => {
                return Err(err(
                    field,
                    format!("`{}` takes `{takes}`, not `{choice}`", v.site),
                ))
            }
            (_, Kind::Op(_)) => {}
        }
    }
    Ok(())
}

fn image(d: &Description) -> Result<(), SceneError> {
    let [w, h] = d.image.size;
    in_range("image.size[0]", w, 1, MAX_SIZE)?;
    in_range("image.size[1]", h, 1, MAX_SIZE)?;
    match &d.image.camera {
        Camera::LookAt {
            position,
            target,
            up,
            scale,
            ..
        } => {
            let p = "image.camera.look_at";
            finite(&format!("{p}.position"), position)?;
            finite(&format!("{p}.target"), target)?;
            finite(&format!("{p}.up"), up)?;
            if let Some(s) = scale {
                positive(&format!("{p}.scale"), *s)?;
            }
            let f = [
                position[0] - target[0],
                position[1] - target[1],
                position[2] - target[2],
            ];
            if f.iter().all(|&c| c == 0.0) {
                return Err(err(
                    format!("{p}.target"),
                    "equals the position: the camera has no direction",
                ));
            }
            let c = [
                up[1] * f[2] - up[2] * f[1],
                up[2] * f[0] - up[0] * f[2],
                up[0] * f[1] - up[1] * f[0],
            ];
            let (cl, ul, fl) = (norm(c), norm(*up), norm(f));
            if cl <= 1e-3 * ul * fl {
                return Err(err(
                    format!("{p}.up"),
                    "is zero or parallel to the viewing direction",
                ));
            }
        }
        Camera::Direct {
            position,
            centre,
            scale,
            row_origin,
            rows,
        } => {
            let p = "image.camera.direct";
            finite(&format!("{p}.position"), position)?;
            finite(&format!("{p}.centre"), centre)?;
            positive(&format!("{p}.scale"), *scale)?;
            if rows[0] > rows[1] || rows[1] > *row_origin || row_origin - rows[0] >= h {
                return Err(err(
                    format!("{p}.rows"),
                    format!(
                        "rows {rows:?} must be ordered and map into the image (n = {row_origin} - y, 0 <= y < {h})"
                    ),
                ));
            }
        }
    }
    if let Output::Levels4 { gain } = d.image.output {
        positive("image.output.levels4.gain", gain)?;
    }
    Ok(())
}

fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

fn method(d: &Description) -> Result<(), SceneError> {
    match d.method {
        Method::SphereTrace {
            steps,
            hit_distance,
            max_distance,
            normal_offset,
        } => {
            let p = "method.sphere_trace";
            in_range(&format!("{p}.steps"), steps, 1, MAX_STEPS)?;
            positive(&format!("{p}.hit_distance"), hit_distance)?;
            positive(&format!("{p}.max_distance"), max_distance)?;
            positive(&format!("{p}.normal_offset"), normal_offset)?;
            finite(&format!("{p}.max_distance"), &[max_distance])?;
            let Some(light) = &d.light else {
                return Err(err("light", "sphere tracing needs a light"));
            };
            finite("light.position", &light.position)?;
            if let Some(s) = &d.shadow {
                in_range("shadow.steps", s.steps, 1, MAX_STEPS)?;
                positive("shadow.offset", s.offset)?;
                positive("shadow.factor", s.factor)?;
            }
        }
        Method::AnalyticSpheres { bounces } => {
            in_range("method.analytic_spheres.bounces", bounces, 0, MAX_BOUNCES)?;
            if d.shadow.is_some() {
                return Err(err("shadow", "analytic spheres have no shadow rays"));
            }
        }
    }
    match d.background {
        Background::Constant(v) => finite("background.constant", &[v]),
        Background::Sky { base, slope } => finite("background.sky", &[base, slope]),
        Background::SkyFloor {
            height,
            step,
            base,
            fog,
        } => finite("background.sky_floor", &[height, step, base, fog]),
    }
}

fn material(d: &Description, name: &str) -> Result<(), SceneError> {
    let p = format!("materials.{name}");
    let analytic = matches!(d.method, Method::AnalyticSpheres { .. });
    let colour = |c: &Colour, kind: &str| match c {
        Colour::Plain(v) => finite(&format!("{p}.{kind}.colour"), &[*v]),
        Colour::Textured(Texture::Checker { even, odd_add }) => {
            finite(&format!("{p}.{kind}.colour.checker"), &[*even, *odd_add])
        }
    };
    let exponent = |field: &str, e: u32| in_range(&format!("{p}.{field}"), e, 1, MAX_EXPONENT);
    match &d.materials[name] {
        Material::Mirror {} if analytic => return Ok(()),
        Material::Mirror {} => {
            return Err(err(
                format!("{p}.mirror"),
                "mirrors need the analytic_spheres method",
            ))
        }
        _ if analytic => {
            return Err(err(
                p.clone(),
                "analytic spheres are mirrors: use the mirror material",
            ))
        }
        Material::Phong {
            colour: c,
            diffuse,
            specular,
            exponent: e,
            ambient,
        } => {
            colour(c, "phong")?;
            finite(
                &format!("{p}.phong"),
                &[diffuse[0], diffuse[1], specular[0]],
            )?;
            finite(
                &format!("{p}.phong"),
                &[specular[1], ambient[0], ambient[1]],
            )?;
            exponent("phong.exponent", *e)?;
        }
        Material::BlinnPhong {
            colour: c,
            diffuse,
            specular,
            exponent: e,
            fresnel,
            fresnel_exponent,
            ambient,
            ..
        } => {
            colour(c, "blinn_phong")?;
            finite(
                &format!("{p}.blinn_phong"),
                &[*diffuse, *specular, *fresnel, *ambient],
            )?;
            exponent("blinn_phong.exponent", *e)?;
            exponent("blinn_phong.fresnel_exponent", *fresnel_exponent)?;
        }
        Material::Diffuse {
            colour: c,
            diffuse,
            ambient,
        } => {
            colour(c, "diffuse")?;
            finite(&format!("{p}.diffuse"), &[*diffuse, *ambient])?;
        }
        Material::Toon {
            colour: c,
            bands,
            ambient,
        } => {
            colour(c, "toon")?;
            exponent("toon.bands", *bands)?;
            finite(&format!("{p}.toon.ambient"), &[*ambient])?;
        }
    }
    Ok(())
}

/// A depth-first walk from the root: references, cycles, parameters.
struct Walk<'a> {
    d: &'a Description,
    /// The nodes on the path from the root.
    stack: Vec<String>,
    materials: Vec<String>,
    spheres: Vec<([f64; 3], f64, String)>,
    shapes: BTreeSet<&'static str>,
    /// Nodes visited so far, shared ones once per use.
    uses: usize,
}

impl Walk<'_> {
    /// Visit node `name`, referred to from field `from`.
    fn node(&mut self, name: &str, from: &str) -> Result<(), SceneError> {
        let Some(node) = self.d.nodes.get(name) else {
            return Err(err(from, format!("no node named `{name}`")));
        };
        if let Some(i) = self.stack.iter().position(|n| n == name) {
            let cycle: Vec<&str> = self.stack[i..].iter().map(String::as_str).collect();
            return Err(err(
                from,
                format!("a cycle: {} -> {name}", cycle.join(" -> ")),
            ));
        }
        if self.stack.len() >= 64 {
            return Err(err(from, "the graph is deeper than 64 nodes"));
        }
        self.uses += 1;
        if self.uses > MAX_USES {
            return Err(err(
                "nodes",
                format!(
                    "the scene uses more than {MAX_USES} nodes once shared nodes are counted \
                     per use (at `{from}`): its program would be too large"
                ),
            ));
        }
        self.stack.push(name.to_string());
        let p = format!("nodes.{name}");
        let analytic = matches!(self.d.method, Method::AnalyticSpheres { .. });
        let children = |kind: &str, c: &[String], min: usize, max: usize| {
            let max = max.min(MAX_CHILDREN);
            if c.len() > max {
                return Err(err(
                    format!("{p}.{kind}.children"),
                    format!("a combination has at most {max} children, has {}", c.len()),
                ));
            }
            if c.len() < min {
                let want = if min == max {
                    format!("exactly {min}")
                } else {
                    format!("at least {min}")
                };
                return Err(err(
                    format!("{p}.{kind}.children"),
                    format!("a combination needs {want} children, has {}", c.len()),
                ));
            }
            Ok(())
        };
        match node {
            Node::Union(c) => children("union", &c.children, 1, usize::MAX)?,
            Node::Subtraction(c) => children("subtraction", &c.children, 2, 2)?,
            Node::Intersection(c) => children("intersection", &c.children, 1, usize::MAX)?,
            Node::SmoothUnion(c) => {
                children("smooth_union", &c.children, 1, usize::MAX)?;
                positive(&format!("{p}.smooth_union.k"), c.k)?;
            }
            Node::Repeat(r) => {
                finite(&format!("{p}.repeat.period"), &r.period)?;
                if r.period.iter().any(|&c| c < 0.0) || r.period.iter().all(|&c| c == 0.0) {
                    return Err(err(
                        format!("{p}.repeat.period"),
                        "periods must be 0 (no repetition) or positive, one at least positive",
                    ));
                }
            }
            leaf => self.leaf(name, leaf)?,
        }
        if analytic && !matches!(node, Node::Union(_) | Node::Sphere(_)) {
            return Err(err(
                p.clone(),
                "analytic spheres take spheres and unions only",
            ));
        }
        let kids: Vec<(String, String)> = match node {
            Node::Union(c) | Node::Subtraction(c) | Node::Intersection(c) => {
                named_children(&p, node_kind(node), &c.children)
            }
            Node::SmoothUnion(c) => named_children(&p, "smooth_union", &c.children),
            Node::Repeat(r) => vec![(r.child.clone(), format!("{p}.repeat.child"))],
            _ => Vec::new(),
        };
        for (child, field) in kids {
            self.node(&child, &field)?;
        }
        self.stack.pop();
        Ok(())
    }

    fn leaf(&mut self, name: &str, node: &Node) -> Result<(), SceneError> {
        let kind = node_kind(node);
        let p = format!("nodes.{name}.{kind}");
        self.shapes.insert(kind);
        match node {
            Node::Plane(s) => {
                finite(&format!("{p}.height"), &[s.height])?;
            }
            Node::Sphere(s) => {
                positive(&format!("{p}.radius"), s.radius)?;
            }
            Node::Torus(s) => {
                positive(&format!("{p}.ring"), s.ring)?;
                positive(&format!("{p}.tube"), s.tube)?;
            }
            Node::Box(s) => {
                for (i, &c) in s.size.iter().enumerate() {
                    positive(&format!("{p}.size[{i}]"), c)?;
                }
            }
            Node::RoundBox(s) => {
                positive(&format!("{p}.radius"), s.radius)?;
                for (i, &c) in s.size.iter().enumerate() {
                    positive(&format!("{p}.size[{i}]"), c)?;
                    if c <= s.radius {
                        return Err(err(
                            format!("{p}.size[{i}]"),
                            format!("must exceed the radius {}", shown(s.radius)),
                        ));
                    }
                }
            }
            Node::Capsule(s) => {
                finite(&format!("{p}.a"), &s.a)?;
                finite(&format!("{p}.b"), &s.b)?;
                positive(&format!("{p}.radius"), s.radius)?;
                if s.a == s.b {
                    return Err(err(format!("{p}.b"), "equals a: the segment is empty"));
                }
            }
            Node::Cylinder(s) => {
                positive(&format!("{p}.radius"), s.radius)?;
                positive(&format!("{p}.height"), s.height)?;
            }
            _ => unreachable!("a leaf"),
        }
        let (transform, material) = node.shape_parts().expect("a leaf is a shape");
        if transform.len() > MAX_TRANSFORMS {
            return Err(err(
                format!("nodes.{name}.transform"),
                format!(
                    "a shape has at most {MAX_TRANSFORMS} transforms, has {}",
                    transform.len()
                ),
            ));
        }
        let mut centre = [0.0; 3];
        for (i, t) in transform.iter().enumerate() {
            let tp = format!("nodes.{name}.transform[{i}]");
            match t {
                Transform::Translate(v) => {
                    finite(&tp, v)?;
                    centre = [centre[0] + v[0], centre[1] + v[1], centre[2] + v[2]];
                }
                Transform::Scale(s) => positive(&format!("{tp}.scale"), *s)?,
                Transform::Rotate { degrees, .. } => finite(&format!("{tp}.rotate"), &[*degrees])?,
            }
            if matches!(self.d.method, Method::AnalyticSpheres { .. })
                && !matches!(t, Transform::Translate(_))
            {
                return Err(err(tp, "analytic spheres are placed by translate only"));
            }
        }
        if !self.d.materials.contains_key(material) {
            return Err(err(
                format!("nodes.{name}.material"),
                format!("no material named `{material}`"),
            ));
        }
        if !self.materials.iter().any(|m| m == material) {
            self.materials.push(material.to_string());
        }
        if let Node::Sphere(s) = node {
            if matches!(self.d.method, Method::AnalyticSpheres { .. }) {
                self.spheres
                    .push((centre, s.radius, format!("nodes.{name}")));
            }
        }
        Ok(())
    }
}

fn named_children(p: &str, kind: &str, children: &[String]) -> Vec<(String, String)> {
    children
        .iter()
        .enumerate()
        .map(|(i, c)| (c.clone(), format!("{p}.{kind}.children[{i}]")))
        .collect()
}

/// The format's name of a node's kind.
pub fn node_kind(node: &Node) -> &'static str {
    match node {
        Node::Plane(_) => "plane",
        Node::Sphere(_) => "sphere",
        Node::Torus(_) => "torus",
        Node::Box(_) => "box",
        Node::RoundBox(_) => "round_box",
        Node::Capsule(_) => "capsule",
        Node::Cylinder(_) => "cylinder",
        Node::Union(_) => "union",
        Node::SmoothUnion(_) => "smooth_union",
        Node::Subtraction(_) => "subtraction",
        Node::Intersection(_) => "intersection",
        Node::Repeat(_) => "repeat",
    }
}
