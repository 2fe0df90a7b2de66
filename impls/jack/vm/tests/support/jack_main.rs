//! A one-class Jack program compiled and loaded for a profile, for the
//! tests of this crate (included with `#[path]`).

use hack_vm::{Profile, Program};
use std::sync::Arc;

/// `Main.jack` holding `main`, compiled by our Jack compiler for `profile`
/// and loaded; a source that does not compile or load fails the test.
pub fn compile_main(main: &str, profile: Profile) -> Arc<Program> {
    let compiler = match profile {
        Profile::Desktop => jack_compiler::Profile::Desktop,
        Profile::Web => jack_compiler::Profile::Web,
    };
    let classes = jack_compiler::compile_sources(&[("Main.jack", main)], compiler)
        .unwrap_or_else(|e| panic!("compiles: {e}"));
    let files: Vec<(String, String)> = classes
        .into_iter()
        .map(jack_compiler::VmClass::into_file)
        .collect();
    Program::from_sources(&files).expect("loads")
}
