//! jack-compiler
