//! jack
