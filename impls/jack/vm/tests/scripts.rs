//! The course's VM emulator test scripts (`run_script`): the project 7 and
//! 8 tests in `tests/scripts/`, written from their published descriptions,
//! pass under both profiles; a wrong compare file fails at its first
//! differing line; a broken script names its line and column.

use hack_vm::{run_script, Profile};
use std::path::{Path, PathBuf};

/// Every test folder: tests/scripts/projectNN/NAME.
fn test_dirs() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scripts");
    let mut dirs = Vec::new();
    for project in ["project07", "project08"] {
        for e in std::fs::read_dir(root.join(project)).unwrap() {
            dirs.push(e.unwrap().path());
        }
    }
    dirs.sort();
    dirs
}

/// A copy of `dir` in a fresh temporary folder (the script writes its .out there).
fn copy(dir: &Path) -> tempfile::TempDir {
    let tmp = tempfile::tempdir().unwrap();
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        std::fs::copy(&p, tmp.path().join(p.file_name().unwrap())).unwrap();
    }
    tmp
}

/// The script of test folder `dir`, in its copy `tmp`.
fn script_of(dir: &Path, tmp: &Path) -> PathBuf {
    let name = dir.file_name().unwrap().to_string_lossy();
    tmp.join(format!("{name}VME.tst"))
}

/// A fresh temporary folder holding `files` (name, text).
fn folder(files: &[(&str, &str)]) -> tempfile::TempDir {
    let tmp = tempfile::tempdir().unwrap();
    for (name, text) in files {
        std::fs::write(tmp.path().join(name), text).unwrap();
    }
    tmp
}

/// A program that loops for ever: push 1, pop temp 0, goto.
const COUNT_VM: &str = "label L\npush constant 1\npop temp 0\ngoto L\n";

/// 7 + 8, and a script comparing RAM[256] after its three steps with
/// `Add.cmp` (which each test writes).
const ADD_VM: &str = "push constant 7\npush constant 8\nadd\n";
const ADD_TST: &str = "load Add.vm,\noutput-file Add.out,\ncompare-to Add.cmp,\n\
                       output-list RAM[256]%D1.6.1;\nset sp 256,\nrepeat 3 { vmstep; }\noutput;\n";

#[test]
fn the_project_7_and_8_scripts_pass_under_both_profiles() {
    let dirs = test_dirs();
    let names: Vec<String> = dirs
        .iter()
        .map(|d| d.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    assert_eq!(
        names,
        [
            "BasicTest",
            "PointerTest",
            "SimpleAdd",
            "StackTest",
            "StaticTest",
            "BasicLoop",
            "FibonacciElement",
            "FibonacciSeries",
            "NestedCall",
            "SimpleFunction",
            "StaticsTest"
        ]
    );
    for dir in &dirs {
        for profile in Profile::ALL {
            let tmp = copy(dir);
            let script = script_of(dir, tmp.path());
            let report = run_script(&script, profile).unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(report.mismatch, None, "{} under {profile}", dir.display());
            assert_eq!(report.lines, 2);
            let name = dir.file_name().unwrap().to_string_lossy();
            let out = std::fs::read_to_string(tmp.path().join(format!("{name}.out"))).unwrap();
            let cmp = std::fs::read_to_string(tmp.path().join(format!("{name}.cmp"))).unwrap();
            assert_eq!(out, cmp, "{name}: the .out is the .cmp, byte for byte");
        }
    }
}

#[test]
fn a_wrong_compare_file_fails_at_its_first_differing_line() {
    let dir = test_dirs()
        .into_iter()
        .find(|d| d.ends_with("SimpleAdd"))
        .unwrap();
    let tmp = copy(&dir);
    let cmp = tmp.path().join("SimpleAdd.cmp");
    let text = std::fs::read_to_string(&cmp).unwrap().replace("257", "258");
    std::fs::write(&cmp, text).unwrap();
    let report = run_script(&script_of(&dir, tmp.path()), Profile::Desktop).unwrap();
    let m = report.mismatch.expect("the value line differs");
    assert_eq!(m.line, 2);
    assert_eq!(m.expected, "|     258  |      15  |");
    assert_eq!(m.actual, "|     257  |      15  |");
    assert!(
        m.to_string().contains("comparison failure at line 2"),
        "{m}"
    );
}

#[test]
fn scripts_with_loops_echo_and_every_format() {
    let tmp = folder(&[("Count.vm", COUNT_VM)]);
    std::fs::write(
        tmp.path().join("Count.tst"),
        "load Count.vm, output-file Count.out, echo \"counting\";\n\
         output-list RAM[5]%D1.3.1 RAM[0]%X1.4.1 RAM[0]%B1.16.1 sp%S1.4.1;\n\
         set sp 300, set RAM[301] -2, set temp[1] 9;\n\
         while RAM[5] <> 1 { vmstep; } output;\n\
         repeat 2 { vmstep; output; }\n\
         /* a comment */ clear-echo; // done\n",
    )
    .unwrap();
    let report = run_script(&tmp.path().join("Count.tst"), Profile::Desktop).unwrap();
    assert_eq!(report.echo, None, "cleared");
    assert_eq!(report.steps, 4);
    let out = std::fs::read_to_string(tmp.path().join("Count.out")).unwrap();
    assert_eq!(
        out,
        // Headers cut to the width (RAM[5 in 5) or centred; X is four hex
        // digits, B sixteen binary ones, S left-aligned. Outputs after
        // push, pop (RAM[5] = 1), goto, push.
        "|RAM[5|RAM[0]|      RAM[0]      |  sp  |\n\
         |   1 | 012C | 0000000100101100 | 300  |\n\
         |   1 | 012C | 0000000100101100 | 300  |\n\
         |   1 | 012D | 0000000100101101 | 301  |\n"
    );
}

#[test]
fn a_broken_script_names_its_line_and_column() {
    let tmp = tempfile::tempdir().unwrap();
    let path = tmp.path().join("Bad.tst");
    for (text, at, message) in [
        ("vmstep;\n", "1:1", "no program loaded"),
        ("load X.vm;\n\n  frobnicate 3;\n", "1:1", "cannot read"),
        ("repeat 3 {\n vmstep;\n", "2:8", "missing }"),
        ("output-list RAM[0]%Q1.2.3;", "1:1", "the format is one of"),
        ("set RAM[99999] 1;", "1:1", "RAM has addresses"),
    ] {
        std::fs::write(&path, text).unwrap();
        let e = run_script(&path, Profile::Desktop)
            .expect_err(text)
            .to_string();
        assert!(e.contains(&format!("Bad.tst:{at}: ")), "{e}");
        assert!(e.contains(message), "{e}");
    }
}

#[test]
fn a_compare_line_that_differs_only_in_spaces_fails_on_the_desktop_only() {
    let dir = folder(&[("Add.vm", ADD_VM), ("AddVME.tst", ADD_TST)]);
    let tst = dir.path().join("AddVME.tst");
    // The header line with a space more at its end.
    std::fs::write(dir.path().join("Add.cmp"), "|RAM[256]| \n|     15 |\n").unwrap();
    let web = run_script(&tst, Profile::Web).unwrap();
    assert!(web.mismatch.is_none(), "trailing space: {:?}", web.mismatch);
    let desktop = run_script(&tst, Profile::Desktop).unwrap();
    let m = desktop.mismatch.expect("strict on the desktop");
    assert_eq!(m.line, 1);
    std::fs::write(dir.path().join("Add.cmp"), "|RAM[256]|\n|     15 |\n").unwrap();
    let desktop = run_script(&tst, Profile::Desktop).unwrap();
    assert!(desktop.mismatch.is_none(), "{:?}", desktop.mismatch);
}

#[test]
fn a_repeat_of_vmstep_is_the_same_run_as_its_steps_one_by_one() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("Sys.vm"),
        "function Sys.init 1\nlabel L\nlabel M\npush local 0\npush constant 3\nadd\npop local 0\n\
         push local 0\npush constant 60\ngt\nif-goto E\ngoto L\nlabel E\ncall Sys.halt 0\n",
    )
    .unwrap();
    let out = |name: &str, body: &str, profile: Profile| {
        let tst = dir.path().join(format!("{name}.tst"));
        std::fs::write(
            &tst,
            format!("load Sys.vm,\noutput-file {name}.out,\noutput-list RAM[0]%D1.6.1 RAM[257]%D1.6.1;\n{body}\noutput;\n"),
        )
        .unwrap();
        let r = run_script(&tst, profile).unwrap();
        (
            r.steps,
            std::fs::read_to_string(dir.path().join(format!("{name}.out"))).unwrap(),
        )
    };
    for profile in Profile::ALL {
        for n in [1, 7, 50, 200] {
            let one_by_one = out("A", &"vmstep;\n".repeat(n), profile);
            let repeated = out("B", &format!("repeat {n} {{ vmstep; }}"), profile);
            assert_eq!(one_by_one, repeated, "{profile} {n}");
        }
    }
}

#[test]
fn current_function_names_the_running_function_and_the_caller_at_a_desktop_function_line() {
    let dir = folder(&[
        (
            "Sys.vm",
            "function Sys.init 0\ncall Sys.f 0\nlabel L\ngoto L\nfunction Sys.f 0\npush constant 0\nreturn\n",
        ),
        (
            "FVME.tst",
            "load Sys.vm,\noutput-file F.out,\noutput-list currentFunction%S1.10.1;\n\
             repeat 6 { vmstep; output; }\n",
        ),
    ]);
    let tst = dir.path().join("FVME.tst");
    let out = |profile| {
        run_script(&tst, profile).unwrap();
        std::fs::read_to_string(dir.path().join("F.out")).unwrap()
    };
    // Desktop: function Sys.init, call (still Sys.init at Sys.f's function
    // line), function Sys.f, push, return, goto.
    assert_eq!(
        out(Profile::Desktop),
        "|currentFunct|\n| Sys.init   |\n| Sys.init   |\n| Sys.f      |\n| Sys.f      |\n| Sys.init   |\n| Sys.init   |\n"
    );
    // Web: the call enters Sys.f at once.
    assert_eq!(
        out(Profile::Web),
        "|currentFunct|\n| Sys.f      |\n| Sys.f      |\n| Sys.init   |\n| Sys.init   |\n| Sys.init   |\n| Sys.init   |\n"
    );
}

#[test]
fn line_names_the_current_function_and_the_index_of_the_command_the_step_ran() {
    let dir = folder(&[
        (
            "Sys.vm",
            "function Sys.init 0\ncall Sys.f 0\nlabel L\ngoto L\n\
             function Sys.f 0\nlabel X\npush constant 0\nreturn\n",
        ),
        (
            "LVME.tst",
            "load Sys.vm,\noutput-file L.out,\noutput-list line%S1.12.1;\n\
             repeat 6 { vmstep; output; }\n",
        ),
    ]);
    run_script(&dir.path().join("LVME.tst"), Profile::Desktop).unwrap();
    // As the desktop prints it: the function on its call stack and the
    // index (function line 0, labels not counted) of the command just run.
    // The call names the caller (Sys.f's function line has not run), the
    // return the caller and the return's own index.
    assert_eq!(
        std::fs::read_to_string(dir.path().join("L.out")).unwrap(),
        "|     line     |\n| Sys.init.0   |\n| Sys.init.1   |\n| Sys.f.0      |\n| Sys.f.1      |\n\
         | Sys.init.2   |\n| Sys.init.2   |\n"
    );
}

/// `Count.vm` (push 1, pop temp 0, goto, in a loop) and a script `body`
/// after its load, output file and `output-list RAM[5]%D1.3.1`: the
/// report and the output.
fn count_script(body: &str) -> (hack_vm::ScriptReport, String) {
    let tst = format!("load Count.vm, output-file Count.out, output-list RAM[5]%D1.3.1;\n{body}");
    let tmp = folder(&[("Count.vm", COUNT_VM), ("Count.tst", &tst)]);
    let report = run_script(&tmp.path().join("Count.tst"), Profile::Desktop).unwrap();
    let out = std::fs::read_to_string(tmp.path().join("Count.out")).unwrap();
    (report, out)
}

#[test]
fn a_breakpoint_stops_the_script_after_the_step_that_reaches_it() {
    // RAM[5] becomes 1 at the second step: the `output;` after it never runs.
    let (report, out) = count_script("breakpoint RAM[5] 1;\nrepeat 10 { vmstep; output; }\n");
    assert_eq!(report.stopped.as_deref(), Some("Breakpoint reached"));
    assert_eq!(report.steps, 2);
    assert_eq!(out, "|RAM[5|\n|   0 |\n");
    // Cleared, it stops nothing; a breakpoint on another value neither.
    let (report, _) = count_script(
        "breakpoint RAM[5] 1, clear-breakpoints, breakpoint RAM[5] 7;\nrepeat 10 { vmstep; }\n",
    );
    assert_eq!((report.stopped, report.steps), (None, 10));
    // On a text variable, by its text: the goto (push 0, pop 1).
    let (report, _) = count_script("breakpoint line __implicit.2;\nrepeat 10 { vmstep; }\n");
    assert_eq!(report.stopped.as_deref(), Some("Breakpoint reached"));
    assert_eq!(report.steps, 3);
}

#[test]
fn a_bang_terminator_stops_the_script() {
    let (report, out) = count_script("vmstep! output;\n");
    assert_eq!(
        report.stopped.as_deref(),
        Some("Script reached a '!' terminator")
    );
    assert_eq!((report.steps, out.as_str()), (1, "|RAM[5|\n"));
}

#[test]
fn a_star_in_a_desktop_compare_line_matches_any_one_character() {
    let dir = folder(&[("Add.vm", ADD_VM), ("AddVME.tst", ADD_TST)]);
    let tst = dir.path().join("AddVME.tst");
    std::fs::write(dir.path().join("Add.cmp"), "|RAM[256]|\n|     *5 |\n").unwrap();
    let r = run_script(&tst, Profile::Desktop).unwrap();
    assert!(r.mismatch.is_none(), "{:?}", r.mismatch);
    // Still the same length: a star stands for one character, not more.
    std::fs::write(dir.path().join("Add.cmp"), "|RAM[256]|\n|    *5 |\n").unwrap();
    let r = run_script(&tst, Profile::Desktop).unwrap();
    assert_eq!(r.mismatch.map(|m| m.line), Some(2));
}

/// A hostile script is refused with its line and column, never read
/// without bound, run for ever or allowed to overwrite what it reads.
#[test]
fn a_script_is_bounded_in_what_it_reads_nests_repeats_and_writes() {
    let tmp = folder(&[("Count.vm", COUNT_VM)]);
    let tst = tmp.path().join("Bad.tst");
    // Other names of the compare file: through a folder, and a link.
    std::fs::create_dir(tmp.path().join("sub")).unwrap();
    std::os::unix::fs::symlink("Count.out", tmp.path().join("Link.out")).unwrap();
    let error = |text: &str| {
        std::fs::write(&tst, text).unwrap();
        run_script(&tst, Profile::Desktop)
            .map(|r| format!("ran: {:?}", r.mismatch))
            .unwrap_or_else(|e| e.to_string())
    };
    for (text, expected) in [
        ("load /dev/zero;", "1:1: /dev/zero is not a regular file"),
        (
            "load Count.vm, compare-to /dev/zero;",
            "1:16: /dev/zero is not a regular file",
        ),
        (
            "load Count.vm;\nrepeat 4000000000 { vmstep; }",
            "2:1: repeat count 4000000000 is above 2147483647",
        ),
        (
            "load Count.vm, output-file Bad.tst;",
            "1:16: output-file \"Bad.tst\" would overwrite",
        ),
        (
            "load Count.vm, output-file Count.vm;",
            "would overwrite a program, script or compare file",
        ),
        (
            "load Count.vm, output-file ../x.out;",
            "is not a file name in the script's folder",
        ),
        (
            "load Count.vm, output-file /tmp/x.out;",
            "is not a file name in the script's folder",
        ),
        (
            "load Count.vm, compare-to Count.out, output-file Count.out;",
            "output-file \"Count.out\" is the compare file",
        ),
        (
            "load Count.vm, output-file Count.out, compare-to Count.out;",
            "1:39: compare-to \"Count.out\" is the output file",
        ),
        (
            "load Count.vm, output-file Count.out, compare-to sub/../Count.out;",
            "1:39: compare-to \"sub/../Count.out\" is the output file",
        ),
        (
            "load Count.vm, output-file Link.out, compare-to Count.out;",
            "1:38: compare-to \"Count.out\" is the output file",
        ),
        (
            "load Count.vm, compare-to Count.out, output-file Link.out;",
            "1:38: output-file \"Link.out\" is the compare file",
        ),
        (
            "load Count.vm;\nrepeat { vmstep; }",
            "2:1: this repeat ran 100000000 times and the program has not ended",
        ),
    ] {
        if text.contains("Count.out") {
            std::fs::write(tmp.path().join("Count.out"), "").unwrap();
        }
        let got = error(text);
        assert!(got.contains(expected), "{text}: {got}");
    }
    // 100,000 nested blocks: refused at the 65th, not a stack overflow.
    let nested = format!("load Count.vm;\n{}", "repeat 1 {\n".repeat(100_000));
    assert!(
        error(&nested).contains("66:1: blocks nested deeper than 64"),
        "{}",
        error(&nested)
    );
    // A write that fails is located at its output-file command.
    std::fs::create_dir(tmp.path().join("Out.out")).unwrap();
    let got = error("load Count.vm,\n  output-file Out.out;\nvmstep;");
    assert!(got.contains("Bad.tst:2:3: cannot write"), "{got}");
}
