//! The dispatch loop. SP, LCL, ARG, THIS and THAT live in host registers
//! while it runs; an access to RAM[0..4] through a computed address takes a
//! slow path that reads or writes the cached register, so the memory model
//! stays exactly that of spec §1. No allocation, no hashing per instruction.

use crate::exit::Exit;
use crate::machine::{
    Frame, Machine, Watcher, ARG_OK, HOST, LOCAL_OK, MAX_DEPTH, THAT_OK, THIS_OK,
};
use crate::program::{Op, Program};
use jack_os::{math, Builtin, Ram, Stop, RAM_SIZE};

/// The VM registers RAM[0..=4], cached.
#[derive(Clone, Copy, Debug)]
struct Regs {
    sp: u16,
    lcl: u16,
    arg: u16,
    this: u16,
    that: u16,
}

type Words = [i16; RAM_SIZE];

impl Regs {
    fn load(w: &Words) -> Regs {
        Regs {
            sp: w[0] as u16,
            lcl: w[1] as u16,
            arg: w[2] as u16,
            this: w[3] as u16,
            that: w[4] as u16,
        }
    }

    fn store(self, w: &mut Words) {
        w[0] = self.sp as i16;
        w[1] = self.lcl as i16;
        w[2] = self.arg as i16;
        w[3] = self.this as i16;
        w[4] = self.that as i16;
    }
}

/// `5 <= a <= 24576`: an ordinary word (not a register, not outside RAM).
#[inline(always)]
fn plain_word(a: u16) -> bool {
    a.wrapping_sub(5) < (RAM_SIZE - 5) as u16
}

/// Read RAM[a] for a register or an address outside RAM.
#[cold]
#[inline(never)]
fn read_slow(r: Regs, a: u16) -> i16 {
    (match a {
        0 => r.sp,
        1 => r.lcl,
        2 => r.arg,
        3 => r.this,
        4 => r.that,
        _ => 0xFFFF,
    }) as i16
}

/// Write RAM[a] for a register or an address outside RAM (dropped).
#[cold]
#[inline(never)]
fn write_slow(mut r: Regs, a: u16, v: i16) -> Regs {
    let v = v as u16;
    match a {
        0 => r.sp = v,
        1 => r.lcl = v,
        2 => r.arg = v,
        3 => r.this = v,
        4 => r.that = v,
        _ => {}
    }
    r
}

fn words(ram: &mut Ram) -> &mut Words {
    ram.words_mut()
        .try_into()
        .expect("the RAM has RAM_SIZE words")
}

/// Why the loop stopped early (the call stack is added by the caller).
enum Halt {
    Exit(Exit),
    Error(String),
    Os(Stop),
}

const POP_BELOW: &str = "Cannot pop the stack below 256 in strict mode";
const ARG_OOB: &str = "Argument offset out of bounds";
const LOCAL_OOB: &str = "Local offset out of bounds";
const THIS_UNINIT: &str = "The this segment cannot be accessed since it was not initialized";
const THAT_UNINIT: &str = "The that segment cannot be accessed since it was not initialized";

impl Machine {
    /// Run instructions of `code` (the fused or the plain array) until the
    /// step count reaches `stop_at` (None) or the run ends (Some).
    pub(crate) fn exec<const W: bool>(
        &mut self,
        program: &Program,
        code: &[Op],
        stop_at: u64,
        watch: &mut Option<(&[bool], &mut dyn Watcher)>,
    ) -> Option<Exit> {
        let mut pc = self.pc as usize;
        let mut steps = self.steps;
        let mut cur = self.cur;
        let mut nargs = self.nargs;
        let mut flags = self.flags;
        let functions = &program.functions;
        let frames = &mut self.frames;
        let os = &mut self.os;
        let ram = &mut self.ram;
        let mut profile = self.profile.as_deref_mut();
        let mut profile_mark = self.profile_mark;
        let scratch = &mut self.scratch;
        let mut w = words(ram);
        let mut regs = Regs::load(w);

        let halt: Option<Halt> = 'run: loop {
            macro_rules! rd {
                ($a:expr) => {{
                    let a: u16 = $a;
                    if plain_word(a) {
                        w[a as usize]
                    } else {
                        read_slow(regs, a)
                    }
                }};
            }
            macro_rules! wr {
                ($a:expr, $v:expr) => {{
                    let a: u16 = $a;
                    let v: i16 = $v;
                    if plain_word(a) {
                        w[a as usize] = v;
                    } else {
                        regs = write_slow(regs, a, v);
                    }
                }};
            }
            macro_rules! push {
                ($v:expr) => {{
                    let v: i16 = $v;
                    wr!(regs.sp, v);
                    regs.sp = regs.sp.wrapping_add(1);
                }};
            }
            macro_rules! pop {
                () => {{
                    if regs.sp == 256 {
                        break 'run Some(Halt::Error(POP_BELOW.into()));
                    }
                    regs.sp = regs.sp.wrapping_sub(1);
                    rd!(regs.sp)
                }};
            }
            macro_rules! binary {
                (|$x:ident, $y:ident| $e:expr) => {{
                    let $y = pop!();
                    let $x = pop!();
                    push!($e);
                }};
            }
            macro_rules! this_ok {
                ($bit:expr, $msg:expr) => {
                    if flags & $bit == 0 {
                        break 'run Some(Halt::Error($msg.into()));
                    }
                };
            }
            macro_rules! charge {
                () => {
                    if let Some(p) = profile.as_deref_mut() {
                        p[cur as usize] += steps - profile_mark;
                        profile_mark = steps;
                    }
                };
            }
            // A built-in through the OS: pop the arguments, call, push the result.
            macro_rules! builtin {
                ($b:expr, $n:expr) => {{
                    let b: Builtin = $b;
                    let mut args = [0i16; 8];
                    let n = usize::from($n).min(args.len());
                    for i in (0..n).rev() {
                        args[i] = pop!();
                    }
                    regs.store(w);
                    let c = os.call(b, &args[..n], ram, &mut steps);
                    w = words(ram);
                    regs = Regs::load(w);
                    push!(c.value);
                    if let Some(stop) = c.stop {
                        break 'run Some(Halt::Os(stop));
                    }
                }};
            }

            if steps >= stop_at {
                break None;
            }
            let op = code[pc];
            pc += 1;
            steps += 1;
            match op {
                Op::PushConst(c) => push!(c),
                Op::PushLocal(i) => push!(rd!(regs.lcl.wrapping_add(i))),
                Op::PushArg(i) => {
                    if i >= nargs {
                        break Some(Halt::Error(ARG_OOB.into()));
                    }
                    push!(rd!(regs.arg.wrapping_add(i)))
                }
                Op::PushThis(i) => push!(rd!(regs.this.wrapping_add(i))),
                Op::PushThisChk(i) => {
                    this_ok!(THIS_OK, THIS_UNINIT);
                    push!(rd!(regs.this.wrapping_add(i)))
                }
                Op::PushThat(i) => push!(rd!(regs.that.wrapping_add(i))),
                Op::PushThatChk(i) => {
                    this_ok!(THAT_OK, THAT_UNINIT);
                    push!(rd!(regs.that.wrapping_add(i)))
                }
                Op::PushAbs(a) => push!(w[a as usize]),
                Op::PushPtr(0) => push!(regs.this as i16),
                Op::PushPtr(_) => push!(regs.that as i16),
                Op::PopLocal(i) => {
                    let v = pop!();
                    wr!(regs.lcl.wrapping_add(i), v)
                }
                Op::PopArg(i) => {
                    if i >= nargs {
                        break Some(Halt::Error(ARG_OOB.into()));
                    }
                    let v = pop!();
                    wr!(regs.arg.wrapping_add(i), v)
                }
                Op::PopThis(i) => {
                    let v = pop!();
                    wr!(regs.this.wrapping_add(i), v)
                }
                Op::PopThisChk(i) => {
                    this_ok!(THIS_OK, THIS_UNINIT);
                    let v = pop!();
                    wr!(regs.this.wrapping_add(i), v)
                }
                Op::PopThat(i) => {
                    let v = pop!();
                    wr!(regs.that.wrapping_add(i), v)
                }
                Op::PopThatChk(i) => {
                    this_ok!(THAT_OK, THAT_UNINIT);
                    let v = pop!();
                    wr!(regs.that.wrapping_add(i), v)
                }
                Op::PopAbs(a) => {
                    let v = pop!();
                    w[a as usize] = v;
                }
                Op::PopPtr(0) => {
                    regs.this = pop!() as u16;
                    flags |= THIS_OK;
                }
                Op::PopPtr(_) => {
                    regs.that = pop!() as u16;
                    flags |= THAT_OK;
                }
                Op::PopRam(a) => {
                    let v = pop!();
                    wr!(a, v)
                }
                Op::Fail(m) => break Some(Halt::Error(program.messages[m as usize].clone())),
                Op::EntryAccess { local, push, index } => {
                    let entry_invocation = frames.is_empty();
                    let ok = if entry_invocation {
                        flags & if local { LOCAL_OK } else { ARG_OK } != 0
                    } else if local {
                        index < functions[cur as usize].n_vars
                    } else {
                        index < nargs
                    };
                    if !ok {
                        let m = match (entry_invocation, local) {
                            (true, true) => "The local segment cannot be accessed since it was not initialized",
                            (true, false) => "The argument segment cannot be accessed since it was not initialized",
                            (false, true) => LOCAL_OOB,
                            (false, false) => ARG_OOB,
                        };
                        break Some(Halt::Error(m.into()));
                    }
                    let a = if local { regs.lcl } else { regs.arg }.wrapping_add(index);
                    if push {
                        push!(rd!(a));
                    } else {
                        let v = pop!();
                        wr!(a, v);
                    }
                }
                Op::Add => binary!(|x, y| x.wrapping_add(y)),
                Op::Sub => binary!(|x, y| x.wrapping_sub(y)),
                Op::And => binary!(|x, y| x & y),
                Op::Or => binary!(|x, y| x | y),
                Op::Eq => binary!(|x, y| -i16::from(x == y)),
                Op::Gt => binary!(|x, y| -i16::from(x > y)),
                Op::Lt => binary!(|x, y| -i16::from(x < y)),
                Op::Neg => {
                    let v = pop!();
                    push!(v.wrapping_neg())
                }
                Op::Not => {
                    let v = pop!();
                    push!(!v)
                }
                Op::Goto(t) => pc = t as usize,
                Op::IfGoto(t) => {
                    if pop!() != 0 {
                        pc = t as usize;
                    }
                }
                Op::Multiply => binary!(|x, y| math::multiply(x, y)),
                Op::Divide => {
                    let profile = os.profile();
                    let y = rd!(regs.sp.wrapping_sub(1));
                    match math::divide(profile, rd!(regs.sp.wrapping_sub(2)), y) {
                        Some(q) if regs.sp != 256 && regs.sp != 257 => {
                            regs.sp = regs.sp.wrapping_sub(1);
                            wr!(regs.sp.wrapping_sub(1), q);
                        }
                        _ => builtin!(Builtin::MathDivide, 2u8),
                    }
                }
                Op::CallBuiltin { builtin, nargs: n } => builtin!(builtin, n),
                Op::Call {
                    callee,
                    nargs: n,
                    ret,
                } => {
                    if frames.len() >= MAX_DEPTH {
                        break Some(Halt::Error(format!(
                            "Jack call stack deeper than {MAX_DEPTH} frames"
                        )));
                    }
                    let f = &functions[callee as usize];
                    let mut watched = false;
                    if W {
                        if let Some((set, watcher)) = watch {
                            if set.get(callee as usize).copied().unwrap_or(false) {
                                scratch.clear();
                                for k in (1..=n).rev() {
                                    scratch.push(rd!(regs.sp.wrapping_sub(k)));
                                }
                                watcher.on_call(program, callee as u32, scratch);
                                watched = true;
                            }
                        }
                    }
                    charge!();
                    let base = regs.sp;
                    push!(ret as i16);
                    push!(regs.lcl as i16);
                    push!(regs.arg as i16);
                    push!(regs.this as i16);
                    push!(regs.that as i16);
                    regs.arg = base.wrapping_sub(n);
                    regs.lcl = base.wrapping_add(5);
                    for _ in 0..f.n_vars {
                        push!(0);
                    }
                    frames.push(Frame {
                        caller: cur,
                        ret_pc: pc as u32,
                        ret: ret as i16,
                        nargs,
                        flags,
                        watched,
                    });
                    cur = callee as u32;
                    nargs = n;
                    flags = 0;
                    pc = f.start as usize;
                }
                Op::Return => {
                    let frame = regs.lcl;
                    let ret = rd!(frame.wrapping_sub(5));
                    let v = pop!();
                    wr!(regs.arg, v);
                    regs.sp = regs.arg.wrapping_add(1);
                    regs.that = rd!(frame.wrapping_sub(1)) as u16;
                    regs.this = rd!(frame.wrapping_sub(2)) as u16;
                    regs.arg = rd!(frame.wrapping_sub(3)) as u16;
                    regs.lcl = rd!(frame.wrapping_sub(4)) as u16;
                    charge!();
                    let Some(fr) = frames.pop() else {
                        // A return from the entry function ends the run.
                        break Some(Halt::Exit(Exit::Halted));
                    };
                    let callee = cur;
                    cur = fr.caller;
                    nargs = fr.nargs;
                    flags = fr.flags;
                    if W && fr.watched {
                        if let Some((_, watcher)) = watch {
                            regs.store(w);
                            watcher.on_return(program, callee, v, ram);
                            w = words(ram);
                        }
                    }
                    if fr.ret_pc == HOST {
                        break Some(Halt::Exit(Exit::Returned(v)));
                    }
                    pc = if ret == fr.ret {
                        fr.ret_pc as usize
                    } else {
                        match resume_pc(program, cur, ret) {
                            Some(p) => p as usize,
                            None => {
                                break Some(Halt::Error(format!(
                                    "Return address {ret} is not a command of {}",
                                    program.function_name(cur)
                                )))
                            }
                        }
                    };
                }
                Op::Halt => {
                    steps -= 1;
                    break Some(Halt::Exit(Exit::Halted));
                }
            }
        };

        regs.store(w);
        self.pc = pc as u32;
        self.steps = steps;
        self.cur = cur;
        self.nargs = nargs;
        self.flags = flags;
        self.profile_mark = profile_mark;
        let halt = halt?;
        Some(match halt {
            Halt::Exit(e) => e,
            Halt::Error(message) => Exit::RuntimeError {
                message,
                stack: self.call_stack(),
            },
            Halt::Os(Stop::Halt) => Exit::Halted,
            Halt::Os(Stop::SysError(code)) => Exit::SysError {
                code,
                stack: self.call_stack(),
            },
            Halt::Os(Stop::RuntimeError(message)) => Exit::RuntimeError {
                message,
                stack: self.call_stack(),
            },
            Halt::Os(Stop::Hang(message)) => Exit::Hang {
                message,
                stack: self.call_stack(),
            },
            Halt::Os(Stop::BlockedForever) => Exit::BlockedForever {
                stack: self.call_stack(),
            },
        })
    }
}

/// Resume position in `caller` for a RET word that is not the one the call
/// wrote (the program overwrote its frame): command `ret + 1`. None for the
/// `function` line, which is never executed.
fn resume_pc(program: &Program, caller: u32, ret: i16) -> Option<u32> {
    let f = &program.functions[caller as usize];
    let idx = usize::try_from(i32::from(ret) + 1).ok()?;
    let pc = *f.resume.get(idx).or(f.resume.last())?;
    (pc != u32::MAX).then_some(pc)
}
