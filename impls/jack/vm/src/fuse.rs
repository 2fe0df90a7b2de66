//! Superinstructions: sequences the Jack compiler emits all the time (spec
//! §4.3 templates) fused into one instruction. Each index of the fused array
//! holds the longest pattern starting there, so a jump into the middle of a
//! sequence still finds a valid (possibly fused) instruction, and the plain
//! array with the same indexing can take over at any point.
//!
//! A fused instruction performs the same memory reads and writes, in the
//! same order, as its commands; it only skips re-reading stack words it has
//! just written. When its fast-path conditions do not hold (a stack pointer
//! near 256 or near the end of RAM, an argument or `this`/`that` access that
//! would fail) it does nothing and the plain commands run instead, so errors
//! and step counts are exactly those of the plain commands.

use crate::machine::{ARGS_FIT, NEAR, NEAR_THAT, NEAR_THIS, THAT_OK, THIS_OK};
use crate::program::{Bin, Dst, Op, Operand, Src, ABS, ARG, CONST, LCL, PTR, THAT, THIS};

/// The most VM commands one fused instruction stands for.
pub(crate) const MAX_FUSED_STEPS: u64 = 8;

/// The fused instruction array (same indexing as `plain`); `starts` holds
/// each function's first instruction. Under the desktop profile (`desktop`)
/// no fused instruction ends in a `pop pointer` of a value it computes: the
/// desktop tests that value, and the plain command does.
pub(crate) fn fuse(plain: &[Op], starts: &[u32], desktop: bool) -> Vec<Op> {
    (0..plain.len())
        .map(|i| match plain[i] {
            Op::Call {
                callee,
                nargs,
                ret,
                method: false,
            } if nargs >= 1 && opens_as_method(plain, starts[usize::from(callee)]) => Op::Call {
                callee,
                nargs,
                ret,
                method: true,
            },
            Op::Function { n_vars, .. } if opens_as_method(plain, i as u32 + 1) => Op::Function {
                n_vars,
                method: true,
            },
            _ => match longest(&plain[i..]) {
                fused if desktop && (pops_pointer(fused) || far(fused)) => plain[i],
                fused if desktop => with_operands(fused, desktop_need),
                fused => fused,
            },
        })
        .collect()
}

/// Desktop: a `this`/`that` operand needs its pointer's near bit (see
/// [`crate::exec`]), not the web IDE's flag.
fn desktop_need(o: Operand) -> Operand {
    let need = match usize::from(o.base) {
        THIS => NEAR_THIS,
        THAT => NEAR_THAT,
        _ => return o,
    };
    Operand { need, ..o }
}

/// Desktop: whether fused instruction `op` has a `this`/`that` operand at
/// an offset of [`NEAR`] or more, which its near bits do not cover (the
/// plain commands test such an access in full).
fn far(op: Op) -> bool {
    let mut far = false;
    with_operands(op, |o| {
        far |= matches!(usize::from(o.base), THIS | THAT) && o.off >= NEAR;
        o
    });
    far
}

/// `op` with `f` applied to each of its operands.
fn with_operands(op: Op, mut f: impl FnMut(Operand) -> Operand) -> Op {
    match op {
        Op::Push2(a, b) => Op::Push2(f(a), f(b)),
        Op::Move(a, d) => Op::Move(f(a), f(d)),
        Op::MoveRun { from, to, len } => Op::MoveRun {
            from: f(from),
            to: f(to),
            len,
        },
        Op::BinSS { op, a, b } => Op::BinSS {
            op,
            a: f(a),
            b: f(b),
        },
        Op::BinPop { op, a, b, d } => Op::BinPop {
            op,
            a: f(a),
            b: f(b),
            d: f(d),
        },
        Op::BinS { op, b } => Op::BinS { op, b: f(b) },
        Op::BinSPop { op, b, d } => Op::BinSPop {
            op,
            b: f(b),
            d: f(d),
        },
        Op::CmpJump {
            op,
            a,
            b,
            not,
            target,
        } => Op::CmpJump {
            op,
            a: f(a),
            b: f(b),
            not,
            target,
        },
        Op::ArrayRead { index, base } => Op::ArrayRead {
            index: f(index),
            base: f(base),
        },
        Op::ArrayReadPop { index, base, to } => Op::ArrayReadPop {
            index: f(index),
            base: f(base),
            to: f(to),
        },
        Op::StoreThatSrc(v) => Op::StoreThatSrc(f(v)),
        Op::PushReturn(a) => Op::PushReturn(f(a)),
        other => other,
    }
}

/// Whether fused instruction `op` ends in a `pop pointer` (a target `PTR`).
fn pops_pointer(op: Op) -> bool {
    let d = match op {
        Op::Move(_, d) | Op::BinPop { d, .. } | Op::BinSPop { d, .. } => d,
        Op::ArrayReadPop { to, .. } => to,
        _ => return false,
    };
    usize::from(d.base) == PTR
}

/// Whether the function at `start` opens with `push argument 0; pop
/// pointer 0`, as every Jack method does.
fn opens_as_method(plain: &[Op], start: u32) -> bool {
    plain[start as usize..].starts_with(&[Op::PushArg(0), Op::PopPtr(0)])
}

fn src(op: Op) -> Option<Src> {
    Some(match op {
        Op::PushConst(c) => Operand::new(CONST, 0, c as u16),
        Op::PushLocal(i) => Operand::new(LCL, 0, i),
        Op::PushArg(i) => Operand::new(ARG, ARGS_FIT, i),
        Op::PushThis(i) => Operand::new(THIS, 0, i),
        Op::PushThisChk(i) => Operand::new(THIS, THIS_OK, i),
        Op::PushThat(i) => Operand::new(THAT, 0, i),
        Op::PushThatChk(i) => Operand::new(THAT, THAT_OK, i),
        Op::PushAbs(a) => Operand::new(ABS, 0, a),
        _ => return None,
    })
}

fn dst(op: Op) -> Option<Dst> {
    Some(match op {
        Op::PopLocal(i) => Operand::new(LCL, 0, i),
        Op::PopArg(i) => Operand::new(ARG, ARGS_FIT, i),
        Op::PopThis(i) => Operand::new(THIS, 0, i),
        Op::PopThisChk(i) => Operand::new(THIS, THIS_OK, i),
        Op::PopThat(i) => Operand::new(THAT, 0, i),
        Op::PopThatChk(i) => Operand::new(THAT, THAT_OK, i),
        Op::PopAbs(a) => Operand::new(ABS, 0, a),
        Op::PopPtr(p) => Operand::new(PTR, 0, u16::from(p)),
        _ => return None,
    })
}

fn bin(op: Op) -> Option<Bin> {
    Some(match op {
        Op::Add => Bin::Add,
        Op::Sub => Bin::Sub,
        Op::And => Bin::And,
        Op::Or => Bin::Or,
        Op::Eq => Bin::Eq,
        Op::Gt => Bin::Gt,
        Op::Lt => Bin::Lt,
        Op::Multiply => Bin::Mul,
        Op::Divide => Bin::Div,
        _ => return None,
    })
}

fn cmp(op: Op) -> Option<Bin> {
    bin(op).filter(|b| matches!(b, Bin::Eq | Bin::Gt | Bin::Lt))
}

fn is_that0(op: Op) -> bool {
    matches!(op, Op::PushThat(0) | Op::PushThatChk(0))
}

/// `pop temp 0; pop pointer 1; push temp 0; pop that 0`: the tail of
/// `let a[i] = e`.
fn is_store_tail(p: &[Op]) -> bool {
    matches!(
        p,
        [
            Op::PopAbs(5),
            Op::PopPtr(1),
            Op::PushAbs(5),
            Op::PopThat(0) | Op::PopThatChk(0),
            ..
        ]
    )
}

/// How many (up to 4) `push from+k; pop to+k` pairs open `p`.
fn move_run(p: &[Op], from: Src, to: Dst) -> usize {
    if usize::from(from.base) == CONST || usize::from(to.base) == PTR {
        return 1;
    }
    let shifted = |o: Operand, k: usize| Operand {
        off: o.off.wrapping_add(k as u16),
        ..o
    };
    (1..4)
        .take_while(|&k| {
            let pair = (p.get(2 * k).copied(), p.get(2 * k + 1).copied());
            pair.0.and_then(src) == Some(shifted(from, k))
                && pair.1.and_then(dst) == Some(shifted(to, k))
        })
        .count()
        + 1
}

fn longest(p: &[Op]) -> Op {
    let at = |i: usize| p.get(i).copied().unwrap_or(Op::Halt);
    let (s0, s1) = (src(at(0)), src(at(1)));
    if let (Some(a), Some(b)) = (s0, s1) {
        if let Some(op) = cmp(at(2)) {
            match (at(3), at(4)) {
                (Op::Not, Op::IfGoto(target)) => {
                    return Op::CmpJump {
                        op,
                        a,
                        b,
                        not: true,
                        target,
                    }
                }
                (Op::IfGoto(target), _) => {
                    return Op::CmpJump {
                        op,
                        a,
                        b,
                        not: false,
                        target,
                    }
                }
                _ => {}
            }
        }
        if at(2) == Op::Add && at(3) == Op::PopPtr(1) && is_that0(at(4)) {
            if let Some(to) = dst(at(5)) {
                return Op::ArrayReadPop {
                    index: a,
                    base: b,
                    to,
                };
            }
            return Op::ArrayRead { index: a, base: b };
        }
        if let Some(op) = bin(at(2)) {
            if let Some(d) = dst(at(3)) {
                return Op::BinPop { op, a, b, d };
            }
            return Op::BinSS { op, a, b };
        }
    }
    if let Some(v) = s0 {
        if is_store_tail(&p[1..]) {
            return Op::StoreThatSrc(v);
        }
    }
    if is_store_tail(p) {
        return Op::StoreThat;
    }
    if let Some(op) = cmp(at(0)) {
        if let (Op::Not, Op::IfGoto(target)) = (at(1), at(2)) {
            return Op::CmpNotJump { op, target };
        }
    }
    if at(0) == Op::Add && at(1) == Op::PopPtr(1) && is_that0(at(2)) {
        return Op::PtrRead;
    }
    if let Some(b) = s0 {
        if let Some(op) = bin(at(1)) {
            if let Some(d) = dst(at(2)) {
                return Op::BinSPop { op, b, d };
            }
            return Op::BinS { op, b };
        }
        if at(1) == Op::Return {
            return Op::PushReturn(b);
        }
        if let Some(d) = dst(at(1)) {
            let len = move_run(p, b, d);
            if len >= 2 {
                return Op::MoveRun {
                    from: b,
                    to: d,
                    len: len as u8,
                };
            }
            return Op::Move(b, d);
        }
        if let Some(b2) = s1 {
            return Op::Push2(b, b2);
        }
    }
    if let (Op::Not, Op::IfGoto(target)) = (at(0), at(1)) {
        return Op::NotIfGoto(target);
    }
    at(0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn jack_templates_fuse() {
        let cond = [
            Op::PushLocal(1),
            Op::PushConst(8192),
            Op::Lt,
            Op::Not,
            Op::IfGoto(9),
        ];
        assert_eq!(
            longest(&cond),
            Op::CmpJump {
                op: Bin::Lt,
                a: Operand::new(LCL, 0, 1),
                b: Operand::new(CONST, 0, 8192),
                not: true,
                target: 9
            }
        );
        let read = [
            Op::PushConst(2),
            Op::PushLocal(0),
            Op::Add,
            Op::PopPtr(1),
            Op::PushThat(0),
        ];
        assert_eq!(
            longest(&read),
            Op::ArrayRead {
                index: Operand::new(CONST, 0, 2),
                base: Operand::new(LCL, 0, 0)
            }
        );
        let store = [
            Op::PushLocal(2),
            Op::PopAbs(5),
            Op::PopPtr(1),
            Op::PushAbs(5),
            Op::PopThat(0),
        ];
        assert_eq!(longest(&store), Op::StoreThatSrc(Operand::new(LCL, 0, 2)));
        let prologue = [Op::PushArg(0), Op::PopPtr(0), Op::PushThis(1)];
        assert_eq!(
            longest(&prologue),
            Op::Move(Operand::new(ARG, ARGS_FIT, 0), Operand::new(PTR, 0, 0))
        );
        let copy = [
            Op::PushArg(1),
            Op::PopThis(0),
            Op::PushArg(2),
            Op::PopThis(1),
            Op::PushArg(3),
            Op::PopThis(2),
            Op::PushArg(5),
            Op::PopThis(3),
        ];
        assert_eq!(
            longest(&copy),
            Op::MoveRun {
                from: Operand::new(ARG, ARGS_FIT, 1),
                to: Operand::new(THIS, 0, 0),
                len: 3
            }
        );
        assert_eq!(
            longest(&[
                Op::PushConst(0),
                Op::PopLocal(0),
                Op::PushConst(1),
                Op::PopLocal(1)
            ]),
            Op::Move(Operand::new(CONST, 0, 0), Operand::new(LCL, 0, 0))
        );
        let read_into = [
            Op::PushConst(2),
            Op::PushLocal(0),
            Op::Add,
            Op::PopPtr(1),
            Op::PushThat(0),
            Op::PopLocal(3),
        ];
        assert_eq!(
            longest(&read_into),
            Op::ArrayReadPop {
                index: Operand::new(CONST, 0, 2),
                base: Operand::new(LCL, 0, 0),
                to: Operand::new(LCL, 0, 3)
            }
        );
        assert_eq!(longest(&[Op::Add, Op::Halt]), Op::Add);
        assert_eq!(
            longest(&[Op::PushConst(0), Op::Return]),
            Op::PushReturn(Operand::new(CONST, 0, 0))
        );
        for op in [cond.as_slice(), &read, &store, &copy, &read_into]
            .into_iter()
            .flat_map(|code| fuse(code, &[], false))
        {
            assert!(op.steps() <= MAX_FUSED_STEPS);
        }
    }
}
