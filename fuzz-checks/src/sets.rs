//! Vector-set and scene files: parsed, validated and, when small, answered
//! by the reference implementations (a legal vector must never panic one).

use common::F316;
use reference::{RefImpl, Reference, Scene, Settings};
use vectors::{Vector, VectorSet};

/// Vectors of one fuzzed set that are evaluated.
const EVALUATED: usize = 8;

/// Any text is a valid set or an error naming the file; a valid set
/// round-trips through its file text, and the reference implementations
/// answer its first vectors without panicking.
pub fn vector_set(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let set = match VectorSet::parse("fuzz.json", text) {
        Ok(set) => set,
        Err(e) => {
            assert!(e.to_string().starts_with("fuzz.json"), "{e}");
            return;
        }
    };
    let again = VectorSet::parse("again.json", &set.to_json()).expect("a saved set loads");
    assert_eq!(again, set);
    let impls = RefImpl::ALL.map(Reference::seed);
    for v in set.vectors.iter().take(EVALUATED) {
        match v {
            Vector::Op(o) => {
                reference::op(o.op, &o.args(), Default::default()).expect("validated arity");
            }
            Vector::Sdf(s) => impls.iter().for_each(|r| {
                r.sdf(s.p);
            }),
            Vector::Pixel(p) => impls.iter().for_each(|r| {
                r.pixel(usize::from(p.x), usize::from(p.y));
            }),
            Vector::Image(_) => {}
        }
    }
}

/// Any text is a scene or an error; a scene prepares for every reference
/// implementation or fails with an error, and answers an SDF query.
pub fn scene(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(scene) = serde_json::from_str::<Scene>(text) else {
        return;
    };
    for which in RefImpl::ALL {
        if let Ok(r) = Reference::new(which, &scene, Settings::default()) {
            r.sdf([F316::ZERO; 3]);
        }
    }
}
