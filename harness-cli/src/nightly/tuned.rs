//! The tuned-scenes step: the descriptions `harness tune` wrote for the
//! seed and rtdemo scenes with 0 differing pixels (`vectors/scenes/tests/
//! *-tuned-best.json`, docs/tuning.md) through the scene step's
//! comparisons: ref-f316, gpu-f316 and the generated Jack program bit for
//! bit, and each one's cost per pixel in the report's scene table, beside
//! its untuned scene's row from the scenes step.

use super::step::Step;
use super::{scenes, Night};
use anyhow::Result;

/// The tuned descriptions, under `vectors/scenes/`, each with the name of
/// the untuned scene it was tuned from.
pub const TUNED: [(&str, &str); 2] = [
    ("tests/seed-tuned-best.json", "seed"),
    ("tests/rtdemo-tuned-best.json", "rtdemo"),
];

/// The tuned-scenes step.
pub struct Tuned;

impl Step for Tuned {
    fn key(&self) -> &'static str {
        "tuned"
    }

    fn name(&self) -> String {
        "tuned scenes".into()
    }

    fn run(&self, night: &mut Night<'_>) -> Result<()> {
        for (file, base) in TUNED {
            let before = night.builder.report_mut().scenes.len();
            scenes::each_scene(night, &[scenes::shipped_dir().join(file)])?;
            for row in &mut night.builder.report_mut().scenes[before..] {
                row.tuned_from = Some(base.to_string());
            }
        }
        Ok(())
    }
}
