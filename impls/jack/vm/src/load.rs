//! Loading: files to a checked, decoded [`Program`] (spec §2.1, §2.2, §2.4
//! static slots, §2.6 entry point). Every failure is a [`LoadError`] naming
//! the file and line; nothing here panics on any input.

use crate::error::LoadError;
use crate::parse::{self, Arith, Command, Line, Segment};
use crate::program::{Code, FnId, Function, Op, Program};
use jack_os::Builtin;
use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

/// Name of the function formed by commands before the first `function` line.
pub const IMPLICIT: &str = "__implicit";

/// The built-in init calls of the synthetic `Sys.init`, in order (§2.6).
const SYNTHETIC_CALLS: [&str; 8] = [
    "Math.init",
    "String.init",
    "Array.init",
    "Output.init",
    "Screen.init",
    "Keyboard.init",
    "Memory.init",
    "Main.main",
];

/// Static slots available: RAM 16..=255.
const STATIC_SLOTS: usize = 240;

/// A function as parsed, before decoding.
struct RawFunction {
    name: String,
    file: String,
    line: usize,
    n_vars: u16,
    /// True when the command list starts with the `function` line (index 0).
    has_header: bool,
    body: Vec<Line>,
}

impl Program {
    /// Load every `.vm` file of `dir`, in file-name order.
    pub fn load_dir(dir: &Path) -> Result<Arc<Program>, LoadError> {
        Program::load_dir_in_order(dir, &[])
    }

    /// Load every `.vm` file of `dir`: the files named in `order` (base
    /// names, `Main` for `Main.vm`) first, in that order, then the others
    /// in file-name order. The load order decides where each file's
    /// statics go (the desktop's segments follow it, the web IDE numbers
    /// statics by first appearance in it): the official tools take the
    /// order their directory listing gives, which need not be sorted.
    pub fn load_dir_in_order(dir: &Path, order: &[String]) -> Result<Arc<Program>, LoadError> {
        let io = |source| LoadError::Io {
            path: dir.to_path_buf(),
            source,
        };
        let mut paths = Vec::new();
        for entry in std::fs::read_dir(dir).map_err(io)? {
            let path = entry.map_err(io)?.path();
            if path.extension().is_some_and(|e| e == "vm") && path.is_file() {
                paths.push(path);
            }
        }
        paths.sort();
        let mut sources = Vec::with_capacity(paths.len());
        for path in paths {
            let text = common::input::read_text(&path)?;
            let name = path
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            sources.push((name, text));
        }
        if sources.is_empty() {
            return Err(LoadError::Program(format!(
                "no .vm files in {}",
                dir.display()
            )));
        }
        in_load_order(&mut sources, order)?;
        Program::from_sources(&sources)
    }

    /// Load in-memory sources `(file name, text)`, in the order given. File
    /// names end in `.vm`; with several files each function must be named
    /// `Base.f` after its file's base name.
    pub fn from_sources<S: AsRef<str>, T: AsRef<str>>(
        sources: &[(S, T)],
    ) -> Result<Arc<Program>, LoadError> {
        let multi = sources.len() > 1;
        let mut raw: Vec<RawFunction> = Vec::new();
        let mut command_lines = 0;
        for (file, text) in sources {
            let file = file.as_ref();
            let lines = parse::parse(file, text.as_ref())?;
            command_lines += lines.len();
            split_functions(file, lines, multi, &mut raw)?;
        }
        let raw = dedupe(raw)?;
        build(raw, command_lines).map(Arc::new)
    }
}

/// Put `(file name, text)` sources in the load order `order` (base names:
/// `Main` for `Main.vm`): the named files first, in that order, then the
/// others as they were. A name that is not among the files, or is named
/// twice, is an error.
pub fn in_load_order<T>(sources: &mut Vec<(String, T)>, order: &[String]) -> Result<(), LoadError> {
    let base = |f: &str| f.strip_suffix(".vm").unwrap_or(f).to_string();
    let mut rest: Vec<(String, T)> = std::mem::take(sources);
    for name in order {
        let name = base(name.trim());
        let at = rest
            .iter()
            .position(|(f, _)| base(f) == name)
            .ok_or_else(|| {
                LoadError::Program(format!(
                "the load order names {name}, which is not one of the files (or is named twice)"
            ))
            })?;
        sources.push(rest.remove(at));
    }
    sources.extend(rest);
    Ok(())
}

/// Group a file's commands into functions and check the file-name rule.
fn split_functions(
    file: &str,
    lines: Vec<Line>,
    multi: bool,
    out: &mut Vec<RawFunction>,
) -> Result<(), LoadError> {
    let base = file.strip_suffix(".vm").unwrap_or(file);
    for l in lines {
        if let Command::Function(name, n_vars) = &l.command {
            if multi && name.split_once('.').map(|(class, _)| class) != Some(base) {
                return Err(LoadError::at(
                    file,
                    l.line,
                    format!("function {name} must be named {base}.<name> in file {file}"),
                ));
            }
            out.push(RawFunction {
                name: name.clone(),
                file: file.to_string(),
                line: l.line,
                n_vars: *n_vars,
                has_header: true,
                body: Vec::new(),
            });
            continue;
        }
        let current = match out.last_mut() {
            Some(f) if f.file == file => f,
            _ => {
                out.push(RawFunction {
                    name: IMPLICIT.to_string(),
                    file: file.to_string(),
                    line: l.line,
                    n_vars: 0,
                    has_header: false,
                    body: Vec::new(),
                });
                out.last_mut().expect("just pushed")
            }
        };
        current.body.push(l);
    }
    Ok(())
}

/// Reject duplicate function names; a later `Sys.init` replaces an earlier one.
fn dedupe(raw: Vec<RawFunction>) -> Result<Vec<RawFunction>, LoadError> {
    let mut out: Vec<RawFunction> = Vec::with_capacity(raw.len());
    let mut seen: HashMap<String, usize> = HashMap::new();
    for f in raw {
        match seen.get(&f.name) {
            Some(&i) if f.name == "Sys.init" => out[i] = f,
            Some(_) => {
                return Err(LoadError::at(
                    &f.file,
                    f.line,
                    format!("VM Already has a function named {}", f.name),
                ));
            }
            None => {
                seen.insert(f.name.clone(), out.len());
                out.push(f);
            }
        }
    }
    Ok(out)
}

/// Choose the entry (§2.6), adding the synthetic `Sys.init` when needed.
fn choose_entry(raw: &mut Vec<RawFunction>) -> Result<FnId, LoadError> {
    let find = |raw: &[RawFunction], n: &str| raw.iter().position(|f| f.name == n);
    let sys_init = find(raw, "Sys.init");
    let implicit = find(raw, IMPLICIT);
    if sys_init.is_some() && implicit.is_some() {
        return Err(LoadError::Program(
            "Sys.init is defined and there are commands outside any function (__implicit): no single entry point"
                .to_string(),
        ));
    }
    let id = if let Some(i) = sys_init {
        i
    } else if find(raw, "Main.main").is_some() {
        let body = SYNTHETIC_CALLS
            .iter()
            .map(|n| Line {
                line: 0,
                command: Command::Call(n.to_string(), 0),
            })
            .collect();
        raw.push(RawFunction {
            name: "Sys.init".to_string(),
            file: String::new(),
            line: 0,
            n_vars: 0,
            has_header: true,
            body,
        });
        raw.len() - 1
    } else if let Some(i) = implicit {
        i
    } else if raw.len() == 1 {
        0
    } else {
        return Err(LoadError::Program(
            "Could not determine an entry point for VM".to_string(),
        ));
    };
    Ok(id as FnId)
}

/// What a `call` resolves to.
enum Target {
    Vm(FnId),
    Os(Builtin),
}

fn build(mut raw: Vec<RawFunction>, command_lines: usize) -> Result<Program, LoadError> {
    // Entry errors are reported after the checks of the functions' code.
    let before = raw.len();
    let chosen = choose_entry(&mut raw);
    let entry = *chosen.as_ref().unwrap_or(&FnId::MAX);
    let synthetic_entry = raw.len() > before;
    if raw.len() > u16::MAX as usize {
        return Err(LoadError::Program(format!(
            "too many functions ({})",
            raw.len()
        )));
    }
    let by_name: HashMap<String, FnId> = raw
        .iter()
        .enumerate()
        .map(|(i, f)| (f.name.clone(), i as FnId))
        .collect();

    let mut statics: HashMap<(String, u16), usize> = HashMap::new();
    let mut messages: Vec<String> = Vec::new();
    let mut plain: Vec<Op> = Vec::new();
    let mut functions = Vec::with_capacity(raw.len());
    // Desktop jump targets that differ from the web ones: (instruction, target).
    // and the desktop's static addresses: (instruction, desktop instruction).
    let mut desktop_ops: Vec<(usize, Op)> = Vec::new();
    // The first command the web IDE refuses at load but the desktop runs.
    let mut web_refusal: Option<(String, usize, String)> = None;
    let static_base = desktop_static_bases(&raw);
    // The desktop's address of each function's command 0 (its invisible
    // start-up code follows the program's own lines).
    let mut addresses = Vec::with_capacity(raw.len());
    let mut next_address = 0u32;
    for (i, f) in raw.iter().enumerate() {
        if synthetic_entry && i == raw.len() - 1 {
            addresses.push(command_lines as u32 + 3);
        } else {
            addresses.push(next_address);
            next_address += u32::from(f.has_header) + f.body.len() as u32;
        }
    }

    for (id, f) in raw.iter().enumerate() {
        let id = id as FnId;
        let class = f.name.split('.').next().unwrap_or(&f.name).to_string();
        plain.push(Op::Function {
            n_vars: f.n_vars,
            method: false,
        });
        let start = plain.len() as u32;

        // Pass 1: instruction positions of labels and of each command index.
        let first_index = usize::from(f.has_header);
        let mut labels: HashMap<&str, u32> = HashMap::new();
        // Labels directly followed by a label: a desktop jump there wastes
        // a step (crate::timing), taken by a `Goto` placed after the function.
        let mut paired: Vec<&str> = Vec::new();
        let mut resume = vec![u32::MAX; first_index];
        let mut pc = start;
        for (k, l) in f.body.iter().enumerate() {
            resume.push(pc);
            match &l.command {
                Command::Label(name) => {
                    if labels.insert(name, pc).is_some() {
                        return Err(LoadError::at(
                            &f.file,
                            l.line,
                            format!("Cannot redeclare label {name}"),
                        ));
                    }
                    if matches!(
                        f.body.get(k + 1),
                        Some(Line {
                            command: Command::Label(_),
                            ..
                        })
                    ) {
                        paired.push(name);
                    }
                }
                _ => pc += 1,
            }
        }
        resume.push(pc); // one past the last command: the trailing Halt
                         // The wasted-step jumps follow the Halt at `pc`.
        let wasted_jump = |name: &str| {
            paired
                .iter()
                .position(|p| *p == name)
                .map(|j| pc + 1 + j as u32)
        };

        // Pass 2: decode.
        for (k, l) in f.body.iter().enumerate() {
            let err = |m: String| LoadError::at(&f.file, l.line, m);
            let fail = |messages: &mut Vec<String>, m: String| {
                messages.push(m);
                Op::Fail((messages.len() - 1) as u16)
            };
            let op = match &l.command {
                Command::Label(_) => continue,
                Command::Function(..) => unreachable!("function lines start a new function"),
                Command::Goto(name) | Command::IfGoto(name) => {
                    let target = *labels
                        .get(name.as_str())
                        .ok_or_else(|| err(format!("Undeclared label {name}")))?;
                    if let Some(t) = wasted_jump(name) {
                        desktop_ops.push((
                            plain.len(),
                            if matches!(l.command, Command::Goto(_)) {
                                Op::Goto(t)
                            } else {
                                Op::IfGoto(t)
                            },
                        ));
                    }
                    if matches!(l.command, Command::Goto(_)) {
                        Op::Goto(target)
                    } else {
                        Op::IfGoto(target)
                    }
                }
                Command::Return => Op::Return,
                Command::Arith(a) => match a {
                    Arith::Add => Op::Add,
                    Arith::Sub => Op::Sub,
                    Arith::Neg => Op::Neg,
                    Arith::Eq => Op::Eq,
                    Arith::Gt => Op::Gt,
                    Arith::Lt => Op::Lt,
                    Arith::And => Op::And,
                    Arith::Or => Op::Or,
                    Arith::Not => Op::Not,
                },
                Command::Call(name, n) => {
                    let index = k + first_index;
                    match resolve(&by_name, name, *n).map_err(err)? {
                        Target::Vm(callee) => Op::Call {
                            callee: callee as u16,
                            nargs: *n,
                            ret: index as u16,
                            method: false,
                        },
                        Target::Os(Builtin::MathMultiply) => Op::Multiply,
                        Target::Os(Builtin::MathDivide) => Op::Divide,
                        Target::Os(builtin) => Op::CallBuiltin {
                            builtin,
                            nargs: *n as u8,
                        },
                    }
                }
                Command::Push(seg, i) | Command::Pop(seg, i) => {
                    let push = matches!(l.command, Command::Push(..));
                    let i = *i;
                    match seg {
                        Segment::Constant if push => Op::PushConst(i as i16),
                        Segment::Constant => Op::PopRam(i),
                        Segment::Local | Segment::Argument if id == entry => Op::EntryAccess {
                            local: *seg == Segment::Local,
                            push,
                            index: i,
                        },
                        Segment::Local if i >= f.n_vars => {
                            fail(&mut messages, "Local offset out of bounds".into())
                        }
                        Segment::Local if push => Op::PushLocal(i),
                        Segment::Local => Op::PopLocal(i),
                        Segment::Argument if push => Op::PushArg(i),
                        Segment::Argument => Op::PopArg(i),
                        // Checked forms; the this/that analysis below relaxes them.
                        Segment::This if push => Op::PushThisChk(i),
                        Segment::This => Op::PopThisChk(i),
                        Segment::That if push => Op::PushThatChk(i),
                        Segment::That => Op::PopThatChk(i),
                        Segment::Pointer if push => Op::PushPtr(i as u8),
                        Segment::Pointer => Op::PopPtr(i as u8),
                        Segment::Temp if push => Op::PushAbs(5 + i),
                        Segment::Temp => Op::PopAbs(5 + i),
                        Segment::Static => {
                            let address =
                                16 + u32::from(static_base[f.file.as_str()]) + u32::from(i);
                            // The desktop's static segment of a file ends at
                            // its largest index: any index fits, whatever
                            // RAM word it reaches (RAM[256] for `static 240`
                            // of a lone class).
                            let desktop = if address > jack_os::KBD as u32 {
                                fail(&mut messages, "Out of segment space".into())
                            } else if push {
                                Op::PushAbs(address as u16)
                            } else {
                                Op::PopAbs(address as u16)
                            };
                            desktop_ops.push((plain.len(), desktop));
                            let next = statics.len();
                            let slot = *statics.entry((class.clone(), i)).or_insert(next);
                            if i >= STATIC_SLOTS as u16 {
                                let m = format!(
                                    "Illegal static index {i} (must be between 0 and {})",
                                    STATIC_SLOTS - 1
                                );
                                web_refusal
                                    .get_or_insert_with(|| (f.file.clone(), l.line, m.clone()));
                                fail(&mut messages, m)
                            } else if slot >= STATIC_SLOTS {
                                fail(
                                    &mut messages,
                                    format!("Too many static variables: {class}'s static {i} needs slot {slot} of {STATIC_SLOTS}"),
                                )
                            } else if push {
                                Op::PushAbs(16 + slot as u16)
                            } else {
                                Op::PopAbs(16 + slot as u16)
                            }
                        }
                    }
                }
            };
            plain.push(op);
        }
        let arg_reach = plain[start as usize..]
            .iter()
            .filter_map(|op| match op {
                Op::PushArg(i) | Op::PopArg(i) => Some(i.saturating_add(1)),
                _ => None,
            })
            .max()
            .unwrap_or(0);
        plain.push(Op::Halt);
        for name in &paired {
            plain.push(Op::Goto(labels[name]));
        }
        functions.push(Function {
            name: f.name.clone(),
            file: f.file.clone(),
            n_vars: f.n_vars,
            headed: f.has_header,
            arg_reach,
            start,
            resume,
            address: addresses[id as usize],
        });
    }
    if plain.len() >= u32::MAX as usize / 2 {
        return Err(LoadError::Program("program too large".to_string()));
    }
    for f in &functions {
        relax_this_that(&mut plain, f.start as usize);
    }
    chosen?;
    let statics = statics.len().min(STATIC_SLOTS);
    let starts: Vec<u32> = functions.iter().map(|f| f.start).collect();
    let mut desktop = plain.clone();
    for (at, op) in desktop_ops {
        desktop[at] = op;
    }
    // The desktop's RET word is the program address of the command after
    // the call (crate::timing), not a command index.
    for (i, f) in functions.iter().enumerate() {
        let end = functions
            .get(i + 1)
            .map_or(desktop.len(), |next| next.start as usize - 1);
        let body = desktop.iter_mut().enumerate().take(end);
        for (pc, op) in body.skip(f.start as usize) {
            if let Op::Call { ret, .. } = op {
                *ret = f
                    .desktop_return_address(pc as u32)
                    .map_or(u16::MAX, |a| a as u16);
            }
        }
    }
    // The desktop tests every `this`/`that` address: its code keeps the
    // checked forms, whose tests follow the profile (crate::exec).
    for op in &mut desktop {
        *op = match *op {
            Op::PushThis(i) => Op::PushThisChk(i),
            Op::PushThat(i) => Op::PushThatChk(i),
            Op::PopThis(i) => Op::PopThisChk(i),
            Op::PopThat(i) => Op::PopThatChk(i),
            other => other,
        };
    }
    let code = |plain: Vec<Op>, desktop: bool| Code {
        fused: crate::fuse::fuse(&plain, &starts, desktop),
        plain,
    };
    // In the order of crate::timing::index.
    let code = [code(desktop, true), code(plain, false)];
    Ok(Program {
        functions,
        by_name,
        code,
        messages,
        entry,
        synthetic_entry,
        web_refusal,
        command_lines,
        statics,
        native: Default::default(),
        interpreted: Default::default(),
    })
}

/// The desktop VM emulator's static segments: one per file, in load
/// order, each as long as the file's largest static index + 1; `static i`
/// of a file is RAM[16 + its base + i] (the web IDE numbers statics by
/// first appearance instead, spec §2.4 and §6).
fn desktop_static_bases(raw: &[RawFunction]) -> HashMap<&str, u16> {
    let mut largest: Vec<(&str, Option<u16>)> = Vec::new();
    for f in raw {
        let at = match largest.iter().position(|(file, _)| *file == f.file) {
            Some(at) => at,
            None => {
                largest.push((&f.file, None));
                largest.len() - 1
            }
        };
        for l in &f.body {
            if let Command::Push(Segment::Static, i) | Command::Pop(Segment::Static, i) = l.command
            {
                let top = &mut largest[at].1;
                *top = Some(top.map_or(i, |t| t.max(i)));
            }
        }
    }
    let mut base = 0u16;
    let mut bases = HashMap::new();
    for (file, top) in largest {
        bases.insert(file, base);
        base = base.saturating_add(top.map_or(0, |t| t.saturating_add(1)));
    }
    bases
}

fn resolve(by_name: &HashMap<String, FnId>, name: &str, n: u16) -> Result<Target, String> {
    if let Some(&id) = by_name.get(name) {
        return Ok(Target::Vm(id));
    }
    match jack_os::lookup(name) {
        Some(os) => {
            let expected = os.builtin.vm_arity();
            if usize::from(n) != expected {
                Err(format!(
                    "OS function {name} expects {expected} arguments, not {n}"
                ))
            } else {
                Ok(Target::Os(os.builtin))
            }
        }
        None => Err(format!("Undefined function {name}")),
    }
}

/// The this/that initialisation analysis (§2.5): a `this`/`that` access is
/// an error unless a `pop pointer 0`/`1` ran earlier in the same
/// invocation. Where every path from the function's start passes such a
/// pop, the unchecked form is used. A call leaves the caller's flags as
/// they were (each invocation has its own).
fn relax_this_that(code: &mut [Op], start: usize) {
    let end = start
        + code[start..]
            .iter()
            .position(|op| *op == Op::Halt)
            .expect("every function ends in Halt");
    let n = end - start + 1;
    // Must-analysis: bit 0 = this initialised, bit 1 = that. 0b100 = unvisited (top).
    const TOP: u8 = 0b111;
    let mut state_in = vec![TOP; n];
    state_in[0] = 0;
    let mut work = vec![0usize];
    while let Some(i) = work.pop() {
        let s = state_in[i];
        let op = code[start + i];
        let out = match op {
            Op::PopPtr(0) => s | 1,
            Op::PopPtr(_) => s | 2,
            _ => s,
        } & 0b11;
        let mut succ = [usize::MAX; 2];
        match op {
            Op::Goto(t) => succ[0] = t as usize - start,
            Op::IfGoto(t) => {
                succ[0] = t as usize - start;
                succ[1] = i + 1;
            }
            Op::Return | Op::Halt | Op::Fail(_) => {}
            _ => succ[0] = i + 1,
        }
        for j in succ.into_iter().filter(|&j| j < n) {
            let merged = state_in[j] & out;
            if merged != state_in[j] {
                state_in[j] = merged;
                work.push(j);
            }
        }
    }
    for (i, s) in state_in.into_iter().enumerate() {
        let op = &mut code[start + i];
        let this = s & 1 != 0 && s != TOP;
        let that = s & 2 != 0 && s != TOP;
        *op = match *op {
            Op::PushThisChk(k) if this => Op::PushThis(k),
            Op::PopThisChk(k) if this => Op::PopThis(k),
            Op::PushThatChk(k) if that => Op::PushThat(k),
            Op::PopThatChk(k) if that => Op::PopThat(k),
            other => other,
        };
    }
}
