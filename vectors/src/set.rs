//! Vector sets: the on-disk format (JSON, versioned) of a named list of test
//! vectors for one level, and its validation.
//!
//! A set file looks like
//! ```json
//! {"format_version": 1, "name": "ops-small", "level": "ops",
//!  "description": "...", "seed": 316,
//!  "vectors": [{"category": "cancellation", "op": "add", "a": [0,127,8192], "b": [1,127,8192]}]}
//! ```
//! Per level a vector is `{category, op, a, b?}` (ops), `{category, p:
//! [[s,e,m],[s,e,m],[s,e,m]]}` (sdf), `{category, x, y}` (pixels) or
//! `{category}` (image: the whole picture). Loading validates every field
//! and names the offending one: `ops-small.json: vectors[12].a: expected
//! [s,e,m]`.

use common::{Op, F316};
use serde::{Deserialize, Serialize};
use serde_json::Value;
use std::fmt;
use std::path::{Path, PathBuf};
use std::str::FromStr;

/// The version of the set format this crate reads and writes.
pub const FORMAT_VERSION: u32 = 1;

/// The level of comparison a vector belongs to (see the design).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Level {
    /// Single Float316 operations on operand triples.
    Ops,
    /// Signed distance and colour of the scene at a query point.
    Sdf,
    /// The shade of one pixel before dithering and its dithered bit.
    Pixels,
    /// The whole 512x256 image.
    Image,
}

impl Level {
    /// Every level, in the order `--level all` runs them.
    pub const ALL: [Level; 4] = [Level::Ops, Level::Sdf, Level::Pixels, Level::Image];

    /// The name used on the command line and in files.
    pub const fn name(self) -> &'static str {
        match self {
            Level::Ops => "ops",
            Level::Sdf => "sdf",
            Level::Pixels => "pixels",
            Level::Image => "image",
        }
    }
}

impl fmt::Display for Level {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Level {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Level::ALL
            .into_iter()
            .find(|l| l.name() == s)
            .ok_or_else(|| format!("unknown level `{s}` (expected ops, sdf, pixels or image)"))
    }
}

/// One Float316 operation applied to its operands.
#[derive(Clone, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct OpVector {
    /// Why the vector exists (`cancellation`, `exponent-gap-7`, ...).
    pub category: String,
    /// The operation.
    pub op: Op,
    /// First operand.
    pub a: F316,
    /// Second operand, for binary operations only.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub b: Option<F316>,
}

impl OpVector {
    /// The operands in call order.
    pub fn args(&self) -> Vec<F316> {
        std::iter::once(self.a).chain(self.b).collect()
    }
}

/// A scene query point, as a Float316 triple per coordinate. Float
/// implementations use the exact f64 value of each triple.
#[derive(Clone, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct SdfVector {
    /// Why the point exists (`near-sphere`, `torus-axis`, ...).
    pub category: String,
    /// The point (x, y, z).
    pub p: [F316; 3],
}

impl SdfVector {
    /// The exact f64 value of the point.
    pub fn p_f64(&self) -> [f64; 3] {
        self.p.map(F316::to_f64)
    }
}

/// One pixel of the 512x256 image.
#[derive(Clone, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct PixelVector {
    /// Why the pixel was chosen (`silhouette`, `border`, ...).
    pub category: String,
    /// Column, 0..512.
    pub x: u16,
    /// Row, 0..256.
    pub y: u16,
}

/// The whole image (the only vector of the `image` level).
#[derive(Clone, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct ImageVector {
    /// Category name, usually `image`.
    pub category: String,
}

/// One test vector of any level.
#[derive(Clone, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Vector {
    Op(OpVector),
    Sdf(SdfVector),
    Pixel(PixelVector),
    Image(ImageVector),
}

impl Vector {
    /// The level this vector belongs to.
    pub fn level(&self) -> Level {
        match self {
            Vector::Op(_) => Level::Ops,
            Vector::Sdf(_) => Level::Sdf,
            Vector::Pixel(_) => Level::Pixels,
            Vector::Image(_) => Level::Image,
        }
    }

    /// The category name the vector carries.
    pub fn category(&self) -> &str {
        match self {
            Vector::Op(v) => &v.category,
            Vector::Sdf(v) => &v.category,
            Vector::Pixel(v) => &v.category,
            Vector::Image(v) => &v.category,
        }
    }

    /// A short stable name of the input, usable in file names and reports:
    /// `op-sqrt-0-3-8192`, `sdf-...`, `pixel-312-87`, `image`.
    pub fn slug(&self) -> String {
        let t = |v: F316| format!("{}-{}-{}", v.s, v.e, v.m);
        match self {
            Vector::Op(v) => match v.b {
                Some(b) => format!("op-{}-{}-{}", v.op, t(v.a), t(b)),
                None => format!("op-{}-{}", v.op, t(v.a)),
            },
            Vector::Sdf(v) => format!("sdf-{}-{}-{}", t(v.p[0]), t(v.p[1]), t(v.p[2])),
            Vector::Pixel(v) => format!("pixel-{}-{}", v.x, v.y),
            Vector::Image(_) => "image".to_string(),
        }
    }

    /// The input as the localize command line spells it
    /// (`--op sqrt --a 0,3,8192`, `--point ...`, `--pixel 312,87`);
    /// `None` for the whole image.
    pub fn localize_args(&self) -> Option<String> {
        let t = |v: F316| format!("{},{},{}", v.s, v.e, v.m);
        match self {
            Vector::Op(v) => Some(match v.b {
                Some(b) => format!("--op {} --a {} --b {}", v.op, t(v.a), t(b)),
                None => format!("--op {} --a {}", v.op, t(v.a)),
            }),
            Vector::Sdf(v) => Some(format!("--point {}:{}:{}", t(v.p[0]), t(v.p[1]), t(v.p[2]))),
            Vector::Pixel(v) => Some(format!("--pixel {},{}", v.x, v.y)),
            Vector::Image(_) => None,
        }
    }
}

impl fmt::Display for Vector {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Vector::Op(v) => match v.b {
                Some(b) => write!(f, "{}({:?}, {:?})", v.op, v.a, b),
                None => write!(f, "{}({:?})", v.op, v.a),
            },
            Vector::Sdf(v) => write!(f, "scene({:?}, {:?}, {:?})", v.p[0], v.p[1], v.p[2]),
            Vector::Pixel(v) => write!(f, "pixel({},{})", v.x, v.y),
            Vector::Image(_) => write!(f, "image"),
        }
    }
}

/// A named, versioned list of vectors of one level.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct VectorSet {
    /// Always [`FORMAT_VERSION`] once loaded.
    pub format_version: u32,
    /// The set's name (`ops-small`); the file is `NAME.json`.
    pub name: String,
    /// The level every vector belongs to.
    pub level: Level,
    /// What the set is for and how it was made.
    #[serde(default)]
    pub description: String,
    /// The generator seed (absent for hand-written and repro files).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seed: Option<u64>,
    /// The vectors, all of `level`.
    pub vectors: Vec<Vector>,
}

/// Why a set could not be loaded.
#[derive(Debug, thiserror::Error)]
pub enum SetError {
    /// The file could not be read or written.
    #[error("{file}: {source}")]
    Io {
        file: String,
        #[source]
        source: std::io::Error,
    },
    /// The file is not a readable regular UTF-8 file of bounded size.
    #[error(transparent)]
    Input(#[from] common::input::InputError),
    /// The file is not JSON.
    #[error("{file}: not valid JSON: {source}")]
    Json {
        file: String,
        #[source]
        source: serde_json::Error,
    },
    /// A field is missing or has the wrong shape; `path` names it
    /// (`vectors[12].a`).
    #[error("{file}: {path}: {message}")]
    Field {
        file: String,
        path: String,
        message: String,
    },
}

impl VectorSet {
    /// A set from its parts, with the current format version.
    pub fn new(
        name: &str,
        level: Level,
        description: &str,
        seed: Option<u64>,
        vectors: Vec<Vector>,
    ) -> Self {
        VectorSet {
            format_version: FORMAT_VERSION,
            name: name.to_string(),
            level,
            description: description.to_string(),
            seed,
            vectors,
        }
    }

    /// A one-vector set reproducing one input (saved as a one-line file).
    pub fn repro(vector: Vector) -> Self {
        let name = format!("repro-{}", vector.slug());
        VectorSet::new(
            &name,
            vector.level(),
            "one failing input, written by harness diff",
            None,
            vec![vector],
        )
    }

    /// Load and validate a set file.
    pub fn load(path: &Path) -> Result<Self, SetError> {
        let text = common::input::read_text_limited(path, MAX_SET_BYTES)?;
        Self::parse(&path.display().to_string(), &text)
    }

    /// Parse and validate the text of a set; `file` names it in errors.
    pub fn parse(file: &str, text: &str) -> Result<Self, SetError> {
        let value: Value = serde_json::from_str(text).map_err(|source| SetError::Json {
            file: file.to_string(),
            source,
        })?;
        crate::validate::set_from_value(&value).map_err(|(path, message)| SetError::Field {
            file: file.to_string(),
            path,
            message,
        })
    }

    /// The file text: the header, then one vector per line (readable
    /// diffs); a one-vector set is written on a single line.
    pub fn to_json(&self) -> String {
        let header = |vectors: &str| {
            let mut h = serde_json::Map::new();
            h.insert("format_version".into(), self.format_version.into());
            h.insert("name".into(), self.name.clone().into());
            h.insert("level".into(), self.level.name().into());
            h.insert("description".into(), self.description.clone().into());
            if let Some(seed) = self.seed {
                h.insert("seed".into(), seed.into());
            }
            let h = serde_json::to_string(&Value::Object(h)).expect("a map serialises");
            format!("{},\"vectors\":{vectors}}}", &h[..h.len() - 1])
        };
        let lines: Vec<String> = self
            .vectors
            .iter()
            .map(|v| serde_json::to_string(v).expect("vectors serialise"))
            .collect();
        if lines.len() <= 1 {
            header(&format!("[{}]", lines.join(""))) + "\n"
        } else {
            header(&format!("[\n{}\n]", lines.join(",\n"))) + "\n"
        }
    }

    /// Write the set to `path`.
    pub fn save(&self, path: &Path) -> Result<(), SetError> {
        std::fs::write(path, self.to_json()).map_err(|source| SetError::Io {
            file: path.display().to_string(),
            source,
        })
    }
}

/// The directory of the committed sets (`vectors/sets`).
pub fn sets_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("sets")
}

/// Load a committed set by name (`ops-small`) from [`sets_dir`].
/// The largest set file [`VectorSet::load`] reads: a whole TestFloat
/// level-2 campaign of one binary operation is about 92 MB of JSON.
pub const MAX_SET_BYTES: u64 = 1 << 30;

/// The committed set `name` from [`sets_dir`].
pub fn load_named(name: &str) -> Result<VectorSet, SetError> {
    VectorSet::load(&sets_dir().join(format!("{name}.json")))
}
