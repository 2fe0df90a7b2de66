//! The command line's integration tests, one module per file, in a single
//! test binary: one link of the binary's dependencies instead of one per
//! file, and every file's tests run side by side.

mod binary;
#[path = "../../harness/tests/support/mod.rs"]
mod support;

mod bindings;
mod cast;
mod check;
mod cli;
mod containment;
mod gates;
mod gpu;
mod gpu_check;
mod hardening;
mod jack_scenes;
mod nightly_scenes;
mod nightly_testfloat;
mod runtime_dir;
mod scene_domain;
mod tune;
