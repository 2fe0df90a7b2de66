//! Every kind of compile error: the official message, file, line and column,
//! and that one run reports several errors.

use jack_compiler::{compile_dir, compile_sources, CompileDirError, Profile};

/// The errors of compiling `files`, as `file:line:col: message` strings.
fn errors(files: &[(&str, &str)], profile: Profile) -> Vec<String> {
    match compile_sources(files, profile) {
        Ok(_) => Vec::new(),
        Err(e) => e.0.iter().map(ToString::to_string).collect(),
    }
}

fn web(src: &str) -> Vec<String> {
    errors(&[("Main.jack", src)], Profile::Web)
}

#[test]
fn class_name_must_match_file_name() {
    assert_eq!(
        web("class Mian { }"),
        ["Main.jack:1:7: Class name Mian doesn't match file name Main"]
    );
}

#[test]
fn duplicate_subroutine() {
    let src = "class Main {\n  function void f() { return; }\n  method void f() { return; }\n}";
    assert_eq!(web(src), ["Main.jack:3:15: Subroutine f already declared"]);
}

#[test]
fn missing_return_and_bare_return() {
    let src = "class Main {\n  function int f() {\n    if (true) { return; }\n    while (true) { }\n  }\n}";
    assert_eq!(
        web(src),
        [
            "Main.jack:2:16: Subroutine f: not all code paths return a value",
            "Main.jack:3:17: A non void subroutine must return a value",
        ]
    );
}

#[test]
fn undeclared_variables_are_all_reported() {
    let src = "class Main {\n  function void f() {\n    let x = y;\n    do Output.printInt(z[1]);\n    return;\n  }\n}";
    assert_eq!(
        web(src),
        [
            "Main.jack:3:9: Undeclared variable x",
            "Main.jack:3:13: Undeclared variable y",
            "Main.jack:4:24: Undeclared variable z",
        ]
    );
}

#[test]
fn unknown_types_in_every_position() {
    let src = "class Main {\n  field Vec v;\n  function Vec f(Pt p) {\n    var Rgb c;\n    return c;\n  }\n}";
    assert_eq!(
        web(src),
        [
            "Main.jack:2:9: Unknown type Vec",
            "Main.jack:3:12: Unknown type Vec",
            "Main.jack:3:18: Unknown type Pt",
            "Main.jack:4:9: Unknown type Rgb",
        ]
    );
    // OS classes, primitives and classes of the program are known.
    let ok = "class Main { field Array a; field String s; field Main m; field boolean b; field char c; function void f() { return; } }";
    assert_eq!(web(ok), Vec::<String>::new());
}

#[test]
fn call_validation_messages() {
    let src = "class Main {
  field int n;
  method void m() { return; }
  function void g(int a) { return; }
  function void f() {
    var int i; var Main o; var String s;
    do Foo.bar();
    do Sys.init();
    do Math.bit(1, 2);
    do Main.nope();
    do Math.max(1);
    do Main.g();
    do Main.m();
    do String.length();
    do o.g(1);
    do s.new(3);
    do g(1);
    do i.foo();
    return;
  }
}";
    assert_eq!(
        web(src),
        [
            "Main.jack:7:8: Class Foo doesn't exist",
            "Main.jack:8:8: Class Sys doesn't exist",
            "Main.jack:9:8: Class Math doesn't exist",
            "Main.jack:10:8: Class Main doesn't contain a function/constructor nope",
            "Main.jack:11:8: Math.max expected 2 arguments, got 1",
            "Main.jack:12:8: Main.g expected 1 arguments, got 0",
            "Main.jack:13:8: Method Main.m was called as a function/constructor",
            "Main.jack:14:8: Method String.length was called as a function/constructor",
            "Main.jack:15:8: G Main.g was called as a method",
            "Main.jack:16:8: Constructor String.new was called as a method",
            "Main.jack:17:8: G Main.g was called as a method",
            "Main.jack:18:8: Class int doesn't exist",
        ]
    );
}

#[test]
fn calls_into_other_classes_are_checked_against_them() {
    let main = "class Main { function void main() { var Pt p; let p = Pt.new(1); do p.move(); do Pt.move(); return; } }";
    let pt = "class Pt { field int x; constructor Pt new(int ax) { return this; } method void move() { return; } }";
    assert_eq!(
        errors(&[("Main.jack", main), ("Pt.jack", pt)], Profile::Web),
        ["Main.jack:1:82: Method Pt.move was called as a function/constructor"]
    );
}

#[test]
fn os_class_override_must_follow_the_interface() {
    let math = "class Math {\n  function int multiply(int a, int b) { return 0; }\n  function int abs(int x, int y) { return 0; }\n  function int bit(int x, int i) { return 0; }\n}";
    let main = "class Main { function void main() { do Math.bit(1, 2); do Math.multiply(1, 2); return; } }";
    assert_eq!(
        errors(&[("Main.jack", main), ("Math.jack", math)], Profile::Web),
        ["Math.jack:3:16: OS subroutine Math.abs must follow the interface function int abs(int)"]
    );
}

#[test]
fn syntax_errors_first_per_file_and_semantic_errors_of_other_files() {
    let a = "class A {\n  function void f() {\n    return(1);\n  }\n}";
    let b = "class B {\n  function void f() {\n    let x = 1 +;\n  }\n}";
    let c = "class C { function void f() { let y = 1; return; } }";
    let main = "class Main { function void main() { do A.anything(1, 2, 3); return; } }";
    assert_eq!(
        errors(
            &[
                ("A.jack", a),
                ("B.jack", b),
                ("C.jack", c),
                ("Main.jack", main)
            ],
            Profile::Web
        ),
        [
            "A.jack:3:11: Expected ';' or whitespace after 'return', found '('",
            "B.jack:3:16: Expected an expression, found ';'",
            "C.jack:1:35: Undeclared variable y",
        ]
    );
}

#[test]
fn lexical_errors_have_positions() {
    assert_eq!(
        web("class Main {\n  function void f() { var int _x; return; }\n}"),
        ["Main.jack:2:31: An identifier cannot start with '_'"]
    );
    assert_eq!(
        web("class Main { /* never closed"),
        ["Main.jack:1:14: Unterminated comment"]
    );
    assert_eq!(
        web("class Main { function void f() { do Output.printString(\"abc\n\"); return; } }"),
        ["Main.jack:1:56: Unterminated string literal"]
    );
}

#[test]
fn grammar_quirks_are_errors_with_positions() {
    let cases = [
        (
            "let x = thisX;",
            "1:53: A name that starts with 'this' cannot be used in an expression (thisX)",
        ),
        ("let x = a [1];", "1:55: Expected ';', found '['"),
        ("do Output . printInt(1);", "1:55: Expected '(', found '.'"),
        (
            "return-1;",
            "1:51: Expected ';' or whitespace after 'return', found '-'",
        ),
        (
            "if (x) { } else if (x) { }",
            "1:61: Expected '{', found 'if'",
        ),
    ];
    for (stmts, want) in cases {
        let src = format!("class Main {{ function void f() {{ var int x; {stmts} return; }} }}");
        assert_eq!(web(&src), [format!("Main.jack:{want}")], "{stmts}");
    }
}

#[test]
fn deep_nesting_is_a_compile_error() {
    let e = format!("{}1{}", "(".repeat(5000), ")".repeat(5000));
    let src = format!("class Main {{ function int f() {{ return {e}; }} }}");
    let errs = web(&src);
    assert_eq!(errs.len(), 1);
    assert!(
        errs[0].ends_with("Nesting deeper than 200 levels"),
        "{errs:?}"
    );
}

#[test]
fn compile_dir_reads_sorted_files_and_reports_io_problems() {
    let dir = std::env::temp_dir().join(format!("jack-compiler-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    assert!(matches!(
        compile_dir(&dir, Profile::Web),
        Err(CompileDirError::NoSources(_))
    ));
    std::fs::write(
        dir.join("Main.jack"),
        "class Main { function void main() { do B.f(); return; } }",
    )
    .unwrap();
    std::fs::write(
        dir.join("B.jack"),
        "class B { function void f() { return; } }",
    )
    .unwrap();
    std::fs::write(dir.join("notes.txt"), "not jack").unwrap();
    let out = compile_dir(&dir, Profile::Web).unwrap();
    let names: Vec<&str> = out.iter().map(|c| c.class_name.as_str()).collect();
    assert_eq!(names, ["B", "Main"]);
    std::fs::write(dir.join("Bad.jack"), [b'c', b'\n', b'x', 0xff, 0xfe, 0x00]).unwrap();
    // Not UTF-8: the error locates the first bad byte.
    let err = compile_dir(&dir, Profile::Web).unwrap_err();
    assert!(
        matches!(
            err,
            CompileDirError::Input(common::input::InputError::NotUtf8 {
                line: 2,
                column: 2,
                ..
            })
        ),
        "{err:?}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(matches!(
        compile_dir(&dir, Profile::Web),
        Err(CompileDirError::Io { .. })
    ));
}
