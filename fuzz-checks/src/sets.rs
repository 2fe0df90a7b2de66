//! Vector-set and scene files: parsed, validated and, when small, answered
//! by the reference implementations (a legal vector must never panic one).

use common::F316;
use reference::{Described, RefImpl, Reference, Scene, Settings};
use scene::Formulation;
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

/// The most statements a checked description's lowered program may hold.
/// The checks bound it (at most [`scene::check::MAX_USES`] node uses, each
/// of at most [`scene::check::MAX_TRANSFORMS`] transforms and
/// [`scene::check::MAX_CHILDREN`] children, a bounded number of
/// materials); the shipped scenes lower to a few hundred statements. A
/// description past it grows the program faster than its checks say.
pub const MAX_STATEMENTS: usize = 200_000;

/// Any text is a scene or an error. A scene description (a `version` at
/// the top, docs/scenes.md) is parsed and checked by the scene crate: an
/// error names a field or the JSON's line; a checked description lowers to
/// a valid program of at most [`MAX_STATEMENTS`] statements for both
/// formulations, prepares for every reference implementation or fails
/// with an error, and answers an SDF query. Any other object is the seed
/// scene's parameter file, which prepares or fails the same way.
pub fn scene(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if scene::is_description(text) {
        described(text);
        return;
    }
    let Ok(scene) = serde_json::from_str::<Scene>(text) else {
        return;
    };
    for which in RefImpl::ALL {
        if let Ok(r) = Reference::new(which, &scene, Settings::default()) {
            r.sdf([F316::ZERO; 3]);
        }
    }
}

/// The property of [`scene`] for a scene description.
fn described(text: &str) {
    let checked = match scene::parse(text) {
        Ok(checked) => checked,
        Err(e) => {
            let message = e.to_string();
            let (place, what) = message.split_once(": ").unwrap_or(("", ""));
            assert!(
                !place.trim().is_empty() && !what.trim().is_empty(),
                "an error that names no field or says nothing: {message}"
            );
            return;
        }
    };
    for form in [Formulation::Float316, Formulation::Ieee] {
        let program = scene::lower(&checked, form);
        assert_eq!(program.validate(), Ok(()), "{form:?}");
        let statements = program.statements().len();
        assert!(
            statements <= MAX_STATEMENTS,
            "{form:?}: {statements} statements, more than {MAX_STATEMENTS}"
        );
    }
    for which in RefImpl::ALL {
        match Described::new(which, &checked, Settings::default()) {
            Ok(r) => {
                r.sdf([F316::ZERO; 3]);
            }
            Err(e) => assert!(!e.to_string().trim().is_empty(), "{which:?}"),
        }
    }
}
