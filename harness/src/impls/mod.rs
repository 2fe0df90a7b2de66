//! One adapter module per implementation, and [`open`] to get any of the
//! six by name.

pub mod gpu;
pub mod jack;
pub mod reference;

use crate::contain::Contained;
use crate::implementation::{ImplError, ImplName, Implementation, UnknownImpl};

/// The clean implementation `name`, ready to evaluate. Fails with
/// [`ImplError::Unavailable`] (saying why) when it cannot run here.
pub fn open(name: ImplName) -> Result<Box<dyn Implementation>, ImplError> {
    Ok(Contained::boxed(match name {
        ImplName::RefF64 | ImplName::RefF32 | ImplName::RefF316 => {
            Box::new(reference::RefAdapter::new(name)?)
        }
        ImplName::GpuF32 | ImplName::GpuF316 => Box::new(gpu::GpuAdapter::new(name)?),
        ImplName::Jack => Box::new(jack::JackAdapter::new(jack::Profile::Desktop)?),
    }))
}

/// An implementation by its label: a name, optionally with `+FAULT`:
/// `ref-f316+sqrt-floor-div` (any reference variant on ref-f316, ref-f64 or
/// ref-f32), `jack+web-divide` (the web IDE's flooring `Math.divide`),
/// `ref-f64+f32-oracle` (ref-f32 posing as the f64 oracle).
pub fn open_label(label: &str) -> Result<Box<dyn Implementation>, OpenError> {
    let (name, fault) = match label.split_once('+') {
        Some((n, f)) => (n, Some(f)),
        None => (label, None),
    };
    let name: ImplName = name.parse()?;
    Ok(match (name, fault) {
        (_, None) => return Ok(open(name)?),
        (ImplName::RefF64, Some("f32-oracle")) => {
            Box::new(reference::RefAdapter::f32_posing_as_f64()?)
        }
        (ImplName::RefF64 | ImplName::RefF32 | ImplName::RefF316, Some(v)) => {
            let variant = v
                .parse()
                .map_err(|e: ::reference::UnknownVariant| OpenError::Fault(e.to_string()))?;
            Box::new(reference::RefAdapter::with_variant(name, variant)?)
        }
        (ImplName::Jack, Some("web-divide")) => jack::open_web_profile()?,
        (_, Some(f)) => return Err(OpenError::Fault(format!("{name} has no fault `{f}`"))),
    })
    .map(Contained::boxed)
}

/// Why an implementation label could not be opened.
#[derive(Debug, thiserror::Error)]
pub enum OpenError {
    #[error(transparent)]
    Name(#[from] UnknownImpl),
    #[error("{0}")]
    Fault(String),
    #[error(transparent)]
    Impl(#[from] ImplError),
}
