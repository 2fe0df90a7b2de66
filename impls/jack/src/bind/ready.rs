//! Reaching the "ready" point of a bound program: after its init
//! statements, or by running the program from its entry (`Sys.init`, which
//! calls `Main.main`) with scripted keys until the first call of a named
//! function, stopping just before that call.
//!
//! A watcher cannot stop the emulator, so the run goes in slices watching
//! only that function; in the slice where it is called, the exact
//! instruction is found by bisection over re-runs of the slice from its
//! start (runs are deterministic, and an instruction budget stops exactly
//! between two commands).

use super::error::BindError;
use super::spec::Ready;
use super::statement::{compile, Classes, Context};
use super::vm::call_returning;
use super::JackProgram;
use crate::JackError;
use hack_vm::{Config, Exit, FnId, KeyScript, Machine, Program, Ram, Watcher};

/// Instructions the run to `until_call` may take unless the binding says.
pub const DEFAULT_READY_BUDGET: u64 = 200_000_000;

/// Instructions per watched slice of the run.
const SLICE: u64 = 1 << 20;

/// The key script of `keys` held `hold` instructions each; errors name
/// `field`.
pub(crate) fn key_script(
    field: &str,
    keys: &str,
    hold: Option<u64>,
) -> Result<KeyScript, BindError> {
    KeyScript::parse(keys, hold.unwrap_or(KeyScript::DEFAULT_HOLD))
        .map_err(|e| BindError::new(field, e.to_string()))
}

/// A fresh machine of `program` with the keys of `ready` (none for init).
pub(crate) fn config(program: &JackProgram, ready: &Ready) -> Result<Config, BindError> {
    let keys = match ready {
        Ready::Init { .. } => KeyScript::default(),
        Ready::Run { keys, hold, .. } => key_script("ready.keys", keys, *hold)?,
    };
    Ok(Config {
        profile: program.profile,
        divide: Some(program.divide),
        keys,
        ..Config::default()
    })
}

/// The machine at the ready point.
pub(crate) fn reach(
    program: &JackProgram,
    ready: &Ready,
    classes: &Classes,
) -> Result<Machine, JackError> {
    let mut m = Machine::new(program.program.clone(), config(program, ready)?);
    match ready {
        Ready::Init { init } => {
            let context = Context {
                vars: Vec::new(),
                skip: false,
            };
            for (i, text) in init.iter().enumerate() {
                let field = format!("ready.init[{i}]");
                let call = compile(
                    &field,
                    text,
                    &context,
                    classes,
                    &program.program,
                    &program.signatures,
                )?;
                call_returning(&mut m, &call, &mut [], &field)?;
            }
            Ok(m)
        }
        Ready::Run {
            run,
            until_call,
            budget,
            ..
        } => {
            let entry = program.program.function_name(program.program.entry());
            if run != "Main.main" && run != entry {
                return Err(BindError::new(
                    "ready.run",
                    format!(
                        "`{run}`: a run starts from the program's entry ({entry}, which calls Main.main); \
                         write `Main.main`, or use `init` to call other functions"
                    ),
                )
                .into());
            }
            let target = program.program.function_id(until_call).ok_or_else(|| {
                BindError::new("ready.until_call", program.signatures.missing(until_call))
            })?;
            let budget = budget.unwrap_or(DEFAULT_READY_BUDGET);
            run_until_call(m, target, budget).map_err(|why| {
                BindError::new(
                    "ready.until_call",
                    format!("`{until_call}` is never called: {why}"),
                )
                .into()
            })
        }
    }
}

/// Notes whether the watched function was called.
struct Called(bool);

impl Watcher for Called {
    fn on_call(&mut self, _: &Program, _: FnId, _: &[i16], _: &Ram) {
        self.0 = true;
    }
    fn on_return(&mut self, _: &Program, _: FnId, _: i16, _: &Ram) {}
}

/// Whether running `m` for `n` instructions calls a watched function.
fn calls_within(m: &Machine, watch: &[bool], n: u64) -> bool {
    let mut m = m.clone();
    let mut called = Called(false);
    m.run_watched(Some(n), watch, &mut called);
    called.0
}

/// Run `m` from where it stands until just before its first call of
/// `target`, within `budget` instructions.
fn run_until_call(mut m: Machine, target: FnId, budget: u64) -> Result<Machine, String> {
    let mut watch = vec![false; m.program().functions().len()];
    watch[target as usize] = true;
    let start = m.steps();
    loop {
        let before = m.clone();
        let mut called = Called(false);
        let left = budget.saturating_sub(m.steps() - start).max(1);
        let exit = m.run_watched(Some(SLICE.min(left)), &watch, &mut called);
        if called.0 {
            // The smallest n whose run makes the call: the call is the
            // command that starts at instruction n - 1.
            let (mut lo, mut hi) = (0, m.steps() - before.steps());
            while hi - lo > 1 {
                let mid = lo + (hi - lo) / 2;
                if calls_within(&before, &watch, mid) {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            let mut ready = before;
            if lo > 0 {
                ready.run(Some(lo));
            }
            return Ok(ready);
        }
        let used = m.steps() - start;
        match exit {
            Exit::Budget { .. } if used < budget => {}
            Exit::Budget { stack } => {
                return Err(format!(
                    "the budget of {budget} instructions ran out first (in {stack}); \
                     check `ready.keys` or raise `ready.budget`"
                ))
            }
            exit => {
                return Err(format!(
                    "the run ended first, after {used} instructions: {exit}"
                ))
            }
        }
    }
}
