//! A user's project whose ports the harness verifies from `cargo test`:
//! `harness.toml` declares them (here, the Python Float316 of
//! `examples/pipe-python` and a copy with a rounding bug in `mul`), and
//! `tests/ports.rs` compares them with ref-f316.
