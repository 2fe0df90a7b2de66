//! Running compiled statements on a machine: arguments from registers,
//! return values into them, the end of a run as an outcome.

use super::statement::{Call, Slot};
use crate::JackError;
use common::Outcome;
use hack_vm::{Exit, Machine};

/// The values of a context's variables (object pointers, ints, booleans).
pub(crate) type Regs = Vec<i16>;

/// Instructions a constructor, getter or init statement may take.
pub(crate) const SETUP_BUDGET: u64 = 50_000_000;

/// The arguments of `call` from `regs`.
pub(crate) fn arguments(call: &Call, regs: &[i16]) -> Vec<i16> {
    call.args
        .iter()
        .map(|s| match *s {
            Slot::Var(v) => regs[v],
            Slot::Lit(n) => n,
            Slot::Skip => 0,
        })
        .collect()
}

/// Run `call` with at most `budget` instructions; on a return its value
/// goes to the target register.
pub(crate) fn run(
    m: &mut Machine,
    call: &Call,
    regs: &mut [i16],
    budget: u64,
) -> Result<Exit, JackError> {
    let args = arguments(call, regs);
    let exit = m.call(&call.name, &args, Some(budget))?;
    if let (Exit::Returned(v), Some(t)) = (&exit, call.target) {
        regs[t] = *v;
    }
    Ok(exit)
}

/// Run a set-up statement that must return: its value.
pub(crate) fn call_returning(
    m: &mut Machine,
    call: &Call,
    regs: &mut [i16],
    field: &str,
) -> Result<i16, JackError> {
    match run(m, call, regs, SETUP_BUDGET)? {
        Exit::Returned(v) => Ok(v),
        exit => Err(JackError::Unexpected {
            what: format!("`{field}` ({})", call.name),
            exit,
        }),
    }
}

/// The outcome of a query from its [`Exit`]: `Sys.error(out_of_domain)` is
/// [`Outcome::OutOfDomain`], any other code a `SysError`, an exhausted
/// budget a hang; any other end is an error (`what` names the query).
pub fn outcome_of(
    exit: Exit,
    out_of_domain: Option<i16>,
    what: impl FnOnce() -> String,
) -> Result<Outcome<i16>, JackError> {
    match exit {
        Exit::Returned(v) => Ok(Outcome::Value(v)),
        Exit::SysError { code, .. } if Some(code) == out_of_domain => Ok(Outcome::OutOfDomain),
        Exit::SysError { code, .. } => Ok(Outcome::SysError(code)),
        Exit::Budget { .. } | Exit::Hang { .. } => Ok(Outcome::Hang),
        exit @ (Exit::Halted | Exit::RuntimeError { .. } | Exit::BlockedForever { .. }) => {
            Err(JackError::Unexpected { what: what(), exit })
        }
    }
}

/// Run `calls` in order, sharing `budget`; the first end that is not a
/// return stops them. The outcome of the last, and the instructions run.
pub(crate) fn run_all(
    m: &mut Machine,
    calls: &[Call],
    regs: &mut [i16],
    budget: u64,
    out_of_domain: Option<i16>,
) -> Result<(Outcome<i16>, u64), JackError> {
    let start = m.steps();
    let mut last = Outcome::Value(0);
    for call in calls {
        let left = budget.saturating_sub(m.steps() - start).max(1);
        let exit = run(m, call, regs, left)?;
        last = outcome_of(exit, out_of_domain, || call.name.clone())?;
        if !matches!(last, Outcome::Value(_)) {
            break;
        }
    }
    Ok((last, m.steps() - start))
}
