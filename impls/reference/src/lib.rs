//! The Rust reference of the seed scene: Float316 arithmetic bit-exact with
//! the Jack program (`ref-f316`), and the float formulation in f64 and f32
//! (`ref-f64`, `ref-f32`), all from one scene pipeline generic over the
//! number type. Also: run-time precision variants and injected faults, and
//! an op tracer for Float316.
//!
//! Entry points: [`Reference`] (an implementation with a scene: `sdf`,
//! `pixel`, `render`, `trace_pixel`, `trace_sdf`), [`op`] and [`trace_op`]
//! (one Float316 operation), [`Scene`] (the parameters, serde), [`Settings`]
//! and [`Variant`] (variants and faults by name); [`Described`]: any scene
//! description, lowered to the scene crate's intermediate form and
//! interpreted on the same engines.

mod api;
mod consts;
mod counter;
mod described;
mod engine;
mod float;
mod float316;
mod formulation;
mod interp;
mod pipeline;
mod recorder;
mod scene;
mod settings;
mod shadow;
mod tracer;
mod vec3;

pub use api::{
    op, trace_op, PixelValue, RefImpl, Reference, RenderedImage, RequestError, Scalar, SdfValue,
    Trace, UnknownImpl,
};
pub use counter::OpCounts;
pub use described::{Described, DescribedError, SceneImage, ScenePixel};
pub use engine::{Decision, Engine, Trap, R};
pub use formulation::{Formulated, Formulation};
pub use recorder::Decided;
pub use scene::{Camera, Floor, March, Scene, SceneError, Shading, Sphere, Torus};
pub use settings::{Arith, Settings, UnknownVariant, Variant, VariantKind};
pub use shadow::{
    blame, candidate_sites, Blame, DecisionRecord, Follow, OutputValue, Sh, ShadowEngine, ShadowOp,
    ShadowOptions, ShadowOutput, ShadowRun, SiteKey,
};
