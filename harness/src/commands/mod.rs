//! One module per subcommand.

pub mod bench;
pub mod cast;
pub mod check;
pub mod diff;
pub mod jack;
pub mod localize;
pub mod nightly;
pub mod render;
pub mod selftest;
pub mod vectors;
