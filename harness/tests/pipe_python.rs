//! The Python adapter of `examples/pipe-python` (the one docs/protocol.md
//! shows) agrees with ref-f316 bit for bit on every committed ops set.

use harness::cast::Cast;
use harness::implementation::Implementation;
use harness::pipe::{Pipe, PipeConfig};
use harness::runner::{diff_set, RunOptions};
use vectors::Level;

#[test]
fn the_python_float316_adapter_agrees_with_ref_f316_on_every_ops_set() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/pipe-python");
    let mut config = PipeConfig::new("float316.py", "python3", &["adapter.py"]);
    config.dir = Some(dir.into());
    let pipe = Pipe::open(&config).unwrap();
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
