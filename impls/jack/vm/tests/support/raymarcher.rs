//! The Jack raymarcher (impls/jack/raymarcher) as a loaded program, for the
//! tests and benches of this crate (included with `#[path]`; hack-vm cannot
//! depend on the `jack` crate, which embeds the same sources).

use hack_vm::{Config, Engine, Exit, Machine, Program};
use jack_compiler::VmClass;
use std::path::Path;
use std::sync::Arc;

/// The raymarcher compiled under the desktop profile.
pub fn raymarcher() -> Arc<Program> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../raymarcher");
    let classes = jack_compiler::compile_dir(&dir, jack_compiler::Profile::Desktop)
        .expect("the raymarcher compiles");
    let files: Vec<(String, String)> = classes.into_iter().map(VmClass::into_file).collect();
    Program::from_sources(&files).expect("the raymarcher loads")
}

/// A machine of `program` on `engine` that has run `Main.init` (the
/// snapshot the pixels are asked from).
pub fn initialised(program: &Arc<Program>, engine: Engine) -> Machine {
    let config = Config {
        engine,
        ..Config::default()
    };
    let mut m = Machine::new(program.clone(), config);
    let exit = m.call("Main.init", &[], None).expect("Main.init exists");
    assert_eq!(exit, Exit::Returned(0));
    m
}
