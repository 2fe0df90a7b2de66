//! Compiled programs RUN on the Hack VM emulator (`hack-vm`): every language
//! construct is checked by its behaviour, in both profiles.

use std::sync::Arc;

use hack_vm::{Config, Exit, Machine, Program};
use jack_compiler::{compile_dir, compile_sources, Profile, VmClass};

const BUDGET: Option<u64> = Some(50_000_000);

const MAIN: &str = r#"
/** Test entry points; each returns one number. */
class Main {
    static Array s;

    function int precedence() { return 10 - 2 * 3; }
    function int grouped() { return 10 - (2 * 3); }
    function int chain() { return 2 * 3 + 4 * 5; }
    function int unary() { return -5 - -3; }
    function int notTrue() { return ~true; }
    function int constants() { return (true + false) + (null + 32767); }
    function int minimum() { return -32767 - 1; }
    function int logic(int a, int b) { return (a & b) + (a | b); }
    function int multiply(int a, int b) { return a * b; }
    function int divide(int a, int b) { return a / b; }

    /** Bits: 1 if a < b, 2 if a > b, 4 if a = b. */
    function int compare(int a, int b) {
        var int r;
        let r = 0;
        if (a < b) { let r = r + 1; }
        if (a > b) { let r = r + 2; }
        if (a = b) { let r = r + 4; } else { let r = r + 0; }
        return r;
    }

    function int collatz(int n) {
        var int steps;
        let steps = 0;
        while (~(n = 1)) {
            if ((n & 1) = 0) {
                let n = n / 2;
            } else {
                let n = (3 * n) + 1;
            }
            let steps = steps + 1;
        }
        return steps;
    }

    function int firstSquareAbove(int x) {
        var int i;
        let i = 0;
        while (true) {
            if (i * i > x) {
                return i;
            }
            let i = i + 1;
        }
        return -1;
    }

    function int fib(int n) {
        if (n < 2) {
            return n;
        }
        return Main.fib(n - 1) + Main.fib(n - 2);
    }

    /** `do` discards results: a thousand of them leave the stack as it was. */
    function int discard() {
        var int i;
        let i = 0;
        while (i < 1000) {
            do Main.fib(3);
            let i = i + 1;
        }
        return i;
    }

    function int objects() {
        var Counter a, b;
        let a = Counter.new(3);
        let b = Counter.new(5);
        do a.tick();
        do b.twice();
        return (a.get() * 100) + b.get() + (Counter.instances() * 1000);
    }

    function int identity() {
        var Counter a, b;
        let a = Counter.new(1);
        let b = Counter.new(1);
        return (a.isSelf(a) & 1) + (b.isSelf(a) & 2);
    }

    /** A class without fields: its constructor does not allocate. */
    function int zeroField() {
        var Unit u;
        let u = Unit.new();
        return u.me() + 1;
    }

    function int arrays() {
        var Array a, b;
        var int i, sum;
        let a = Array.new(10);
        let i = 0;
        while (i < 10) {
            let a[i] = i * i;
            let i = i + 1;
        }
        let b = Array.new(2);
        let b[0] = a;
        let b[1] = a[a[2]];
        let sum = 0;
        let i = 0;
        while (i < 10) {
            let sum = sum + a[i];
            let i = i + 1;
        }
        return sum + b[1];
    }

    /** `let s[1] = e`: the address is computed before e changes s. */
    function int addressFirst() {
        var Array first;
        let first = Array.new(3);
        let s = first;
        let s[1] = Main.swap();
        return first[1] + (s[1] * 10);
    }

    function int swap() {
        let s = Array.new(3);
        return 7;
    }

    function int strings() {
        var String h, t;
        let h = "Hello";
        let t = String.new(4);
        do t.appendChar(72);
        let t = t.appendChar(105);
        return (h.length() * 1000) + (h.charAt(1) * 10) + t.length();
    }

    function void main() {
        do Memory.poke(20000, Main.fib(10));
        do Memory.poke(20001, Main.objects());
        return;
    }
}
"#;

const COUNTER: &str = r#"
class Counter {
    field int count, step;
    static int instances;

    constructor Counter new(int aStep) {
        let step = aStep;
        let count = 0;
        let instances = instances + 1;
        return this;
    }

    method void tick() {
        let count = count + step;
        return;
    }

    /** Unqualified calls are method calls on this. */
    method int twice() {
        do tick();
        do tick();
        return count;
    }

    method int get() { return count; }

    method boolean isSelf(Counter other) { return other = this; }

    function int instances() { return instances; }
}
"#;

const UNIT: &str = r#"
class Unit {
    constructor Unit new() { return this; }
    method int me() { return this; }
}
"#;

fn machine(profile: Profile) -> Machine {
    let sources = [
        ("Main.jack", MAIN),
        ("Counter.jack", COUNTER),
        ("Unit.jack", UNIT),
    ];
    let vm = compile_sources(&sources, profile).unwrap_or_else(|e| panic!("{e}"));
    let files: Vec<(String, String)> = vm.into_iter().map(VmClass::into_file).collect();
    let program: Arc<Program> = Program::from_sources(&files).unwrap_or_else(|e| panic!("{e}"));
    Machine::new(
        program,
        Config {
            profile,
            ..Config::default()
        },
    )
}

fn call(m: &mut Machine, name: &str, args: &[i16]) -> i16 {
    match m.call(name, args, BUDGET).expect("function exists") {
        Exit::Returned(v) => v,
        other => panic!("{name}{args:?} ended with {other}"),
    }
}

#[test]
fn expressions_run_left_to_right() {
    for profile in [Profile::Desktop, Profile::Web] {
        let mut m = machine(profile);
        assert_eq!(call(&mut m, "Main.precedence", &[]), 24);
        assert_eq!(call(&mut m, "Main.grouped", &[]), 4);
        assert_eq!(call(&mut m, "Main.chain", &[]), 50);
        assert_eq!(call(&mut m, "Main.unary", &[]), -2);
        assert_eq!(call(&mut m, "Main.notTrue", &[]), 0);
        assert_eq!(call(&mut m, "Main.constants", &[]), 32766);
        assert_eq!(call(&mut m, "Main.minimum", &[]), -32768);
        assert_eq!(call(&mut m, "Main.logic", &[12, 10]), 22);
        assert_eq!(call(&mut m, "Main.multiply", &[300, 300]), 24464);
        assert_eq!(call(&mut m, "Main.compare", &[1, 2]), 1);
        assert_eq!(call(&mut m, "Main.compare", &[2, 1]), 2);
        assert_eq!(call(&mut m, "Main.compare", &[3, 3]), 4);
        assert_eq!(call(&mut m, "Main.compare", &[32767, -1]), 2);
        assert_eq!(call(&mut m, "Main.compare", &[-32768, 1]), 1);
    }
}

#[test]
fn division_follows_the_profile_of_the_os() {
    let mut desktop = machine(Profile::Desktop);
    let mut web = machine(Profile::Web);
    assert_eq!(call(&mut desktop, "Main.divide", &[-7, 2]), -3);
    assert_eq!(call(&mut web, "Main.divide", &[-7, 2]), -4);
    assert_eq!(call(&mut desktop, "Main.divide", &[7, 2]), 3);
    assert_eq!(call(&mut web, "Main.divide", &[7, 2]), 3);
}

#[test]
fn control_flow_and_recursion() {
    let mut m = machine(Profile::Desktop);
    assert_eq!(call(&mut m, "Main.collatz", &[27]), 111);
    assert_eq!(call(&mut m, "Main.firstSquareAbove", &[50]), 8);
    assert_eq!(call(&mut m, "Main.fib", &[10]), 55);
    assert_eq!(call(&mut m, "Main.discard", &[]), 1000);
}

#[test]
fn objects_methods_statics_and_this() {
    let mut m = machine(Profile::Desktop);
    assert_eq!(call(&mut m, "Main.objects", &[]), 2310);
    // Two more instances: the static counter is shared by the class.
    assert_eq!(call(&mut m, "Main.identity", &[]), 1);
    assert_eq!(call(&mut m, "Counter.instances", &[]), 4);
    assert_eq!(call(&mut m, "Main.zeroField", &[]), 1);
}

#[test]
fn arrays_and_the_address_first_quirk() {
    let mut m = machine(Profile::Web);
    assert_eq!(call(&mut m, "Main.arrays", &[]), 301);
    assert_eq!(call(&mut m, "Main.addressFirst", &[]), 7);
}

#[test]
fn string_literals_and_string_methods() {
    let mut m = machine(Profile::Desktop);
    assert_eq!(call(&mut m, "Main.strings", &[]), 5000 + 1010 + 2);
}

#[test]
fn main_runs_from_the_synthetic_sys_init() {
    let mut m = machine(Profile::Desktop);
    assert_eq!(m.run(BUDGET), Exit::Halted);
    assert_eq!(m.ram().read(20000), 55);
    assert_eq!(m.ram().read(20001), 2310);
}

#[test]
fn the_raymarcher_compiles_and_loads_in_both_profiles() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../raymarcher");
    for profile in [Profile::Desktop, Profile::Web] {
        let vm = compile_dir(&dir, profile).unwrap_or_else(|e| panic!("{e}"));
        let files: Vec<(String, String)> = vm.into_iter().map(VmClass::into_file).collect();
        Program::from_sources(&files).unwrap_or_else(|e| panic!("{e}"));
    }
}
