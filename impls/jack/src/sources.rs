//! The Jack sources of the raymarcher, embedded in the crate, and their
//! compilation to a loaded VM [`Program`].

use crate::{Bindings, BoundProgram, Budgets, JackError, JackProgram};
use hack_vm::{Profile, Program};
use jack_compiler::VmClass;
use std::sync::Arc;

/// Every class of the raymarcher as (file name, source), in file name order
/// (the order `harness jack run impls/jack/raymarcher` loads them).
pub const SOURCES: [(&str, &str); 8] = [
    ("Camera.jack", include_str!("../raymarcher/Camera.jack")),
    ("Float316.jack", include_str!("../raymarcher/Float316.jack")),
    ("Image.jack", include_str!("../raymarcher/Image.jack")),
    ("Main.jack", include_str!("../raymarcher/Main.jack")),
    ("March.jack", include_str!("../raymarcher/March.jack")),
    ("Scene.jack", include_str!("../raymarcher/Scene.jack")),
    ("Shade.jack", include_str!("../raymarcher/Shade.jack")),
    ("Vec.jack", include_str!("../raymarcher/Vec.jack")),
];

/// The raymarcher's bindings (`raymarcher/bindings.toml`), as TOML text.
pub const BINDINGS: &str = include_str!("../raymarcher/bindings.toml");

/// The raymarcher's bindings, parsed.
pub fn bindings() -> Bindings {
    toml::from_str(BINDINGS).expect("the raymarcher's bindings parse")
}

/// The raymarcher compiled under `profile` and opened through its
/// bindings.
pub fn bound(profile: Profile, budgets: Budgets) -> Result<BoundProgram, JackError> {
    let program = JackProgram::from_jack(&SOURCES, profile)?;
    BoundProgram::open(&program, &bindings(), budgets)
}

/// Compile the embedded sources with the compiler of the official tool
/// `profile` names (desktop or web IDE) and load the VM code.
pub fn program(profile: Profile) -> Result<Arc<Program>, JackError> {
    let compiler = match profile {
        Profile::Desktop => jack_compiler::Profile::Desktop,
        Profile::Web => jack_compiler::Profile::Web,
    };
    let classes = jack_compiler::compile_sources(&SOURCES, compiler)?;
    let vm: Vec<(String, String)> = classes.into_iter().map(VmClass::into_file).collect();
    Ok(Program::from_sources(&vm)?)
}
