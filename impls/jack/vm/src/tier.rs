//! [`crate::Engine::Auto`]: a machine runs on the interpreter until the
//! program's machines of its profile have run a threshold of steps on the
//! interpreter between them (so that the many short runs from clones of one
//! snapshot, a pixel or an op each, count together), then on the program's
//! compiled code, which it compiles at that point if no machine has yet.
//! The switch falls between two slices of the run (`Machine::drive`), where
//! the dispatcher can take over from any instruction, so the run is the
//! same instruction by instruction as on either engine alone.

use crate::machine::Machine;
use std::sync::atomic::Ordering;

/// An Auto machine that has not switched yet.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Tier {
    /// Interpreted steps (of the program, all machines) that trigger the switch.
    threshold: u64,
    /// The machine's step count when it last added its steps to the
    /// program's count.
    credited: u64,
}

impl Tier {
    /// A tier for a new machine that switches after `threshold`.
    pub(crate) fn new(threshold: u64) -> Tier {
        Tier {
            threshold,
            credited: 0,
        }
    }
}

impl Machine {
    /// For an Auto machine that still interprets: switch to compiled code
    /// if the program has it or the threshold is reached (compiling then;
    /// where that fails the machine interprets for good), else the step
    /// count at which to look again. `u64::MAX` once there is nothing more
    /// to decide.
    pub(crate) fn tier_limit(&mut self) -> u64 {
        let Some(tier) = self.tier else {
            return u64::MAX;
        };
        let (profile, divide) = (self.os.profile(), self.os.divide_rule());
        let native = match self.program.native_made(profile, divide) {
            Some(made) => made.as_ref().ok().cloned(),
            None => {
                let counter = &self.program.interpreted[crate::timing::index(profile)];
                let total = counter.load(Ordering::Relaxed) + (self.steps - tier.credited);
                if total < tier.threshold {
                    return self.steps.saturating_add(tier.threshold - total);
                }
                self.program.native(profile, divide).ok()
            }
        };
        self.tier_credit();
        self.native = native;
        self.tier = None;
        u64::MAX
    }

    /// Add the steps this machine has interpreted since the last time to
    /// the program's count.
    pub(crate) fn tier_credit(&mut self) {
        if let Some(tier) = &mut self.tier {
            let counter = &self.program.interpreted[crate::timing::index(self.os.profile())];
            counter.fetch_add(self.steps - tier.credited, Ordering::Relaxed);
            tier.credited = self.steps;
        }
    }
}
