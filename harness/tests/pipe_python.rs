//! The Python adapter of `examples/pipe-python` (the one docs/protocol.md
//! shows) agrees with ref-f316 bit for bit on every committed ops set, and
//! so does its port without halve, double and quarter, on the operations
//! it has.

use harness::cast::Cast;
use harness::implementation::Implementation;
use harness::pipe::{Pipe, PipeConfig};
use harness::runner::{diff_set, RunOptions};
use vectors::Level;

/// An adapter of `examples/pipe-python`, started under `label`. Its port
/// answers out of domain where the reference does: compared there too.
fn python_adapter(label: &str, script: &str) -> Pipe {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/pipe-python");
    let mut config = PipeConfig::new(label, "python3", &[script]);
    config.dir = Some(dir.into());
    config.checks_domain = true;
    Pipe::open(&config).unwrap()
}

#[test]
fn the_python_float316_adapter_agrees_with_ref_f316_on_every_ops_set() {
    let pipe = python_adapter("float316.py", "adapter.py");
    assert!(pipe.supports(Level::Ops) && !pipe.supports(Level::Sdf));
    let reference = Cast::builtin().open("ref-f316").unwrap();
    let mut compared = 0;
    for name in vectors::named::SETS.iter().map(|s| s.name) {
        let set = vectors::load_named(name).unwrap();
        if set.level != Level::Ops {
            continue;
        }
        let report = diff_set(&[reference.as_ref(), &pipe], &set, RunOptions::default());
        assert_eq!(
            report.failures().count(),
            0,
            "{}",
            harness::text::level_report(&report)
        );
        assert!(
            !report.diverged(),
            "{}",
            harness::text::level_report(&report)
        );
        compared += report.comparisons[0].vectors;
    }
    assert!(compared > 1000, "{compared} vectors");
}

/// A port that scales inline lists the operations it has in its
/// handshake: it is sent no other, its answers to those it has agree, the
/// others are counted as unsupported (not a divergence, not a failure),
/// and a pixel is still localized through it, its trace replayed.
#[test]
fn a_port_without_halve_double_and_quarter_is_compared_on_what_it_has() {
    let pipe = python_adapter("inline", "inline_scaling_adapter.py");
    let reference = Cast::builtin().open("ref-f316").unwrap();
    let set = vectors::load_named("ops-small").unwrap();
    let report = diff_set(&[reference.as_ref(), &pipe], &set, RunOptions::default());
    let text = harness::text::level_report(&report);
    assert_eq!(report.failures().count(), 0, "{text}");
    assert!(!report.diverged(), "{text}");
    let c = &report.comparisons[0];
    let scaling: Vec<&str> = c.unsupported.keys().map(String::as_str).collect();
    assert_eq!(scaling, ["double", "halve", "quarter"], "{text}");
    let left_out: usize = c.unsupported.values().sum();
    assert_eq!(c.vectors + left_out, set.vectors.len(), "{text}");
    assert!(
        text.contains("unsupported by one side, not compared: double "),
        "{text}"
    );
    // Localizing a pixel replays ref-f316's trace through the port: the
    // operations it lacks are taken as traced, the others are checked.
    let input = vectors::Vector::Op(vectors::OpVector {
        category: "t".into(),
        op: common::Op::Halve,
        a: common::F316::ONE,
        b: None,
    });
    let l = harness::localize::localize(reference.as_ref(), &pipe, reference.as_ref(), &input);
    assert!(l
        .unwrap_err()
        .to_string()
        .contains("inline has no such operation"));
    let pixel = vectors::Vector::Pixel(vectors::PixelVector {
        category: "t".into(),
        x: 312,
        y: 87,
    });
    let trace = reference.trace(&pixel).unwrap();
    let replayed = harness::localize::replay(&pipe, &trace).unwrap();
    assert_eq!(replayed, trace);
}
