//! The raymarcher through its bindings (`raymarcher/bindings.toml`) agrees
//! with its own entry points, answer for answer and trace for trace.

use common::{Op, F316};
use jack::{Bindings, BoundPixel, BoundProgram, Budgets, JackProgram, Profile, Raymarcher};
use std::sync::OnceLock;

fn bound() -> &'static BoundProgram {
    static B: OnceLock<BoundProgram> = OnceLock::new();
    B.get_or_init(|| jack::sources::bound(Profile::Desktop, Budgets::default()).unwrap())
}

fn entry() -> &'static Raymarcher {
    static R: OnceLock<Raymarcher> = OnceLock::new();
    R.get_or_init(|| Raymarcher::new(Profile::Desktop, Budgets::default()).unwrap())
}

/// Every operation on every pair (or single operand) of a few values of
/// both signs, magnitudes and zero.
fn op_cases() -> Vec<(Op, Vec<F316>)> {
    let vals = [
        F316::new(0, 129, 10240),
        F316::new(1, 127, 12288),
        F316::new(0, 140, 9000),
        F316::ZERO,
        F316::new(1, 120, 16383),
    ];
    let mut cases = Vec::new();
    for op in Op::ALL {
        for &a in &vals {
            for &b in &vals {
                cases.push((op, [a, b][..op.arity()].to_vec()));
            }
        }
    }
    cases
}

#[test]
fn ops_sdf_and_pixels_agree_with_the_entry_points() {
    for (op, args) in op_cases() {
        let x = bound().op(op, &args).unwrap();
        let y = entry().op(op, &args).unwrap();
        assert_eq!(x.outcome, y.outcome, "{op}{args:?}");
        assert_eq!(
            bound().trace_op(op, &args).unwrap(),
            entry().trace_op(op, &args).unwrap()
        );
    }
    let p = [F316::new(0, 127, 8192), F316::ZERO, F316::new(0, 128, 8192)];
    assert_eq!(
        bound().sdf(p).unwrap().outcome,
        entry().sdf(p).unwrap().outcome
    );
    let tb: Vec<_> = bound().trace_sdf(p).unwrap();
    let te: Vec<_> = entry().trace_sdf(p).unwrap();
    assert_eq!(tb.len(), te.len());
    assert!(tb.iter().zip(&te).all(|(a, b)| a.same_computation(b)));
    for (x, y) in [(330, 150), (100, 200), (0, 0), (511, 255)] {
        assert_eq!(
            bound().pixel(x, y).unwrap().outcome,
            entry().pixel(x, y).unwrap().outcome.map(BoundPixel::from)
        );
        let tb = bound().trace_pixel(x, y).unwrap();
        let te = entry().trace_pixel(x, y).unwrap();
        assert_eq!(tb.len(), te.len());
        assert!(tb.iter().zip(&te).all(|(a, b)| a.same_computation(b)));
    }
}

fn port() -> &'static BoundProgram {
    static P: OnceLock<BoundProgram> = OnceLock::new();
    P.get_or_init(|| {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/jack-port");
        let program = JackProgram::from_dir(std::path::Path::new(dir), Profile::Desktop).unwrap();
        let text = std::fs::read_to_string(format!("{dir}/bindings.toml")).unwrap();
        let bindings: Bindings = toml::from_str(&text).unwrap();
        BoundProgram::open(&program, &bindings, Budgets::default()).unwrap()
    })
}

/// A shade clamped to [0, 1] as ref-f316 clamps it.
fn clamped(v: F316) -> F316 {
    match reference::op(Op::Gt, &[v, F316::ONE], reference::Arith::default()).unwrap() {
        common::Outcome::Value(common::OpValue::Bool(true)) => F316::ONE,
        _ if v.s == 1 => F316::ZERO,
        _ => v,
    }
}

#[test]
fn the_port_agrees_with_the_raymarcher() {
    for (op, args) in op_cases() {
        assert_eq!(
            port().op(op, &args).unwrap().outcome,
            entry().op(op, &args).unwrap().outcome,
            "{op}{args:?}"
        );
    }
    let p = [F316::new(0, 127, 8192), F316::ZERO, F316::new(0, 128, 8192)];
    assert_eq!(
        port().sdf(p).unwrap().outcome,
        entry().sdf(p).unwrap().outcome
    );
    // The port's pixel function gives the shade alone, before its render
    // loop clamps it.
    for (x, y) in [(330, 150), (100, 200), (0, 0), (511, 255)] {
        let got = port().pixel(x, y).unwrap().outcome.value().unwrap();
        let want = entry().pixel(x, y).unwrap().outcome.value().unwrap();
        assert_eq!((got.clamped, got.white), (false, None), "pixel ({x},{y})");
        assert_eq!(clamped(got.shade), want.value, "pixel ({x},{y})");
    }
}

#[test]
fn normalized_coordinates_are_the_references() {
    use common::OpValue;
    let reference = reference::Reference::seed(reference::RefImpl::F316);
    let coords = |x, y| {
        let t = reference.trace_pixel(x, y).unwrap().records;
        let num = |r: &common::TraceRecord| match r.result {
            common::Outcome::Value(OpValue::Num(v)) => v,
            other => panic!("{other:?}"),
        };
        let divs: Vec<&common::TraceRecord> = t
            .iter()
            .filter(|r| r.op == common::Op::Div)
            .take(2)
            .collect();
        (num(divs[0]), num(divs[1]).negated())
    };
    for x in 0..512 {
        assert_eq!(jack::normalized_coords(x, 7).0, coords(x, 7).0, "x = {x}");
    }
    for y in 0..256 {
        assert_eq!(jack::normalized_coords(3, y).1, coords(3, y).1, "y = {y}");
    }
}

/// Every record's result is what ref-f316 gives on the same operands, but
/// the port's sub called from its invSqrt with the result aliased to an
/// operand (examples/jack-port/Num.jack), whose sign comes out flipped.
fn replays_to_the_reference(trace: &[common::TraceRecord]) {
    assert!(!trace.is_empty());
    for r in trace {
        let want = reference::op(r.op, &r.args, reference::Arith::default()).unwrap();
        let aliased = r.op == Op::Sub && r.path.iter().any(|f| f == "Num.invSqrt");
        let want = match want {
            common::Outcome::Value(common::OpValue::Num(v)) if aliased => {
                common::Outcome::Value(common::OpValue::Num(v.negated()))
            }
            want => want,
        };
        assert_eq!(r.result, want, "{r}");
    }
}

#[test]
fn whole_program_mode_captures_the_first_rows_and_their_traces() {
    for (b, name) in [(bound(), "raymarcher"), (port(), "port")] {
        let run = b.run_whole(&[(5, 1)], 400_000_000, &mut |_| {}).unwrap();
        assert_eq!(
            run.outcome,
            common::Outcome::Hang,
            "{name}: the budget ends the run"
        );
        let done: Vec<usize> = (0..run.shades.len())
            .filter(|&i| run.captured[i].is_some() || run.shades[i].is_some())
            .collect();
        assert!(done.len() > 600, "{name}: {} pixels", done.len());
        // The last pixel may not be drawn yet when the budget ends.
        for &i in done[..done.len() - 1].iter().step_by(37) {
            let (x, y) = (i % 512, i / 512);
            let want = entry().pixel(x, y).unwrap().outcome.value().unwrap();
            // The port draws with Screen.drawPixel inline: its colour is
            // on the screen.
            let white = run.captured[i].unwrap_or(run.screen[i]);
            assert_eq!(white, want.white, "{name} ({x},{y})");
            if let Some(shade) = run.shades[i] {
                assert_eq!(clamped(shade), want.value, "{name} ({x},{y})");
            }
        }
        replays_to_the_reference(&run.traces[&(5, 1)]);
    }
    // The raymarcher's per-pixel function is the whole pixel: its trace is
    // the entry point's.
    let run = bound()
        .run_whole(&[(5, 1)], 400_000_000, &mut |_| {})
        .unwrap();
    let whole = &run.traces[&(5, 1)];
    let query = entry().trace_pixel(5, 1).unwrap();
    assert_eq!(whole.len(), query.len());
    assert!(whole.iter().zip(&query).all(|(a, b)| a.same_computation(b)));
    assert!(whole[0]
        .path
        .join(" > ")
        .contains("Main.main > Image.render > Image.shadeAt"));
}

/// The whole program (`cargo test --release -p jack -- --ignored`).
/// Ignored under `cargo test`: two whole-program runs (the bound program
/// and the port), each with a traced pixel, after the whole image.
#[test]
#[ignore = "two whole Main.main runs and the image: scripts/nightly.sh"]
fn whole_program_mode_captures_the_render() {
    let render = entry().render().unwrap();
    let want: Vec<bool> = render
        .pixels
        .iter()
        .map(|p| p.outcome.value().unwrap().white)
        .collect();
    for b in [bound(), port()] {
        let run = b
            .run_whole(&[(330, 150)], 40_000_000_000, &mut |_| {})
            .unwrap();
        assert_eq!(run.outcome, common::Outcome::Value(()));
        assert_eq!(run.image(), want);
        assert_eq!(run.screen, want);
        replays_to_the_reference(&run.traces[&(330, 150)]);
    }
}
