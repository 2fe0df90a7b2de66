//! Property tests: the loader never panics on random or mutated text, and
//! running with fused instructions gives exactly the state of running one
//! plain command at a time (RAM, step count and end), on random programs
//! that poke at registers, RAM edges, the this/that checks and the built-ins.

use hack_vm::{Config, Engine, Exit, KeyScript, LoadError, Machine, Program, Watcher};
use proptest::prelude::*;
use proptest::test_runner::TestCaseError;
use std::sync::Arc;

const VALID: &str = "function Main.main 2\npush constant 7\npop local 0\nlabel L\npush local 0\n\
                     push constant 1\nsub\npop local 0\npush local 0\nif-goto L\npush argument 0\n\
                     call Math.multiply 2\npush static 3\npop this 1\nreturn\n";

/// `loaded`, after checking that an error at a line names a file and a
/// line that exists (`Main.vm:LINE: ...`; `Sys.vm` is two lines long).
fn located(text: &str, loaded: Result<Arc<Program>, LoadError>) -> Result<Arc<Program>, LoadError> {
    if let Err(e) = &loaded {
        if let LoadError::Syntax { file, line, .. } = e {
            let lines = match file.as_str() {
                "Main.vm" => text.split('\n').count(),
                "Sys.vm" => 2,
                other => panic!("{e}: unknown file {other}"),
            };
            assert!((1..=lines).contains(line), "{e}");
            assert!(
                e.to_string().starts_with(&format!("{file}:{line}: ")),
                "{e}"
            );
        }
    }
    loaded
}

proptest! {
    #[test]
    fn loader_never_panics_on_random_text(text in "[ a-z0-9./$_:\\-\n\t/*]{0,200}") {
        let _ = located(&text, Program::from_sources(&[("Main.vm", text.as_str())]));
    }

    #[test]
    fn loader_never_panics_on_mutated_programs(
        edits in prop::collection::vec((0usize..400, 0u8..4, prop::sample::select(
            vec!["push", "pop", "function", "call", "return", "label", "goto", "if-goto", " ", "\n", "0",
                 "32768", "-1", "local", "this", "Main.main", "Sys.init", "/*", "//", "x", "99999999999999999999"])), 0..6)
    ) {
        let mut text = VALID.to_string();
        for (at, kind, word) in edits {
            let at = (at % (text.len() + 1)..=text.len()).find(|&i| text.is_char_boundary(i)).unwrap_or(text.len());
            match kind {
                0 => text.insert_str(at, word),
                1 => { text.truncate(at); }
                2 => { let end = (at + word.len()).min(text.len()); if text.is_char_boundary(end) { text.replace_range(at..end, word); } }
                _ => { text.insert(at, '\n'); }
            }
        }
        let two = [("Main.vm", text.as_str()), ("Sys.vm", "function Sys.init 0\ncall Main.main 0\n")];
        if let Ok(p) = located(&text, Program::from_sources(&two)) {
            // Whatever loads also runs without panicking, on either engine.
            for engine in [Engine::Interp, Engine::Native] {
                let mut m = Machine::new(p.clone(), Config { engine, ..Config::default() });
                let _ = m.run(Some(10_000));
            }
        }
    }

    #[test]
    fn compiled_execution_equals_interpretation(case in engine_case()) {
        engines_agree(&case, Engine::Native, None)?;
    }

    /// Auto with a threshold that lands among the budgets and key changes:
    /// the run switches from the interpreter to compiled code mid-way and
    /// still agrees with the interpreter alone.
    #[test]
    fn tiered_execution_equals_interpretation(case in engine_case(), threshold in threshold()) {
        engines_agree(&case, Engine::Auto, Some(threshold))?;
    }

    /// The same on code shaped as the Jack compiler shapes it.
    #[test]
    fn tiered_structured_code_equals_interpretation(case in structured_case(), threshold in threshold()) {
        engines_agree(&case, Engine::Auto, Some(threshold))?;
    }

    /// Code shaped as the Jack compiler shapes it, whose stack depth is
    /// fixed at each instruction (compiled code then tests the stack once
    /// per function and the budget once per loop): budgets and key changes
    /// land inside loops, and some statements move SP, LCL or ARG.
    #[test]
    fn compiled_structured_code_equals_interpretation(case in structured_case()) {
        engines_agree(&case, Engine::Native, None)?;
    }
}

proptest! {
    // A case takes well under a millisecond: sixteen times the usual
    // number reaches rare shapes (a division by zero on an argument that
    // its own operand overwrote) in every run.
    #![proptest_config(ProptestConfig {
        cases: ProptestConfig::default().cases * 16,
        ..ProptestConfig::default()
    })]

    #[test]
    fn fused_execution_equals_plain_execution(
        body in prop::collection::vec(command(), 1..60),
        labels in prop::collection::vec(0usize..60, 3),
        args in prop::array::uniform2(any::<i16>()),
        web in any::<bool>(),
        pad in pad(),
    ) {
        fused_agrees_with_plain(&random_program(body, labels, pad), &args, web)?;
    }
}

/// A statement of structured code (rendered by [`render`]).
#[derive(Clone, Debug)]
enum Stmt {
    /// expression; pop target
    Let(Vec<String>, String),
    /// while (expression) { body }, or a loop counting local 2 up to n.
    While(Vec<String>, Vec<Stmt>),
    Count(u8, Vec<Stmt>),
    /// if (expression) { then } else { else }
    If(Vec<String>, Vec<Stmt>, Vec<Stmt>),
    /// Plain commands that change the machine under the compiled code: a
    /// value to SP, LCL or ARG (`pop constant`), or a return.
    Raw(String),
}

/// An expression: commands that push exactly one word.
fn expression() -> impl Strategy<Value = Vec<String>> {
    let seg = prop::sample::select(vec![
        "local", "argument", "this", "that", "temp", "static", "pointer",
    ]);
    let leaf = prop_oneof![
        (0i16..40).prop_map(|v| vec![format!("push constant {v}")]),
        // -2 to 2 as words, made by sums past 65535.
        (0u16..5).prop_map(|k| wrapped_word(k).lines().map(String::from).collect()),
        (seg, 0u16..3).prop_map(|(s, i)| vec![format!(
            "push {s} {}",
            if s == "pointer" { i % 2 } else { i }
        )]),
    ];
    leaf.prop_recursive(3, 12, 2, |inner| {
        prop_oneof![
            (
                inner.clone(),
                inner.clone(),
                prop::sample::select(vec![
                    "add",
                    "sub",
                    "and",
                    "or",
                    "eq",
                    "gt",
                    "lt",
                    "call Math.multiply 2",
                    "call Math.divide 2",
                    "call Math.min 2",
                    "call Math.max 2",
                    "call Main.g 2",
                    "call Main.m 2",
                    "call Main.s 2",
                    "call Main.n 2",
                    "call Main.v 2",
                ])
            )
                .prop_map(|(a, b, op)| [a, b, vec![op.to_string()]].concat()),
            (
                inner,
                prop::sample::select(vec![
                    "neg",
                    "not",
                    "call Main.r 1",
                    "call Main.m 1",
                    "call Main.c 1",
                    "call Math.abs 1",
                    "call Math.sqrt 1",
                    "call Memory.peek 1"
                ])
            )
                .prop_map(|(a, op)| [a, vec![op.to_string()]].concat()),
        ]
    })
}

fn statement() -> impl Strategy<Value = Stmt> {
    let target = prop::sample::select(vec![
        "local", "argument", "this", "that", "temp", "static", "pointer",
    ]);
    let leaf = prop_oneof![
        6 => (expression(), target, 0u16..3).prop_map(|(e, t, i)| {
            Stmt::Let(e, format!("pop {t} {}", if t == "pointer" { i % 2 } else { i }))
        }),
        1 => prop::sample::select(vec![
            "push constant 300\npop constant 0", "push constant 2040\npop constant 0",
            "push constant 400\npop constant 1", "push constant 250\npop constant 2",
            "push constant 7\nreturn",
        ]).prop_map(|r| Stmt::Raw(r.to_string())),
        1 => (0u16..8).prop_map(|k| Stmt::Raw(arg_beside_stack(k))),
        // An `argument` read above a pushed word (where ARG lies beside
        // the stack, the word it reads may be held in a register).
        2 => (0i16..40, 0u16..3).prop_map(|(c, i)| {
            Stmt::Let(vec![format!("push constant {c}\npush argument {i}\nadd")], "pop temp 0".to_string())
        }),
    ];
    leaf.prop_recursive(3, 24, 4, |inner| {
        let body = prop::collection::vec(inner, 0..4);
        prop_oneof![
            (expression(), body.clone()).prop_map(|(e, b)| Stmt::While(e, b)),
            (0u8..6, body.clone()).prop_map(|(n, b)| Stmt::Count(n, b)),
            (expression(), body.clone(), body).prop_map(|(e, t, f)| Stmt::If(e, t, f)),
        ]
    })
}

/// The VM commands of `stmts`, with labels numbered from `labels`.
fn render(stmts: &[Stmt], labels: &mut u32, out: &mut Vec<String>) {
    for s in stmts {
        let k = *labels;
        *labels += 1;
        match s {
            Stmt::Let(e, pop) => {
                out.extend(e.iter().cloned());
                out.push(pop.clone());
            }
            Stmt::While(e, body) => {
                out.push(format!("label W{k}"));
                out.extend(e.iter().cloned());
                out.push(format!("not\nif-goto E{k}"));
                render(body, labels, out);
                out.push(format!("goto W{k}\nlabel E{k}"));
            }
            Stmt::Count(n, body) => {
                out.push(format!("push constant 0\npop local 2\nlabel W{k}\npush local 2\npush constant {n}\nlt\nnot\nif-goto E{k}"));
                render(body, labels, out);
                out.push(format!(
                    "push local 2\npush constant 1\nadd\npop local 2\ngoto W{k}\nlabel E{k}"
                ));
            }
            Stmt::If(e, then, other) => {
                out.extend(e.iter().cloned());
                out.push(format!("if-goto T{k}"));
                render(other, labels, out);
                out.push(format!("goto E{k}\nlabel T{k}"));
                render(then, labels, out);
                out.push(format!("label E{k}"));
            }
            Stmt::Raw(r) => out.push(r.clone()),
        }
    }
}

fn structured_case() -> impl Strategy<Value = EngineCase> {
    (
        prop::collection::vec(statement(), 1..8),
        // Three arguments cover every `argument` index the statements use
        // (so compiled code runs them); two fail the entry test at some.
        prop::collection::vec(any::<i16>(), 2..=3),
        any::<bool>(),
        prop::collection::vec(0u64..400, 0..5),
        prop::option::of(1u64..50),
        prop::option::of(any::<u8>()),
        pad(),
        // ARG beside the stack from the function's start, where the entry
        // test must see it for every later `argument` access.
        prop::option::weighted(0.5, 2u16..5),
    )
        .prop_map(|(stmts, args, web, budgets, hold, watched, pad, arg)| {
            let mut body: Vec<String> = arg.map(arg_beside_stack).into_iter().collect();
            render(&stmts, &mut 0, &mut body);
            EngineCase {
                src: random_program(body, Vec::new(), pad),
                args,
                web,
                budgets,
                hold,
                watched,
            }
        })
}

/// Enter Main.f of `program` with `args` without running anything.
fn enter(program: &std::sync::Arc<Program>, config: Config, args: &[i16]) -> Machine {
    let mut m = Machine::new(program.clone(), config);
    let e = m.call("Main.f", args, Some(0)).expect("Main.f exists");
    assert!(matches!(e, Exit::Budget { .. }));
    m
}

/// `Main.f` made of `body` with labels L0.. inserted at `labels`, placed
/// after a function of `pad` two-command statements (so that its code lies
/// that deep in the program), and the functions it may call.
fn random_program(body: Vec<String>, labels: Vec<usize>, pad: u16) -> String {
    let mut lines: Vec<String> = body;
    // Each forward skip (see [`forward_skip`]) gets its own label.
    for (i, line) in lines.iter_mut().enumerate() {
        *line = line.replace("SKIP#", &format!("SKIP{i}"));
    }
    for (k, at) in labels.into_iter().enumerate() {
        lines.insert(at.min(lines.len()), format!("label L{k}"));
    }
    format!(
        "function Main.main 0\npush constant 0\nreturn\nfunction Main.pad 0\n{}push constant 0\nreturn\n\
         function Main.f 3\n{}\npush constant 0\nreturn\n{}",
        "push constant 1\npop temp 0\n".repeat(usize::from(pad)),
        lines.join("\n"),
        // Fused argument reads are checked once per call: a call with
        // too few arguments must fail exactly where plain code fails.
        // Main.m opens like a method, which a fused call runs itself.
        // Main.r recurses (calls and returns inside compiled code). Main.s
        // and Main.w are setters (through THIS, and through THAT, which
        // can point into their own frame). Main.g, Main.m, Main.s and
        // Main.w with two arguments run inline in compiled callers, and
        // so do the runs that nest them: Main.n (a getter, a setter and a
        // method called from one body, as `set(get() + 1)`), the chain
        // Main.c -> Main.d -> Main.g with Main.z (no arguments) on the
        // way, and Main.v, whose nested Main.w can write into either
        // frame. Main.q recurses, running Main.c's chain at every level.
        // Main.r, Main.q, Main.ga and Main.gb open with a test whose
        // branch reaches a `return` (one way, or both for Main.ga with
        // two arguments), which compiled callers run inline, calling
        // through the host the other way: Main.ga reads a local, Main.gb
        // sets THAT and reads through it, and its inline way writes a
        // static. The other ways of Main.r, Main.q, Main.gb and Main.gc
        // (Fibonacci's shape, on the argument's low three bits) run inline
        // too, where the call is the caller's own: their calls run as
        // nested runs (guarded ones with their base case inline), or
        // through the host from inside the run (Main.gc's call of Main.lp,
        // whose loop never runs inline).
        "function Main.g 1\npush argument 0\npush argument 1\nadd\npop local 0\npush local 0\nreturn\n\
         function Main.m 1\npush argument 0\npop pointer 0\npush this 0\npush argument 1\nadd\nreturn\n\
         function Main.r 0\npush argument 0\nif-goto MORE\npush constant 0\nreturn\nlabel MORE\n\
         push argument 0\npush constant 1\nsub\ncall Main.r 1\npush constant 3\nadd\nreturn\n\
         function Main.s 0\npush argument 0\npop pointer 0\npush argument 1\npop this 1\npush constant 0\nreturn\n\
         function Main.w 0\npush argument 0\npop pointer 1\npush argument 1\npop that 0\npush constant 0\nreturn\n\
         function Main.c 0\npush argument 0\ncall Main.z 0\nadd\ncall Main.d 1\nreturn\n\
         function Main.d 0\npush argument 0\npush argument 0\ncall Main.g 2\nreturn\n\
         function Main.n 1\npush argument 0\npush argument 1\ncall Main.g 2\npop local 0\n\
         push argument 0\npush local 0\ncall Main.s 2\npop temp 1\npush argument 0\npop pointer 0\n\
         push this 1\npush local 0\ncall Main.m 2\nadd\nreturn\n\
         function Main.z 0\npush constant 5\nreturn\n\
         function Main.v 0\npush argument 0\npush argument 1\ncall Main.w 2\npop temp 0\n\
         push argument 1\nreturn\n\
         function Main.q 0\npush argument 0\nif-goto MORE\npush constant 0\nreturn\nlabel MORE\n\
         push argument 0\ncall Main.c 1\npop temp 0\npush argument 0\npush constant 1\nsub\n\
         call Main.q 1\nreturn\n\
         function Main.ga 1\npush argument 0\npush local 0\nlt\nif-goto NEG\npush argument 0\n\
         push argument 1\nadd\nreturn\nlabel NEG\npush argument 0\nneg\npop local 0\npush local 0\n\
         return\n\
         function Main.gb 0\npush argument 0\npop pointer 1\npush that 0\npush argument 0\neq\n\
         if-goto DONE\npush argument 0\n\
         push constant 1\nsub\ncall Main.gb 1\nreturn\nlabel DONE\npush argument 0\npop static 3\n\
         push constant 7\nreturn\n\
         function Main.gc 0\npush argument 0\npush constant 7\nand\npush constant 2\nlt\n\
         if-goto BASE\npush argument 0\npush constant 7\nand\npush constant 1\nsub\n\
         call Main.gc 1\ncall Main.lp 1\npush argument 0\npush constant 7\nand\n\
         push constant 2\nsub\ncall Main.gc 1\nadd\nreturn\nlabel BASE\npush argument 0\n\
         return\n\
         function Main.lp 1\npush argument 0\npush constant 31\nand\npop local 0\nlabel TOP\npush local 0\n\
         push constant 0\ngt\nnot\nif-goto OUT\npush local 0\npush constant 5\nsub\n\
         pop local 0\ngoto TOP\nlabel OUT\npush local 0\npush static 2\nadd\nreturn\n"
    )
}

/// A random program and how to run it on two engines.
#[derive(Debug, Clone)]
struct EngineCase {
    src: String,
    args: Vec<i16>,
    web: bool,
    /// Successive budgets (the last run has 3000 more).
    budgets: Vec<u64>,
    /// Key changes every `hold` instructions (None: no keys).
    hold: Option<u64>,
    /// Watch calls to and returns from the functions whose id modulo 7 is
    /// a set bit of the mask's low 7 bits (bit 7 set: a watch set only
    /// half as long as the function list, the rest unwatched).
    watched: Option<u8>,
}

fn engine_case() -> impl Strategy<Value = EngineCase> {
    (
        prop::collection::vec(command(), 1..60),
        prop::collection::vec(0usize..60, 3),
        prop::collection::vec(any::<i16>(), 2..=2),
        any::<bool>(),
        prop::collection::vec(budget(), 1..5),
        prop::option::of(1u64..50),
        prop::option::of(any::<u8>()),
        pad(),
        // Early in the function, where most budgets stop.
        prop::option::weighted(0.3, forward_skip()),
        prop::option::weighted(
            0.1,
            (
                prop_oneof![3 => Just(257u16), 1 => 255u16..259],
                prop_oneof![3 => Just(1791u16), 1 => 1788u16..1795],
            ),
        ),
        prop::option::weighted(0.25, frame_dive()),
    )
        .prop_map(
            |(mut body, labels, args, web, mut budgets, hold, watched, pad, skip, long, dive)| {
                body.splice(0..0, skip);
                body.splice(0..0, dive);
                if let Some((sp, pushes)) = long {
                    body.insert(0, stack_long_block(sp, pushes));
                    // The first stop after the block: a stop inside it
                    // leaves it to the interpreter.
                    if let Some(b) = budgets.first_mut() {
                        *b += u64::from(pushes) + 8;
                    }
                }
                EngineCase {
                    src: random_program(body, labels, pad),
                    args,
                    web,
                    budgets,
                    hold,
                    watched,
                }
            },
        )
}

/// Pops into the function's own frame. Either Main.f's three locals and
/// one to four of its saved words, then perhaps a `pop constant` into THIS
/// or THAT, which compiled code leaves to the interpreter, and a call run
/// inline: the code after it has static depths below LCL, and compiled
/// code enters it through the dispatcher there. Or one to three of its
/// locals, then pushes onto their words and a `local` access that may
/// reach a pushed word, which compiled code would hold in a register.
fn frame_dive() -> impl Strategy<Value = String> {
    let call = prop_oneof![
        Just(""),
        Just("call Main.z 0\n"),
        Just("push constant 1\npush constant 2\ncall Main.g 2\n"),
    ];
    let saved =
        (4usize..=7, prop::option::of(3u16..=4), call).prop_map(|(pops, register, call)| {
            let mut code = "pop temp 0\n".repeat(pops);
            if let Some(r) = register {
                code += &format!("pop constant {r}\n");
            }
            code + call + "pop temp 1"
        });
    let locals =
        (1usize..=3, 1usize..=3, 0u16..3, any::<bool>()).prop_map(|(pops, pushes, k, read)| {
            let access = if read {
                format!("push local {k}\nadd\n")
            } else {
                format!("pop local {k}\n")
            };
            format!(
                "{}{}{access}pop temp 1",
                "pop temp 0\n".repeat(pops),
                "push constant 5\n".repeat(pushes)
            )
        });
    prop_oneof![saved, locals]
}

/// A budget of the random programs' runs: most end within 20 steps, so
/// most budgets stop there (on every step of the paths that fall
/// through into blocks which do not test the budget).
fn budget() -> impl Strategy<Value = u64> {
    prop_oneof![3 => 0u64..24, 1 => 0u64..200]
}

/// The opening of a `Main.f` body after which its stack depths are not
/// static (a branch leaves one more word on one path): each block then
/// tests its own stack, so code that moves SP or the segment registers
/// with `pop constant` still runs compiled from the next block.
const UNKNOWN_DEPTH: &str = "push constant 0\nif-goto MOVE\npush constant 1\nlabel MOVE\n";

/// [`UNKNOWN_DEPTH`], then SP moved to `sp`.
fn sp_moved_to(sp: u16) -> String {
    format!("{UNKNOWN_DEPTH}push constant {sp}\npop constant 0\n")
}

/// SP set to `sp`, then a block of `pushes` pushes (code whose depths are
/// not static, where each block tests its stack range on entry: at 1,791
/// pushes from 256 the desktop's range is one word), then SP set back to
/// `sp` by its last push.
fn stack_long_block(sp: u16, pushes: u16) -> String {
    format!(
        "{}{}push constant {sp}\npop constant 0",
        sp_moved_to(sp),
        "push constant 1\n".repeat(usize::from(pushes - 1))
    )
}

/// The length of the function before `Main.f` (see [`random_program`]):
/// none, or enough that `Main.f` starts hundreds of instructions into the
/// program, as most functions of a real program do.
fn pad() -> impl Strategy<Value = u16> {
    prop_oneof![Just(0u16), 1u16..300]
}

/// ARG set to LCL + `k` (LCL read from RAM[1] through THAT = 0): the
/// `argument` words then lie on or beside the stack words that compiled
/// code keeps in registers (Main.f has three locals).
fn arg_beside_stack(k: u16) -> String {
    format!("push constant 0\npop pointer 1\npush that 1\npush constant {k}\nadd\npop constant 2")
}

/// An Auto threshold that lands inside the runs: most random programs end
/// within 20 steps, looping ones run to the last budget.
fn threshold() -> impl Strategy<Value = u64> {
    prop_oneof![3 => 0u64..20, 1 => 0u64..400, 1 => 400u64..3400]
}

/// Records every call and return it is told about.
#[derive(Default)]
struct Log(Vec<(bool, u32, Vec<i16>)>);

impl Watcher for Log {
    fn on_call(&mut self, _: &Program, function: u32, args: &[i16], _: &hack_vm::Ram) {
        self.0.push((true, function, args.to_vec()));
    }
    fn on_return(&mut self, _: &Program, function: u32, value: i16, _: &hack_vm::Ram) {
        self.0.push((false, function, vec![value]));
    }
}

/// Run `case` on the interpreter and on `engine` (with Auto's threshold
/// `threshold`): the same end, step count, RAM and watched calls after
/// every budget.
fn engines_agree(
    case: &EngineCase,
    engine: Engine,
    threshold: Option<u64>,
) -> Result<(), TestCaseError> {
    let (program, base) = loaded(&case.src, case.web, Engine::Interp);
    let keys = match case.hold {
        Some(hold) => KeyScript::parse("A,B,SPACE,ENTER,Z", hold).expect("a valid key script"),
        None => KeyScript::none(),
    };
    let config = |engine| Config {
        keys: keys.clone(),
        engine,
        auto_threshold: threshold,
        ..base.clone()
    };
    let mut a = enter(&program, config(Engine::Interp), &case.args);
    let mut b = enter(&program, config(engine), &case.args);
    if engine != Engine::Auto {
        prop_assert_eq!(b.engine(), Engine::Native);
    }
    let watch: Vec<bool> = case.watched.map_or(Vec::new(), |mask| {
        let n = program.functions().len();
        let len = if mask & 0x80 != 0 { n / 2 } else { n };
        (0..len).map(|i| mask >> (i % 7) & 1 != 0).collect()
    });
    let (mut log_a, mut log_b) = (Log::default(), Log::default());
    let run = |m: &mut Machine, log: &mut Log, budget| {
        if case.watched.is_some() {
            m.run_watched(Some(budget), &watch, log)
        } else {
            m.run(Some(budget))
        }
    };
    for &budget in case.budgets.iter().chain(&[3000]) {
        let end_a = run(&mut a, &mut log_a, budget);
        let end_b = run(&mut b, &mut log_b, budget);
        prop_assert_eq!(a.steps(), b.steps(), "{}", case.src);
        prop_assert_eq!(&end_a, &end_b, "{}", case.src);
        prop_assert!(a.ram() == b.ram(), "RAM differs\n{}", case.src);
        prop_assert_eq!(&log_a.0, &log_b.0, "{}", case.src);
        // Where the run stands: a stop inside an inline run has the frames
        // of every run around it, as the interpreter has them.
        prop_assert_eq!(a.call_stack(), b.call_stack(), "{}", case.src);
        prop_assert_eq!(a.current_function(), b.current_function(), "{}", case.src);
        prop_assert_eq!(
            a.next_command_index(),
            b.next_command_index(),
            "{}",
            case.src
        );
        // Auto switches where the threshold falls inside a run, or at the
        // start of the next run where it falls on the run's end.
        if let Some(t) = threshold {
            if b.steps() < t {
                prop_assert_eq!(b.engine(), Engine::Interp);
            } else if b.steps() > t {
                prop_assert_eq!(b.engine(), Engine::Native);
            }
        }
    }
    Ok(())
}

/// `src` loaded as `Main.vm`, and the configuration of `engine` under the
/// web profile (`web`) or the desktop's.
fn loaded(src: &str, web: bool, engine: Engine) -> (Arc<Program>, Config) {
    let program = Program::from_sources(&[("Main.vm", src)]).expect("test programs load");
    let profile = if web {
        hack_vm::Profile::Web
    } else {
        hack_vm::Profile::Desktop
    };
    let config = Config {
        profile,
        engine,
        ..Config::default()
    };
    (program, config)
}

/// `Main.f` of `src` run by the interpreter with fused instructions, and
/// one plain command at a time, under the desktop (`web` false) or web
/// profile for up to 3,000 steps: the same steps, end and RAM.
fn fused_agrees_with_plain(src: &str, args: &[i16], web: bool) -> Result<(), TestCaseError> {
    let (program, config) = loaded(src, web, Engine::Interp);
    const BUDGET: u64 = 3000;
    let mut fused = enter(&program, config.clone(), args);
    let fused_end = fused.run(Some(BUDGET));
    let mut plain = enter(&program, config, args);
    let plain_end = loop {
        let e = plain.run(Some(1));
        if !matches!(e, Exit::Budget { .. }) || plain.steps() >= BUDGET {
            break e;
        }
    };
    prop_assert_eq!(fused.steps(), plain.steps(), "{}", src);
    prop_assert_eq!(&fused_end, &plain_end, "{}", src);
    prop_assert!(fused.ram() == plain.ram(), "RAM differs\n{}", src);
    Ok(())
}

/// A fused `push a; push b; divide` whose `a` reads the word where `b`
/// lands (ARG moved onto the stack) and whose divisor is 0: once `b` is
/// pushed, plain code must not run `push a` again, so that the word under
/// the failed division holds `a`'s value (the long differential run found
/// the fused path leaving `b`'s there).
#[test]
fn a_fused_division_by_zero_leaves_the_stack_as_the_plain_commands_do() {
    // Main.f has 2 arguments and 3 locals: SP = 266; ARG becomes 266, and
    // `argument 1` is the word at 267, which `push temp 0` overwrites.
    let body = "push constant 266\npop constant 2\npush constant 3\npop constant 267\n\
                push argument 1\npush temp 0\ncall Math.divide 2\npop temp 1";
    let src = random_program(vec![body.to_string()], vec![], 0);
    for web in [false, true] {
        fused_agrees_with_plain(&src, &[0, 0], web).expect("fused and plain agree");
    }
}

/// `this`/`that` reads of stack words that compiled code still holds in
/// registers (pushed earlier in the same block): the address test must
/// send them to the interpreter, whether the pointer is at a held word
/// or below it with the word in its span. LCL comes from RAM[1].
#[test]
fn pointer_reads_of_held_stack_words_agree() {
    let body = "push constant 1\npop pointer 1\npush that 0\npop local 0\n\
                goto A\nlabel A\n\
                push constant 77\npush local 0\npush constant 3\nadd\npop pointer 1\n\
                push that 0\npop local 1\n\
                goto B\nlabel B\n\
                push constant 88\npush local 0\npush constant 2\nadd\npop pointer 1\n\
                push that 1\npop local 2\n\
                push local 1\npush local 2\nadd\nreturn";
    for web in [false, true] {
        let case = EngineCase {
            src: random_program(vec![body.to_string()], vec![], 0),
            args: vec![0, 0],
            web,
            budgets: vec![],
            hold: None,
            watched: None,
        };
        engines_agree(&case, Engine::Native, None).expect("the engines agree");
    }
}

/// A block that pops one of Main.f's locals and pushes onto its word,
/// which compiled code holds in a register, then reads that local: the
/// word the read finds in RAM is the one the push left, so compiled code
/// must leave such a block to the interpreter (the `local` words of a
/// block with static depths lie below its held words only where the
/// highest local index is below the lowest held word, strictly).
#[test]
fn a_local_read_of_a_word_pushed_over_it_agrees() {
    agree_at_each_stop(
        "push constant 9\npop local 2\npop temp 0\npush constant 5\npush local 2\nadd\n\
         pop temp 1\npush temp 1\nreturn",
        12,
    );
}

/// A `pop constant` into a stack word that compiled code holds in a
/// register (SP = 266: the pushes of 1, 2 and 7 lie at 266..=268, and 7
/// is popped into 267): the pop that follows reads the 7 from RAM.
#[test]
fn a_pop_constant_onto_a_held_stack_word_agrees() {
    agree_at_each_stop(
        "push constant 1\npush constant 2\npush constant 7\npop constant 267\npop temp 0\n\
         pop temp 1\npush temp 0\npush temp 1\nadd\nreturn",
        14,
    );
}

/// Web: a `that` index too large for the block's one span test
/// (24,571) with THAT = 0 reaches the stack words at the top of RAM, which
/// compiled code holds in registers (SP moved to 24,570 where depths are
/// not static): the first read finds the pushed 2 and the second the word
/// the first pushed (compiled code once forgot that word without writing
/// it, so RAM still held the 0 under it), and the write replaces the word
/// the second read pushed.
#[test]
fn a_far_that_access_of_held_stack_words_agrees() {
    let body = format!(
        "{}push constant 1\npush constant 2\npush constant 0\npop pointer 1\n\
         push that 24571\npush that 24572\npush constant 9\npop that 24573\n\
         pop temp 0\npop temp 1\npop temp 2\n\
         push temp 0\npush temp 1\nadd\npush temp 2\nadd\nreturn",
        sp_moved_to(24570)
    );
    agree_on(&body, 0, &[1, 2], &[true], &(0..24).collect::<Vec<_>>());
}

/// Web: a `that` index past the span tests (24,572) whose address lies
/// past RAM (THAT = 7): the interpreter reads -1 there, and compiled code,
/// which tests such an access on its own, leaves it to the interpreter.
#[test]
fn a_far_that_read_past_ram_agrees() {
    let body = "push constant 7\npop pointer 1\npush that 24572\npop temp 0\npush temp 0\nreturn";
    agree_on(body, 0, &[1, 2], &[true], &(0..8).collect::<Vec<_>>());
}

/// Desktop: a `that` index whose span cannot fit the desktop's range for
/// THAT (2048 to 24576) at any THAT: `that 22600` with THAT = 2048 stops
/// where the interpreter stops, with nothing read past RAM.
#[test]
fn a_that_index_past_the_desktops_range_agrees() {
    let body =
        "push constant 2048\npop pointer 1\npush that 22600\npop temp 0\npush temp 0\nreturn";
    agree_on(body, 0, &[1, 2], &[false], &(0..8).collect::<Vec<_>>());
}

/// `Main.f` of `body` after a function of `pad` statements, run on both
/// engines under each profile in `profiles` from each first budget in
/// `budgets` (then to the end): they agree.
fn agree_on(body: &str, pad: u16, args: &[i16], webs: &[bool], budgets: &[u64]) {
    let src = random_program(vec![body.to_string()], vec![], pad);
    agree_at_every_budget(&src, args, webs, budgets.iter().copied());
}

/// [`agree_on`] for `body` called with arguments 1 and 2, under both
/// profiles, its first budget each of `0..budgets`.
fn agree_at_each_stop(body: &str, budgets: u64) {
    agree_on(
        body,
        0,
        &[1, 2],
        &[false, true],
        &(0..budgets).collect::<Vec<_>>(),
    );
}

/// Locals that compiled code holds in registers across blocks (desktop):
/// RAM gets them wherever compiled code stops or leaves (every budget
/// inside the loop; a callee whose `Sys.wait` the interpreter runs, after
/// which `Main.h` is entered again through the dispatcher and reads them
/// back; a division by zero in the first block) and at its return; a stop
/// on `Main.h`'s `function` line leaves
/// the words under its locals as they were (nonzero, from `Main.f`'s
/// pushes), not as the line would zero them.
#[test]
fn held_locals_reach_ram_wherever_compiled_code_stops() {
    let src = format!(
        "function Main.main 0\npush constant 0\nreturn\n\
         function Main.f 0\n{}{}push argument 0\npush argument 1\ncall Main.h 2\nreturn\n\
         function Main.h 2\npush constant 0\npop local 0\nlabel LOOP\n\
         push local 0\npush argument 0\nadd\npop local 0\n\
         push local 1\npush constant 1\nadd\npop local 1\n\
         push local 1\npush constant 3\nlt\nif-goto LOOP\n\
         push local 0\ncall Main.k 1\npush local 0\nadd\npop local 1\npush local 1\nreturn\n\
         function Main.k 0\npush constant 1\ncall Sys.wait 1\npop temp 0\npush argument 0\nreturn\n",
        "push constant 11\n".repeat(12),
        "pop temp 0\n".repeat(12),
    );
    for budget in 0..90 {
        let case = EngineCase {
            src: src.clone(),
            args: vec![5, 7],
            web: false,
            budgets: vec![budget],
            hold: None,
            watched: None,
        };
        engines_agree(&case, Engine::Native, None)
            .unwrap_or_else(|e| panic!("first budget {budget}: {e}"));
    }
    // A leave in the first block, after the `function` line: a division
    // by zero, which the interpreter runs (and which ends the run). (The
    // branch keeps `Main.h` from running inline in `Main.f`.)
    let src = "function Main.main 0\npush constant 0\nreturn\n\
               function Main.f 0\npush argument 0\ncall Main.h 1\nreturn\n\
               function Main.h 1\npush constant 7\npop local 0\npush local 0\npush argument 0\n\
               call Math.divide 2\npop temp 0\npush constant 0\nif-goto X\nlabel X\n\
               push local 0\nreturn\n";
    let case = EngineCase {
        src: src.to_string(),
        args: vec![0, 0],
        web: false,
        budgets: vec![0],
        hold: None,
        watched: None,
    };
    engines_agree(&case, Engine::Native, None).expect("the engines agree");
}

/// ARG moved onto the locals (LCL + k, desktop; THAT set again, as the
/// desktop's THAT 0 is the interpreter's, and a block started where
/// compiled code can take over): `argument` accesses then reach
/// the words of locals that compiled code would hold in registers, so the
/// entry test must leave them to the interpreter.
#[test]
fn argument_words_on_held_locals_agree() {
    for k in 0..3 {
        let body = format!(
            "{}\npush constant 3000\npop pointer 1\ngoto HELD\nlabel HELD\n\
             push constant 8\npop local 0\npush argument 0\npop local 1\n\
             push constant 9\npop argument 1\npush local 0\npush local 1\nadd\npush local 2\nadd\nreturn",
            arg_beside_stack(k)
        );
        agree_on(&body, 0, &[1, 2], &[false], &[0]);
    }
}

/// ARG on the stack words a block keeps in registers (code whose stack
/// depths are static, where the function's entry test must see it): an
/// `argument` read of a word just pushed, and a write under a pushed word.
#[test]
fn argument_words_on_the_held_stack_agree() {
    for k in 0..6 {
        let body = format!(
            "{}\npush constant 5\npush constant 6\npush argument 0\npush argument 1\nadd\nadd\n\
             push constant 9\npop argument 1\nadd\npop local 0\npush local 0\nreturn",
            arg_beside_stack(k)
        );
        agree_on(&body, 0, &[1, 2], &[false, true], &[0]);
    }
}

/// A desktop built-in called from compiled code that moves SP out of the
/// stack: Main.f unlinks the heap's first block (capacity 0, next block 0),
/// so `Memory.alloc(n)` walks on to word 0, takes SP (261, the stack after
/// its argument) for the capacity, and for n = 259..=261 writes 0 there and
/// returns 2. The push of that 2 at SP = 0 writes SP itself and then fails
/// with "Stack overflow", leaving RAM[0] = 2, on both engines.
#[test]
fn a_desktop_built_in_that_moves_sp_to_zero_overflows_on_its_push() {
    for n in 259..=261 {
        let src = format!(
            "function Main.main 0\npush constant 0\nreturn\n\
             function Main.f 0\npush constant 0\npop constant 2048\npush constant 0\n\
             pop constant 2049\npush constant {n}\ncall Memory.alloc 1\nreturn\n"
        );
        let (m, exit) = native_call(&src, false);
        assert!(
            matches!(&exit, Exit::RuntimeError { message, .. } if message.starts_with("Stack overflow")),
            "{exit:?}"
        );
        assert_eq!(m.ram().read(0), 2);
        agree_at_every_budget(&src, &[], &[false], 0..10);
    }
}

/// An inline run holds the words it pushes after a nested call at their
/// depth after the call's result (web): Main.y, run inline in Main.f,
/// pushes 1 at 267, gets Main.z's 5 at 268, pushes 7 at 269 and pops it,
/// then reads 269 through `that`. The interpreter reads the 7 it left
/// there; compiled code must see that 269 is one of the run's words, not
/// read the saved LCL that Main.z's frame wrote there (the sum is 13).
#[test]
fn a_that_read_of_a_word_pushed_after_a_nested_call_agrees() {
    let src = "function Main.main 0\npush constant 0\nreturn\n\
               function Main.f 0\npush constant 269\ncall Main.y 1\nreturn\n\
               function Main.y 0\npush argument 0\npop pointer 1\npush constant 1\n\
               call Main.z 0\npush constant 7\npop temp 0\npush that 0\nadd\nadd\nreturn\n\
               function Main.z 0\npush constant 5\nreturn\n";
    returns_and_agrees(src, &[true], 13, 0..20);
}

/// Code with static stack depths that pops into its own frame, so that a
/// block's depth lies below LCL: Main.f (LCL 263) pops its three locals
/// and the saved THAT (or more), and `pop constant 3`, which compiled
/// code leaves to the interpreter, puts SP at 261 or below for the block
/// of `call Main.z 0`, run inline. SP there is LCL plus a negative depth:
/// compiled code once took the depth for an unsigned 16-bit offset, and
/// wrote the call's frame and Main.z's result 128 KB past RAM.
#[test]
fn a_block_whose_depth_lies_below_lcl_calls_where_the_interpreter_does() {
    for pops in 4..=6 {
        let body = format!(
            "{}pop constant 3\ncall Main.z 0",
            "pop temp 0\n".repeat(pops)
        );
        agree_at_each_stop(&body, 12);
    }
}

/// The entry test that `argument` words lie below the stack words held in
/// registers, where those lie below LCL: `pop constant 2` (left to the
/// interpreter) moves ARG to 262, just under LCL, and the next block pops
/// the locals and the saved THAT, pushes 5 at 262 and reads `argument 0`
/// there. The test's bound, LCL - 1, must not wrap to LCL + 65,535, under
/// which compiled code read the old word from RAM (5 + 0, not 5 + 5).
#[test]
fn argument_words_on_held_words_below_lcl_agree() {
    let body = format!(
        "push constant 262\npop constant 2\n{}push constant 5\npush argument 0\nadd\npop temp 1",
        "pop temp 0\n".repeat(4)
    );
    agree_at_each_stop(&body, 12);
}

/// The same where the block starts at LCL itself (Main.f has no locals):
/// its held words start at LCL - 1, where ARG now points.
#[test]
fn argument_words_on_held_words_below_lcl_from_lcl_agree() {
    let src = "function Main.main 0\npush constant 0\nreturn\n\
               function Main.f 0\npush constant 262\npop constant 2\npop temp 0\n\
               push constant 5\npush argument 0\nadd\npop temp 1\npush constant 0\nreturn\n";
    agree_at_every_budget(src, &[1, 2], &[false, true], 0..12);
}

/// The web's record that THAT was set (its "not initialized" error) kept
/// across blocks: Main.f sets THAT on one path only, so the loader keeps
/// the test on the `push that 0` after the paths meet, and compiled code
/// must carry the bit that its `pop pointer 1` set to that later block.
#[test]
fn a_pointer_set_in_one_block_counts_as_set_in_the_next() {
    let body = "push argument 0\nif-goto SET\ngoto B\nlabel SET\npush constant 3000\n\
                pop pointer 1\nlabel B\npush argument 0\nif-goto READ\npush constant 0\n\
                return\nlabel READ\npush that 0\nreturn";
    agree_on(body, 0, &[1, 2], &[true], &(0..20).collect::<Vec<_>>());
}

/// A block that pops below the depth it starts at holds that word too:
/// Main.f moves ARG to LCL + 1, then its block L pops local 2 and pushes
/// 5 in its place, which `argument 1` reads. A budget stop on L's first
/// line enters L through the function's entry test with ARG moved, so
/// the test must count the popped word among those held in registers;
/// else compiled code reads the word's old value from RAM.
#[test]
fn a_block_that_pops_below_its_start_holds_the_word_it_pops() {
    let body = format!(
        "{}\nlabel L\npop temp 0\npush constant 5\npush argument 1\nadd\n\
         pop local 0\npush local 0\nreturn",
        arg_beside_stack(1)
    );
    agree_at_each_stop(&body, 40);
}

/// An inline run reads its arguments from the caller's registers, not
/// from RAM, until something may have written them: Main.a's `that`
/// points at its own argument 1 (web), Main.b writes its argument 0, and
/// Main.c's nested Main.a writes Main.c's argument 1 before Main.c reads
/// it. Each returns what the interpreter does (99, 7 + 55, 99), with
/// every budget stop inside the runs.
#[test]
fn inline_runs_read_arguments_written_in_the_run() {
    // Main.f's stack starts at 261: the arguments of Main.a are at 261
    // and 262, those of Main.c at 262 and 263 (below them, the sum so
    // far). Argument 0 is the address of argument 1.
    let src = "function Main.main 0\npush constant 0\nreturn\n\
         function Main.f 0\npush constant 262\npush constant 55\ncall Main.a 2\n\
         push constant 3\npush constant 55\ncall Main.b 2\nadd\n\
         push constant 263\npush constant 55\ncall Main.c 2\nadd\nreturn\n\
         function Main.a 0\npush argument 0\npop pointer 1\npush constant 99\npop that 0\n\
         push argument 1\nreturn\n\
         function Main.b 0\npush constant 7\npop argument 0\npush argument 0\npush argument 1\n\
         add\nreturn\n\
         function Main.c 0\npush argument 0\npush argument 1\ncall Main.a 2\npop temp 0\n\
         push argument 1\nreturn\n"
        .to_string();
    let (m, exit) = native_call(&src, true);
    assert_eq!(exit, Exit::Returned(99 + 62 + 99));
    assert_eq!(m.compiled_steps(), m.steps() - 1, "inline runs, compiled");
    agree_at_every_budget(&src, &[], &[true], 0..60);
}

/// A guarded run (Main.h opens with a test and a branch to a `return`)
/// whose inline way reads, through THAT (web), a word its opening pushed
/// above SP: compiled code holds that word in a register, so its span
/// test must cover the opening's words too. Main.f's stack starts at 261:
/// the argument there, the frame at 262..=266, Main.h's LCL 267, where
/// its opening pushes 1 and then 2 (at 268), and `lt` leaves the
/// condition at 267; its inline way sets THAT to 268 and `push that 0`
/// reads the 2.
#[test]
fn a_guarded_runs_inline_way_reads_a_word_its_opening_pushed() {
    let src = "function Main.main 0\npush constant 0\nreturn\n\
         function Main.f 0\npush constant 1\ncall Main.h 1\nreturn\n\
         function Main.h 0\npush argument 0\npush constant 2\nlt\nif-goto LEAF\npush constant 0\n\
         return\nlabel LEAF\npush constant 268\npop pointer 1\npush that 0\nreturn\n"
        .to_string();
    let (_, exit) = native_call(&src, true);
    assert_eq!(exit, Exit::Returned(2));
    agree_at_every_budget(&src, &[], &[true], 0..12);
}

/// A guarded run whose opening sets THAT (Main.h: `pop pointer 1`), and
/// whose branch goes the host's way: the call through the host passes
/// the caller's THAT, and the caller reads through it after the return
/// (desktop, where a compiled call keeps the caller's registers): 5, not
/// the callee's word at 4000.
#[test]
fn a_guarded_run_that_goes_to_the_host_keeps_the_callers_pointers() {
    let src = "function Main.main 0\npush constant 0\nreturn\n\
         function Main.f 0\npush constant 3000\npop pointer 1\npush constant 5\npop that 0\n\
         push constant 4000\ncall Main.h 1\npop temp 0\npush that 0\nreturn\n\
         function Main.h 0\npush argument 0\npop pointer 1\npush that 0\nif-goto ONE\n\
         push constant 2\ncall Main.z 0\nadd\nreturn\nlabel ONE\npush constant 1\nreturn\n\
         function Main.z 0\npush constant 7\nreturn\n"
        .to_string();
    let (_, exit) = native_call(&src, false);
    assert_eq!(exit, Exit::Returned(5));
    agree_at_every_budget(&src, &[], &[false, true], 0..24);
}

/// A guarded run whose two ways both run inline, the first writing an
/// argument word (`pop argument 0`) and the second reading it: each way
/// starts from what the opening knew, so the second reads the caller's
/// argument (1, returned as 1), not the first way's value.
#[test]
fn each_way_of_a_guarded_run_starts_from_its_opening() {
    for (arg, expect) in [(1, 1), (3, 9)] {
        let src = format!(
            "function Main.main 0\npush constant 0\nreturn\n\
             function Main.f 0\npush constant {arg}\ncall Main.h 1\nreturn\n\
             function Main.h 0\npush argument 0\npush constant 2\nlt\nif-goto SMALL\n\
             push constant 9\npop argument 0\npush argument 0\nreturn\nlabel SMALL\n\
             push argument 0\nreturn\n"
        );
        for web in [false, true] {
            let (_, exit) = native_call(&src, web);
            assert_eq!(exit, Exit::Returned(expect), "{arg} web {web}");
        }
        agree_at_every_budget(&src, &[], &[false, true], 0..16);
    }
}

/// A recursion in Fibonacci's shape whose other way runs inline, its two
/// recursive calls nested guarded runs (their base case inline, else a
/// call through the host from inside the run), with a call of a looping
/// function through the host between them, and the way reached on the
/// desktop through the wasted step of a label followed by another:
/// `Main.f` returns fib(3).
const FIB_WITH_A_LOOP: &str = "function Main.main 0\npush constant 0\nreturn\n\
    function Main.f 0\npush constant 3\ncall Main.fib 1\nreturn\n\
    function Main.fib 0\npush argument 0\npush constant 2\nlt\nnot\nif-goto MORE\n\
    push argument 0\nreturn\nlabel MORE\nlabel REST\n\
    push argument 0\npush constant 1\nsub\ncall Main.fib 1\n\
    push argument 0\ncall Main.spin 1\nadd\n\
    push argument 0\npush constant 2\nsub\ncall Main.fib 1\nadd\nreturn\n\
    function Main.spin 1\npush argument 0\npop local 0\nlabel TOP\npush local 0\n\
    if-goto MORE\npush constant 0\nreturn\nlabel MORE\npush local 0\n\
    push constant 1\nsub\npop local 0\ngoto TOP\n";

/// [`FIB_WITH_A_LOOP`] for fib(2), without the loop: its whole way runs
/// inline, under the one budget test of its call, which counts the
/// wasted step.
fn fib_wholly_inline() -> String {
    let pure = FIB_WITH_A_LOOP
        .replace("push constant 3", "push constant 2")
        .replace("push argument 0\ncall Main.spin 1\nadd\n", "");
    assert_eq!(native_call(&pure, false).1, Exit::Returned(1), "fib(2)");
    pure
}

/// A recursion's way whose call through the host (Main.z, a loop where
/// its argument is over 100) is followed at once by a nested guarded run
/// that returns inline: the budget test after the first covers the
/// second's call, its run and the way's return.
const A_HOST_CALL_THEN_A_RUN: &str = "function Main.main 0\npush constant 0\nreturn\n\
    function Main.f 0\npush constant 3\ncall Main.r 1\nreturn\n\
    function Main.r 0\npush argument 0\npush constant 2\nlt\nif-goto BASE\n\
    push argument 0\npush constant 1\nsub\ncall Main.r 1\ncall Main.z 1\nreturn\n\
    label BASE\npush argument 0\nreturn\n\
    function Main.z 0\npush argument 0\npush constant 100\ngt\nif-goto BIG\n\
    push argument 0\npush constant 1\nadd\nreturn\nlabel BIG\nlabel L\n\
    push constant 0\nif-goto L\npush constant 0\nreturn\n";

/// The engines agree at every budget of [`FIB_WITH_A_LOOP`]'s whole run
/// (stops inside the run after each call through the host, and in the
/// callees), on both profiles, and with the loop's function watched; and
/// so do they on [`fib_wholly_inline`] and [`A_HOST_CALL_THEN_A_RUN`].
#[test]
fn a_recursions_other_way_inline_agrees_at_every_budget() {
    let src = FIB_WITH_A_LOOP;
    for web in [false, true] {
        let (m, exit) = native_call(src, web);
        assert_eq!(exit, Exit::Returned(2), "web {web}");
        assert!(m.steps() < 130, "the budgets below cover the whole run");
    }
    agree_at_every_budget(src, &[], &[false, true], 0..130);
    agree_at_every_budget(&fib_wholly_inline(), &[], &[false, true], 0..40);
    agree_at_every_budget(A_HOST_CALL_THEN_A_RUN, &[], &[false, true], 0..60);
    let program = Program::from_sources(&[("Main.vm", src)]).expect("it loads");
    let spin = program
        .functions()
        .iter()
        .position(|f| f.name == "Main.spin")
        .expect("Main.spin");
    for web in [false, true] {
        let case = EngineCase {
            src: src.to_string(),
            args: vec![],
            web,
            budgets: vec![0, 150],
            hold: None,
            watched: Some(1u8 << (spin % 7)),
        };
        if let Err(e) = engines_agree(&case, Engine::Native, None) {
            panic!("web {web}: {e}");
        }
    }
}

/// The budget tests of a recursion's run count its steps exactly, not
/// more: under a budget of the whole run's steps, compiled code runs as
/// many of them as it does with no budget (a test that counted more would
/// leave for the interpreter near the end).
#[test]
fn a_budget_that_covers_a_run_exactly_keeps_it_compiled() {
    let interpreted = |src: &str, web, budget| {
        let (m, exit) = native_call_within(src, web, budget);
        (exit, m.steps(), m.steps() - m.compiled_steps())
    };
    let wholly_inline = fib_wholly_inline();
    for src in [FIB_WITH_A_LOOP, &wholly_inline, A_HOST_CALL_THEN_A_RUN] {
        for web in [false, true] {
            let (exit, steps, free) = interpreted(src, web, None);
            assert!(matches!(exit, Exit::Returned(_)), "{exit}");
            let exact = interpreted(src, web, Some(steps));
            assert_eq!(exact, (exit, steps, free), "web {web}\n{src}");
        }
    }
}

/// Web: a recursion's other way run inline whose nested guarded runs go
/// the host's way, and one of those callees (Main.g, its loop) writes the
/// saved THAT of the run's frame through a pointer (RAM[266]: Main.f's
/// frame from 256, its argument, then the run's saved words): the run's
/// return takes THAT from that word, as the interpreter does (1234), not
/// from what the call saved.
#[test]
fn a_callee_through_the_host_may_write_the_frame_of_the_run_around_it() {
    let src = "function Main.main 0\npush constant 0\nreturn\n\
               function Main.f 0\npush constant 2\ncall Main.r 1\npop temp 0\npush pointer 1\n\
               return\n\
               function Main.r 0\npush argument 0\nif-goto MORE\npush constant 5\nreturn\n\
               label MORE\npush argument 0\npush constant 1\nsub\ncall Main.r 1\ncall Main.g 1\n\
               return\n\
               function Main.g 0\npush argument 0\nif-goto WRITE\npush constant 5\nreturn\n\
               label WRITE\npush constant 266\npop pointer 1\npush constant 1234\npop that 0\n\
               label LOOP\npush constant 0\n\
               if-goto LOOP\npush constant 6\nreturn\n";
    // The same write by callees called through the host themselves (no
    // guarded runs: Main.h writes before its first test, and Main.r's
    // base case holds a loop, so that only its other way runs inline).
    let direct = src.replace("call Main.g 1", "call Main.h 1").replace(
        "if-goto MORE\npush constant 5",
        "if-goto MORE\nlabel BASE\npush constant 0\nif-goto BASE\npush constant 5",
    )
        + "function Main.h 0\nlabel LOOP\npush constant 266\npop pointer 1\npush constant 1234\n\
           pop that 0\npush constant 0\nif-goto LOOP\npush argument 0\nreturn\n";
    for src in [src, direct.as_str()] {
        let (_, exit) = native_call(src, true);
        assert_eq!(exit, Exit::Returned(1234));
        agree_at_every_budget(src, &[], &[true], 0..80);
    }
}

/// Desktop: a recursion's other way run inline sets THAT with `pop
/// pointer 1` (tested there to lie in the desktop's range), then calls
/// Main.g (its loop) through the host, which writes the saved THAT of its
/// frame (a pop below its LCL, then a push) below the range: after the
/// call, the run's `push that 0` tests THAT again, as the interpreter
/// does, and stops with its error rather than read RAM[100].
#[test]
fn a_pointer_a_run_tested_is_tested_again_after_a_call_through_the_host() {
    let src = "function Main.main 0\npush constant 0\nreturn\n\
               function Main.f 0\npush constant 2\ncall Main.r 1\nreturn\n\
               function Main.r 0\npush argument 0\nif-goto MORE\npush constant 5\nreturn\n\
               label MORE\npush constant 3000\npop pointer 1\n\
               push constant 7\ncall Main.g 1\npop temp 0\npush that 0\n\
               push argument 0\npush constant 1\nsub\ncall Main.r 1\nadd\nreturn\n\
               function Main.g 0\nlabel LOOP\npush constant 0\nif-goto LOOP\n\
               pop temp 0\npush constant 100\npush constant 0\nreturn\n";
    let (_, exit) = native_call(src, false);
    assert!(matches!(exit, Exit::RuntimeError { .. }), "{exit}");
    agree_at_every_budget(src, &[], &[false], 0..90);
}

/// `Main.f` of `src` (a program of its own, not [`random_program`]'s)
/// called with no arguments on the compiled engine, under the web
/// profile or the desktop's: the machine after it, and its exit.
fn native_call(src: &str, web: bool) -> (Machine, Exit) {
    native_call_within(src, web, None)
}

/// [`native_call`] under `budget` steps (None: no budget).
fn native_call_within(src: &str, web: bool, budget: Option<u64>) -> (Machine, Exit) {
    let (program, config) = loaded(src, web, Engine::Native);
    let mut m = Machine::new(program, config);
    let exit = m.call("Main.f", &[], budget).expect("Main.f exists");
    (m, exit)
}

/// Both engines agree on `Main.f` of `src` called with `args`, under the
/// web profile where `webs` holds `true` and the desktop's where it holds
/// `false`, its first budget each of `budgets`.
fn agree_at_every_budget(
    src: &str,
    args: &[i16],
    webs: &[bool],
    budgets: impl IntoIterator<Item = u64> + Clone,
) {
    for &web in webs {
        for budget in budgets.clone() {
            let case = EngineCase {
                src: src.to_string(),
                args: args.to_vec(),
                web,
                budgets: vec![budget],
                hold: None,
                watched: None,
            };
            if let Err(e) = engines_agree(&case, Engine::Native, None) {
                panic!("web {web}, first budget {budget}: {e}");
            }
        }
    }
}

/// A called function (not run inline: it branches) that rewrites its
/// caller's saved THAT, by popping below its LCL and pushing over the
/// word, through the web's `that`, or by `pop constant` (Main.f calls it
/// with its frame at 263..=267): the caller's `push that 0` after the return
/// reads the word the new THAT points at, 22, not 11 at the old one: a
/// compiled call's return takes the caller's registers from the frame in
/// RAM, as the interpreter does, not from what the caller had.
#[test]
fn a_callee_that_rewrites_its_callers_saved_that_agrees() {
    let pop_below = "pop temp 0\npush constant 2200";
    let through_that = "push constant 267\npop pointer 1\npush constant 2200\npop that 0";
    let pop_constant = "push constant 2200\npop constant 267";
    for (rewrite, webs) in [
        (pop_below, &[false, true][..]),
        (through_that, &[true][..]),
        (pop_constant, &[false, true][..]),
    ] {
        let src = format!(
            "function Main.main 0\npush constant 0\nreturn\n\
             function Main.f 1\npush constant 2100\npop pointer 1\npush constant 11\npop that 0\n\
             push constant 2200\npop pointer 1\npush constant 22\npop that 0\n\
             push constant 2100\npop pointer 1\npush constant 7\ncall Main.x 1\npop temp 1\n\
             push that 0\nreturn\n\
             function Main.x 0\npush argument 0\nif-goto A\nlabel A\n{rewrite}\n\
             push constant 0\nreturn\n"
        );
        returns_and_agrees(&src, webs, 22, 0..40);
    }
}

/// `src`'s `Main.f` returns `value` on the compiled engine under each
/// profile of `webs`, and both engines agree from each first budget of
/// `budgets`.
fn returns_and_agrees(src: &str, webs: &[bool], value: i16, budgets: std::ops::Range<u64>) {
    for &web in webs {
        let (_, exit) = native_call(src, web);
        assert_eq!(exit, Exit::Returned(value), "web {web}");
        agree_at_every_budget(src, &[], &[web], budgets.clone());
    }
}

/// An inline callee (one straight block) that writes a word of its own
/// frame by `pop constant` (Main.f calls it with its frame at 263..=267:
/// its RET word, then the saved LCL, ARG, THIS and THAT): its return
/// reads the frame back from RAM, as the interpreter does, not the words
/// the call wrote.
#[test]
fn an_inline_callee_that_pops_into_its_own_frame_agrees() {
    for at in 263..=267 {
        let src = format!(
            "function Main.main 0\npush constant 0\nreturn\n\
             function Main.f 1\npush constant 2200\npop pointer 1\npush constant 22\npop that 0\n\
             push constant 2100\npop pointer 1\npush constant 7\ncall Main.y 1\npop temp 1\n\
             push that 0\nreturn\n\
             function Main.y 0\npush constant 2200\npop constant {at}\npush argument 0\nreturn\n"
        );
        agree_at_every_budget(&src, &[], &[false, true], 0..20);
    }
}

/// An inline callee that writes its own argument word (262, where Main.f
/// pushes it) by `pop constant`, and on the web by `Memory.poke`, then
/// pushes it: it reads 99 from RAM, not the 7 its caller's code holds.
#[test]
fn an_inline_callee_that_writes_its_argument_reads_it_back() {
    let pop = "push constant 99\npop constant 262";
    let poke = "push constant 262\npush constant 99\ncall Memory.poke 2\npop temp 0";
    for (write, webs) in [(pop, &[false, true][..]), (poke, &[true][..])] {
        let src = format!(
            "function Main.main 0\npush constant 0\nreturn\n\
             function Main.f 1\npush constant 7\ncall Main.y 1\nreturn\n\
             function Main.y 0\n{write}\npush argument 0\nreturn\n"
        );
        returns_and_agrees(&src, webs, 99, 0..12);
    }
}

/// Callees short enough to run inline that step outside their own words:
/// `Main.lo` reads `local 0` though it has no locals, which both profiles
/// stop on; `Main.pb` pops its frame's saved THAT into `temp 0` and pushes
/// over it before a nested call, so that its return brings back THAT = 1;
/// `Main.pa` calls `Main.add2` with two arguments it never pushed (its
/// frame's saved THIS and THAT: 2100 + 2200), and `Main.ps` calls
/// `Main.set2` with one argument pushed and the other its saved THAT,
/// which the callee's result then overwrites with 0, and `Main.pc`, after
/// a nested call of two arguments, pops one word more than it holds (its
/// saved THAT) and pushes 0 over it, as `Main.pd` does after a nested
/// call of none; `Main.po`'s nested `Main.wr` writes
/// 1 over `Main.po`'s saved THAT by `pop constant`. Both engines agree, under
/// both profiles, at every early budget: the inline runs may not assume
/// the words they skip.
#[test]
fn inline_callees_that_step_outside_their_words_agree() {
    let program = |calls: &str, f: &str| {
        format!(
            "function Main.main 0\npush constant 0\nreturn\n\
             function Main.f 1\npush constant 2200\npop pointer 1\n{calls}\nreturn\n{f}\n\
             function Main.z 0\npush constant 5\nreturn\n"
        )
    };
    let lo = program(
        "call Main.lo 0",
        "function Main.lo 0\npush constant 5\npush local 0\nadd\nreturn",
    );
    let pb = program(
        "call Main.pb 0\npop temp 2\npush pointer 1",
        "function Main.pb 0\npop temp 0\npush constant 1\ncall Main.z 0\nreturn",
    );
    let pa = program(
        "push constant 2100\npop pointer 0\ncall Main.pa 0",
        "function Main.pa 0\ncall Main.add2 2\nreturn\n\
         function Main.add2 0\npush argument 0\npush argument 1\nadd\nreturn",
    );
    let ps = program(
        "call Main.ps 0\npop temp 2\npush pointer 1",
        "function Main.ps 0\npush constant 9\ncall Main.set2 2\npush constant 4\nreturn\n\
         function Main.set2 0\npush constant 1\npop argument 1\npush constant 0\nreturn",
    );
    let pc = program(
        "call Main.pc 0\npop temp 2\npush pointer 1",
        "function Main.pc 0\npush constant 1\npush constant 2\ncall Main.add2 2\n\
         pop temp 0\npop temp 1\npush constant 0\nreturn\n\
         function Main.add2 0\npush argument 0\npush argument 1\nadd\nreturn",
    );
    let po = program(
        "call Main.po 0\npop temp 2\npush pointer 1",
        "function Main.po 0\ncall Main.wr 0\nreturn\n\
         function Main.wr 0\npush constant 1\npop constant 266\npush constant 0\nreturn",
    );
    let pd = program(
        "call Main.pd 0\npop temp 2\npush pointer 1",
        "function Main.pd 0\ncall Main.z 0\npop temp 0\npop temp 1\npush constant 0\nreturn",
    );
    let both = [false, true];
    for (src, value) in [
        (&pb, 1),
        (&pa, 4300),
        (&ps, 0),
        (&pc, 0),
        (&pd, 0),
        (&po, 1),
    ] {
        returns_and_agrees(src, &both, value, 0..24);
    }
    for web in both {
        let (_, exit) = native_call(&lo, web);
        assert!(
            matches!(exit, Exit::RuntimeError { .. }),
            "web {web}: {exit:?}"
        );
        agree_at_every_budget(&lo, &[], &[web], 0..24);
    }
}

/// An inline run whose first instruction is a nested call (on the web,
/// where the `function` line is no step): the budget test before the run
/// counts the call, the nested run and the return, so that a stop on each
/// step of it falls where the interpreter's does.
#[test]
fn budget_stops_in_a_run_that_opens_with_a_nested_call_agree() {
    let src = "function Main.main 0\npush constant 0\nreturn\n\
               function Main.f 0\npush constant 1\npop temp 0\ncall Main.o 0\nreturn\n\
               function Main.o 0\ncall Main.z 0\nreturn\n\
               function Main.z 0\npush constant 5\nreturn\n";
    agree_at_every_budget(src, &[], &[false, true], 0..10);
}

/// `this`/`that` accesses whose pointer changes inside the block, so that
/// one address test cannot cover them: a second `pop pointer 1` (to 24575,
/// whose `that 5` lies past RAM), a nested inline run whose return brings
/// back a THAT it wrote into its own frame (24575 again), and on the
/// desktop a `that` access after a `pop pointer 0` tested only THIS (THAT
/// left at 100, below the heap), and a `push this 0` after a `pop pointer
/// 1` tested only THAT (THIS set to 100 by `pop constant 3`, which the
/// desktop does not check). Both engines agree, at every early budget.
#[test]
fn pointer_accesses_after_the_pointer_changes_agree() {
    let main = "function Main.main 0\npush constant 0\nreturn\n";
    let repoint = format!(
        "{main}function Main.f 0\npush constant 3000\npop pointer 1\npush that 0\npop temp 0\n\
         push constant 24575\npop pointer 1\npush that 5\nreturn\n"
    );
    let nested = format!(
        "{main}function Main.f 1\npush constant 2200\npop pointer 1\ncall Main.oc 0\nreturn\n\
         function Main.oc 0\npush that 0\npop temp 0\ncall Main.wt 0\npop temp 1\npush that 3\nreturn\n\
         function Main.wt 0\npush constant 24575\npop constant 271\npush constant 0\nreturn\n"
    );
    let this_only = format!(
        "{main}function Main.f 0\npush constant 100\npop pointer 1\nlabel X\n\
         push constant 3000\npop pointer 0\npush that 0\nreturn\n"
    );
    let that_only = format!(
        "{main}function Main.f 0\npush constant 100\npop constant 3\nlabel X\n\
         push constant 3000\npop pointer 1\npush this 0\nreturn\n"
    );
    for (src, webs) in [
        (&repoint, &[false, true][..]),
        (&nested, &[false, true][..]),
        (&this_only, &[false][..]),
        (&that_only, &[false][..]),
    ] {
        agree_at_every_budget(src, &[], webs, 0..12);
    }
}

/// A recursion without end that calls, at every level, a callee short
/// enough to run inline whose run pushes ten words, adds them, and only
/// then makes a nested call (of `Main.z`, inline too): on the desktop that
/// run is what overflows the stack, and compiled code must leave for the
/// interpreter before it (the stack test counts the run's highest word,
/// which lies before its nested call), whichever word of the run the end
/// falls on.
#[test]
fn an_inline_run_at_the_stack_end_overflows_where_the_interpreter_does() {
    overflows_in_main_deep_where_the_interpreter_does(&format!(
        "push argument 0\n{}{}call Main.z 0\nadd\nreturn\n",
        "push constant 1\n".repeat(9),
        "add\n".repeat(9)
    ));
}

/// [`an_inline_run_at_the_stack_end_overflows_where_the_interpreter_does`]
/// with a guarded run: Main.deep opens with a test whose taken way pushes
/// ten words and returns, run inline; the call's stack test must count
/// that way's words above the opening's.
#[test]
fn a_guarded_run_at_the_stack_end_overflows_where_the_interpreter_does() {
    overflows_in_main_deep_where_the_interpreter_does(&format!(
        "push argument 0\nif-goto MANY\npush constant 0\ncall Main.z 0\nreturn\nlabel MANY\n\
         push argument 0\n{}{}return\n",
        "push constant 1\n".repeat(9),
        "add\n".repeat(9)
    ));
}

/// A desktop recursion without end (Main.r, 6 words a level) that calls
/// Main.deep, of body `deep`, at every level, from each alignment of its
/// frames with the stack's end: it stops with "Stack overflow", and the
/// engines agree on the way there.
fn overflows_in_main_deep_where_the_interpreter_does(deep: &str) {
    let src = |pad: usize| {
        format!(
            "function Main.main 0\npush constant 0\nreturn\n\
         function Main.f 0\n{}push constant 400\ncall Main.r 1\nreturn\n\
         function Main.r 0\npush argument 0\ncall Main.deep 1\npop temp 0\n\
         push argument 0\npush constant 1\nsub\ncall Main.r 1\nreturn\n\
         function Main.deep 0\n{deep}\
         function Main.z 0\npush constant 5\nreturn\n",
            "push constant 0\n".repeat(pad),
        )
    };
    for pad in 0..6 {
        let (_, exit) = native_call(&src(pad), false);
        assert!(
            matches!(&exit, Exit::RuntimeError { message, .. } if message.contains("Stack overflow")),
            "{exit:?}"
        );
        // (About 10,000 steps to the overflow.)
        agree_at_every_budget(&src(pad), &[], &[false], [0, 9000, 10010]);
    }
}

/// Web: a guarded run near the end of RAM, where the web's stack runs
/// out: the call's stack test must count the run's words (the opening's
/// and the ten of its returning way), or compiled code would push past
/// RAM, where the interpreter drops its writes and reads -1.
#[test]
fn a_guarded_run_at_the_end_of_ram_agrees() {
    let callee = format!(
        "function Main.gh 0\npush argument 0\nif-goto MANY\npush constant 0\ncall Main.z 0\n\
         return\nlabel MANY\npush argument 0\n{}{}return\n",
        "push constant 1\n".repeat(9),
        "add\n".repeat(9)
    );
    for sp in 24556..24578 {
        let body = format!(
            "{}push constant 1\ncall Main.gh 1\npop temp 0\npush temp 0\nreturn",
            sp_moved_to(sp)
        );
        let src = random_program(vec![body], vec![], 0) + &callee;
        agree_at_every_budget(&src, &[1, 2], &[true], [0, 1000]);
    }
}

/// A guarded run whose returning way is a lone `return` (of the desktop
/// callee's local), its other way a loop the host runs: the budget test
/// counts the opening's three steps and the return's, and a stop at each
/// step of the run agrees.
#[test]
fn budget_stops_in_a_guarded_run_agree() {
    let src = "function Main.main 0\npush constant 0\nreturn\n\
         function Main.f 0\npush constant 1\ncall Main.h 1\npush constant 1\ncall Main.h 1\nadd\n\
         return\n\
         function Main.h 1\npush argument 0\nif-goto BASE\nlabel SPIN\ngoto SPIN\n\
         label BASE\nreturn\n";
    let (_, exit) = native_call(src, false);
    assert_eq!(exit, Exit::Returned(0));
    agree_at_every_budget(src, &[], &[false], 0..16);
}

/// Callees that each call the next one eight times, nine levels deep, all
/// short enough to run inline: inlining them all would translate 8^8
/// copies of the last; the bound on an inline run's size keeps the
/// compile small, and the engines agree on the first few thousand steps.
#[test]
fn a_wide_tree_of_inline_calls_compiles_within_its_bound() {
    let mut src = String::from(
        "function Main.main 0\npush constant 0\nreturn\n\
         function Main.f 0\npush constant 3\ncall Main.t0 1\nreturn\n",
    );
    for k in 0..8 {
        let call = format!("push argument 0\ncall Main.t{} 1\nadd\n", k + 1);
        src += &format!(
            "function Main.t{k} 0\npush argument 0\n{}return\n",
            call.repeat(8)
        );
    }
    src += "function Main.t8 0\npush argument 0\nreturn\n";
    agree_at_every_budget(&src, &[], &[false, true], [0, 100, 2000]);
}

/// A block of 1,791 pushes, the whole desktop stack less one word,
/// entered with SP one word too high (code whose depths are not static,
/// where each block tests its stack): the last push overflows.
#[test]
fn a_block_as_long_as_the_stack_overflows_at_its_last_push() {
    let unsettled = "push constant 0\nif-goto X\npush constant 1\nlabel X";
    for (sp, pushes) in [(257, 1791), (256, 1791), (256, 1792), (258, 1790)] {
        let body = format!(
            "{unsettled}\npush constant {sp}\npop constant 0\n{}pop temp 0",
            "push constant 1\n".repeat(pushes)
        );
        agree_on(&body, 0, &[0, 0], &[false], &[0]);
    }
}

/// Code with static depths whose stack range is longer than the desktop's
/// stack (1,793 words from LCL with its three locals, against 1,792 from
/// 256): the function's entry test cannot pass, so the pushes run
/// interpreted and overflow at the stack's end.
#[test]
fn static_depths_deeper_than_the_stack_overflow_where_the_interpreter_does() {
    let body = format!("{}pop temp 0", "push constant 1\n".repeat(1790));
    agree_on(&body, 0, &[0, 0], &[false], &[0]);
}

/// A compiled call at the stack's base into a function that pops one word
/// past its frame: Main.f pops everything down to SP = 256 and calls
/// Main.x (not inline: a jump), whose sixth pop would read word 255. The
/// call's own entry test must see that Main.x reaches below its frame and
/// make the whole test, so both engines stop at that pop.
#[test]
fn a_called_function_that_pops_below_its_frame_stops_where_the_interpreter_does() {
    let src = format!(
        "function Main.main 0\npush constant 0\nreturn\n\
         function Main.f 3\n{}call Main.x 0\nreturn\n\
         function Main.x 0\ngoto A\nlabel A\n{}push constant 0\nreturn\n",
        "pop temp 0\n".repeat(10),
        "pop temp 0\n".repeat(6)
    );
    agree_at_every_budget(&src, &[1, 2], &[false, true], 0..24);
}

/// Budget stops in a function that starts deep in the program, on every
/// step of a path that falls through into a block which does not test the
/// budget (a forward jump's target), and of the code after a call, under
/// both profiles.
#[test]
fn budget_stops_deep_in_the_program_agree() {
    let body = format!(
        "push constant 0\nif-goto X\n{}label X\n{}push constant 2\ncall Main.r 1\npop temp 2\n{}push constant 1",
        "push constant 1\npop temp 0\n".repeat(10),
        "push constant 2\npop temp 1\n".repeat(10),
        "push constant 3\npop temp 3\n".repeat(10)
    );
    let budgets: Vec<u64> = (1..90).collect();
    agree_on(&body, 300, &[0, 0], &[false, true], &budgets);
}

/// Inline runs nested in inline runs, under both profiles: Main.n's
/// getter, setter and method, the chain Main.c -> Main.d -> Main.g with
/// Main.z on the way, and Main.v's Main.w writing a word `k` above
/// Main.f's SP: Main.v's RET word (its return goes to the interpreter),
/// its saved ARG (its caller goes on in the interpreter), a word of
/// Main.v's stack, or Main.w's RET word (compiled code leaves inside the
/// nested run); last, Main.n of THIS 0, whose Main.s leaves compiled code
/// (on the desktop) after Main.g's nested return. With Main.w's
/// RET word, budget stops fall on every step, with no function watched
/// and with Main.g watched (compiled code leaves at its call, nested two
/// deep).
#[test]
fn stops_inside_nested_inline_runs_agree() {
    let body = |k: u16| {
        format!(
            "push constant 3000\npush constant 7\ncall Main.n 2\npop temp 0\n\
             push constant 9\ncall Main.c 1\npop temp 1\n\
             push constant 0\npop pointer 1\npush that 0\npush constant {k}\nadd\n\
             push constant 77\ncall Main.v 2\npop temp 2\n\
             push constant 0\npush constant 7\ncall Main.n 2\npop temp 3"
        )
    };
    for k in [2, 4, 8] {
        agree_on(&body(k), 0, &[0, 0], &[false, true], &[0]);
    }
    let src = random_program(vec![body(9)], vec![], 0);
    let program = Program::from_sources(&[("Main.vm", src.as_str())]).expect("it loads");
    let id = |name: &str| {
        program
            .functions()
            .iter()
            .position(|f| f.name == name)
            .expect("a function of the program")
    };
    // (The watch set names functions by id modulo 7: none on the way.)
    let g = id("Main.g");
    assert!(["Main.c", "Main.d", "Main.z"]
        .iter()
        .all(|f| id(f) % 7 != g % 7));
    for watched in [None, Some(1u8 << (g % 7))] {
        for web in [false, true] {
            for budget in 0..90 {
                let case = EngineCase {
                    src: src.clone(),
                    args: vec![0, 0],
                    web,
                    budgets: vec![budget],
                    hold: None,
                    watched,
                };
                if let Err(e) = engines_agree(&case, Engine::Native, None) {
                    panic!("web {web}, watched {watched:?}, first budget {budget}: {e}");
                }
            }
        }
    }
}

/// A recursion (Main.q) that runs the nested chain Main.c -> Main.d ->
/// Main.g at each of its 300 levels, past the frame stack's first
/// capacity and the bound on compiled nesting (and, on the desktop, past
/// the stack's end), with Main.g watched or not: compiled calls stop where
/// the frames of every nested run would not fit.
#[test]
fn a_deep_recursion_through_nested_inline_runs_agrees() {
    let src = random_program(
        vec!["push constant 300\ncall Main.q 1\npop temp 0".to_string()],
        vec![],
        0,
    );
    let program = Program::from_sources(&[("Main.vm", src.as_str())]).expect("it loads");
    let g = program
        .functions()
        .iter()
        .position(|f| f.name == "Main.g")
        .expect("Main.g");
    for watched in [None, Some(1u8 << (g % 7))] {
        for web in [false, true] {
            let case = EngineCase {
                src: src.clone(),
                args: vec![0, 0],
                web,
                budgets: vec![0, 5000],
                hold: None,
                watched,
            };
            if let Err(e) = engines_agree(&case, Engine::Native, None) {
                panic!("web {web}, watched {watched:?}: {e}");
            }
        }
    }
}

/// A recursion whose last level calls a chain of three callees that run
/// inline, the innermost dividing by zero: compiled code leaves inside the
/// chain and writes the frame-stack entries of all three. Over depths
/// around the bound on compiled nesting (256 frames), one of them puts the
/// chain's last frame on the bound: the outermost call must count all
/// three frames in its room test (the machine checks that no leave wrote
/// past the limit), and the engines agree on the error and its stack.
#[test]
fn a_leave_inside_nested_inline_runs_at_the_nesting_bound_agrees() {
    for depth in 250..262 {
        let src = format!(
            "function Main.main 0\npush constant 0\nreturn\n\
             function Main.f 0\npush constant {depth}\ncall Main.q 1\nreturn\n\
             function Main.q 0\npush argument 0\nif-goto MORE\npush constant 0\ncall Main.c 1\n\
             return\nlabel MORE\npush argument 0\npush constant 1\nsub\ncall Main.q 1\nreturn\n\
             function Main.c 0\npush argument 0\ncall Main.d 1\nreturn\n\
             function Main.d 0\npush argument 0\ncall Main.e 1\nreturn\n\
             function Main.e 0\npush constant 1\npush argument 0\ncall Math.divide 2\nreturn\n"
        );
        for web in [false, true] {
            let (_, exit) = native_call(&src, web);
            assert!(
                matches!(exit, Exit::SysError { .. } | Exit::RuntimeError { .. }),
                "{exit:?}"
            );
            agree_at_every_budget(&src, &[], &[web], [0]);
        }
    }
}

/// Compiled calls nest at most 256 deep on the host's stack: in a
/// recursion 1,000 deep, every 256th call is left to the interpreter, and
/// compiled code is entered again above it, so that the host's stack holds
/// at most 256 compiled frames whatever the VM's depth. Each compiled call
/// of Main.r runs its callee's other way inline, the recursive call in it,
/// so it needs room for two frames: at the first two bounds, which are
/// also the frame stack's capacity (256, then 512), the call one frame
/// above the bound goes to the interpreter too (depths 200, 256, 600 and
/// 1,000 interpret 1, 3, 5 and 6 steps).
#[test]
fn compiled_calls_nest_at_most_256_deep() {
    let src = "function Main.main 0\npush constant 0\nreturn\n\
               function Main.r 0\npush argument 0\nif-goto MORE\npush constant 0\nreturn\n\
               label MORE\npush argument 0\npush constant 1\nsub\ncall Main.r 1\n\
               push constant 1\nadd\nreturn\n";
    let program = Program::from_sources(&[("Main.vm", src)]).expect("it loads");
    let config = Config {
        profile: hack_vm::Profile::Web,
        engine: Engine::Native,
        ..Config::default()
    };
    let mut m = Machine::new(program, config);
    let exit = m.call("Main.r", &[1000], None).expect("Main.r exists");
    assert_eq!(exit, Exit::Returned(1000));
    // The calls 255, 256, 511, 512 and 768 levels down, and the last
    // return, to the host.
    assert_eq!(m.steps() - m.compiled_steps(), 6);
}

/// A one-operand operator (`neg`, `not`) on an empty stack pops below
/// word 256, and a desktop static past RAM[255] lies in the stack: each
/// fails, or writes a stack word the block has pushed, as the interpreter
/// has it, on the compiled engine too.
#[test]
fn stack_edges_of_operators_and_statics_agree() {
    for op in ["neg", "not"] {
        let src = format!("{op}\n");
        for profile in [hack_vm::Profile::Desktop, hack_vm::Profile::Web] {
            let (interp, native) = on_both_engines(&src, profile, 10);
            let failed = matches!(interp.0, Exit::RuntimeError { .. });
            assert!(failed, "{op} {profile:?}: {}", interp.0);
            assert_eq!(native, interp, "{op} {profile:?}");
        }
    }
    // Main.f's stack starts at 261 (desktop): its sixth push lands on
    // RAM[266], static 250's word, which `pop static 250` then writes.
    let body = "push constant 1\npush constant 2\npush constant 3\npush constant 4\n\
                push constant 5\npush constant 6\npush constant 99\npop static 250\n\
                add\nadd\nadd\nadd\nadd\npop temp 0";
    agree_on(body, 0, &[0, 0], &[false], &[0, 3, 7]);
}

/// Commands that push k - 2 as a word, by a sum past 65535 (32767 + 32767
/// + k).
fn wrapped_word(k: u16) -> String {
    format!("push constant 32767\npush constant 32767\nadd\npush constant {k}\nadd")
}

/// Compiled code computes words in 32-bit registers, where a sum can pass
/// 65535 (32767 + 32767 + k is k - 2 as a word): every use that needs the
/// word itself sees its low 16 bits, as the interpreter's 16-bit
/// arithmetic has it: a branch on a sum that is 0 as a word, comparisons
/// (signed, equal), a division by such a zero (an error) and by such a 1,
/// `Math.abs`, `min` and `max` of -2 made so, and a pointer set from such
/// a sum and passed to a compiled call (stopped inside it at every
/// budget, so the callee's registers reach the context).
#[test]
fn words_past_sixteen_bits_agree() {
    let bodies = [
        format!("{}\nif-goto WRAP\npush constant 7\npop temp 0\nlabel WRAP", wrapped_word(2)),
        format!("{}\npush constant 0\neq\npop temp 0", wrapped_word(2)),
        format!("{}\npush constant 2\nlt\npop temp 1\n{}\npush constant 0\ngt\npop temp 2", wrapped_word(3), wrapped_word(3)),
        format!("push constant 5\n{}\ncall Math.divide 2\npop temp 0", wrapped_word(2)),
        format!("push constant 5\n{}\ncall Math.divide 2\npop temp 0\n{}\npush constant 1\ncall Math.divide 2\npop temp 1", wrapped_word(3), wrapped_word(4)),
        format!("{}\ncall Math.abs 1\npop temp 0", wrapped_word(0)),
        format!("{}\npush constant 1\ncall Math.min 2\npop temp 0\npush constant 1\n{}\ncall Math.max 2\npop temp 1", wrapped_word(0), wrapped_word(0)),
        format!("push constant 3000\npop pointer 1\n{}\npop pointer 0\npush constant 3\ncall Main.r 1\npop temp 0", wrapped_word(3)),
        format!("push constant 3000\npop pointer 0\n{}\npop pointer 1\npush constant 3\ncall Main.r 1\npop temp 0", wrapped_word(4)),
    ];
    for body in &bodies {
        agree_on(
            body,
            0,
            &[0, 0],
            &[false, true],
            &(0..40).step_by(3).collect::<Vec<_>>(),
        );
    }
}

/// A branch on comparisons combined by `not`, `and` and `or` (as Jack
/// writes a loop's test), for every pair of outcomes: the branch goes the
/// interpreter's way, and the words stay in RAM as it leaves them.
#[test]
fn branches_on_combined_comparisons_agree() {
    for combine in ["and", "or"] {
        for (not_a, not_b, not_both) in [
            (false, false, false),
            (true, true, false),
            (true, true, true),
            (false, false, true),
            (true, false, false),
        ] {
            let not = |n: bool| if n { "not\n" } else { "" };
            let body = format!(
                "push argument 0\npush constant 0\ngt\n{}push argument 1\npush constant 0\nlt\n{}\
                 {combine}\n{}if-goto TAKEN\npush constant 1\npop temp 0\ngoto END\n\
                 label TAKEN\npush constant 2\npop temp 0\nlabel END",
                not(not_a),
                not(not_b),
                not(not_both)
            );
            for args in [[0, 0], [1, 0], [0, -1], [1, -1]] {
                agree_on(&body, 0, &args, &[false], &[1000]);
            }
        }
    }
}

/// A web `that` access onto a stack word that the block holds in a
/// register, past the first one: the block pushes three words from SP = S
/// with THAT at S + 2 (S read through RAM[0] before it, by the interpreter,
/// after which a `goto` enters the block compiled), and its `push that 0`
/// reads the third, 33, not the 99 that RAM had there.
#[test]
fn a_that_read_of_the_third_held_stack_word_agrees() {
    let body = "push constant 99\npush constant 99\npush constant 99\n\
                pop temp 5\npop temp 6\npop temp 7\n\
                push constant 0\npop pointer 1\npush that 0\npop temp 0\ngoto HELD\n\
                label HELD\npush temp 0\npush constant 2\nadd\npop pointer 1\n\
                push constant 11\npush constant 22\npush constant 33\npush that 0\n\
                pop temp 1\npop temp 2\npop temp 3\npop temp 4";
    agree_on(body, 0, &[0, 0], &[true], &[1000]);
}

/// Code whose stack depths are not fixed (here before any `function`
/// line) tests the stack in each block: SP set to 2040 by `pop constant 0`,
/// a block of ten pushes overflows the desktop's stack (it ends at 2047)
/// at the same push on both engines, and on the web (whose stack runs on)
/// both finish.
#[test]
fn a_block_past_the_stack_end_overflows_where_depths_are_not_fixed() {
    let src = format!(
        "push constant 2040\npop constant 0\ngoto B\nlabel B\n{}label END\ngoto END\n",
        "push constant 1\n".repeat(10)
    );
    for profile in [hack_vm::Profile::Desktop, hack_vm::Profile::Web] {
        let (interp, native) = on_both_engines(&src, profile, 100);
        let failed = matches!(interp.0, Exit::RuntimeError { .. });
        assert_eq!(
            failed,
            profile == hack_vm::Profile::Desktop,
            "{profile:?}: {}",
            interp.0
        );
        assert_eq!(native, interp, "{profile:?}");
    }
}

/// How program `src` ends from its start within `budget` steps, and after
/// how many, on the interpreter and on the compiled engine.
fn on_both_engines(
    src: &str,
    profile: hack_vm::Profile,
    budget: u64,
) -> ((Exit, u64), (Exit, u64)) {
    let program = Program::from_sources(&[("Main.vm", src)]).expect("it loads");
    let run = |engine| {
        let config = Config {
            profile,
            engine,
            ..Config::default()
        };
        let mut m = Machine::new(program.clone(), config);
        let exit = m.run(Some(budget));
        (exit, m.steps())
    };
    (run(Engine::Interp), run(Engine::Native))
}

/// A call near the desktop stack's end of a callee run inline, which
/// pushes, adds and pushes again before its nested call: its highest
/// stack word is counted exactly, so wherever the run fits it runs
/// compiled (only the entry's last return is interpreted), with the same
/// result as the interpreter; 1,772 words pushed first and it overflows
/// on both engines.
#[test]
fn an_inline_run_near_the_stack_end_runs_where_it_fits() {
    for k in 1760..=1773 {
        let src = format!(
            "function Main.main 0\npush constant 0\nreturn\n\
             function Main.f 0\n{}push constant 5\ncall Main.p 1\npop temp 0\n{}\
             push constant 0\nreturn\n\
             function Main.p 0\npush argument 0\npush constant 3\nadd\npush argument 0\n\
             call Main.g 2\nreturn\n\
             function Main.g 0\npush argument 0\npush argument 1\nsub\nreturn\n",
            "push constant 1\n".repeat(k),
            "pop temp 1\n".repeat(k)
        );
        let program = Program::from_sources(&[("Main.vm", src.as_str())]).expect("it loads");
        let run = |engine| {
            let config = Config {
                engine,
                ..Config::default()
            };
            let mut m = Machine::new(program.clone(), config);
            let exit = m.call("Main.f", &[], None).expect("Main.f exists");
            (exit, m.steps(), m.steps() - m.compiled_steps())
        };
        let (interp, native) = (run(Engine::Interp), run(Engine::Native));
        assert_eq!(native.0, interp.0, "{k} pushed");
        assert_eq!(native.1, interp.1, "{k} pushed");
        if k <= 1771 {
            assert_eq!(native.2, 1, "{k} pushed: steps interpreted");
        } else {
            assert!(
                matches!(interp.0, Exit::RuntimeError { .. }),
                "{k}: {}",
                interp.0
            );
        }
    }
}

/// Built-ins called from compiled code where the interpreter's rules
/// decide: a `Memory.poke` of each register (of SP too, so that the
/// built-in's push lands where SP then says: a register, the stack's end,
/// past RAM), `Memory.peek` and `poke` at the ends of the words they may
/// touch, a host-called built-in that moves SP out of the stack, a
/// built-in's error, and built-ins with SP at either end of the stack,
/// under both profiles, with budget stops on the way.
#[test]
fn builtins_that_move_registers_or_stop_agree() {
    let budgets = [0, 3, 5];
    for a in 0..5 {
        for v in [0, 1, 2, 3, 4, 256, 2047, 24577] {
            let body = format!(
                "push constant 7\npush constant {a}\npush constant {v}\ncall Memory.poke 2\n\
                 pop temp 0\npush constant 3\ncall Math.abs 1\npop temp 1"
            );
            agree_on(&body, 0, &[1, 2], &[false, true], &budgets);
        }
    }
    let unsettled = "push constant 0\nif-goto X\npush constant 1\nlabel X";
    for sp in [256, 257, 258, 2039, 2040, 2041, 2042, 2045, 2046, 2047] {
        let body = format!(
            "{unsettled}\npush constant {sp}\npop constant 0\npush constant 9\npush constant 4\n\
             call Math.max 2\npop temp 0\npush constant 5\ncall Output.printChar 1\npop temp 1"
        );
        agree_on(&body, 0, &[0, 0], &[false, true], &budgets);
    }
    // Memory.peek and poke at each end of the words they may touch (the
    // heap and the screen on the desktop, which stops outside them; any
    // word on the web).
    for a in [0, 4, 5, 2047, 2048, 24576, 24577, 32767] {
        let body = format!(
            "push constant {a}\npush constant 9\ncall Memory.poke 2\npop temp 0\n\
             push constant {a}\ncall Memory.peek 1\npop temp 1"
        );
        agree_on(&body, 0, &[0, 0], &[false, true], &[0]);
    }
    // A host-called built-in that moves SP out of the stack (the web's
    // `setCharAt` of a string whose characters lie at word 0 writes SP):
    // its result is pushed into LCL, ARG, THIS or THAT (set to other values
    // first), at RAM[5000], over the 7 there, at RAM's last word, and past
    // RAM (nowhere), and the web's stack runs on without an overflow.
    for sp in [1, 2, 3, 4, 5000, 24576, 24577] {
        let body = format!(
            "push constant 77\npop pointer 0\npush constant 88\npop pointer 1\n\
             push constant 7\npop constant 5000\npush constant 5\npop constant 3001\n\
             push constant 0\npop constant 3002\npush constant 3000\npush constant 0\n\
             push constant {sp}\ncall String.setCharAt 3\npop temp 0"
        );
        agree_on(&body, 0, &[0, 0], &[true], &budgets);
    }
    for error in [
        "push constant 1\nneg\ncall Math.sqrt 1",
        "push constant 3\ncall Sys.error 1",
    ] {
        let body = format!("push constant 1\npop temp 0\n{error}\npop temp 1\npush constant 2");
        agree_on(&body, 0, &[0, 0], &[false, true], &budgets);
    }
}

/// `String.length`, `charAt` and `appendChar`, which compiled code runs
/// itself, on strings laid out by hand at the ends of the words a built-in
/// may touch (each profile's layout: the web's char array at `RAM[s+2]`,
/// here also one whose next char is the length word itself), with lengths
/// and indexes at and past their bounds (ERR15, ERR17, ERR16 on the web
/// once the length wraps).
#[test]
fn string_built_ins_at_their_edges_agree() {
    let push = |v: i32| {
        if v < 0 {
            format!("push constant {}\nneg", -v)
        } else {
            format!("push constant {v}")
        }
    };
    // The desktop's Memory.poke stops outside the heap and the screen:
    // there the word stays 0.
    let poke = |web: bool, a: i32, v: i32| {
        if web || (2048..=24576).contains(&a) {
            format!("{}\n{}\ncall Memory.poke 2\npop temp 0\n", push(a), push(v))
        } else {
            String::new()
        }
    };
    // Each profile's edges: the web's plain words start at 5 and end at
    // 24576; the desktop's heap and screen start at 2048. The web's char
    // array at 3000, under the length word, and at or past the end.
    let cases = [
        (true, [4, 3000, 24574, 24575, 24576]),
        (false, [2046, 2047, 3000, 24575, 24576]),
    ];
    for (web, s) in cases.into_iter().flat_map(|(web, at)| at.map(|s| (web, s))) {
        for (len, cap) in [(0, 0), (2, 3), (2, 2), (7, 9), (-1, 4), (32767, -1)] {
            let arrays = if web {
                vec![3000, s + 1 - len, 24576 - len, 24577 - len]
            } else {
                vec![3000]
            };
            for array in arrays {
                let layout = poke(web, s, cap) + &poke(web, s + 1, len) + &poke(web, s + 2, array);
                let char_at = |i: i32| format!("{}\n{}\ncall String.charAt 2\n", push(s), push(i));
                // An error ends the run: the reads that may pass run first,
                // and each that must fail in a run of its own.
                let last = if len > 0 {
                    char_at(len - 1) + "pop temp 1\n"
                } else {
                    String::new()
                };
                let passing = format!(
                    "{last}{0}\ncall String.length 1\npop temp 2\n{0}\n\
                     push constant 77\ncall String.appendChar 2\npop temp 3\n{0}\n\
                     call String.length 1",
                    push(s)
                );
                for body in [passing, char_at(-1), char_at(len)] {
                    agree_on(&(layout.clone() + &body), 0, &[0, 0], &[web], &[0]);
                }
            }
        }
    }
}

#[test]
fn a_broken_translation_is_caught() {
    // Most seeds find a wrong `sub` within 256 cases, not all: the runner
    // stops at the first failure, so a large bound costs nothing when the
    // test passes and makes a miss vanishingly rare. The failing case is
    // not shrunk: only whether there is one matters here, and shrinking
    // took three quarters of the test's time.
    let mut runner = proptest::test_runner::TestRunner::new(ProptestConfig {
        cases: 4096,
        max_shrink_iters: 0,
        failure_persistence: None,
        ..ProptestConfig::default()
    });
    let found = runner.run(&engine_case(), |case| {
        engines_agree(&case, Engine::NativeBrokenSub, None)
    });
    assert!(found.is_err(), "a wrong `sub` went unnoticed");
}

/// One VM command of the random programs.
fn command() -> impl Strategy<Value = String> {
    let value = prop_oneof![
        0u16..8,
        250u16..262,
        // The desktop's stack ends at 2047 ("Stack overflow" past it).
        2040u16..2050,
        3000u16..3004,
        16380u16..16390,
        24570u16..24578,
        Just(32767)
    ];
    let seg = prop::sample::select(vec!["local", "argument", "this", "that", "temp", "static"]);
    prop_oneof![
        4 => value.clone().prop_map(|v| format!("push constant {v}")),
        3 => (seg.clone(), 0u16..4).prop_map(|(s, i)| format!("push {s} {i}")),
        3 => (seg.clone(), 0u16..4).prop_map(|(s, i)| format!("pop {s} {i}")),
        1 => (0u16..2).prop_map(|p| format!("push pointer {p}")),
        // An index past the span tests: with the pointer at 0..5, a word at
        // the top of RAM, where SP may stand (a value below).
        1 => (prop::sample::select(vec!["push", "pop"]), prop::sample::select(vec!["this", "that"]), 24570u16..24577)
            .prop_map(|(op, s, i)| format!("{op} {s} {i}")),
        2 => (0u16..2).prop_map(|p| format!("pop pointer {p}")),
        1 => value.clone().prop_map(|v| format!("pop constant {}", v % 6)),
        4 => prop::sample::select(vec!["add", "sub", "neg", "eq", "gt", "lt", "and", "or", "not"]).prop_map(String::from),
        1 => prop::sample::select(vec!["call Math.multiply 2", "call Math.divide 2", "call Math.abs 1", "call Main.g 1", "call Main.g 2", "call Main.m 1", "call Main.m 2", "call Main.r 1", "call Main.s 2", "call Main.w 2", "call Main.n 2", "call Main.n 1", "call Main.c 1", "call Main.v 2", "call Main.ga 1", "call Main.ga 2", "call Main.gb 1", "call Main.gc 1"]).prop_map(String::from),
        // Built-ins, which compiled code calls through the host: reads and
        // writes of any word, the heap, strings, the screen, an error.
        2 => prop::sample::select(vec![
            "call Memory.peek 1", "call Memory.poke 2", "call Math.min 2", "call Math.max 2",
            "call Math.sqrt 1", "call Memory.alloc 1", "call Array.new 1", "call String.new 1",
            "call String.length 1", "call String.appendChar 2", "call String.charAt 2",
            "call Output.printChar 1",
            "call Output.printInt 1", "call Screen.drawPixel 2", "call Keyboard.keyPressed 0",
            "call Sys.error 1",
        ]).prop_map(String::from),
        // A string built and read (compiled code runs these built-ins
        // itself): appends past its capacity (ERR17), a char inside or
        // past its length (ERR15).
        1 => (0u16..4, 0u16..5, 0u16..5).prop_map(|(cap, n, i)| {
            let appends: String = (0..n)
                .map(|k| format!("push temp 5\npush constant {}\ncall String.appendChar 2\npop temp 6\n", 65 + k))
                .collect();
            format!(
                "push constant {cap}\ncall String.new 1\npop temp 5\n{appends}push temp 5\n\
                 push constant {i}\ncall String.charAt 2\npush temp 5\ncall String.length 1\nadd"
            )
        }),
        // A string whose words are the stack's (SP read through RAM[0]):
        // its length and chars are words compiled code holds in registers.
        1 => (1u16..6, prop::bool::ANY).prop_map(|(k, append)| format!(
            "push constant 0\npop pointer 1\npush that 0\npush constant {k}\nsub\n{}",
            if append { "push constant 66\ncall String.appendChar 2" } else { "call String.length 1" }
        )),
        // ARG moved onto the stack, k words above SP (read through RAM[0]),
        // then an operation on an argument and a word that may be 0: the
        // second push may overwrite the argument the first one read.
        1 => (prop::sample::select(vec![(1, 0), (0, 1), (2, 0), (0, 2)]),
              prop::sample::select(vec!["constant 0", "temp 0", "local 0"]),
              prop::sample::select(vec!["call Math.divide 2", "call Math.multiply 2", "lt"]))
            .prop_map(|((k, j), d, op)| format!(
                "push constant 0\npop pointer 1\npush that 0\npush constant {k}\nadd\npop constant 2\n\
                 push argument {j}\npush {d}\n{op}"
            )),
        // A poke of a register (SP, LCL, ARG, THIS, THAT) or a word near them.
        1 => (0u16..7, value).prop_map(|(a, v)| format!(
            "push constant {a}\npush constant {v}\ncall Memory.poke 2"
        )),
        // A write k words above SP (read through RAM[0]) by an inlined
        // setter: onto its arguments, its frame (RET, the saved registers)
        // or its own stack.
        1 => (0u16..10, 0u16..300).prop_map(|(k, v)| format!(
            "push constant 0\npop pointer 1\npush that 0\npush constant {k}\nadd\npush constant {v}\ncall Main.w 2"
        )),
        // The same through Main.v, whose run nests Main.w's: onto either
        // frame, or onto Main.v's stack.
        1 => (0u16..16, 0u16..300).prop_map(|(k, v)| format!(
            "push constant 0\npop pointer 1\npush that 0\npush constant {k}\nadd\npush constant {v}\ncall Main.v 2"
        )),
        1 => Just("push constant 24576\npop pointer 1\npush that 0".to_string()),
        // A sum past 65535, which compiled code's 32-bit registers hold
        // with bits above the word's.
        1 => (0u16..5).prop_map(wrapped_word),
        // THIS or THAT at SP (read through RAM[0]): their accesses meet
        // the stack words that compiled code keeps in registers.
        1 => (0u16..2).prop_map(|p| format!("push constant 0\npop pointer 1\npush that 0\npop pointer {p}")),
        1 => (0u8..3).prop_map(|l| format!("if-goto L{l}")),
        1 => (0u8..3).prop_map(|l| format!("goto L{l}")),
        1 => Just("return".to_string()),
        3 => forward_skip(),
        1 => (0u16..8).prop_map(arg_beside_stack),
        // Shapes the fuser turns into one instruction: runs of moves
        // between consecutive words, and an array read into a variable.
        1 => (seg.clone(), 0u16..3, seg.clone(), 0u16..3, 1u16..6).prop_map(|(s, i, d, j, n)| {
            (0..n).map(|k| format!("push {s} {}\npop {d} {}", i + k, j + k)).collect::<Vec<_>>().join("\n")
        }),
        1 => (seg.clone(), 0u16..4, seg.clone(), 0u16..4, seg.clone(), 0u16..4).prop_map(|(a, i, b, j, d, k)| {
            format!("push {a} {i}\npush {b} {j}\nadd\npop pointer 1\npush that 0\npop {d} {k}")
        }),
    ]
}

/// A forward branch, mostly not taken, over straight code that falls
/// through into its target: a block that does not test the budget, which
/// the block before it must cover (`SKIP#` becomes a label of its own).
fn forward_skip() -> impl Strategy<Value = String> {
    (0u16..3, 1usize..7).prop_map(|(c, n)| {
        format!(
            "push constant {}\nif-goto SKIP#\n{}label SKIP#",
            c / 2,
            "push constant 1\npop temp 0\n".repeat(n)
        )
    })
}

/// A compiled call of more arguments than compiled code takes (250) is
/// left to the interpreter: with SP moved to 256 and 252 arguments, ARG is
/// 4 (THAT's word), whose value the callee's `push argument 0` reads from
/// the register (3000, set by compiled code just before), not from a RAM
/// word compiled code does not keep; with 250 arguments ARG is 6, a plain
/// word. The callee shows what it read in `temp 1`.
#[test]
fn a_call_whose_arguments_reach_the_registers_agrees() {
    for n in [250, 251, 252, 255] {
        let body = format!(
            "{}goto GO\nlabel GO\npush constant 3000\npop pointer 1\ncall Main.x {n}\npop temp 0",
            sp_moved_to(256)
        );
        let src = format!(
            "{}function Main.x 0\npush argument 0\npush argument 1\nadd\npop temp 1\n\
             push constant 0\npush constant 0\nif-goto NO\nreturn\nlabel NO\nreturn\n",
            random_program(vec![body], vec![], 0)
        );
        agree_at_every_budget(&src, &[1, 2], &[false, true], 0..24);
    }
}

/// A web function of 250 locals entered by the dispatcher with LCL at 7
/// (a call at SP = 2, whose frame words are the registers ARG, THIS, THAT
/// and RAM[5..=6]): its blocks' stack words are plain, but its saved LCL
/// and ARG are the registers THIS and THAT, which its return must read as
/// the interpreter does, after THIS and THAT are restored (from RAM[5]
/// and RAM[6]), not from RAM words compiled code does not keep: the return
/// leaves to the interpreter. The callee puts the call's RET word back in
/// ARG (7: Main.f's command after the call, its `function` line 0 and its
/// label not counted), so that a compiled return would find it, and writes
/// 1234 over the saved THIS, which the interpreter then also takes as LCL.
#[test]
fn a_return_whose_saved_frame_is_the_registers_agrees() {
    let body = format!("{}call Main.y 0\npop temp 0", sp_moved_to(2));
    let src = format!(
        "{}function Main.y 250\npush constant 7\npop constant 2\n\
         push constant 1234\npop temp 0\npush constant 5\nreturn\n",
        random_program(vec![body], vec![], 0)
    );
    agree_at_every_budget(&src, &[1, 2], &[true], 0..20);
}

/// Web, an `argument` index too large for the entry test (24,571), which
/// each access then tests on its own, with ARG moved to 0 so that the
/// word is plain: Main.f has 2 arguments, and the interpreter stops with
/// its error rather than read the word.
#[test]
fn an_argument_index_past_the_arguments_fails_as_the_interpreter_does() {
    let body = format!(
        "{UNKNOWN_DEPTH}push constant 0\npop constant 2\ngoto GO\nlabel GO\n\
         push argument 24571\npop temp 0\npush temp 0\nreturn"
    );
    agree_on(&body, 0, &[1, 2], &[true], &(0..12).collect::<Vec<_>>());
}

/// Web, `argument 24571` and `local 24571` (indices too large for the
/// entry test, so each access tests its own address) of functions that
/// have them, with SP moved to 24,571 and the segment's base to 0, so that
/// the access reads the word the block has just pushed and holds in a
/// register (7), where RAM still holds an older push (1). Main.a is called
/// with 24,572 arguments at SP = 24,572 (so ARG = 0), and takes the new SP
/// from its frame's saved THAT; Main.b has 24,572 locals, and a call at
/// SP = 0 puts them in RAM[5..=24576] (the frame's words are the
/// registers), whose last it takes as LCL (0).
#[test]
fn far_local_and_argument_reads_of_held_stack_words_agree() {
    let read = format!(
        "{UNKNOWN_DEPTH}pop temp 7\ngoto GO\nlabel GO\npush constant 7\npush constant 8\n\
         push SEG 24571\npop temp 0\npop temp 1\npop temp 2\npush constant 0\nreturn\n"
    );
    let calls = [
        (
            "push constant 24571\npop pointer 1\npush constant 24572\npop constant 0\n\
             call Main.a 24572",
            "function Main.a 0\npop constant 0\n",
            "argument",
        ),
        (
            "push constant 0\npop constant 0\ncall Main.b 0",
            "function Main.b 24572\npop constant 1\npush constant 24571\npop constant 0\n",
            "local",
        ),
    ];
    for (call, head, segment) in calls {
        let src = format!(
            "{}{head}{}",
            random_program(vec![call.to_string()], vec![], 0),
            read.replace("SEG", segment)
        );
        agree_at_every_budget(&src, &[1, 2], &[true], 0..24);
    }
}

/// Web, a compiled call made with SP moved near the end of RAM (so each
/// block tests its own stack), of a callee that zeroes no locals and of one
/// that zeroes 2: at SP = 24,573 the frame would reach past RAM, at 24,572
/// the frame fits and the locals do not, so the call's own test leaves it
/// to the interpreter, which drops those writes. Compiled code writing them
/// would go past the RAM buffer (which debug builds trap).
#[test]
fn a_call_whose_frame_would_pass_the_end_of_ram_agrees() {
    for (sp, locals) in [(24573, 0), (24573, 2), (24572, 2)] {
        let body = format!(
            "{}goto GO\nlabel GO\ncall Main.k 0\npop temp 0",
            sp_moved_to(sp)
        );
        let src = format!(
            "{}function Main.k {locals}\npush constant 0\nif-goto NO\nlabel NO\npush constant 3\nreturn\n",
            random_program(vec![body], vec![], 0)
        );
        agree_at_every_budget(&src, &[1, 2], &[true], 0..16);
    }
}

/// An inline run's arguments taken from the caller's registers: the block
/// pushed and popped six words above them first (10 to 15, still in its
/// registers), so only the words at the call's own depth are its
/// arguments (1 and 2: Main.g returns 3).
#[test]
fn an_inline_runs_arguments_are_the_words_under_the_call() {
    let body = format!(
        "{}{}push constant 1\npush constant 2\ncall Main.g 2\npop temp 1\npush temp 1\nreturn",
        (10..16)
            .map(|k| format!("push constant {k}\n"))
            .collect::<String>(),
        "pop temp 0\n".repeat(6)
    );
    agree_at_each_stop(&body, 12);
}

/// A compiled call that returns in compiled code where the caller's stack
/// depths are not static (a branch leaves one more word on one path): SP
/// after it is the word above the call's base less its arguments, which
/// the next block's pushes and `add` then use.
#[test]
fn sp_after_a_compiled_call_with_unknown_depths_agrees() {
    let body = format!(
        "{UNKNOWN_DEPTH}push constant 7\npush constant 2\ncall Main.r 1\npush constant 5\n\
         add\nadd\npop temp 0\npush temp 0\nreturn"
    );
    agree_at_each_stop(&body, 24);
}

/// A called function (not run inline) that rewrites its caller's saved
/// ARG (Main.f calls it with its frame at 263..=267, ARG's word at 265):
/// the return gives Main.f that ARG, so compiled code leaves it to the
/// interpreter from the instruction after the call, whose own return
/// then writes its value at RAM[300].
#[test]
fn a_callee_that_rewrites_its_callers_saved_arg_agrees() {
    let src = "function Main.main 0\npush constant 0\nreturn\n\
               function Main.f 1\npush constant 7\ncall Main.x 1\npop temp 1\n\
               push constant 22\nreturn\n\
               function Main.x 0\npush argument 0\nif-goto A\nlabel A\n\
               push constant 300\npop constant 265\npush constant 0\nreturn\n";
    agree_at_every_budget(src, &[], &[false, true], 0..16);
}

/// Desktop, a run inline (Main.r) that sets THAT in the heap, then runs
/// Main.w inline, which rewrites the word where its frame saved THAT (at
/// 271) to 5: after Main.w's return THAT is 5, outside the desktop's range,
/// so Main.r's `push that 0` stops as the interpreter does; the range its
/// own `pop pointer 1` showed holds no longer.
#[test]
fn a_nested_run_that_rewrites_the_saved_that_clears_what_its_caller_knew() {
    let src = "function Main.main 0\npush constant 0\nreturn\n\
               function Main.f 0\ncall Main.r 0\nreturn\n\
               function Main.r 0\npush constant 2100\npop pointer 1\npush constant 9\n\
               call Main.w 1\npop temp 1\npush that 0\nreturn\n\
               function Main.w 0\npush constant 5\npop constant 271\npush constant 0\nreturn\n";
    agree_at_every_budget(src, &[], &[false], 0..16);
}

/// Web, a return whose frame ends past RAM: Main.k is called at SP =
/// 24,573 (so its saved THAT would be word 24,577, which the call drops),
/// takes SP from its saved THIS (24,570) and returns from a block compiled
/// code runs. The interpreter restores THAT from past RAM (-1); compiled
/// code, which would read the word past the RAM buffer, leaves the return
/// to it.
#[test]
fn a_return_whose_frame_ends_past_ram_agrees() {
    let body = "push constant 24570\npop pointer 0\npush constant 24573\npop constant 0\n\
                call Main.k 0\npop temp 0";
    let src = format!(
        "{}function Main.k 0\npop temp 0\npop constant 0\n\
         {UNKNOWN_DEPTH}goto GO\nlabel GO\npush constant 3\nreturn\n",
        random_program(vec![body.to_string()], vec![], 0)
    );
    agree_at_every_budget(&src, &[1, 2], &[true], 0..20);
}
