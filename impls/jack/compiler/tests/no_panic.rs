//! No input makes the compiler panic or overflow the stack: random bytes,
//! random token soups and mutations of a valid program all give Ok or Err.

use jack_compiler::{compile_sources, Profile};
use proptest::prelude::*;

const VALID: &str = r#"class Main {
    field int x; static Array a;
    constructor Main new(int ax) { let x = ax; return this; }
    method int get() { return x; }
    function void main() {
        var Main m; var int i; var String s;
        let m = Main.new(3);
        let a = Array.new(4);
        let i = 0;
        while (i < 4) { let a[i] = -i * m.get(); let i = i + 1; }
        if (~(a[1] = 0) & true) { let s = "ok"; } else { let s = null; }
        do Output.printString(s);
        do Memory.deAlloc(a);
        return;
    }
}"#;

/// Compiles `src` under both profiles: code comes with a Jack position
/// per line, and every error names `Main.jack` and a line and column
/// inside the text (`Main.jack:LINE:COL: ...`).
fn compile_both(src: &str) {
    let lines = src.split('\n').count() as u32;
    for profile in [Profile::Desktop, Profile::Web] {
        match compile_sources(&[("Main.jack", src)], profile) {
            Ok(classes) => {
                for c in classes {
                    assert_eq!(c.lines.len(), c.code.lines().count());
                }
            }
            Err(errors) => {
                assert!(!errors.0.is_empty());
                for e in errors.0 {
                    assert_eq!(e.file, "Main.jack");
                    assert!((1..=lines).contains(&e.pos.line) && e.pos.col >= 1, "{e}");
                    let at = format!("Main.jack:{}:{}: ", e.pos.line, e.pos.col);
                    assert!(e.to_string().starts_with(&at), "{e}");
                }
            }
        }
    }
}

#[derive(Debug, Clone)]
enum Edit {
    Insert(usize, char),
    Delete(usize),
    Replace(usize, char),
}

fn edit() -> impl Strategy<Value = Edit> {
    let ch = prop_oneof![
        prop::sample::select(
            "{}()[].,;+-*/&|<>=~\"_ \n/*aZ09"
                .chars()
                .collect::<Vec<_>>()
        ),
        any::<char>(),
    ];
    prop_oneof![
        (any::<usize>(), ch.clone()).prop_map(|(i, c)| Edit::Insert(i, c)),
        any::<usize>().prop_map(Edit::Delete),
        (any::<usize>(), ch).prop_map(|(i, c)| Edit::Replace(i, c)),
    ]
}

fn apply(src: &str, edits: &[Edit]) -> String {
    let mut chars: Vec<char> = src.chars().collect();
    for e in edits {
        match *e {
            Edit::Insert(i, c) => chars.insert(i % (chars.len() + 1), c),
            Edit::Delete(i) if !chars.is_empty() => {
                chars.remove(i % chars.len());
            }
            Edit::Replace(i, c) if !chars.is_empty() => {
                let n = chars.len();
                chars[i % n] = c;
            }
            _ => {}
        }
    }
    chars.into_iter().collect()
}

#[test]
fn the_valid_program_compiles() {
    for profile in [Profile::Desktop, Profile::Web] {
        compile_sources(&[("Main.jack", VALID)], profile).unwrap_or_else(|e| panic!("{e}"));
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    #[test]
    fn random_bytes(bytes in prop::collection::vec(any::<u8>(), 0..400)) {
        compile_both(&String::from_utf8_lossy(&bytes));
    }

    #[test]
    fn random_token_soup(toks in prop::collection::vec(prop::sample::select(vec![
        "class", "Main", "{", "}", "(", ")", "[", "]", ".", ",", ";", "function", "method",
        "constructor", "void", "int", "var", "let", "do", "if", "else", "while", "return",
        "x", "=", "+", "-", "~", "1", "\"s\"", "this", "true", " ", "\n",
    ]), 0..200)) {
        compile_both(&toks.concat());
    }

    #[test]
    fn mutated_valid_program(edits in prop::collection::vec(edit(), 1..8)) {
        compile_both(&apply(VALID, &edits));
    }
}

#[test]
fn pathological_nesting_is_an_error() {
    let deep = [
        format!(
            "class Main {{ function int f() {{ return {}1; }} }}",
            "-~".repeat(50_000)
        ),
        format!(
            "class Main {{ function int f() {{ return {}0{}; }} }}",
            "f(".repeat(50_000),
            ")".repeat(50_000)
        ),
        format!(
            "class Main {{ function int f() {{ var Array a; return {}0{}; }} }}",
            "a[".repeat(50_000),
            "]".repeat(50_000)
        ),
        format!(
            "class Main {{ function void f() {{ {}{} return; }} }}",
            "while (1) {".repeat(50_000),
            "}".repeat(50_000)
        ),
    ];
    for src in &deep {
        for profile in [Profile::Desktop, Profile::Web] {
            assert!(compile_sources(&[("Main.jack", src.as_str())], profile).is_err());
        }
    }
}

#[test]
fn deepest_accepted_nesting_compiles() {
    // 190 nested parentheses stay under the limit and compile.
    let src = format!(
        "class Main {{ function int f() {{ return {}1{}; }} }}",
        "(".repeat(190),
        ")".repeat(190)
    );
    assert!(compile_sources(&[("Main.jack", src.as_str())], Profile::Web).is_ok());
}

#[test]
fn long_programs_compile_without_deep_recursion() {
    let stmts = "let x = x + 1; if (x) { let x = 0; } ".repeat(50_000);
    let src = format!("class Main {{ function int f() {{ var int x; {stmts} return x; }} }}");
    let out = compile_sources(&[("Main.jack", src.as_str())], Profile::Web).unwrap();
    assert!(out[0].code.contains("label Main_99999\n"));
    let sum = "1 + ".repeat(100_000);
    let src = format!("class Main {{ function int f() {{ return {sum}1; }} }}");
    assert!(compile_sources(&[("Main.jack", src.as_str())], Profile::Web).is_ok());
}
