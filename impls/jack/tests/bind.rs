//! The raymarcher through its bindings (`raymarcher/bindings.toml`) agrees
//! with its own entry points, answer for answer and trace for trace.

use common::{Op, F316};
use jack::{Bindings, BoundProgram, Budgets, JackProgram, Profile, Raymarcher};
use std::sync::OnceLock;

fn bound() -> &'static BoundProgram {
    static B: OnceLock<BoundProgram> = OnceLock::new();
    B.get_or_init(|| {
        let program = JackProgram::from_jack(&jack::sources::SOURCES, Profile::Desktop).unwrap();
        let bindings: Bindings = toml::from_str(jack::sources::BINDINGS).unwrap();
        BoundProgram::open(&program, &bindings, Budgets::default()).unwrap()
    })
}

fn entry() -> &'static Raymarcher {
    static R: OnceLock<Raymarcher> = OnceLock::new();
    R.get_or_init(|| Raymarcher::new(Profile::Desktop, Budgets::default()).unwrap())
}

#[test]
fn ops_sdf_and_pixels_agree_with_the_entry_points() {
    let vals = [
        F316::new(0, 129, 10240),
        F316::new(1, 127, 12288),
        F316::new(0, 140, 9000),
        F316::ZERO,
        F316::new(1, 120, 16383),
    ];
    for op in Op::ALL {
        for &a in &vals {
            for &b in &vals {
                let args: Vec<F316> = [a, b][..op.arity()].to_vec();
                let x = bound().op(op, &args).unwrap();
                let y = entry().op(op, &args).unwrap();
                assert_eq!(x.outcome, y.outcome, "{op}{args:?}");
                assert_eq!(
                    bound().trace_op(op, &args).unwrap(),
                    entry().trace_op(op, &args).unwrap()
                );
            }
        }
    }
    let p = [F316::new(0, 127, 8192), F316::ZERO, F316::new(0, 128, 8192)];
    assert_eq!(bound().sdf(p).unwrap().outcome, entry().sdf(p).unwrap().outcome);
    let tb: Vec<_> = bound().trace_sdf(p).unwrap();
    let te: Vec<_> = entry().trace_sdf(p).unwrap();
    assert_eq!(tb.len(), te.len());
    assert!(tb.iter().zip(&te).all(|(a, b)| a.same_computation(b)));
    for (x, y) in [(330, 150), (100, 200), (0, 0), (511, 255)] {
        assert_eq!(
            bound().pixel(x, y).unwrap().outcome,
            entry().pixel(x, y).unwrap().outcome
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

#[test]
fn the_port_agrees_with_the_raymarcher() {
    let vals = [
        F316::new(0, 129, 10240),
        F316::new(1, 127, 12288),
        F316::new(0, 140, 9000),
        F316::ZERO,
        F316::new(1, 120, 16383),
    ];
    for op in Op::ALL {
        for &a in &vals {
            for &b in &vals {
                let args: Vec<F316> = [a, b][..op.arity()].to_vec();
                assert_eq!(
                    port().op(op, &args).unwrap().outcome,
                    entry().op(op, &args).unwrap().outcome,
                    "{op}{args:?}"
                );
            }
        }
    }
    let p = [F316::new(0, 127, 8192), F316::ZERO, F316::new(0, 128, 8192)];
    assert_eq!(port().sdf(p).unwrap().outcome, entry().sdf(p).unwrap().outcome);
    for (x, y) in [(330, 150), (100, 200), (0, 0), (511, 255)] {
        assert_eq!(
            port().pixel(x, y).unwrap().outcome,
            entry().pixel(x, y).unwrap().outcome,
            "pixel ({x},{y})"
        );
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
        let divs: Vec<&common::TraceRecord> =
            t.iter().filter(|r| r.op == common::Op::Div).take(2).collect();
        (num(divs[0]), num(divs[1]).negated())
    };
    for x in 0..512 {
        assert_eq!(jack::normalized_coords(x, 7).0, coords(x, 7).0, "x = {x}");
    }
    for y in 0..256 {
        assert_eq!(jack::normalized_coords(3, y).1, coords(3, y).1, "y = {y}");
    }
}
