//! One module per subcommand.

pub mod bench;
pub mod cast;
pub mod check;
pub mod diff;
pub mod explain;
pub mod jack;
pub mod localize;
pub mod merge;
pub mod nightly;
pub mod render;
pub mod render_scene;
pub mod selftest;
pub mod sweep;
pub mod tune;
pub mod vectors;
