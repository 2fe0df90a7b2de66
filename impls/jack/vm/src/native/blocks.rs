//! Basic blocks of one VM function, as the translator sees them: where
//! compiled code may be entered (leaders), how many steps each block
//! charges (each instruction's [`Op::steps`], the same count the
//! interpreter charges), and how far its stack pointer moves, so that one
//! test at the block's entry covers every stack access inside it.

use crate::program::Op;
use crate::timing::STACK_BASE;
use jack_os::Builtin;

/// A frame's locals are zeroed by straight-line stores up to this many; a
/// `function` line or a call that zeroes more is left to the interpreter.
pub(crate) const MAX_INLINE_LOCALS: u16 = 64;

/// How the translator handles one instruction.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Kind {
    /// Runs inside the block; control falls through.
    Straight,
    /// `goto` or `if-goto`: ends the block.
    Jump,
    /// A call of a VM function, a return, or a call of a built-in that
    /// does not block (through a host call, `builtin::call`): compiled,
    /// ends the block.
    CallOrReturn,
    /// Left to the interpreter (blocking built-ins, halt, load-time failures, the
    /// entry function's checked accesses, `pop constant` outside plain RAM,
    /// a `function` line with more than [`MAX_INLINE_LOCALS`] locals):
    /// the block ends before it, and compiled code exits there.
    Interpreted,
}

pub(crate) fn kind(op: Op) -> Kind {
    match op {
        Op::Goto(_) | Op::IfGoto(_) => Kind::Jump,
        Op::Call { .. } | Op::Return => Kind::CallOrReturn,
        Op::CallBuiltin { builtin, .. } if inline_builtin(builtin) => Kind::Straight,
        Op::CallBuiltin { builtin, .. } if !builtin.blocks() => Kind::CallOrReturn,
        Op::CallBuiltin { .. } | Op::Halt | Op::Fail(_) | Op::EntryAccess { .. } => {
            Kind::Interpreted
        }
        Op::PopRam(a) if !crate::native::plain_address(a) => Kind::Interpreted,
        // A desktop static past RAM[255] (a file's index past 239) may
        // alias the stack: left to the interpreter.
        Op::PushAbs(a) | Op::PopAbs(a) if a > 255 => Kind::Interpreted,
        Op::Function { n_vars, .. } if n_vars > MAX_INLINE_LOCALS => Kind::Interpreted,
        _ => Kind::Straight,
    }
}

/// Whether compiled code runs built-in `b` itself, in its block: the
/// arithmetic ones, and `Memory.peek`/`poke` and `String.length`,
/// `charAt` and `appendChar` of words that need no rule (else it leaves
/// for the interpreter there).
pub(crate) fn inline_builtin(b: Builtin) -> bool {
    matches!(
        b,
        Builtin::MathAbs
            | Builtin::MathMin
            | Builtin::MathMax
            | Builtin::MemoryPeek
            | Builtin::MemoryPoke
            | Builtin::StringLength
            | Builtin::StringCharAt
            | Builtin::StringAppendChar
    )
}

/// How far above SP before its pops a built-in call reaches: the desktop
/// writes its frame there (5 words) and then pushes its result, and stops
/// with "Stack overflow" where they do not fit.
const BUILTIN_REACH: i32 = 6;

/// Stack words an instruction pops, then pushes (calls and returns:
/// only what the block-entry test must cover).
pub(crate) fn stack_effect(op: Op) -> (i32, i32) {
    match op {
        Op::PushConst(_)
        | Op::PushLocal(_)
        | Op::PushArg(_)
        | Op::PushThis(_)
        | Op::PushThisChk(_)
        | Op::PushThat(_)
        | Op::PushThatChk(_)
        | Op::PushAbs(_)
        | Op::PushPtr(_) => (0, 1),
        Op::PopLocal(_)
        | Op::PopArg(_)
        | Op::PopThis(_)
        | Op::PopThisChk(_)
        | Op::PopThat(_)
        | Op::PopThatChk(_)
        | Op::PopAbs(_)
        | Op::PopPtr(_)
        | Op::PopRam(_)
        | Op::IfGoto(_)
        | Op::Return => (1, 0),
        Op::Add
        | Op::Sub
        | Op::And
        | Op::Or
        | Op::Eq
        | Op::Gt
        | Op::Lt
        | Op::Multiply
        | Op::Divide => (2, 1),
        Op::Neg | Op::Not => (1, 1),
        Op::Function { n_vars, .. } => (0, i32::from(n_vars)),
        Op::CallBuiltin { nargs, .. } => (i32::from(nargs), 1),
        _ => (0, 0),
    }
}

/// Whether `op` is a `pop constant` into the stack (RAM[256] and up), a
/// write no stack-depth reasoning sees.
pub(crate) fn pops_into_stack(op: Op) -> bool {
    matches!(op, Op::PopRam(a) if a >= STACK_BASE)
}

/// The end of the code that `blocks` (from [`blocks`], of a function
/// starting at `start`) cover.
pub(crate) fn code_end(blocks: &[Block], start: u32) -> u32 {
    blocks.last().map_or(start, |b| b.end.max(b.start + 1))
}

/// Whether no instruction in `start..end` (stack depths before each, SP -
/// LCL, in `depths` from `start`; None where unreached) pops a word below
/// `floor`: a call pops its arguments, whose callee's ARG then lies at or
/// above it. The words below `floor` are then never stack words.
pub(crate) fn pops_stay_above(code: &[Op], start: u32, depths: &[Option<i32>], floor: i32) -> bool {
    depths.iter().enumerate().all(|(k, d)| {
        let Some(d) = *d else { return true };
        let pops = match code[start as usize + k] {
            Op::Call { nargs, .. } => i32::from(nargs),
            op => stack_effect(op).0,
        };
        pops == 0 || d - pops >= floor
    })
}

/// The lowest and highest stack pointer over `ops`, relative to SP before
/// them.
pub(crate) fn depth_range(ops: &[Op]) -> (i32, i32) {
    walk_depths(ops, false)
}

/// [`depth_range`] where each call of a VM function pops its arguments
/// and pushes its result, as code that goes on after the call sees the
/// stack (the words a block or an inline run holds in registers).
pub(crate) fn depth_range_through_calls(ops: &[Op]) -> (i32, i32) {
    walk_depths(ops, true)
}

fn walk_depths(ops: &[Op], through_calls: bool) -> (i32, i32) {
    let (mut depth, mut min_depth, mut max_depth) = (0i32, 0i32, 0i32);
    for &op in ops {
        if let Op::CallBuiltin { .. } = op {
            max_depth = max_depth.max(depth + BUILTIN_REACH);
        }
        let (pops, pushes) = match op {
            Op::Call { nargs, .. } if through_calls => (i32::from(nargs), 1),
            op => stack_effect(op),
        };
        depth -= pops;
        min_depth = min_depth.min(depth);
        depth += pushes;
        max_depth = max_depth.max(depth);
    }
    (min_depth, max_depth)
}

/// How far `ops` move the stack pointer in all (calls not counted).
pub(crate) fn net_depth(ops: &[Op]) -> i32 {
    ops.iter()
        .map(|&op| {
            let (pops, pushes) = stack_effect(op);
            pushes - pops
        })
        .sum()
}

/// One basic block: instructions `start..end` (global indices) run
/// compiled; `exit_at` is the instruction after them when the block ends
/// by leaving compiled code for the interpreter.
#[derive(Clone, Debug)]
pub(crate) struct Block {
    pub start: u32,
    pub end: u32,
    /// Steps charged when the whole block runs (its instructions, a final
    /// call or return included).
    pub steps: u64,
    /// Lowest and highest stack pointer, relative to the entry's, over the
    /// block (a final call's frame and a return's frame are checked apart).
    pub min_depth: i32,
    pub max_depth: i32,
    /// Whether the entry test must check SP: the block touches the stack,
    /// or holds a `function` line (whose stack rule applies even with no
    /// locals).
    pub checks_stack: bool,
}

/// The blocks of the function whose instructions are `code[start..end]`,
/// in order, and for each instruction index (relative to `start`) the
/// block that begins there, if one does. Blocks begin at `start`, at
/// every jump target, after every instruction that ends a block, and at
/// each of `entries` (where the machine may stand when compiled code is
/// entered).
pub(crate) fn blocks(
    code: &[Op],
    start: u32,
    end: u32,
    entries: &[u32],
) -> (Vec<Block>, Vec<Option<u32>>) {
    let len = (end - start) as usize;
    let mut leader = vec![false; len];
    leader[0] = true;
    for &e in entries {
        leader[(e - start) as usize] = true;
    }
    // (A jump, call or return ends its block, and an interpreted
    // instruction is a block of its own, in the loop below.)
    for &op in &code[start as usize..end as usize] {
        if let Op::Goto(t) | Op::IfGoto(t) = op {
            leader[(t - start) as usize] = true;
        }
    }
    let mut blocks = Vec::new();
    let mut index = vec![None; len];
    let mut i = 0;
    while i < len {
        index[i] = Some(blocks.len() as u32);
        let (mut steps, mut checks_stack) = (0, false);
        let mut j = i;
        loop {
            let op = code[start as usize + j];
            if kind(op) == Kind::Interpreted {
                break;
            }
            let (pops, pushes) = stack_effect(op);
            checks_stack |= pops + pushes > 0 || matches!(op, Op::Function { .. });
            steps += op.steps();
            j += 1;
            if kind(op) != Kind::Straight || j == len || leader[j] {
                break;
            }
        }
        let (min_depth, max_depth) = depth_range(&code[start as usize + i..start as usize + j]);
        blocks.push(Block {
            start: start + i as u32,
            end: start + j as u32,
            steps,
            min_depth,
            max_depth,
            checks_stack,
        });
        // An interpreted instruction is a block of its own with no compiled
        // instruction: entering it exits at once.
        i = j.max(i + 1);
    }
    (blocks, index)
}

/// SP - LCL before each instruction of `code[start..end]` (relative to
/// `start`), where the function's code fixes it: every path from the
/// function's start (SP - LCL = `entry`) reaches an instruction with one
/// value, as Jack-compiled code does. `None` where two paths disagree
/// (hand-written code); an instruction no path reaches has no depth.
pub(crate) fn static_depths(
    code: &[Op],
    start: u32,
    end: u32,
    entry: i32,
) -> Option<Vec<Option<i32>>> {
    let mut depth = vec![None; (end - start) as usize];
    let mut work = vec![(start, entry)];
    while let Some((pc, d)) = work.pop() {
        let Some(slot) = depth.get_mut((pc - start) as usize) else {
            // Past the function's code (never: it ends in Halt and jumps).
            return None;
        };
        match *slot {
            Some(known) if known == d => continue,
            Some(_) => return None,
            None => *slot = Some(d),
        }
        let op = code[pc as usize];
        let after = d + match op {
            Op::Call { nargs, .. } => 1 - i32::from(nargs),
            Op::EntryAccess { push, .. } => {
                if push {
                    1
                } else {
                    -1
                }
            }
            _ => {
                let (pops, pushes) = stack_effect(op);
                pushes - pops
            }
        };
        match op {
            Op::Goto(t) => work.push((t, after)),
            Op::IfGoto(t) => work.extend([(t, after), (pc + 1, after)]),
            Op::Return | Op::Halt | Op::Fail(_) => {}
            _ if pc + 1 < end => work.push((pc + 1, after)),
            _ => {}
        }
    }
    Some(depth)
}

/// Where each block tests the step budget, and how many steps it covers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Budget {
    /// The block tests the budget on every entry: the function's first
    /// block, a loop's head (the target of a backward jump), a call's
    /// continuation (a built-in's too). Other blocks are reached only forward from a block
    /// whose test covered them (or from the dispatcher, which tests).
    pub tested: bool,
    /// The most steps from the block's start to the next block that tests
    /// (or to where compiled code leaves), over every path.
    pub covers: u64,
}

/// The budget tests of `blocks` (from [`blocks`], with `index` the block
/// at each instruction relative to `start`). Every cycle of the flow
/// graph holds a backward jump, so paths between tested blocks are
/// finite and `covers` bounds them.
pub(crate) fn budgets(
    code: &[Op],
    start: u32,
    blocks: &[Block],
    index: &[Option<u32>],
) -> Vec<Budget> {
    let at = |pc: u32| index[(pc - start) as usize].expect("jumps land on blocks") as usize;
    let mut tested = vec![false; blocks.len()];
    if let Some(t) = tested.first_mut() {
        *t = true;
    }
    // Flow edges of compiled code between blocks (a call's continuation
    // is entered after the callee, so it tests). A function's code ends
    // in `Halt` and jumps, so a block that falls through, branches or
    // calls has a next block.
    let succ = |b: &Block| -> Vec<usize> {
        if b.end == b.start {
            return Vec::new();
        }
        match code[b.end as usize - 1] {
            Op::Goto(t) => vec![at(t)],
            Op::IfGoto(t) => vec![at(t), at(b.end)],
            Op::Return | Op::Call { .. } | Op::CallBuiltin { .. } => Vec::new(),
            _ => vec![at(b.end)],
        }
    };
    for (i, b) in blocks.iter().enumerate() {
        if b.end == b.start {
            continue;
        }
        match code[b.end as usize - 1] {
            Op::Call { .. } | Op::CallBuiltin { .. } => {
                tested[at(b.end)] = true;
            }
            _ => {}
        }
        for s in succ(b) {
            if s <= i {
                tested[s] = true;
            }
        }
    }
    let mut covers = vec![0u64; blocks.len()];
    for i in (0..blocks.len()).rev() {
        let b = &blocks[i];
        let next = succ(b)
            .into_iter()
            .map(|s| if tested[s] { 0 } else { covers[s] })
            .max()
            .unwrap_or(0);
        covers[i] = b.steps + next;
    }
    tested
        .into_iter()
        .zip(covers)
        .map(|(tested, covers)| Budget { tested, covers })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::{
        blocks, budgets, depth_range_through_calls, kind, static_depths, Budget, Kind,
        MAX_INLINE_LOCALS,
    };
    use crate::program::Op;
    use jack_os::Builtin;

    /// Where compiled code stops for the interpreter, at each edge: the
    /// arithmetic built-ins run inside the block and the others through
    /// the host; statics to RAM[255] are compiled, past it (where they may
    /// alias the stack) interpreted; a `function` line zeroes up to
    /// `MAX_INLINE_LOCALS` locals itself.
    #[test]
    fn kinds_at_their_edges() {
        let builtin = |builtin, nargs| Op::CallBuiltin { builtin, nargs };
        assert_eq!(kind(builtin(Builtin::MathAbs, 1)), Kind::Straight);
        assert_eq!(kind(builtin(Builtin::StringCharAt, 2)), Kind::Straight);
        assert_eq!(
            kind(builtin(Builtin::OutputPrintInt, 1)),
            Kind::CallOrReturn
        );
        assert_eq!(kind(builtin(Builtin::SysWait, 1)), Kind::Interpreted);
        for (a, k) in [(255, Kind::Straight), (256, Kind::Interpreted)] {
            assert_eq!(kind(Op::PushAbs(a)), k, "push {a}");
            assert_eq!(kind(Op::PopAbs(a)), k, "pop {a}");
        }
        let function = |n_vars| Op::Function {
            n_vars,
            method: false,
        };
        assert_eq!(kind(function(MAX_INLINE_LOCALS)), Kind::Straight);
        assert_eq!(kind(function(MAX_INLINE_LOCALS + 1)), Kind::Interpreted);
    }

    /// SP - LCL before each instruction of Jack-shaped code: the entry
    /// function's checked `pop local`/`push local`, a branch to a return,
    /// a loop whose head is reached twice at one depth, a call, and an
    /// unreached `Halt` (no depth). A range ending at a straight
    /// instruction follows nothing past it.
    #[test]
    fn static_depths_follow_jack_shaped_code() {
        let entry = |push| Op::EntryAccess {
            local: true,
            push,
            index: 0,
        };
        let call = Op::Call {
            callee: 0,
            nargs: 1,
            ret: 0,
            method: false,
        };
        let code = [
            Op::PushConst(1),
            entry(false),
            entry(true),
            Op::IfGoto(9),
            Op::PushConst(3), // the loop's head
            call,
            Op::PopAbs(5),
            Op::Goto(4),
            Op::PushConst(0),
            Op::PushConst(2), // the branch's target
            Op::Return,
            Op::Halt,
        ];
        let depths = |d: &[i32]| d.iter().map(|&d| (d >= 0).then_some(d)).collect::<Vec<_>>();
        assert_eq!(
            static_depths(&code, 0, code.len() as u32, 0),
            Some(depths(&[0, 1, 0, 1, 0, 1, 1, 0, -1, 0, 1, -1]))
        );
        assert_eq!(static_depths(&code, 0, 2, 0), Some(depths(&[0, 1])));
    }

    /// A block's stack range stops at its final call, as the stack stands
    /// before it: the call's argument words and frame are tested with the
    /// call, so arguments pushed by an earlier block do not lower it. Code
    /// that goes on after a call sees its arguments popped and its result
    /// pushed.
    #[test]
    fn a_blocks_range_leaves_its_final_calls_arguments_to_the_call() {
        let call = Op::Call {
            callee: 0,
            nargs: 2,
            ret: 0,
            method: false,
        };
        let code = [Op::PushConst(1), call, Op::Return];
        let (blocks, _) = blocks(&code, 0, code.len() as u32, &[]);
        assert_eq!((blocks[0].min_depth, blocks[0].max_depth), (0, 1));
        assert_eq!(depth_range_through_calls(&code[..2]), (-1, 1));
    }

    /// A block that ends in a return covers its own steps only: compiled
    /// code leaves there, so the block laid out after it (here a forward
    /// jump's target, which tests no budget) is not on its path. A budget
    /// test that counted it would send the return's block to the
    /// interpreter whenever fewer steps than both are left.
    #[test]
    fn a_return_covers_no_block_after_it() {
        let code = [
            Op::IfGoto(3),
            Op::PushConst(0),
            Op::Return,
            Op::PushConst(1), // the forward jump's target
            Op::PushConst(2),
            Op::Return,
            Op::Halt,
        ];
        let (blocks, index) = blocks(&code, 0, code.len() as u32, &[]);
        let budgets = budgets(&code, 0, &blocks, &index);
        let (second, target) = (index[1].unwrap() as usize, index[3].unwrap() as usize);
        assert!(
            !budgets[target].tested,
            "the target is reached forward only"
        );
        assert_eq!(
            budgets[second],
            Budget {
                tested: false,
                covers: blocks[second].steps
            }
        );
    }
}
