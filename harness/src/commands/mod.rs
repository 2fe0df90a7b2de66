//! One module per subcommand.

pub mod jack;
pub mod render;
