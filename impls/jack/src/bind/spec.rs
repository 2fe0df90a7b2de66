//! What a user writes: the bindings of a Jack program, as plain data
//! (deserialized from the `[impl.NAME]` table of a `harness.toml`, see
//! `docs/bindings.md`). Nothing here is checked yet; [`crate::BoundProgram`]
//! checks every field against the program and names the field it rejects.

use serde::Deserialize;
use std::collections::BTreeMap;

/// The bindings of one Jack program.
#[derive(Clone, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Bindings {
    /// Where the program is ready to be queried.
    pub ready: Ready,
    /// The float class.
    pub float: Layout,
    /// The 3-vector class (needed by an SDF function that takes `p`).
    #[serde(default)]
    pub vec3: Option<Layout>,
    /// The SDF result class (a distance and a colour), for an SDF function
    /// that gives `hit`.
    #[serde(default)]
    pub sdf_result: Option<Layout>,
    /// Operation name (`add`, `inv_sqrt`, ...) to its call statement.
    #[serde(default)]
    pub ops: BTreeMap<String, String>,
    /// The statements of one SDF query.
    #[serde(default)]
    pub sdf: Option<Statements>,
    /// The statements of one pixel.
    #[serde(default)]
    pub pixel: Option<Statements>,
    /// Whether the shade the pixel statements give is clamped to [0, 1]
    /// already (the default) or taken before the program clamps it.
    #[serde(default)]
    pub pixel_shade: PixelShade,
    /// How whole-program mode sees pixels and their operations.
    #[serde(default)]
    pub capture: Option<Capture>,
    /// The `Sys.error` code by which the program says an operand is out of
    /// an operation's domain (reported as "out of domain", like the
    /// reference's floor and mod2 outside their table).
    #[serde(default)]
    pub out_of_domain: Option<i16>,
    /// Instruction budgets per query, in place of the defaults
    /// ([`crate::Budgets`]): `budget = { op = 3000000 }`.
    #[serde(default)]
    pub budget: BudgetFields,
}

/// `budget = { op = N, sdf = N, pixel = N }`: instructions one query may
/// take before it is reported as a hang; each absent one keeps its default.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BudgetFields {
    /// Per operation (`ops.NAME`).
    #[serde(default)]
    pub op: Option<u64>,
    /// Per SDF query.
    #[serde(default)]
    pub sdf: Option<u64>,
    /// Per pixel.
    #[serde(default)]
    pub pixel: Option<u64>,
}

impl BudgetFields {
    /// `defaults` with the budgets given here in their place.
    pub fn over(&self, defaults: crate::Budgets) -> crate::Budgets {
        crate::Budgets {
            op: self.op.unwrap_or(defaults.op),
            sdf: self.sdf.unwrap_or(defaults.sdf),
            pixel: self.pixel.unwrap_or(defaults.pixel),
        }
    }
}

/// `pixel_shade`: what the `shade` of the pixel statements is.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum PixelShade {
    /// Clamped to [0, 1], as the reference compares it.
    #[default]
    Clamped,
    /// Before the clamp (a pixel function whose caller clamps): the
    /// harness clamps it as the reference does.
    Unclamped,
}

/// A class of the program: its fields in declaration order, by role, and
/// how to make an object of it.
#[derive(Clone, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Layout {
    /// The class name.
    pub class: String,
    /// One role per field, in the order the class declares its fields
    /// (`s`, `e`, `m` for a float; `x`, `y`, `z` for a vector; `distance`,
    /// `colour` for an SDF result; `_` for a field the harness leaves alone).
    pub fields: Vec<String>,
    /// A constructor statement (`Float316.new(s, e, m)`), or `alloc`: a
    /// `Memory.alloc` of one word per field, then field writes.
    pub new: String,
}

/// One statement or several, run in order on the same machine.
#[derive(Clone, Debug, PartialEq, Eq, Deserialize)]
#[serde(untagged)]
pub enum Statements {
    /// `"white = Image.pixel(x, y)"`.
    One(String),
    /// `["Scene.eval(p)", "distance = Scene.distance()", ...]`.
    Many(Vec<String>),
}

impl Statements {
    /// The statements as a list.
    pub fn list(&self) -> Vec<&str> {
        match self {
            Statements::One(s) => vec![s.as_str()],
            Statements::Many(v) => v.iter().map(String::as_str).collect(),
        }
    }
}

/// Where the program is ready: after init statements, or after running the
/// program's entry with scripted keys up to the first call of a function.
#[derive(Clone, Debug, PartialEq, Eq, Deserialize)]
#[serde(try_from = "ReadyFields")]
pub enum Ready {
    /// Call these statements in order from a fresh machine.
    Init {
        /// `["Main.init()"]`.
        init: Vec<String>,
    },
    /// Run the program (`Sys.init`, hence `Main.main`) until it first calls
    /// `until_call`; stop just before that call.
    Run {
        /// The function the run starts from: `Main.main` (the program's
        /// own `Sys.init` calls it).
        run: String,
        /// Keys pressed in turn (`SPACE`, `A`, ...; see `harness jack run`).
        #[serde(default)]
        keys: String,
        /// Instructions each key is held (and then released).
        #[serde(default)]
        hold: Option<u64>,
        /// The function whose first call is the ready point.
        until_call: String,
        /// Instructions the run may take to get there.
        #[serde(default)]
        budget: Option<u64>,
    },
}

/// `ready`'s table as written, before it is told apart: an error then
/// names the field that is missing or does not belong (an untagged enum
/// could only say that no variant matched).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ReadyFields {
    init: Option<Vec<String>>,
    run: Option<String>,
    keys: Option<String>,
    hold: Option<u64>,
    until_call: Option<String>,
    budget: Option<u64>,
}

impl TryFrom<ReadyFields> for Ready {
    type Error = String;

    fn try_from(f: ReadyFields) -> Result<Ready, String> {
        match (f.init, f.run) {
            (Some(_), Some(_)) => Err("`init` and `run` exclude each other: give one".into()),
            (Some(init), None) => {
                let extra = [
                    ("keys", f.keys.is_some()),
                    ("hold", f.hold.is_some()),
                    ("until_call", f.until_call.is_some()),
                    ("budget", f.budget.is_some()),
                ];
                match extra.iter().find(|(_, given)| *given) {
                    Some((name, _)) => Err(format!("`{name}` belongs to `run`, not to `init`")),
                    None => Ok(Ready::Init { init }),
                }
            }
            (None, Some(run)) => Ok(Ready::Run {
                run,
                keys: f.keys.unwrap_or_default(),
                hold: f.hold,
                until_call: f.until_call.ok_or(
                    "`until_call` is missing: the function whose first call is the ready point",
                )?,
                budget: f.budget,
            }),
            (None, None) => Err("give `init` (statements) or `run` (the entry to run)".into()),
        }
    }
}

impl Default for Ready {
    fn default() -> Self {
        Ready::Init { init: Vec::new() }
    }
}

/// How whole-program mode captures pixels.
#[derive(Clone, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Capture {
    /// A statement naming the program's per-pixel function and what its
    /// arguments and return value are: `"white = Image.shadeAt(_, _, x, y)"`
    /// (x and y ints), `"shade = Render.shade(u, v)"`. Each return is one
    /// pixel.
    #[serde(default)]
    pub pixel: Option<String>,
    /// A program function that draws one pixel: `"Canvas.plot(x, y)"` (a
    /// black pixel) or `"Canvas.plot(x, y, white)"`. Each call is one pixel.
    #[serde(default)]
    pub draw: Option<String>,
    /// Keys pressed in turn during the run (default: those of `ready`).
    #[serde(default)]
    pub keys: Option<String>,
    /// Instructions each key is held (and then released).
    #[serde(default)]
    pub hold: Option<u64>,
}
