//! What a step of the night is: the one trait every step implements.

use super::Night;
use anyhow::Result;

/// One step of the night.
pub trait Step {
    /// What `--steps` selects it by (the three level sets share `levels`).
    fn key(&self) -> &'static str;
    /// Its line in the log and in the report's step timings.
    fn name(&self) -> String;
    /// Whether it runs whatever `--steps` says (opening the cast).
    fn always(&self) -> bool {
        false
    }
    /// Do the work, adding results to `night.builder`'s report.
    fn run(&self, night: &mut Night<'_>) -> Result<()>;
}
