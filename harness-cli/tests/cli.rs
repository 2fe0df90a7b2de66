//! The command-line contract of diff, localize, selftest, bench and jack: exit codes,
//! repro files that reproduce, errors that name the field.

use crate::binary;

use binary::{assert_says, assert_status, harness, text};
use std::path::Path;
use std::process::Output;

fn ops_small() -> String {
    vectors::sets_dir()
        .join("ops-small.json")
        .display()
        .to_string()
}

#[test]
fn a_bad_vector_file_is_an_input_error_naming_the_field() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("bad.json");
    std::fs::write(
        &file,
        r#"{"format_version":1,"name":"bad","level":"ops","vectors":[{"category":"c","op":"sqrt","a":[0,1]}]}"#,
    )
    .unwrap();
    let o = harness(&[
        "diff",
        "ref-f316",
        "ref-f316",
        "--vectors",
        file.to_str().unwrap(),
    ]);
    assert_status(&o, 2, &["bad.json: vectors[0].a: expected [s,e,m]"]);
    let o = harness(&["diff", "ref-f99", "ref-f316"]);
    assert_status(&o, 2, &["unknown implementation `ref-f99`"]);
}

#[test]
fn a_divergence_exits_1_and_its_repro_file_reproduces_it() {
    let dir = tempfile::tempdir().unwrap();
    let report = dir.path().join("report");
    let o = harness(&[
        "diff",
        "ref-f316+sqrt-floor-div",
        "ref-f316",
        "--vectors",
        &ops_small(),
        "--report",
        report.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    let out = text(&o);
    assert!(
        out.contains("localize: harness localize ref-f316+sqrt-floor-div ref-f316 --op sqrt"),
        "{out}"
    );
    assert!(report.join("report.json").exists());
    let repro = std::fs::read_dir(report.join("repro"))
        .unwrap()
        .next()
        .unwrap()
        .unwrap()
        .path();
    assert_eq!(std::fs::read_to_string(&repro).unwrap().lines().count(), 1);
    let again = harness(&[
        "diff",
        "ref-f316+sqrt-floor-div",
        "ref-f316",
        "--vectors",
        repro.to_str().unwrap(),
    ]);
    assert_eq!(again.status.code(), Some(1), "{}", text(&again));
    let clean = harness(&[
        "diff",
        "ref-f316",
        "ref-f316",
        "--vectors",
        repro.to_str().unwrap(),
    ]);
    assert_eq!(clean.status.code(), Some(0), "{}", text(&clean));
}

#[test]
fn localize_prints_the_first_divergent_operation() {
    let o = harness(&[
        "localize",
        "ref-f316+sqrt-floor-div",
        "ref-f316",
        "--op",
        "sqrt",
        "--a",
        "0,120,15576",
    ]);
    assert_status(&o, 1, &["origin: sqrt((0,120,15576)"]);
    let same = harness(&["localize", "ref-f316", "ref-f316", "--pixel", "312,87"]);
    assert_eq!(same.status.code(), Some(0), "{}", text(&same));
    let bad = harness(&["localize", "ref-f316", "ref-f316", "--pixel", "600,1"]);
    assert_eq!(bad.status.code(), Some(2), "{}", text(&bad));
    // A float implementation has no Float316 operations to compare.
    let float = harness(&["localize", "ref-f316", "ref-f64", "--pixel", "312,87"]);
    assert_status(&float, 2, &["ref-f64 computes with f64"]);
}

#[test]
fn bench_prints_and_writes_the_speed_and_error_table() {
    let dir = tempfile::tempdir().unwrap();
    let json = dir.path().join("bench.json");
    let o = harness(&[
        "bench",
        "ref-f64",
        "ref-f32",
        "--json",
        json.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", text(&o));
    assert_says(&o, "ref-f32");
    let rows: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let rows = rows.as_array().unwrap();
    assert_eq!(rows.len(), 2);
    assert_eq!(rows[0]["implementation"], "ref-f64");
    assert_eq!(rows[0]["pixel_flips"], 0);
    assert_eq!(rows[1]["pixels"], 131072);
}

/// A directory holding `Main.jack` with `source`.
fn jack_main(source: &str) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("Main.jack"), source).unwrap();
    dir
}

/// A Jack class `Main` whose `main` prints `Main.half(arg)`: `x / 2`,
/// which rounds differently under the two profiles when x is negative.
fn half_program(arg: i16) -> tempfile::TempDir {
    jack_main(&format!(
        "class Main {{\n    function void main() {{\n        do Output.printInt(Main.half({arg}));\n        return;\n    }}\n    function int half(int x) {{ return x / 2; }}\n}}\n"
    ))
}

/// `harness jack SUBCOMMAND DIR ARGS...`.
fn jack(subcommand: &str, dir: &Path, args: &[&str]) -> Output {
    let dir = dir.display().to_string();
    let mut all = vec!["jack", subcommand, &dir];
    all.extend(args);
    harness(&all)
}

#[test]
fn jack_run_gives_the_same_run_on_every_engine_and_names_them() {
    let src = half_program(-9);
    let runs: Vec<String> = ["auto", "interp", "native"]
        .iter()
        .map(|e| {
            let o = jack("run", src.path(), &["--engine", e]);
            assert!(o.status.success(), "{e}: {}", text(&o));
            text(&o)
        })
        .collect();
    assert!(runs[0].contains("end: halted"), "{}", runs[0]);
    // The same run but for how much of it compiled code ran: none on the
    // interpreter, nor on a run too short for auto to compile.
    let without_compiled = |t: &str| {
        t.lines()
            .filter(|l| !l.starts_with("compiled: "))
            .collect::<Vec<_>>()
            .join("\n")
    };
    assert_eq!(without_compiled(&runs[0]), without_compiled(&runs[1]));
    assert_eq!(without_compiled(&runs[0]), without_compiled(&runs[2]));
    assert!(runs[0].contains("compiled: 0 (0.00%)\n"), "{}", runs[0]);
    assert!(runs[1].contains("compiled: 0 (0.00%)\n"), "{}", runs[1]);
    assert!(!runs[2].contains("compiled: 0 "), "{}", runs[2]);
    let o = jack("run", src.path(), &["--engine", "jit"]);
    assert_status(&o, 2, &["auto, interp or native"]);
}

#[test]
fn jack_compile_then_run_prints_the_count_the_end_and_the_screen() {
    let src = half_program(-9);
    let out = tempfile::tempdir().unwrap();
    let vm = out.path().join("vm");
    let o = jack("compile", src.path(), &["--out", &vm.display().to_string()]);
    assert!(o.status.success(), "{}", text(&o));
    assert!(vm.join("Main.vm").is_file());
    let png = out.path().join("screen.png");
    let o = jack("run", &vm, &["--screen", &png.display().to_string()]);
    assert!(o.status.success(), "{}", text(&o));
    let t = text(&o);
    assert!(
        t.contains("instructions: ") && t.contains("end: halted"),
        "{t}"
    );
    let screen = image::open(&png).unwrap().to_luma8();
    assert_eq!(screen.dimensions(), (512, 256));
    // Exactly the font's glyphs of "-4" in the first two 8x11 character
    // cells, and nothing else black; the desktop profile (the default)
    // starts text at pixel row 1 (its START_ADDRESS, docs/timing.md).
    let font: serde_json::Value =
        serde_json::from_str(include_str!("../../impls/jack/os/hack-font.json")).unwrap();
    let glyph = |c: char, x: u32, y: u32| {
        font["glyphs"][(c as u32).to_string()][y as usize]
            .as_str()
            .unwrap()
            .as_bytes()[x as usize]
            == b'#'
    };
    for (x, y, p) in screen.enumerate_pixels() {
        let black =
            x < 16 && (1..12).contains(&y) && glyph(['-', '4'][(x / 8) as usize], x % 8, y - 1);
        assert_eq!(p.0[0] == 0, black, "pixel ({x},{y})");
    }
}

#[test]
fn jack_compile_errors_name_file_line_and_column() {
    let compile = |main: &str| {
        let src = jack_main(main);
        let out = src.path().join("out");
        let o = jack(
            "compile",
            src.path(),
            &["--out", &out.display().to_string()],
        );
        (o, out.join("Main.vm").exists())
    };
    let (o, _) =
        compile("class Main {\n  function void main() {\n    let x = ;\n    return;\n  }\n}\n");
    assert_status(&o, 2, &["Main.jack:3:"]);
    // Code the VM would not load is an error at its Jack position, and
    // nothing is written; a call into a class outside the folder is not.
    let (o, written) = compile(
        "class Main {\n  function void main() {\n    var int x;\n    let x = 40000;\n    do Other.f();\n    return;\n  }\n}\n",
    );
    assert_status(&o, 2, &["Main.jack:4:"]);
    assert_says(&o, "would not load");
    assert!(!written);
    let (o, written) =
        compile("class Main {\n  function void main() {\n    do Other.f();\n    return;\n  }\n}\n");
    assert!(o.status.success() && written, "{}", text(&o));
}

/// A copy of the project 8 test folder `name` (its .tst, .cmp and .vm files).
fn vm_test_folder(name: &str) -> tempfile::TempDir {
    let from = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../impls/jack/vm/tests/scripts/project08")
        .join(name);
    let to = tempfile::tempdir().unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let p = e.unwrap().path();
        std::fs::copy(&p, to.path().join(p.file_name().unwrap())).unwrap();
    }
    to
}

#[test]
fn jack_test_runs_a_course_script_and_compares_like_the_official_tools() {
    let dir = vm_test_folder("FibonacciElement");
    let tst = dir
        .path()
        .join("FibonacciElementVME.tst")
        .display()
        .to_string();
    for profile in ["desktop", "web"] {
        let o = harness(&["jack", "test", &tst, "--profile", profile]);
        assert!(o.status.success(), "{}", text(&o));
        assert_says(&o, "Comparison ended successfully");
    }
    let out = std::fs::read_to_string(dir.path().join("FibonacciElement.out")).unwrap();
    assert_eq!(out, "| RAM[0] |RAM[261]|\n|    262 |      3 |\n");
    // A compare file that disagrees: exit 1 at its first differing line.
    std::fs::write(
        dir.path().join("FibonacciElement.cmp"),
        "| RAM[0] |RAM[261]|\n|    262 |      5 |\n",
    )
    .unwrap();
    let o = harness(&["jack", "test", &tst]);
    assert_status(&o, 1, &["comparison failure at line 2"]);
    // A breakpoint stops it before the comparison fails: exit 0, saying so.
    std::fs::write(
        &tst,
        "load,\noutput-file FibonacciElement.out,\ncompare-to FibonacciElement.cmp,\n\
         output-list RAM[0]%D1.6.1 RAM[261]%D1.6.1;\nbreakpoint sp 262;\n\
         repeat 6000 { vmstep; }\noutput;\n",
    )
    .unwrap();
    let o = harness(&["jack", "test", &tst]);
    assert_status(&o, 0, &["Breakpoint reached"]);
    // A script that cannot run: exit 2, with its line and column.
    std::fs::write(&tst, "load,\nvmstep;\nfrobnicate;\n").unwrap();
    let o = harness(&["jack", "test", &tst]);
    assert_status(&o, 2, &["FibonacciElementVME.tst:3:1: unknown"]);
}

#[test]
fn jack_run_sets_words_before_and_prints_ram_ranges_after() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("Main.vm"),
        "function Main.main 0\npush constant 5000\ncall Memory.peek 1\npop static 0\npush constant 0\nreturn\n",
    )
    .unwrap();
    let o = jack(
        "run",
        dir.path(),
        &["--set", "5000=77", "--ram", "16..16", "--ram", "256..272"],
    );
    assert!(o.status.success(), "{}", text(&o));
    let t = text(&o);
    assert!(t.contains("RAM[16..16]: 77\n"), "{t}");
    // The desktop start-up: the hidden call's frame at 256 (RET 11: six
    // command lines and five invisible ones), Main.main's frame right above
    // it at 261, where its return value 0 landed; 7 steps in all.
    assert!(t.contains("instructions: 7\n"), "{t}");
    assert!(
        t.contains("RAM[256..271]: 11 0 0 0 0 0 261 256 0 0 0 0 0 0 0 0\n"),
        "{t}"
    );
    assert!(t.contains("RAM[272..272]: "), "{t}");
    let o = jack("run", dir.path(), &["--ram", "10..5"]);
    assert_status(&o, 2, &["the range is empty"]);
    let o = jack("run", dir.path(), &["--set", "24577=1"]);
    assert_status(&o, 2, &["outside RAM"]);
}

#[test]
fn jack_run_honours_a_preset_stack_pointer_under_both_profiles() {
    let src = jack_main("class Main { function void main() { do Sys.halt(); return; } }\n");
    // Desktop: the start-up frames at 300 and 305, Sys.halt's frame at 310,
    // so SP is 315 at the halt (the desktop VM emulator's figure).
    let o = jack("run", src.path(), &["--set", "0=300", "--ram", "0..0"]);
    assert!(o.status.success(), "{}", text(&o));
    assert_says(&o, "RAM[0..0]: 315\n");
    // Web: seven 0s and Main.main's frame from 300, then Sys.halt's 0.
    let o = jack(
        "run",
        src.path(),
        &["--set", "0=300", "--ram", "0..0", "--profile", "web"],
    );
    assert!(o.status.success(), "{}", text(&o));
    assert_says(&o, "RAM[0..0]: 313\n");
}

#[test]
fn jack_run_takes_a_vm_file_and_stops_an_unbudgeted_run_in_an_idle_loop() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("Main.vm");
    std::fs::write(
        &file,
        "function Main.main 0\ncall Main.halt 0\nreturn\nfunction Main.halt 0\nlabel WHILE_EXP0\n\
         push constant 0\nnot\nnot\nif-goto WHILE_END0\ngoto WHILE_EXP0\nlabel WHILE_END0\n\
         push constant 0\nreturn\n",
    )
    .unwrap();
    let o = jack("run", &file, &[]);
    assert!(o.status.success(), "{}", text(&o));
    let t = text(&o);
    assert!(t.contains("idle: desktop stopped at instruction 1000000 in an idle loop in Sys.init > Main.main > Main.halt"), "{t}");
    assert!(t.contains("end: halted"), "{t}");
    // With a budget, the budget ends the run as before.
    let o = jack(
        "run",
        &file,
        &["--max-instructions", "100", "--profile", "web"],
    );
    assert_status(&o, 1, &["instructions: 100\n"]);
}

#[test]
fn jack_run_loads_files_in_a_stated_order_for_the_statics() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("A.vm"),
        "function A.f 0\npush constant 11\npop static 0\npush constant 0\nreturn\n",
    )
    .unwrap();
    std::fs::write(
        dir.path().join("Main.vm"),
        "function Main.main 0\ncall A.f 0\npop temp 0\npush constant 22\npop static 0\npush constant 0\nreturn\n",
    )
    .unwrap();
    let o = jack("run", dir.path(), &["--ram", "16..17"]);
    assert_says(&o, "RAM[16..17]: 11 22\n");
    let o = jack(
        "run",
        dir.path(),
        &["--ram", "16..17", "--static-order", "Main,A"],
    );
    assert_says(&o, "RAM[16..17]: 22 11\n");
    let o = jack("run", dir.path(), &["--static-order", "B"]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
}

#[test]
fn jack_run_stops_a_runaway_program_at_its_budget_with_the_call_stack() {
    let src = jack_main("class Main {\n  function void main() { do Main.spin(); return; }\n  function void spin() { while (true) { } return; }\n}\n");
    let o = jack("run", src.path(), &["--max-instructions", "1000"]);
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    let t = text(&o);
    assert!(t.contains("instructions: 1000"), "{t}");
    assert!(t.contains("Main.main > Main.spin"), "{t}");
    // Too short a run for auto to compile; the compiled engine runs the
    // loop itself, the last steps (where the budget ends inside a block)
    // interpreted. (The default engine is the environment's choice.)
    let o = jack(
        "run",
        src.path(),
        &["--max-instructions", "1000", "--engine", "auto"],
    );
    assert_says(&o, "compiled: 0 (0.00%)\n");
    let o = jack(
        "run",
        src.path(),
        &["--max-instructions", "1000", "--engine", "native"],
    );
    let t = text(&o);
    assert!(t.contains("instructions: 1000\n"), "{t}");
    let compiled = t
        .lines()
        .find_map(|l| l.strip_prefix("compiled: "))
        .and_then(|l| l.split(' ').next()?.parse::<u64>().ok());
    assert!(compiled.is_some_and(|n| (990..1000).contains(&n)), "{t}");
}

#[test]
fn compare_profiles_names_the_first_call_whose_result_differs() {
    let src = half_program(-9);
    let o = jack("run", src.path(), &["--compare-profiles"]);
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    let t = text(&o);
    assert!(t.contains("call traces: differ after 2 matching calls and returns, in Sys.init > Main.main > Main.half"), "{t}");
    assert!(t.contains("desktop: Main.half returned -4"), "{t}");
    assert!(t.contains("web: Main.half returned -5"), "{t}");
    assert!(
        t.contains("screens: ") && t.contains("pixels differ"),
        "{t}"
    );
    // Without a negative division the profiles agree.
    let src = half_program(9);
    let o = jack("run", src.path(), &["--compare-profiles"]);
    assert!(o.status.success(), "{}", text(&o));
    let t = text(&o);
    assert!(
        t.contains("call traces: same")
            && t.contains("screens: same, the desktop's one pixel row lower"),
        "{t}"
    );
}
