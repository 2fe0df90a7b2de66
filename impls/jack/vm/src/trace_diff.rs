//! Two runs compared by their call traces: every call of a program
//! function (with its arguments) and every return (with its value), in
//! order. The first event where the traces part locates a difference
//! between the runs (the same program under the `desktop` and `web` OS
//! profiles, say) to one Jack function and its call path. The OS's
//! built-in functions are not events: a different `Math.divide` result
//! shows as the first call or return of program code that it changes.

use crate::{Exit, FnId, Machine, Program, Ram, Watcher};
use std::fmt;

/// One event of a call trace.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum CallEvent {
    /// `function` was called with `args` (VM order: `this` first).
    Call { function: String, args: Vec<i16> },
    /// `function` returned `value`.
    Return { function: String, value: i16 },
}

impl fmt::Display for CallEvent {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CallEvent::Call { function, args } => {
                let args: Vec<String> = args.iter().map(i16::to_string).collect();
                write!(f, "call {function}({})", args.join(", "))
            }
            CallEvent::Return { function, value } => write!(f, "{function} returned {value}"),
        }
    }
}

/// Where two call traces part.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TraceDivergence {
    /// The Jack call stack both runs share there, outermost first.
    pub stack: Vec<String>,
    /// The next event of each run; `None` where that run had ended.
    pub a: Option<CallEvent>,
    /// See `a`.
    pub b: Option<CallEvent>,
}

/// The outcome of [`compare_call_traces`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TraceComparison {
    /// Events both traces share from the start (up to the divergence).
    pub matching: u64,
    /// The first difference, if any.
    pub divergence: Option<TraceDivergence>,
}

/// Events gathered from each run before the traces are compared.
const BATCH: usize = 1 << 14;

/// Instructions a run takes at a time while its events are gathered.
const SLICE: u64 = 1 << 20;

/// Run `a` and `b` from where they stand, each for at most `budget` more
/// instructions, comparing their call traces as they go, until the first
/// difference or until both runs end. Both machines are then at most a
/// slice past the point of difference; a further [`Machine::run`] goes on
/// from there (or returns the end again). Functions are matched by name,
/// so the two programs may be compiled differently. `progress` is told
/// how many instructions `a` has run, now and then (for a progress bar).
pub fn compare_call_traces(
    a: &mut Machine,
    b: &mut Machine,
    budget: Option<u64>,
    progress: &mut dyn FnMut(u64),
) -> TraceComparison {
    let pa = std::sync::Arc::clone(a.program());
    let pb = std::sync::Arc::clone(b.program());
    let b_to_a: Vec<Option<FnId>> = (0..pb.functions().len())
        .map(|id| pa.function_id(pb.function_name(id as FnId)))
        .collect();
    let mut stack: Vec<String> = a.call_stack().names().map(String::from).collect();
    let mut sides = [Side::new(a, budget), Side::new(b, budget)];
    let mut matching = 0;
    loop {
        for side in &mut sides {
            side.fill();
        }
        progress(sides[0].machine.steps());
        let [sa, sb] = &sides;
        let common = sa.trace.events.len().min(sb.trace.events.len());
        for i in 0..common {
            let (ea, eb) = (&sa.trace.events[i], &sb.trace.events[i]);
            let same = b_to_a[eb.function as usize] == Some(ea.function)
                && match (ea.kind, eb.kind) {
                    (Kind::Call { .. }, Kind::Call { .. }) => {
                        sa.trace.args(ea) == sb.trace.args(eb)
                    }
                    (Kind::Return { value: x }, Kind::Return { value: y }) => x == y,
                    _ => false,
                };
            if !same {
                return TraceComparison {
                    matching,
                    divergence: Some(TraceDivergence {
                        stack,
                        a: Some(sa.trace.event(&pa, i)),
                        b: Some(sb.trace.event(&pb, i)),
                    }),
                };
            }
            match ea.kind {
                Kind::Call { .. } => stack.push(pa.function_name(ea.function).to_string()),
                Kind::Return { .. } => {
                    stack.pop();
                }
            }
            matching += 1;
        }
        for side in &mut sides {
            side.trace.drop_front(common);
        }
        // At least one side has no events left. A side that has ended
        // with none while the other still has some parts the traces.
        let [sa, sb] = &sides;
        let finished = |s: &Side| s.ended && s.trace.events.is_empty();
        let waiting = |s: &Side| !s.trace.events.is_empty();
        if finished(sa) && finished(sb) {
            return TraceComparison {
                matching,
                divergence: None,
            };
        }
        if (finished(sa) && waiting(sb)) || (finished(sb) && waiting(sa)) {
            let next = |s: &Side, p: &Program| waiting(s).then(|| s.trace.event(p, 0));
            return TraceComparison {
                matching,
                divergence: Some(TraceDivergence {
                    stack,
                    a: next(sa, &pa),
                    b: next(sb, &pb),
                }),
            };
        }
    }
}

/// One run being compared: its machine, what is left of its budget, its
/// events not compared yet.
struct Side<'m> {
    machine: &'m mut Machine,
    left: Option<u64>,
    watch: Vec<bool>,
    trace: Trace,
    ended: bool,
}

impl<'m> Side<'m> {
    fn new(machine: &'m mut Machine, budget: Option<u64>) -> Side<'m> {
        let watch = vec![true; machine.program().functions().len()];
        Side {
            machine,
            left: budget,
            watch,
            trace: Trace::default(),
            ended: false,
        }
    }

    /// Run until [`BATCH`] events wait or the run ends (its end, or its
    /// budget spent).
    fn fill(&mut self) {
        while !self.ended && self.trace.events.len() < BATCH {
            let slice = self.left.map_or(SLICE, |l| l.min(SLICE));
            let before = self.machine.steps();
            let exit = self
                .machine
                .run_watched(Some(slice), &self.watch, &mut self.trace);
            let ran = self.machine.steps() - before;
            self.left = self.left.map(|l| l - ran);
            self.ended = !matches!(exit, Exit::Budget { .. }) || self.left == Some(0);
        }
    }
}

/// A compact event: the arguments of a call live in [`Trace::args`].
#[derive(Clone, Copy, Debug)]
struct Event {
    function: FnId,
    kind: Kind,
}

#[derive(Clone, Copy, Debug)]
enum Kind {
    Call { args_at: usize, nargs: usize },
    Return { value: i16 },
}

/// Events of one run not compared yet.
#[derive(Default)]
struct Trace {
    events: Vec<Event>,
    args: Vec<i16>,
}

impl Trace {
    fn args(&self, e: &Event) -> &[i16] {
        match e.kind {
            Kind::Call { args_at, nargs } => &self.args[args_at..args_at + nargs],
            Kind::Return { .. } => &[],
        }
    }

    /// Event `i` with names, for the report.
    fn event(&self, program: &Program, i: usize) -> CallEvent {
        let e = &self.events[i];
        let function = program.function_name(e.function).to_string();
        match e.kind {
            Kind::Call { .. } => CallEvent::Call {
                function,
                args: self.args(e).to_vec(),
            },
            Kind::Return { value } => CallEvent::Return { function, value },
        }
    }

    /// Forget the first `n` events (compared and equal).
    fn drop_front(&mut self, n: usize) {
        let cut = self.events[n..]
            .iter()
            .find_map(|e| match e.kind {
                Kind::Call { args_at, .. } => Some(args_at),
                Kind::Return { .. } => None,
            })
            .unwrap_or(self.args.len());
        self.events.drain(..n);
        self.args.drain(..cut);
        for e in &mut self.events {
            if let Kind::Call { args_at, .. } = &mut e.kind {
                *args_at -= cut;
            }
        }
    }
}

impl Watcher for Trace {
    fn on_call(&mut self, _: &Program, function: FnId, args: &[i16], _: &Ram) {
        self.events.push(Event {
            function,
            kind: Kind::Call {
                args_at: self.args.len(),
                nargs: args.len(),
            },
        });
        self.args.extend_from_slice(args);
    }

    fn on_return(&mut self, _: &Program, function: FnId, value: i16, _: &Ram) {
        self.events.push(Event {
            function,
            kind: Kind::Return { value },
        });
    }
}
