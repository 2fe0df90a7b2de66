//! Test vectors for the differential harness: the versioned set format
//! ([`VectorSet`], one [`Vector`] per input, each with its category), the
//! deterministic generators ([`gen`]: proptest strategies drawn with a fixed
//! seed, plus catalogues of hard cases) and the catalogue of named sets
//! committed in `vectors/sets/` ([`named`]).

pub mod gen;
pub mod named;
pub mod set;
pub mod shard;
mod validate;

pub use set::{
    load_named, sets_dir, ImageVector, Level, OpVector, PixelVector, SdfVector, SetError, Vector,
    VectorSet, FORMAT_VERSION,
};
pub use shard::Shard;
