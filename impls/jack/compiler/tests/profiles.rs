//! The two profiles on one realistic program: the seed program's desktop
//! tools accept a parameter whose type names a class outside the program
//! (and calls into it, which a .vm file may supply); the web IDE refuses
//! them. Both produce the same code when both accept.

use jack_compiler::{compile_sources, Profile};

const MAIN: &str = r#"
/** Draws a few shaded bars and prints their sum. */
class Main {
    static int count;

    function void main() {
        var Array bars;
        var int i, sum;
        let count = 8;
        let bars = Array.new(count);
        let i = 0;
        while (i < count) {
            let bars[i] = Shade.level(i * 3, count);
            let i = i + 1;
        }
        let sum = Main.total(bars, count);
        do Output.printString("sum=");
        do Output.printInt(sum);
        do bars.dispose();
        return;
    }

    /** Sum of the first n entries. */
    function int total(Array a, int n) {
        var int i, s;
        let i = 0;
        let s = 0;
        while (i < n) {
            let s = s + a[i];
            let i = i + 1;
        }
        return s;
    }
}
"#;

const SHADE: &str = r#"
class Shade {
    /** Level of x out of n, clamped to 0..15; v is unused (as in the seed). */
    function int level(int x, int n) {
        var int l;
        let l = (x * 16) / n;
        if (l > 15) {
            let l = 15;
        }
        return l;
    }

    /** Scales a vector; Vec is not part of this program. */
    function int scale(Vec v, int k) {
        return v.dot(v) * k;
    }
}
"#;

fn sources() -> [(&'static str, &'static str); 2] {
    [("Main.jack", MAIN), ("Shade.jack", SHADE)]
}

#[test]
fn desktop_accepts_a_type_outside_the_program() {
    let out = compile_sources(&sources(), Profile::Desktop).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(out.len(), 2);
    assert!(out[1].code.contains(
        "function Shade.scale 0\n    push argument 0\n    push argument 0\n    call Vec.dot 2\n"
    ));
}

#[test]
fn web_rejects_it_with_the_official_messages() {
    let errs = compile_sources(&sources(), Profile::Web).unwrap_err();
    let msgs: Vec<String> = errs.0.iter().map(ToString::to_string).collect();
    assert_eq!(
        msgs,
        [
            "Shade.jack:14:24: Unknown type Vec",
            "Shade.jack:15:16: Class Vec doesn't exist",
        ]
    );
}

#[test]
fn both_profiles_generate_the_same_code_where_both_accept() {
    let without_vec = SHADE
        .replace("Vec v", "Array v")
        .replace("v.dot(v)", "v[0]");
    let srcs = [("Main.jack", MAIN), ("Shade.jack", without_vec.as_str())];
    let desktop = compile_sources(&srcs, Profile::Desktop).unwrap();
    let web = compile_sources(&srcs, Profile::Web).unwrap();
    assert_eq!(desktop, web);
}

#[test]
fn desktop_names_the_subroutine_kind_where_the_web_ide_capitalises_the_name() {
    let src = "class Main { function void f() { do g(); return; } function void g() { return; } }";
    let msg = |p| {
        compile_sources(&[("Main.jack", src)], p).unwrap_err().0[0]
            .kind
            .to_string()
    };
    assert_eq!(msg(Profile::Web), "G Main.g was called as a method");
    assert_eq!(
        msg(Profile::Desktop),
        "Function Main.g was called as a method"
    );
}

#[test]
fn both_profiles_reject_unknown_os_subroutines_and_primitive_receivers() {
    let src =
        "class Main { function void f() { var int i; do Math.bit(1, 2); do i.foo(); return; } }";
    let msgs = |p| -> Vec<String> {
        compile_sources(&[("Main.jack", src)], p)
            .unwrap_err()
            .0
            .iter()
            .map(|e| e.kind.to_string())
            .collect()
    };
    assert_eq!(
        msgs(Profile::Web),
        ["Class Math doesn't exist", "Class int doesn't exist"]
    );
    assert_eq!(
        msgs(Profile::Desktop),
        [
            "Class Math doesn't contain a function/constructor bit",
            "Class int doesn't exist"
        ]
    );
}
