//! Bad bindings are refused at start-up with an error naming the field.

use jack::{BindError, Bindings, BoundProgram, Budgets, JackError, JackProgram, Profile};
use std::sync::OnceLock;

const DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/jack-port");

fn program() -> &'static JackProgram {
    static P: OnceLock<JackProgram> = OnceLock::new();
    P.get_or_init(|| JackProgram::from_dir(std::path::Path::new(DIR), Profile::Desktop).unwrap())
}

/// The port's bindings with `edit` applied to their TOML text.
fn open_edited(from: &str, to: &str) -> Result<BoundProgram, JackError> {
    let text = std::fs::read_to_string(format!("{DIR}/bindings.toml")).unwrap();
    assert!(text.contains(from), "{from}");
    let bindings: Bindings = toml::from_str(&text.replace(from, to)).unwrap();
    BoundProgram::open(program(), &bindings, Budgets::default())
}

fn bind_error(r: Result<BoundProgram, JackError>) -> BindError {
    match r {
        Err(JackError::Bind(e)) => e,
        Err(e) => panic!("not a binding error: {e}"),
        Ok(_) => panic!("the bad binding was accepted"),
    }
}

#[test]
fn the_port_binds() {
    open_edited("", "").unwrap();
}

#[test]
fn a_function_that_does_not_exist_is_named() {
    let e = bind_error(open_edited(
        "add = \"result = Num.add(a, b)\"",
        "add = \"result = Num.plus(a, b)\"",
    ));
    assert_eq!(e.field, "ops.add");
    assert!(e.message.contains("no function `Num.plus`"), "{e}");
    assert!(e.message.contains("Num has: "), "{e}");
}

#[test]
fn the_wrong_arity_is_named() {
    let e = bind_error(open_edited(
        "sqrt = \"result = Num.sqrt(a)\"",
        "sqrt = \"result = Num.sqrt(a, 1)\"",
    ));
    assert_eq!(e.field, "ops.sqrt");
    assert!(e.message.contains("wrong arity"), "{e}");
    assert!(e.message.contains("function Num sqrt(Num a)"), "{e}");
}

#[test]
fn a_field_order_that_reads_garbage_fails_the_round_trip() {
    let e = bind_error(open_edited(
        "fields = [\"m\", \"e\", \"s\"]",
        "fields = [\"s\", \"e\", \"m\"]",
    ));
    assert_eq!(e.field, "float.fields");
    assert!(e.message.contains("round trip failed"), "{e}");
}

#[test]
fn a_ready_call_never_reached_is_named() {
    let e = bind_error(open_edited(
        "keys = \"SPACE\", until_call = \"Picture.render\"",
        "keys = \"A\", until_call = \"Picture.render\", budget = 3000000",
    ));
    assert_eq!(e.field, "ready.until_call");
    assert!(e.message.contains("never called"), "{e}");
    assert!(e.message.contains("3000000 instructions"), "{e}");
}

#[test]
fn a_method_called_as_on_an_object_must_be_a_method() {
    let e = bind_error(open_edited(
        "add = \"result = Num.add(a, b)\"",
        "add = \"result = a.add(b)\"",
    ));
    assert_eq!(e.field, "ops.add");
    assert!(e.message.contains("not a method"), "{e}");
}

#[test]
fn an_unbound_operation_is_unsupported() {
    let bound = open_edited("halve = \"result = Num.halve(a)\"\n", "").unwrap();
    assert!(!bound.has_op(common::Op::Halve));
    match bound.op(common::Op::Halve, &[common::F316::ONE]) {
        Err(JackError::Unsupported(m)) => assert!(m.contains("ops.halve")),
        other => panic!("{other:?}"),
    }
}

#[test]
fn an_integer_outside_16_bits_is_called_one() {
    let e = bind_error(open_edited(
        "sqrt = \"result = Num.sqrt(a)\"",
        "sqrt = \"result = Num.sqrt(99999999)\"",
    ));
    assert_eq!(e.field, "ops.sqrt");
    assert!(e.message.contains("outside Jack's 16-bit range"), "{e}");
}

/// `ready` is told apart by its fields, and a wrong one is named (an
/// untagged enum could only say that no variant matched).
#[test]
fn a_ready_table_names_what_is_wrong() {
    let text = std::fs::read_to_string(format!("{DIR}/bindings.toml")).unwrap();
    let ready =
        "ready = { run = \"Main.main\", keys = \"SPACE\", until_call = \"Picture.render\" }";
    assert!(text.contains(ready));
    for (bad, says) in [
        ("ready = { run = \"Main.main\" }", "`until_call` is missing"),
        (
            "ready = { init = [], keys = \"A\" }",
            "`keys` belongs to `run`",
        ),
        (
            "ready = { init = [], run = \"Main.main\" }",
            "exclude each other",
        ),
        ("ready = { }", "give `init`"),
        (
            "ready = { run = \"Main.main\", until_call = \"X.y\", speed = 3 }",
            "unknown field `speed`",
        ),
    ] {
        let e = toml::from_str::<Bindings>(&text.replace(ready, bad))
            .err()
            .unwrap_or_else(|| panic!("{bad} was accepted"))
            .to_string();
        assert!(e.contains(says), "{bad}: {e}");
        assert!(!e.contains("untagged"), "{e}");
    }
}

#[test]
fn a_class_the_program_does_not_have_is_named() {
    // `new = "alloc"` calls nothing, so only the class check can see it.
    let e = bind_error(open_edited("class = \"V3\"", "class = \"NoSuchClass\""));
    assert_eq!(e.field, "vec3.class");
    assert!(e.message.contains("no class NoSuchClass"), "{e}");
    let e = bind_error(open_edited("class = \"Num\"", "class = \"Nums\""));
    assert_eq!(e.field, "float.class");
}

/// `Num.above` is a method: called as `Num.above(a, b)` it would take `a`
/// as its object, with the right VM arity by chance (issue 29 item 6).
#[test]
fn a_method_called_as_a_function_is_refused() {
    let e = bind_error(open_edited(
        "gt = \"result = Num.gt(a, b)\"",
        "gt = \"result = Num.above(a, b)\"",
    ));
    assert_eq!(e.field, "ops.gt");
    assert!(e.message.contains("is a method, not a function"), "{e}");
}

/// Operations are bound by the names docs/bindings.md lists, and no other
/// spelling (issue 29 item 6).
#[test]
fn an_undocumented_operation_name_is_refused() {
    for name in ["invsqrt", "invSqrt", "inv-sqrt"] {
        let e = bind_error(open_edited(
            "inv_sqrt = \"result = Num.invSqrt(a)\"",
            &format!("{name} = \"result = Num.invSqrt(a)\""),
        ));
        assert_eq!(e.field, format!("ops.{name}"));
        assert!(e.message.contains("inv_sqrt"), "{e}");
    }
}

/// A pixel binding must give the shade; `pixel_shade` says what it is and
/// needs a `pixel` binding (issue 29 item 3).
#[test]
fn a_pixel_binding_without_a_shade_and_a_pixel_shade_without_pixel_are_named() {
    let e = bind_error(open_edited(
        "pixel = \"shade = Picture.shadeRaw(u, v)\"",
        "pixel = \"Picture.shadeRaw(u, v)\"",
    ));
    assert_eq!(e.field, "pixel");
    assert!(e.message.contains("no statement gives `shade`"), "{e}");
    let e = bind_error(open_edited(
        "pixel = \"shade = Picture.shadeRaw(u, v)\"\n",
        "",
    ));
    assert_eq!(e.field, "pixel_shade");
    assert!(e.message.contains("`pixel` is not bound"), "{e}");
    let text = std::fs::read_to_string(format!("{DIR}/bindings.toml")).unwrap();
    let e = toml::from_str::<Bindings>(&text.replace("\"unclamped\"", "\"raw\"")).unwrap_err();
    assert!(e.message().contains("unknown variant `raw`"), "{e}");
}
