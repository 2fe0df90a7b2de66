//! Which VM instruction each stretch of compiled host code belongs to, for
//! a profile by instruction kind (`scripts/profile.sh`): where the
//! environment variable `HACK_VM_CODE_MAP` names a file, compiling a
//! program writes there one line per stretch, `function start end pc part
//! kind` (tab-separated; `start..end` are byte offsets in the function's
//! code, as a profiler's symbol offsets count them). The translation tags
//! every Cranelift instruction with the VM instruction it runs for
//! ([`source_loc`]), which Cranelift keeps through code generation.

use crate::program::Op;
use cranelift_codegen::ir::SourceLoc;
use cranelift_codegen::CompiledCode;
use std::fmt::Write as _;

/// The part of a VM instruction's compiled code a host instruction is in.
#[derive(Clone, Copy)]
pub(crate) enum Part {
    /// The instruction itself (its side exits included).
    Op = 0,
    /// The entry tests of the block starting at the instruction (budget,
    /// stack range, where the dispatcher enters).
    BlockEntry = 1,
    /// The function's own entry: which entry, registers, the entry test.
    FunctionEntry = 2,
    /// Storing the registers and leaving compiled code.
    Leave = 3,
}

const PARTS: [&str; 4] = ["op", "block entry", "function entry", "leave"];

/// The source location the translation gives the host code of `part` of
/// instruction `pc`.
pub(crate) fn source_loc(pc: u32, part: Part) -> SourceLoc {
    SourceLoc::new(pc * 4 + part as u32)
}

/// The file named by `HACK_VM_CODE_MAP`, if any.
pub(crate) fn wanted() -> Option<std::path::PathBuf> {
    std::env::var_os("HACK_VM_CODE_MAP").map(Into::into)
}

/// Append the lines of function `name` (compiled to `compiled`) to `out`.
pub(crate) fn record(out: &mut String, name: &str, code: &[Op], compiled: &CompiledCode) {
    for s in compiled.buffer.get_srclocs_sorted() {
        let loc = s.loc;
        if loc.is_default() {
            continue;
        }
        let (pc, part) = (loc.bits() / 4, loc.bits() % 4);
        let kind = kind(code[pc as usize]);
        let part = PARTS[part as usize];
        let _ = writeln!(out, "{name}\t{}\t{}\t{pc}\t{part}\t{kind}", s.start, s.end);
    }
}

/// The name of `op`'s kind: its variant, and a built-in's name.
fn kind(op: Op) -> String {
    if let Op::CallBuiltin { builtin, .. } = op {
        return format!("CallBuiltin {}", builtin.full_name());
    }
    let debug = format!("{op:?}");
    let end = debug.find([' ', '(']).unwrap_or(debug.len());
    debug[..end].to_string()
}

#[cfg(test)]
mod tests {
    use super::super::Native;
    use crate::program::Program;
    use jack_os::{DivideRule, Profile};

    /// A small program and its code map under `profile`: `Main.f` has a
    /// local, written once and read back.
    fn mapped(profile: Profile) -> (std::sync::Arc<Program>, String) {
        let source = "function Main.main 0\npush constant 2\ncall Main.f 1\nreturn\n\
                      function Main.f 1\npush argument 0\npush constant 3\nadd\npop local 0\n\
                      push local 0\npush argument 0\ncall Math.multiply 2\nreturn\n";
        map_of(source, profile)
    }

    /// The program of VM code `source` and its code map under `profile`.
    fn map_of(source: &str, profile: Profile) -> (std::sync::Arc<Program>, String) {
        let program = Program::from_sources(&[("Main.vm", source)]).expect("valid VM code");
        let mut map = String::new();
        Native::compile_mapped(
            &program,
            profile,
            DivideRule::Truncate,
            None,
            Some(&mut map),
        )
        .expect("compiles");
        (program, map)
    }

    /// The kinds of `Main.f`'s own instructions that have host code.
    fn kinds_of_f(map: &str) -> Vec<&str> {
        map.lines()
            .filter(|l| l.starts_with("Main.f\t") && l.split('\t').nth(4) == Some("op"))
            .filter_map(|l| l.split('\t').nth(5))
            .collect()
    }

    /// The desktop holds `Main.f`'s local in a register: its `pop local`
    /// leaves no code of its own. The web stores it.
    #[test]
    fn held_locals_have_no_code_of_their_own_on_the_desktop() {
        let (_, desktop) = mapped(Profile::Desktop);
        let (_, web) = mapped(Profile::Web);
        let (desktop, web) = (kinds_of_f(&desktop), kinds_of_f(&web));
        assert!(!desktop.contains(&"PopLocal"), "{desktop:?}");
        assert!(web.contains(&"PopLocal"), "{web:?}");
    }

    /// A `pop constant` to a plain word is compiled code's own store; one
    /// to a register word (here THIS) is left to the interpreter.
    #[test]
    fn pops_to_plain_words_are_compiled() {
        let source = "function Main.main 0\npush constant 7\npop constant 300\n\
                      push constant 8\npop constant 3\npush constant 0\nreturn\n";
        let (program, map) = map_of(source, Profile::Web);
        let start = program.functions[0].start;
        // (An instruction's code may lie in several stretches.)
        let pops: std::collections::BTreeSet<u32> = map
            .lines()
            .map(|l| l.split('\t').collect::<Vec<_>>())
            .filter(|cols| cols[4] == "op" && cols[5] == "PopRam")
            .map(|cols| cols[3].parse().unwrap())
            .collect();
        assert_eq!(Vec::from_iter(pops), [start + 1], "{map}");
    }

    /// A run nested in an inline run is inline too, its return counted in
    /// the outermost caller's code: Main.f pushes three words and pops two
    /// (its depth before the nested call is 2, the call's two arguments).
    #[test]
    fn nested_inline_runs_return_in_the_outermost_caller() {
        let source = "function Main.main 0\npush constant 2\ncall Main.f 1\nreturn\n\
                      function Main.f 0\npush argument 0\npush constant 3\nadd\n\
                      push argument 0\ncall Main.g 2\nreturn\n\
                      function Main.g 0\npush argument 0\npush argument 1\nsub\nreturn\n";
        let (program, map) = map_of(source, Profile::Desktop);
        let g = &program.functions[program.function_id("Main.g").expect("Main.g") as usize];
        let nested_return = map.lines().any(|l| {
            let cols: Vec<&str> = l.split('\t').collect();
            let pc: u32 = cols[3].parse().unwrap();
            cols[0] == "Main.main" && cols[5] == "Return" && (g.start..g.start + 4).contains(&pc)
        });
        assert!(nested_return, "{map}");
    }

    /// The map of a small program: each line's stretch lies inside its
    /// function's code and after the previous one, its instruction inside
    /// the function, and the kinds name what the code runs.
    #[test]
    fn the_code_map_names_each_stretchs_instruction() {
        let (program, map) = mapped(Profile::Desktop);
        let f = &program.functions[program.function_id("Main.f").expect("Main.f") as usize];
        let mut last_end = 0;
        let mut kinds = Vec::new();
        for line in map.lines().filter(|l| l.starts_with("Main.f\t")) {
            let cols: Vec<&str> = line.split('\t').collect();
            let [_, start, end, pc, part, kind] = cols[..] else {
                panic!("six columns: {line}");
            };
            let (start, end, pc): (u32, u32, u32) = (
                start.parse().unwrap(),
                end.parse().unwrap(),
                pc.parse().unwrap(),
            );
            assert!(last_end <= start && start < end, "{line}");
            last_end = end;
            assert!((f.start - 1..f.start + 9).contains(&pc), "{line}");
            assert!(["op", "block entry", "function entry", "leave"].contains(&part));
            kinds.push(kind.to_string());
        }
        for kind in ["PushArg", "Add", "Multiply", "Return"] {
            assert!(kinds.iter().any(|k| k == kind), "{kind} in {kinds:?}");
        }
        // `Main.f` runs inline in `Main.main`: its instructions, its
        // return included, are counted to themselves there.
        let inline_return = map.lines().any(|l| {
            let cols: Vec<&str> = l.split('\t').collect();
            let pc: u32 = cols[3].parse().unwrap();
            cols[0] == "Main.main" && cols[5] == "Return" && (f.start..f.start + 9).contains(&pc)
        });
        assert!(inline_return, "{map}");
        assert_eq!(super::kind(crate::program::Op::PushConst(7)), "PushConst");
    }

    /// Whether `Main.main`'s code holds the return of `callee`, that is,
    /// whether `callee` runs inline there (on the desktop).
    fn runs_inline_in_main(source: &str, callee: &str) -> bool {
        runs_inline_under(source, callee, Profile::Desktop)
    }

    /// [`runs_inline_in_main`] under `profile`.
    fn runs_inline_under(source: &str, callee: &str, profile: Profile) -> bool {
        !returns_inline_in_main(source, callee, profile).is_empty()
    }

    /// The `return`s of `callee` that run inline in `Main.main`'s compiled
    /// code, as indices from the callee's first instruction.
    fn returns_inline_in_main(source: &str, callee: &str, profile: Profile) -> Vec<u32> {
        let (program, map) = map_of(source, profile);
        let id = program.function_id(callee).expect("the callee") as usize;
        let start = program.functions[id].start;
        let end = program
            .functions
            .get(id + 1)
            .map_or(u32::MAX, |next| next.start);
        let mut returns: Vec<u32> = map
            .lines()
            .filter_map(|l| {
                let cols: Vec<&str> = l.split('\t').collect();
                let pc: u32 = cols[3].parse().unwrap();
                (cols[0] == "Main.main" && cols[5] == "Return" && (start..end).contains(&pc))
                    .then(|| pc - start)
            })
            .collect();
        returns.sort_unstable();
        returns.dedup();
        returns
    }

    /// Inline runs go exactly as far as their limits: a chain of one-line
    /// callees 8 deep, a callee of 250 arguments, one of 64 locals and a
    /// run of 96 instructions with its nested runs all run inline; one
    /// level, argument, local or instruction more is called.
    #[test]
    fn inline_runs_reach_their_limits_exactly() {
        let chain = |depth: usize| {
            let mut s =
                String::from("function Main.main 0\npush constant 5\ncall Main.c1 1\nreturn\n");
            for i in 1..depth {
                s += &format!(
                    "function Main.c{i} 0\npush argument 0\ncall Main.c{} 1\nreturn\n",
                    i + 1
                );
            }
            s + &format!("function Main.c{depth} 0\npush argument 0\nreturn\n")
        };
        assert!(runs_inline_in_main(&chain(8), "Main.c8"));
        assert!(!runs_inline_in_main(&chain(9), "Main.c9"));
        let args = |n: usize| {
            "function Main.main 0\n".to_string()
                + &"push constant 1\n".repeat(n)
                + &format!("call Main.f {n}\nreturn\nfunction Main.f 0\npush argument 0\nreturn\n")
        };
        assert!(runs_inline_in_main(&args(250), "Main.f"));
        assert!(!runs_inline_in_main(&args(251), "Main.f"));
        let locals = |n: usize| {
            format!(
                "function Main.main 0\ncall Main.f 0\nreturn\n\
                 function Main.f {n}\npush constant 1\nreturn\n"
            )
        };
        assert!(runs_inline_in_main(&locals(64), "Main.f"));
        assert!(!runs_inline_in_main(&locals(65), "Main.f"));
        // Main.t's run: its own 6 instructions (its `function` line
        // included) and three runs of Main.l, 30 each: 96 in all.
        let total = |extra: usize| {
            format!(
                "function Main.main 0\npush constant 5\ncall Main.t 1\nreturn\n\
                 function Main.t 0\npush argument 0\n{}call Main.l 1\ncall Main.l 1\n\
                 call Main.l 1\nreturn\nfunction Main.l 0\npush argument 0\n{}return\n",
                "neg\n".repeat(extra),
                "neg\n".repeat(27)
            )
        };
        assert!(runs_inline_in_main(&total(0), "Main.t"));
        assert!(!runs_inline_in_main(&total(1), "Main.t"));
    }

    /// Guarded runs: a callee that opens with a test and a branch to a
    /// `return` runs that way inline in its caller (either way of the
    /// branch, a method's opening too, under both profiles); not where its
    /// opening writes a word, leaves one under the condition or reaches
    /// below its own words, nor where the returning way is longer than an
    /// inline run; and up to the argument and local limits of inline runs.
    /// (The other way here is too long to run inline itself.)
    #[test]
    fn guarded_runs_inline_the_way_that_returns() {
        let taken = |opening: &str, n_vars: usize, base: &str| {
            format!(
                "function Main.main 0\npush static 0\ncall Main.g 1\nreturn\n\
                 function Main.g {n_vars}\n{opening}if-goto BASE\npush argument 0\n\
                 push constant 1\nsub\ncall Main.g 1\n{}return\nlabel BASE\n\
                 push argument 0\n{base}return\n",
                "neg\n".repeat(32)
            )
        };
        let test = "push argument 0\npush constant 2\nlt\n";
        let fall = "function Main.main 0\npush constant 5\ncall Main.g 1\nreturn\n\
                    function Main.g 0\npush argument 0\nif-goto MORE\npush constant 0\nreturn\n\
                    label MORE\nlabel LOOP\npush argument 0\npush constant 1\nsub\n\
                    call Main.g 1\ngoto LOOP\n";
        let method = "push argument 0\npop pointer 0\npush this 0\n";
        for profile in [Profile::Desktop, Profile::Web] {
            assert!(runs_inline_under(&taken(test, 0, ""), "Main.g", profile));
            assert!(runs_inline_under(fall, "Main.g", profile));
            assert!(runs_inline_under(&taken(method, 0, ""), "Main.g", profile));
        }
        let write = "push constant 1\npop static 0\npush argument 0\n";
        let left = "push argument 0\npush argument 0\n";
        let below = "add\npush constant 1\npush constant 1\n";
        for opening in [write, left, below] {
            assert!(!runs_inline_in_main(&taken(opening, 0, ""), "Main.g"));
        }
        // The returning way: `push argument 0`, the negations, `return`.
        assert!(runs_inline_in_main(
            &taken(test, 0, &"neg\n".repeat(30)),
            "Main.g"
        ));
        assert!(!runs_inline_in_main(
            &taken(test, 0, &"neg\n".repeat(31)),
            "Main.g"
        ));
        assert!(runs_inline_in_main(&taken(test, 64, ""), "Main.g"));
        assert!(!runs_inline_in_main(&taken(test, 65, ""), "Main.g"));
        let args = |n: usize| {
            "function Main.main 0\n".to_string()
                + &"push constant 1\n".repeat(n)
                + &format!(
                    "call Main.g {n}\nreturn\nfunction Main.g 0\npush argument 0\nif-goto BASE\n\
                     label LOOP\npush constant 0\ncall Main.g 1\ngoto LOOP\nlabel BASE\n\
                     push constant 1\nreturn\n"
                )
        };
        assert!(runs_inline_in_main(&args(250), "Main.g"));
        assert!(!runs_inline_in_main(&args(251), "Main.g"));
        // Code before any `function` line has no opening to run inline.
        let implicit = "push constant 1\nif-goto ONE\npush constant 2\nreturn\nlabel ONE\n\
                        push constant 3\nreturn\nfunction Main.main 0\ncall __implicit 0\nreturn\n";
        for profile in [Profile::Desktop, Profile::Web] {
            assert!(!runs_inline_under(implicit, "__implicit", profile));
        }
    }

    /// A recursion's other way runs inline too, where it calls the callee
    /// itself and the call is the caller's own: its calls are nested runs
    /// (a guarded callee's base case inline, its own other way not) or
    /// calls through the host. Not a way whose calls are of other
    /// functions only, nor one past the limits of inline runs: its
    /// `return` within 32 instructions, 96 translated with its nested runs
    /// (desktop, `function` lines included: 11 of the way, 7 of the nested
    /// Main.g's opening and base case, and 3 + m of each of three runs of
    /// Main.big).
    #[test]
    fn guarded_runs_inline_a_recursions_other_way() {
        let rec = |way: &str| {
            format!(
                "function Main.main 0\npush constant 5\ncall Main.g 1\nreturn\n\
                 function Main.g 0\npush argument 0\npush constant 2\nlt\nif-goto BASE\n\
                 {way}return\nlabel BASE\npush argument 0\nreturn\n\
                 function Main.k 0\npush argument 0\npush constant 2\nlt\nif-goto BASE\n\
                 push argument 0\npush constant 1\nsub\ncall Main.k 1\nreturn\nlabel BASE\n\
                 push argument 0\nreturn\nfunction Main.spin 1\npush argument 0\npop local 0\nlabel L\n\
                 push local 0\npush constant 1\nsub\npop local 0\npush local 0\nif-goto L\n\
                 push constant 0\nreturn\n"
            )
        };
        let inline =
            |source: &str, callee: &str| returns_inline_in_main(source, callee, Profile::Desktop);
        let down = "push argument 0\npush constant 1\nsub\n";
        // Main.g's way of c instructions returns at 4 + c, its base case
        // 2 later.
        let g = format!("{down}call Main.g 1\n");
        assert_eq!(inline(&rec(&g), "Main.g"), [8, 10]);
        let host = format!("{down}call Main.spin 1\ncall Main.g 1\n");
        assert_eq!(inline(&rec(&host), "Main.g"), [9, 11]);
        assert!(inline(&rec(&host), "Main.spin").is_empty());
        let nested = format!("{down}call Main.k 1\n{down}call Main.g 1\nadd\n");
        assert_eq!(inline(&rec(&nested), "Main.g"), [13, 15]);
        // Main.k: its opening and base case (at 10) inline, not its way (8).
        assert_eq!(inline(&rec(&nested), "Main.k"), [10]);
        let others = format!("{down}call Main.k 1\n");
        assert_eq!(inline(&rec(&others), "Main.g"), [10]);
        for profile in [Profile::Desktop, Profile::Web] {
            assert_eq!(returns_inline_in_main(&rec(&g), "Main.g", profile), [8, 10]);
        }
        // Reached through `goto`s (the desktop's wasted step before a label
        // that follows another; the program's own): the recursive way runs
        // inline after up to two; a straight way so reached does not.
        let after = |gotos: &str| {
            format!(
                "function Main.main 0\npush constant 5\ncall Main.g 1\nreturn\n\
                 function Main.g 0\npush argument 0\npush constant 2\nlt\nnot\n\
                 if-goto MORE\npush argument 0\nreturn\nlabel MORE\n{gotos}{g}return\n"
            )
        };
        assert_eq!(inline(&after("label GO\n"), "Main.g"), [6, 11]);
        let two = "goto A\nlabel A\ngoto B\nlabel B\n";
        assert_eq!(inline(&after(two), "Main.g"), [6, 13]);
        let three = "goto A\nlabel A\ngoto B\nlabel B\ngoto C\nlabel C\n";
        assert_eq!(inline(&after(three), "Main.g"), [6]);
        let base_after = format!(
            "function Main.main 0\npush constant 5\ncall Main.g 1\nreturn\n\
             function Main.g 0\npush argument 0\npush constant 2\nlt\nif-goto BASE\n\
             {g}return\nlabel BASE\nlabel B2\npush argument 0\nreturn\n"
        );
        assert_eq!(inline(&base_after, "Main.g"), [8]);
        // The way's `return` is its 32nd instruction at most.
        let long = |n: usize| rec(&format!("{down}{}call Main.g 1\n", "neg\n".repeat(n)));
        assert_eq!(inline(&long(27), "Main.g"), [35, 37]);
        assert_eq!(inline(&long(28), "Main.g"), [38]);
        let total = |m: usize| {
            let big = format!(
                "function Main.big 0\npush constant 1\n{}return\n",
                "neg\n".repeat(m)
            );
            let calls = "call Main.big 0\npop temp 0\n".repeat(3);
            let way = format!("{calls}{down}call Main.g 1\n");
            rec(&way) + &big
        };
        assert_eq!(inline(&total(23), "Main.big"), [24]);
        assert!(inline(&total(24), "Main.big").is_empty());
    }

    /// The host code bytes of the map's instruction stretches (part `op`),
    /// summed by the key `key` gives a stretch's columns (function, start,
    /// end, instruction, part, kind; None: left out).
    fn op_bytes<'m, K: Ord>(
        map: &'m str,
        key: impl Fn(&[&'m str]) -> Option<K>,
    ) -> std::collections::BTreeMap<K, u32> {
        let mut bytes = std::collections::BTreeMap::new();
        for cols in map.lines().map(|l| l.split('\t').collect::<Vec<_>>()) {
            if cols[4] != "op" {
                continue;
            }
            if let Some(k) = key(&cols) {
                let (start, end): (u32, u32) = (cols[1].parse().unwrap(), cols[2].parse().unwrap());
                *bytes.entry(k).or_default() += end - start;
            }
        }
        bytes
    }

    /// The host code bytes of each `kind` instruction of `Main.f`, by
    /// instruction, in program order.
    fn code_bytes(map: &str, kind: &str) -> Vec<u32> {
        op_bytes(map, |cols| {
            (cols[0] == "Main.f" && cols[5] == kind).then(|| cols[3].parse::<u32>().unwrap())
        })
        .into_values()
        .collect()
    }

    /// The host code bytes of `Main.f`'s one `kind` instruction in the
    /// program of VM code `source` under `profile`.
    fn only_code_bytes(source: &str, profile: Profile, kind: &str) -> u32 {
        let (_, map) = map_of(source, profile);
        let bytes = code_bytes(&map, kind);
        assert_eq!(bytes.len(), 1, "{map}");
        bytes[0]
    }

    /// The `this` (`that`) accesses of a run after one `pop pointer` share
    /// one address test, made at the first: the later ones are shorter,
    /// at small indices and at large ones (4,100 on; the test covers any
    /// index that leaves 6 words below the end of RAM). Without the `pop
    /// pointer`, the web's test that the pointer was set is made once too.
    #[test]
    fn accesses_after_the_first_of_a_pointer_share_its_test() {
        for (segment, pointer) in [("this", 0), ("that", 1)] {
            let popped = format!("push argument 0\npop pointer {pointer}\n");
            let push = if segment == "this" {
                "PushThis"
            } else {
                "PushThat"
            };
            for (prelude, kind) in [
                (popped.as_str(), push.to_string()),
                ("", format!("{push}Chk")),
            ] {
                for i in [1, 4100] {
                    let source = format!(
                        "function Main.main 0\npush constant 3000\ncall Main.f 1\nreturn\n\
                         function Main.f 0\n{prelude}push {segment} {i}\npush {segment} {}\n\
                         push {segment} {}\nadd\nadd\nreturn\n",
                        i + 1,
                        i + 2
                    );
                    let (_, map) = map_of(&source, Profile::Web);
                    let bytes = code_bytes(&map, &kind);
                    assert_eq!(bytes.len(), 3, "{map}");
                    assert!(
                        bytes[1] < bytes[0] && bytes[2] < bytes[0],
                        "{kind} {i}: {bytes:?}"
                    );
                }
            }
        }
    }

    /// On the desktop a `pop pointer` tests the pointer's range, which
    /// vouches for word 0 of its segment: `push this 0` (`that 0`) after it
    /// has no test of its own, and is shorter than `push this 1`, whose
    /// word the range does not cover.
    #[test]
    fn word_0_after_a_desktop_pop_pointer_needs_no_test() {
        for (segment, kind) in [("this", "PushThisChk"), ("that", "PushThatChk")] {
            let pointer = if segment == "this" { 0 } else { 1 };
            let access = |index: u16| {
                let source = format!(
                    "function Main.main 0\npush constant 3000\ncall Main.f 1\nreturn\n\
                     function Main.f 0\npush argument 0\npop pointer {pointer}\n\
                     push {segment} {index}\nreturn\n"
                );
                only_code_bytes(&source, Profile::Desktop, kind)
            };
            let (word_0, word_1) = (access(0), access(1));
            assert!(word_0 < word_1, "{segment}: {word_0}, {word_1}");
        }
    }

    /// The function's entry tests LCL and ARG once for every `local` and
    /// `argument` index it uses, up to large ones (5,000 here): the access
    /// itself carries no test, under twice as long as one of `argument 2`
    /// (a longer displacement).
    #[test]
    fn large_segment_indices_are_tested_at_the_entry() {
        let access = |index: u16| {
            let source = format!(
                "function Main.main 0\npush constant 1\ncall Main.f 1\nreturn\n\
                 function Main.f 0\nlabel L\npush argument {index}\npop temp 0\ngoto L\n"
            );
            only_code_bytes(&source, Profile::Web, "PushArg")
        };
        let (small, large) = (access(2), access(5000));
        assert!(large < 2 * small, "{small}, {large}");
    }

    /// An inline run that writes no frame word takes its `push argument`s
    /// from the caller's registers, with no code of their own, and returns
    /// without reading the caller's frame back: its return is under a third
    /// as long as the same function's own compiled return (web).
    #[test]
    fn inline_runs_that_keep_their_frames_read_no_frame() {
        let source = "function Main.main 0\npush constant 2\npush constant 4\ncall Main.f 2\n\
                      return\nfunction Main.f 0\npush argument 0\npush argument 1\nadd\nreturn\n";
        let (program, map) = map_of(source, Profile::Web);
        let f = program.functions[program.function_id("Main.f").expect("Main.f") as usize].start;
        let inline = op_bytes(&map, |cols| {
            let pc: u32 = cols[3].parse().unwrap();
            (cols[0] == "Main.main" && pc >= f).then_some(cols[5])
        });
        assert!(!inline.contains_key("PushArg"), "{inline:?}");
        let own = code_bytes(&map, "Return");
        assert_eq!(own.len(), 1, "{map}");
        assert!(3 * inline["Return"] < own[0], "{inline:?}, own {own:?}");
    }

    /// Where depths are static, the function's entry tests LCL against
    /// its stack range, from 256 less the lowest stack word up. While that
    /// bound is at least 10 it shows the return its saved frame (LCL - 5 ..
    /// LCL - 1 plain words), and the return makes no test of its own: with
    /// 246 locals, whose stack starts 246 words above LCL, the return is
    /// shorter than with 247.
    #[test]
    fn returns_rely_on_the_entrys_range_test_while_it_shows_the_frame() {
        for profile in [Profile::Desktop, Profile::Web] {
            let return_bytes = |locals: usize| {
                let source = format!(
                    "function Main.main 0\npush constant 1\ncall Main.f 1\nreturn\n\
                     function Main.f {locals}\npush constant 5\npush argument 0\nif-goto ONE\n\
                     push constant 1\nadd\nlabel ONE\nreturn\n"
                );
                only_code_bytes(&source, profile, "Return")
            };
            let (shown, tested) = (return_bytes(246), return_bytes(247));
            assert!(shown < tested, "{profile:?}: {shown}, {tested}");
        }
    }

    /// A desktop return leaves R13 and R14 holding its frame and RET word,
    /// as the desktop tool's return does. A run nested in an inline run
    /// leaves those two stores to the next return or leave, which
    /// overwrites them: its return is shorter than the same function's
    /// return where it is the outermost run.
    #[test]
    fn nested_inline_returns_leave_r13_and_r14_to_the_next_return() {
        let g = "function Main.g 0\npush argument 0\npush argument 1\nsub\nreturn\n";
        let nested = format!(
            "function Main.main 0\npush constant 2\ncall Main.f 1\nreturn\n\
             function Main.f 0\npush argument 0\npush constant 3\nadd\n\
             push argument 0\ncall Main.g 2\nreturn\n{g}"
        );
        let outermost = format!(
            "function Main.main 0\npush constant 2\npush constant 3\ncall Main.g 2\nreturn\n{g}"
        );
        let g_return = |source: &str| {
            let (program, map) = map_of(source, Profile::Desktop);
            let g =
                program.functions[program.function_id("Main.g").expect("Main.g") as usize].start;
            let bytes = op_bytes(&map, |cols| {
                let pc: u32 = cols[3].parse().unwrap();
                (cols[0] == "Main.main" && cols[5] == "Return" && pc >= g).then_some(())
            });
            bytes[&()]
        };
        let (nested, outermost) = (g_return(&nested), g_return(&outermost));
        assert!(nested < outermost, "{nested}, {outermost}");
    }
}
