//! Inputs found by hostile runs (issue 20) that once panicked.

use common::{Outcome, F316};
use reference::{RefImpl, Reference};

/// A legal SDF point whose x (exponent 255) exceeds f32's range: the float
/// implementations answer out of domain (as ref-f316 does: its squares
/// leave Float316's range), where they panicked.
#[test]
fn an_sdf_point_beyond_the_float_range_is_out_of_domain() {
    let p = [F316::new(0, 255, 8192), F316::ZERO, F316::ZERO];
    assert_eq!(Reference::seed(RefImpl::F32).sdf(p), Outcome::OutOfDomain);
    assert_eq!(Reference::seed(RefImpl::F316).sdf(p), Outcome::OutOfDomain);
    // f64 holds 2^(255-140) but not 2^(1151-140+13).
    assert!(matches!(
        Reference::seed(RefImpl::F64).sdf(p),
        Outcome::Value(_)
    ));
    let huge = [F316::new(1, 1151, 16383), F316::ZERO, F316::ZERO];
    assert_eq!(
        Reference::seed(RefImpl::F64).sdf(huge),
        Outcome::OutOfDomain
    );
    assert_eq!(
        Reference::seed(RefImpl::F32).sdf(huge),
        Outcome::OutOfDomain
    );
}
