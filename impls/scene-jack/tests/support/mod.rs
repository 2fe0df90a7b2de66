//! Scenes, their generated programs and the reference's answers.

#![allow(dead_code)]

use common::{Outcome, F316};
use reference::{Described, RefImpl, Settings};
use scene::{Checked, Formulation, Program};
use scene_jack::cost::{Counted, Pixel, Runner};
use scene_jack::JackSources;
use std::path::PathBuf;

/// The shipped scenes, the test scene with carved shapes and the user's
/// scene of `examples/scenes`.
pub const SCENES: [&str; 6] = [
    "seed",
    "rtdemo",
    "sdf-engine",
    "toon",
    "tests/carved",
    STILL_LIFE,
];

/// The example of a user's own scene description.
pub const STILL_LIFE: &str = "examples/scenes/still-life";

/// The description of scene `name`: shipped (`seed`, `tests/carved`, in
/// `vectors/scenes`) or an example (`examples/...`, from the repository).
fn path(name: &str) -> PathBuf {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    if name.starts_with("examples/") {
        root.join(format!("{name}.json"))
    } else {
        root.join(format!("vectors/scenes/{name}.json"))
    }
}

pub fn checked(name: &str) -> Checked {
    scene::load(&path(name)).expect("a scene of the repository")
}

pub fn program(name: &str) -> Program {
    scene::lower(&checked(name), Formulation::Float316)
}

pub fn emitted(name: &str) -> JackSources {
    scene_jack::emit(&program(name)).expect("the scene's Jack program")
}

pub fn reference(name: &str) -> Described {
    Described::new(RefImpl::F316, &checked(name), Settings::default()).expect("ref-f316")
}

pub fn runner(name: &str) -> Runner {
    Runner::new(&emitted(name), jack::Profile::Desktop).expect("compiles and sets up")
}

/// Compare the program's pixel (x, y) with the reference's; a mismatch
/// is described.
pub fn pixel_mismatch(r: &Runner, d: &Described, x: u32, y: u32) -> Option<String> {
    let ours: Counted<Pixel> = r.pixel(x, y);
    let theirs = d.pixel(x, y);
    match (&ours.answer, &theirs) {
        (Ok(p), Outcome::Value(v)) => {
            let shade = v.value.triple.expect("Float316 has triples");
            (p.shade != shade || p.level != i16::from(v.level)).then(|| {
                format!(
                    "({x},{y}): jack {:?} level {}, reference {shade:?} level {}",
                    p.shade, p.level, v.level
                )
            })
        }
        (a, b) => Some(format!("({x},{y}): jack {a:?}, reference {b:?}")),
    }
}

/// Compare the SDF at `p`.
pub fn sdf_mismatch(r: &Runner, d: &Described, p: [F316; 3]) -> Option<String> {
    let ours = r.sdf(p);
    let theirs = d.sdf(p);
    match (&ours.answer, &theirs) {
        (Ok((sd, col)), Outcome::Value(v)) => {
            let want = (v.sd.triple.expect("triple"), v.col.triple.expect("triple"));
            ((*sd, *col) != want)
                .then(|| format!("{p:?}: jack {:?}, reference {want:?}", (sd, col)))
        }
        (a, b) => Some(format!("{p:?}: jack {a:?}, reference {b:?}")),
    }
}

/// Points of a grid in [-4, 4]^3 (`n` a side), truncated to Float316.
pub fn grid(n: usize) -> Vec<[F316; 3]> {
    let c = |i: usize| {
        let v = -4.0 + 8.0 * (i as f64 + 0.37) / n as f64;
        F316::from_f64_truncating(v).expect("in range")
    };
    let mut out = Vec::new();
    for i in 0..n {
        for j in 0..n {
            for k in 0..n {
                out.push([c(i), c(j), c(k)]);
            }
        }
    }
    out
}

/// The generated program opened through its own bindings.toml, as the
/// harness opens a user's Jack program.
pub fn bound(j: &JackSources) -> jack::BoundProgram {
    let bindings: jack::Bindings = toml::from_str(&j.bindings).expect("bindings.toml parses");
    let program =
        jack::JackProgram::from_jack(&j.sources(), jack::Profile::Desktop).expect("compiles");
    jack::BoundProgram::open(&program, &bindings, jack::Budgets::default())
        .unwrap_or_else(|e| panic!("the bindings open: {e}"))
}
