//! Op traces of a pixel and an SDF query, and the effect of each variant.

use common::{Op, OpValue, Outcome, F316};
use reference::{op, trace_op, RefImpl, Reference, RequestError, Settings, Variant};

#[test]
fn pixel_trace_agrees_with_the_untraced_pixel_and_names_its_path() {
    let r = Reference::seed(RefImpl::F316);
    let tr = r.trace_pixel(312, 87).unwrap();
    assert_eq!(tr.outcome, r.pixel(312, 87));
    assert!(tr.records.iter().all(|rec| rec.path[0] == "pixel(312,87)"));
    assert!(tr
        .records
        .iter()
        .all(|rec| rec.result.kind() == common::OutcomeKind::Value));
    let torus_sqrt_div = tr.records.iter().find(|rec| {
        rec.op == Op::Div
            && rec.path.len() == 5
            && rec.path[1].starts_with("march step ")
            && rec.path[3] == "torus"
    });
    let rec = torus_sqrt_div.expect("a div inside the torus's sqrt");
    assert_eq!(rec.path[2], "scene");
    assert_eq!(rec.path[4], "sqrt");
    // The last operation decides the dithered bit.
    let last = tr.records.last().unwrap();
    assert_eq!(last.op, Op::Gt);
    let white = tr.outcome.value().unwrap().white;
    assert_eq!(last.result, Outcome::Value(OpValue::Bool(white)));
}

#[test]
fn sdf_trace_starts_with_the_floor() {
    let r = Reference::seed(RefImpl::F316);
    let p = [
        F316::new(0, 127, 8192),
        F316::new(1, 126, 8192),
        F316::new(0, 128, 12288),
    ];
    let tr = r.trace_sdf(p).unwrap();
    assert_eq!(tr.outcome, r.sdf(p));
    let first = &tr.records[0];
    assert_eq!(
        (first.op, first.args.as_slice()),
        (Op::Add, &[p[1], F316::ONE][..])
    );
    assert_eq!(first.path[1..], ["scene".to_string(), "floor".to_string()]);
}

#[test]
fn float_implementations_do_not_trace() {
    let r = Reference::seed(RefImpl::F64);
    assert!(matches!(
        r.trace_pixel(0, 0),
        Err(RequestError::NotTraceable(RefImpl::F64))
    ));
}

#[test]
fn float_sdf_takes_the_value_of_the_triple() {
    let p = [
        F316::new(0, 127, 8192),
        F316::new(1, 126, 8192),
        F316::new(0, 128, 12288),
    ];
    let f316 = Reference::seed(RefImpl::F316).sdf(p).value().unwrap();
    let f64v = Reference::seed(RefImpl::F64).sdf(p).value().unwrap();
    // The floor at y = -0.5 is 0.5 away, nearer than the sphere and torus.
    assert_eq!(f64v.sd.value, 0.5);
    assert_eq!(f316.sd.triple, Some(F316::new(0, 126, 8192)));
    assert_eq!(f64v.sd.triple, None);
}

fn f(x: f64) -> F316 {
    F316::from_f64_truncating(x).unwrap()
}

/// Each arithmetic variant changes a specific operation.
#[test]
fn each_arithmetic_variant_changes_an_operation() {
    let cases: [(Variant, Op, Vec<F316>); 6] = [
        (
            Variant::MulLowProduct,
            Op::Mul,
            vec![F316::new(0, 127, 16383); 2],
        ),
        (
            Variant::MulKeepLow,
            Op::Mul,
            vec![F316::new(0, 127, 16383); 2],
        ),
        (Variant::Newton1, Op::Sqrt, vec![f(2.0)]),
        (Variant::Newton3, Op::InvSqrt, vec![f(2.0)]),
        (Variant::SqrtFloorDiv, Op::Sqrt, vec![f(0.6)]),
        (Variant::AddAlignOffByOne, Op::Add, vec![f(1.0), f(0.75)]),
    ];
    for (v, o, args) in cases {
        let spec = op(o, &args, Settings::default().arith).unwrap();
        let varied = op(o, &args, v.apply(Settings::default()).arith).unwrap();
        assert_ne!(spec, varied, "{v}");
        // The trace records the varied operation itself, with its operands
        // and the varied result.
        let trace = trace_op(o, &args, v.apply(Settings::default()).arith).unwrap();
        let first = &trace.records[0];
        assert_eq!((first.op, &first.args), (o, &args), "{v}");
        assert_eq!(first.result, varied, "{v}");
        assert_eq!(trace.outcome, varied, "{v}");
    }
}

/// One operation under the spec's arithmetic, or under a variant.
fn op_under(variant: Option<Variant>, o: Op, args: &[F316]) -> Outcome<OpValue> {
    let s = variant.map_or(Settings::default(), |v| v.apply(Settings::default()));
    op(o, args, s.arith).unwrap()
}

/// A positive Float316 number as an operation's outcome.
fn positive(e: i16, m: i16) -> Outcome<OpValue> {
    Outcome::Value(OpValue::Num(F316::new(0, e, m)))
}

/// `variant` of `o` gives the spec's result on each of `agreed` (operands
/// and the positive result's exponent and mantissa), and on `apart`'s
/// operands the spec gives the first result and the variant the second.
fn parts_only_at(
    variant: Variant,
    o: Op,
    agreed: &[([F316; 2], (i16, i16))],
    apart: ([F316; 2], (i16, i16), (i16, i16)),
) {
    for v in [None, Some(variant)] {
        for (args, (e, m)) in agreed {
            assert_eq!(op_under(v, o, args), positive(*e, *m), "{variant} {args:?}");
        }
    }
    let (args, (e, m), (fe, fm)) = apart;
    assert_eq!(op_under(None, o, &args), positive(e, m));
    assert_eq!(op_under(Some(variant), o, &args), positive(fe, fm));
}

/// `add-drop-far` drops the smaller operand only 14 or more exponents
/// below: at a gap of 13 it adds as the spec does (a normalised mantissa
/// still contributes its top bit), at 14 an unnormalised one that would
/// still count (16384 >> 14 = 1) is dropped.
#[test]
fn add_drop_far_drops_only_operands_14_exponents_below() {
    let gap_13 = F316::new(0, 114, 8192);
    let gap_14 = F316::new(0, 113, 16384);
    parts_only_at(
        Variant::AddDropFar,
        Op::Add,
        &[([F316::ONE, gap_13], (127, 8193))],
        ([F316::ONE, gap_14], (127, 8193), (127, 8192)),
    );
}

/// `add-carry-bit` takes add's carry from bit 14 of the sum: as the spec's
/// `m > 16383` for sums of normalised mantissas, with and without a carry,
/// and apart from it where a sum of unnormalised ones wraps (30000 + 30000
/// is the word -5536, whose bit 14 is set).
#[test]
fn add_carry_bit_tests_bit_14_of_the_sum() {
    let gap_13 = F316::new(0, 114, 8192);
    let wide = F316::new(0, 127, 30000);
    parts_only_at(
        Variant::AddCarryBit,
        Op::Add,
        &[
            ([F316::ONE, F316::ONE], (128, 8192)),
            ([F316::ONE, gap_13], (127, 8193)),
        ],
        ([wide, wide], (127, -5536), (128, -2768)),
    );
}

/// `div-normalise-once` doubles a quotient below 8192 once instead of
/// normalising it: the same as the spec for normalised operands (their
/// quotient is at least 4096) and for a quotient of exactly 8192, not for
/// an unnormalised divisor (1 / (0,127,32000) has the quotient 2097).
#[test]
fn div_normalise_once_doubles_only_quotients_below_8192() {
    let one_and_a_half = F316::new(0, 127, 12288);
    let wide = F316::new(0, 127, 32000);
    parts_only_at(
        Variant::DivNormaliseOnce,
        Op::Div,
        &[
            ([F316::ONE, F316::ONE], (127, 8192)),
            ([F316::ONE, one_and_a_half], (126, 10922)),
        ],
        ([F316::ONE, wide], (125, 8388), (126, 4194)),
    );
}

/// Newton steps change the number of traced operations.
#[test]
fn newton_steps_shape_the_trace() {
    let n = |v: Option<Variant>| {
        let s = v.map_or(Settings::default(), |v| v.apply(Settings::default()));
        trace_op(Op::Sqrt, &[f(2.0)], s.arith)
            .unwrap()
            .records
            .len()
    };
    assert_eq!(n(Some(Variant::Newton1)), 4);
    assert_eq!(n(None), 7);
    assert_eq!(n(Some(Variant::Newton3)), 10);
}

#[test]
fn pixel_coordinates_open_the_pixel_trace_and_match_in_every_number_type() {
    let f316 = Reference::seed(RefImpl::F316);
    for (x, y) in [(0, 0), (312, 87), (511, 255), (256, 128)] {
        let coords = f316.trace_pixel_coords(x, y).unwrap();
        let pixel = f316.trace_pixel(x, y).unwrap();
        assert!(!coords.records.is_empty());
        assert_eq!(coords.records[..], pixel.records[..coords.records.len()]);
        assert_eq!(coords.outcome, f316.pixel_coords(x, y));
    }
    // u grows to the right, v upwards, in f64 as in Float316.
    let f64s = Reference::seed(RefImpl::F64);
    let [u0, v0] = f64s.pixel_coords(0, 0).value().unwrap();
    let [u1, v1] = f64s.pixel_coords(511, 255).value().unwrap();
    assert!(u0.value < 0.0 && u1.value > 0.0 && v0.value > 0.0 && v1.value < 0.0);
    assert!(u0.triple.is_none());
    let [t, _] = f316.pixel_coords(0, 0).value().unwrap();
    assert!((t.value - u0.value).abs() < 1e-3, "{t:?} {u0:?}");
}

#[test]
fn a_pixel_from_its_coordinates_is_the_pixel_and_its_trace_the_rest_of_the_pixel_trace() {
    let r = Reference::seed(RefImpl::F316);
    for (x, y) in [(312, 87), (100, 200), (0, 255)] {
        let [u, v] = r.pixel_coords(x, y).value().unwrap();
        let uv = [u.triple.unwrap(), v.triple.unwrap()];
        assert_eq!(r.pixel_from_coords(x, y, uv).unwrap(), r.pixel(x, y));
        let head = r.trace_pixel_coords(x, y).unwrap().records;
        let tail = r.trace_pixel_from_coords(x, y, uv).unwrap().records;
        let whole = r.trace_pixel(x, y).unwrap().records;
        assert_eq!([head, tail].concat(), whole);
    }
}
