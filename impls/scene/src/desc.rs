//! The scene description, format version 1: the JSON a user writes
//! (`vectors/scenes/*.json`, documented in `docs/scenes.md`). Every struct
//! rejects unknown fields; [`crate::load`] names the path of a bad field.

use serde::Deserialize;
use std::collections::BTreeMap;

/// A whole scene.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Description {
    /// The format version; only 1 exists.
    pub version: u32,
    /// A short name for reports.
    pub name: String,
    pub image: Image,
    pub method: Method,
    /// The point light (sphere tracing only).
    #[serde(default)]
    pub light: Option<Light>,
    /// Hard shadow rays toward the light (sphere tracing only).
    #[serde(default)]
    pub shadow: Option<Shadow>,
    /// What a ray that hits nothing sees.
    pub background: Background,
    /// Named materials, referred to by shapes.
    #[serde(default)]
    pub materials: BTreeMap<String, Material>,
    /// Named nodes of the scene graph: shapes and combinations.
    pub nodes: BTreeMap<String, Node>,
    /// The node that is the scene.
    pub root: String,
    /// Operation variants chosen per call site (Float316 programs only;
    /// see [`crate::sites`]).
    #[serde(default)]
    pub variants: Vec<SiteVariant>,
}

/// One call site's operation variant.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SiteVariant {
    /// The site's name (`pixel/shadow/normalize`).
    pub site: String,
    /// The variant (`"newton-1"`, `{"steps": 16}`).
    pub variant: crate::sites::Choice,
}

/// Image size, camera and output.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Image {
    /// Width and height in pixels.
    pub size: [u32; 2],
    pub camera: Camera,
    pub output: Output,
}

/// How a pixel becomes a ray.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields, rename_all = "snake_case")]
pub enum Camera {
    /// A camera at `position` looking at `target`: u = (x - w/2) / scale,
    /// v = -((y - h/2) / scale), and the ray direction (u, v) on the image
    /// plane at distance 1 in the camera basis of `handedness`.
    LookAt {
        position: [f64; 3],
        target: [f64; 3],
        up: [f64; 3],
        /// Pixels per unit of the image plane at distance 1 (default: the
        /// image height).
        #[serde(default)]
        scale: Option<f64>,
        /// The coordinate system the scene is written in (default: the
        /// seed's, right-handed).
        #[serde(default)]
        handedness: Handedness,
    },
    /// The BBC demo's formula: with n = `row_origin` - y, u = (x - cx) /
    /// scale, v = (n - cy) / scale, w = 1 / sqrt(u*u + v*v + 1), and the
    /// ray direction (u*w, v*w, -w). Rows whose n lies outside `rows` are
    /// not drawn (level 0, as the cleared screen).
    Direct {
        position: [f64; 3],
        centre: [f64; 2],
        scale: f64,
        row_origin: u32,
        rows: [u32; 2],
    },
}

/// The handedness of a scene's coordinates: which way the look-at camera's
/// image x runs. Mirroring it mirrors the image and nothing else.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(try_from = "String")]
pub enum Handedness {
    /// Right-handed, the seed's (spec section 5), OpenGL's: with x to the
    /// right and y up on the screen, z points at the viewer. The basis is
    /// back = normalize(position - target), right = normalize(cross(up,
    /// back)), up' = cross(back, right), and d = normalize(u, v, -1) in it;
    /// a camera looking along +z sees +x on its left.
    #[default]
    Right,
    /// Left-handed, Shadertoy's `normalize(vec3(uv, 1))` and I<3IQ's: z
    /// points into the screen. The basis is forward = normalize(target -
    /// position), right = normalize(cross(up, forward)), up' =
    /// cross(forward, right), and d = normalize(u, v, 1) in it; a camera
    /// looking along +z sees +x on its right.
    Left,
}

impl TryFrom<String> for Handedness {
    type Error = String;

    /// `"right"` or `"left"` (a string of another type is refused by serde
    /// as an invalid type, naming the field all the same).
    fn try_from(s: String) -> Result<Self, String> {
        match s.as_str() {
            "right" => Ok(Handedness::Right),
            "left" => Ok(Handedness::Left),
            _ => Err(format!(
                "unknown handedness `{s}`, expected `right` or `left`"
            )),
        }
    }
}

/// How a shade in [0, 1] becomes a pixel.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields, rename_all = "snake_case")]
pub enum Output {
    /// One bit per pixel, ordered dithering with the 8x8 Bayer matrix.
    Bayer8,
    /// One bit per pixel, ordered dithering with the 4x4 Bayer matrix.
    Bayer4,
    /// One bit per pixel: white above 0.5.
    Threshold,
    /// Four grey levels, the BBC demo's formula: level = 3 - floor((gain *
    /// sqrt(c) + A / 3) / 16), A the BBC's 4x4 matrix at (x mod 4, n mod 4).
    Levels4 { gain: f64 },
}

/// The ray method.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields, rename_all = "snake_case")]
pub enum Method {
    /// Sphere tracing of the scene's signed distance.
    SphereTrace {
        /// Steps of a view ray.
        steps: u32,
        /// A ray hits when the distance is below this.
        hit_distance: f64,
        /// A ray misses when its depth exceeds this.
        max_distance: f64,
        /// The offset of the tetrahedral normal estimate.
        normal_offset: f64,
    },
    /// Analytic ray-sphere intersection; every shape is a sphere, every
    /// material a mirror; a ray is reflected up to `bounces` times.
    AnalyticSpheres { bounces: u32 },
}

/// A point light.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Light {
    pub position: [f64; 3],
}

/// Hard shadows.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Shadow {
    /// Steps of a shadow ray.
    pub steps: u32,
    /// The shadow ray starts this far along the normal.
    pub offset: f64,
    /// A shaded value in shadow is multiplied by this.
    pub factor: f64,
}

/// A ray that hits nothing.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields, rename_all = "snake_case")]
pub enum Background {
    /// One shade.
    Constant(f64),
    /// A sky gradient: `base + slope * d.y`.
    Sky { base: f64, slope: f64 },
    /// The BBC demo: the sky gradient `d.y` when `d.y >= 0`, else a checker
    /// floor at y = `height`, shaded `-d.y * (parity * step + base) + fog`.
    SkyFloor {
        height: f64,
        step: f64,
        base: f64,
        fog: f64,
    },
}

/// A material (per instance: each shape may name one or carry its own).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields, rename_all = "snake_case")]
pub enum Material {
    /// The seed's Phong: `col * (kd*id * angle(L,n) + ks*is * angle(R,C)^exponent) + ka*ia`.
    /// Each factor pair multiplies in the float formulation; Float316
    /// takes the product truncated once.
    Phong {
        colour: Colour,
        diffuse: [f64; 2],
        specular: [f64; 2],
        exponent: u32,
        ambient: [f64; 2],
    },
    /// Blinn-Phong with Schlick Fresnel and optional 5-sample ambient
    /// occlusion (the C99 engine).
    BlinnPhong {
        colour: Colour,
        diffuse: f64,
        specular: f64,
        exponent: u32,
        fresnel: f64,
        fresnel_exponent: u32,
        ambient: f64,
        #[serde(default)]
        occlusion: bool,
    },
    /// Lambert: `col * kd * angle(L, n) + ka`.
    Diffuse {
        colour: Colour,
        diffuse: f64,
        ambient: f64,
    },
    /// Toon: `col * floor(angle(L, n) * bands) / bands + ka` (I<3IQ).
    Toon {
        colour: Colour,
        bands: u32,
        ambient: f64,
    },
    /// A perfect mirror (analytic spheres only).
    Mirror {},
}

/// A surface colour (a shade factor).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields, rename_all = "snake_case", untagged)]
pub enum Colour {
    Plain(f64),
    Textured(Texture),
}

/// A procedural colour.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields, rename_all = "snake_case")]
pub enum Texture {
    /// `even + odd_add * mod2(floor(x) + floor(z))`.
    Checker { even: f64, odd_add: f64 },
}

/// A node of the scene graph: a shape or a combination of named nodes.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields, rename_all = "snake_case")]
pub enum Node {
    Plane(Plane),
    Sphere(Sphere),
    Torus(Torus),
    Box(BoxShape),
    RoundBox(RoundBox),
    Capsule(Capsule),
    Cylinder(Cylinder),
    Union(Children),
    SmoothUnion(SmoothChildren),
    Subtraction(Children),
    Intersection(Children),
    Repeat(Repeat),
}

impl Node {
    /// A shape's placement (its transforms, applied first listed first) and
    /// its material's name; None for a combination or a repeat.
    pub fn shape_parts(&self) -> Option<(&[Transform], &str)> {
        Some(match self {
            Node::Plane(s) => (&s.transform, &s.material),
            Node::Sphere(s) => (&s.transform, &s.material),
            Node::Torus(s) => (&s.transform, &s.material),
            Node::Box(s) => (&s.transform, &s.material),
            Node::RoundBox(s) => (&s.transform, &s.material),
            Node::Capsule(s) => (&s.transform, &s.material),
            Node::Cylinder(s) => (&s.transform, &s.material),
            Node::Union(_)
            | Node::SmoothUnion(_)
            | Node::Subtraction(_)
            | Node::Intersection(_)
            | Node::Repeat(_) => return None,
        })
    }
}

/// A placement step.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields, rename_all = "snake_case")]
pub enum Transform {
    Translate([f64; 3]),
    /// Uniform scale (positive).
    Scale(f64),
    Rotate {
        axis: Axis,
        degrees: f64,
    },
}

/// A coordinate axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Axis {
    X,
    Y,
    Z,
}

/// A shape struct: its own parameters, then the placement (`transform`,
/// applied in order, first listed first) and the name of its material.
macro_rules! shape {
    ($(#[$doc:meta])* $name:ident { $($(#[$fdoc:meta])* $field:ident: $ty:ty),* $(,)? }) => {
        $(#[$doc])*
        #[derive(Clone, Debug, Deserialize)]
        #[serde(deny_unknown_fields)]
        pub struct $name {
            $($(#[$fdoc])* pub $field: $ty,)*
            #[serde(default)]
            pub transform: Vec<Transform>,
            pub material: String,
        }
    };
}

shape!(
    /// The plane y = `height`, facing +y.
    Plane { height: f64 }
);
shape!(
    /// A sphere around the origin.
    Sphere { radius: f64 }
);
shape!(
    /// A torus around the y axis.
    Torus {
        /// From the centre to the middle of the tube.
        ring: f64,
        tube: f64,
    }
);
shape!(
    /// An axis-aligned box of half extents `size`.
    BoxShape { size: [f64; 3] }
);
shape!(
    /// A box of half extents `size` with its edges rounded by `radius`.
    RoundBox { size: [f64; 3], radius: f64 }
);
shape!(
    /// The segment a-b swept by a sphere of `radius`.
    Capsule { a: [f64; 3], b: [f64; 3], radius: f64 }
);
shape!(
    /// A capped cylinder around the y axis: `radius`, half height `height`.
    Cylinder { radius: f64, height: f64 }
);

/// A combination of named nodes.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Children {
    pub children: Vec<String>,
}

/// IQ's polynomial smooth minimum with blend width `k`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SmoothChildren {
    pub k: f64,
    pub children: Vec<String>,
}

/// Domain repetition: on each axis with a non-zero period `c`,
/// `q = (fract(p / c + 0.5) - 0.5) * c`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Repeat {
    pub period: [f64; 3],
    pub child: String,
}
