//! The exact code templates of spec §4.3, checked as text on small programs
//! (these are facts of the official compiler's output).

use jack_compiler::{compile_sources, Profile};

/// The VM commands of the single class `Main` with `body`, without indentation.
fn vm(src: &str) -> Vec<String> {
    let out =
        compile_sources(&[("Main.jack", src)], Profile::Web).unwrap_or_else(|e| panic!("{e}"));
    out[0].code.lines().map(|l| l.trim().to_string()).collect()
}

/// The commands of `function Main.f` whose body is `body`, after the `function` line.
fn body(decls: &str, stmts: &str) -> Vec<String> {
    let src = format!("class Main {{ function int f(int a, Array b) {{ {decls} {stmts} }} }}");
    let lines = vm(&src);
    lines[1..].to_vec()
}

#[test]
fn function_header_counts_locals() {
    let lines = vm("class Main { function void f() { var int x, y; var Array z; return; } }");
    assert_eq!(lines, ["function Main.f 3", "push constant 0", "return"]);
}

#[test]
fn expressions_are_left_to_right_without_precedence() {
    assert_eq!(
        body("", "return 2 + 3 * 4;"),
        [
            "push constant 2",
            "push constant 3",
            "add",
            "push constant 4",
            "call Math.multiply 2",
            "return"
        ]
    );
    assert_eq!(
        body("", "return a - (a / 2) & a | a < a > a = ~a;"),
        [
            "push argument 0",
            "push argument 0",
            "push constant 2",
            "call Math.divide 2",
            "sub",
            "push argument 0",
            "and",
            "push argument 0",
            "or",
            "push argument 0",
            "lt",
            "push argument 0",
            "gt",
            "push argument 0",
            "not",
            "eq",
            "return"
        ]
    );
}

#[test]
fn constants() {
    assert_eq!(
        body("", "return -true + false + null + 007;"),
        [
            "push constant 1",
            "neg",
            "neg",
            "push constant 0",
            "add",
            "push constant 0",
            "add",
            "push constant 7",
            "add",
            "return"
        ]
    );
}

#[test]
fn string_literal_allocates_and_appends_utf16_codes() {
    assert_eq!(
        body("var String s;", "let s = \"Hi é\"; return 0;"),
        [
            "push constant 4",
            "call String.new 1",
            "push constant 72",
            "call String.appendChar 2",
            "push constant 105",
            "call String.appendChar 2",
            "push constant 32",
            "call String.appendChar 2",
            "push constant 233",
            "call String.appendChar 2",
            "pop local 0",
            "push constant 0",
            "return"
        ]
    );
}

#[test]
fn array_read_and_write_compute_the_address_first() {
    assert_eq!(
        body("", "let b[a] = b[1]; return 0;"),
        [
            "push argument 0",
            "push argument 1",
            "add",
            "push constant 1",
            "push argument 1",
            "add",
            "pop pointer 1",
            "push that 0",
            "pop temp 0",
            "pop pointer 1",
            "push temp 0",
            "pop that 0",
            "push constant 0",
            "return"
        ]
    );
}

#[test]
fn if_and_while_labels_are_numbered_per_class() {
    let src = "class Main {
        function void f(int a) { if (a) { let a = 1; } return; }
        function void g(int a) { while (a) { let a = 0; } if (a) { } else { let a = 2; } return; }
    }";
    assert_eq!(
        vm(src),
        [
            "function Main.f 0",
            "push argument 0",
            "not",
            "if-goto Main_1",
            "push constant 1",
            "pop argument 0",
            "goto Main_0",
            "label Main_1",
            "label Main_0",
            "push constant 0",
            "return",
            "function Main.g 0",
            "label Main_2",
            "push argument 0",
            "not",
            "if-goto Main_3",
            "push constant 0",
            "pop argument 0",
            "goto Main_2",
            "label Main_3",
            "push argument 0",
            "not",
            "if-goto Main_5",
            "goto Main_4",
            "label Main_5",
            "push constant 2",
            "pop argument 0",
            "label Main_4",
            "push constant 0",
            "return"
        ]
    );
}

#[test]
fn nested_if_takes_its_labels_before_the_inner_ones() {
    let lines = body("", "if (a) { if (a) { } } return 0;");
    let labels: Vec<&str> = lines
        .iter()
        .filter(|l| l.contains("Main_"))
        .map(String::as_str)
        .collect();
    assert_eq!(
        labels,
        [
            "if-goto Main_1",
            "if-goto Main_3",
            "goto Main_2",
            "label Main_3",
            "label Main_2",
            "goto Main_0",
            "label Main_1",
            "label Main_0"
        ]
    );
}

#[test]
fn prologues_of_methods_and_constructors() {
    let src = "class Main {
        field int x, y; static int s;
        constructor Main new() { let s = x; return this; }
        method int get() { return y; }
    }";
    assert_eq!(
        vm(src),
        [
            "function Main.new 0",
            "push constant 2",
            "call Memory.alloc 1",
            "pop pointer 0",
            "push this 0",
            "pop static 0",
            "push pointer 0",
            "return",
            "function Main.get 0",
            "push argument 0",
            "pop pointer 0",
            "push this 1",
            "return"
        ]
    );
}

#[test]
fn constructor_of_a_class_without_fields_does_not_allocate() {
    let src = "class Main { constructor Main new() { return this; } }";
    assert_eq!(
        vm(src),
        [
            "function Main.new 0",
            "push constant 0",
            "pop pointer 0",
            "push pointer 0",
            "return"
        ]
    );
}

#[test]
fn calls_of_every_kind() {
    let src = "class Main {
        field int n;
        method void m(int k) { var Main o; do o.m(k); do m(1); do Main.h(); do Output.printInt(k); return; }
        function void h() { return; }
    }";
    assert_eq!(
        vm(src),
        [
            "function Main.m 1",
            "push argument 0",
            "pop pointer 0",
            "push local 0",
            "push argument 1",
            "call Main.m 2",
            "pop temp 0",
            "push pointer 0",
            "push constant 1",
            "call Main.m 2",
            "pop temp 0",
            "call Main.h 0",
            "pop temp 0",
            "push argument 1",
            "call Output.printInt 1",
            "pop temp 0",
            "push constant 0",
            "return",
            "function Main.h 0",
            "push constant 0",
            "return"
        ]
    );
}

#[test]
fn dealloc_quirk_applies_only_to_classes_without_fields() {
    let no_fields = "class Main { method void dispose() { do Memory.deAlloc(this); return; } }";
    assert_eq!(
        vm(no_fields),
        [
            "function Main.dispose 0",
            "push argument 0",
            "pop pointer 0",
            "push pointer 0",
            "pop temp 0",
            "push constant 0",
            "pop temp 0",
            "push constant 0",
            "return"
        ]
    );
    let with_field =
        "class Main { field int x; method void dispose() { do Memory.deAlloc(this); return; } }";
    assert!(vm(with_field).contains(&"call Memory.deAlloc 1".to_string()));
}

#[test]
fn variable_lookup_prefers_locals_and_numbers_in_declaration_order() {
    let src = "class Main {
        static int a, b; field int c;
        method int f(int b, int x) { var int c; let c = a + b + x; return c; }
    }";
    assert_eq!(
        vm(src),
        [
            "function Main.f 1",
            "push argument 0",
            "pop pointer 0",
            "push static 0",
            "push argument 1",
            "add",
            "push argument 2",
            "add",
            "pop local 0",
            "push local 0",
            "return"
        ]
    );
}

#[test]
fn output_is_indented_like_the_web_ide_and_deterministic() {
    let src = "class Main { function void f() { while (false) { } return; } }";
    let a = compile_sources(&[("Main.jack", src)], Profile::Desktop).unwrap();
    let b = compile_sources(&[("Main.jack", src)], Profile::Desktop).unwrap();
    assert_eq!(a, b);
    assert_eq!(
        a[0].code,
        "function Main.f 0\nlabel Main_0\n    push constant 0\n    not\n    if-goto Main_1\n    goto Main_0\nlabel Main_1\n    push constant 0\n    return\n"
    );
}
