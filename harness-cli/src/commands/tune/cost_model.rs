//! What a configuration costs on the Jack VM, estimated from the Float316
//! operations the reference counts: each operation at its measured cost in
//! the untuned scene's generated Jack program, and the program's own code
//! at its measured cost per operation it calls.
//!
//! The costs are measured once, on a sample of pixels of the untuned
//! program under the function profile of the emulator: the VM instructions
//! spent in each `Float316` subroutine (exclusive of the subroutines it
//! calls) over the number of calls of its operation the reference counts on
//! the same pixels (the op-trace convention makes the two equal), and
//! everything else (`Shade.pixel`, `Scene.sdf`, `Ops`, `Float316.copy`, ...)
//! over the operations the program calls itself. A variant's subroutine
//! (`sqrtNewton1`) is charged as its operation; the final check measures
//! the tuned program itself.

use anyhow::{bail, Context};
use common::Op;
use rayon::prelude::*;
use reference::{Described, OpCounts};
use scene_jack::cost::Runner;
use scene_jack::JackSources;
use serde::Serialize;

/// Measured costs, VM instructions.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CostModel {
    /// One call of each operation (indexed as [`Op::ALL`]), exclusive of
    /// the operations it calls.
    pub per_op: [f64; Op::ALL.len()],
    /// The program's own code per operation it calls.
    pub per_outer_call: f64,
    /// `Main.init`, once per image.
    pub init_instructions: u64,
    /// Pixels of the image.
    pub pixels: u64,
    /// Pixels the costs were measured on.
    pub sample: usize,
    /// What the sample took on the emulator and what the model says of it.
    pub sample_measured: u64,
    pub sample_modelled: f64,
}

/// The operation a `Float316` subroutine computes (`Float316.invSqrt`,
/// `Float316.sqrtNewton1`), if any.
fn operation(function: &str) -> Option<Op> {
    let name = function.strip_prefix("Float316.")?;
    name.strip_suffix("Newton1").unwrap_or(name).parse().ok()
}

/// Every `step`-th pixel of every `step`-th row, from the middle of the
/// first block.
fn sample(width: u32, height: u32, step: u32) -> Vec<(u32, u32)> {
    let start = step / 2;
    (start.min(height.saturating_sub(1))..height)
        .step_by(step as usize)
        .flat_map(|y| {
            (start.min(width.saturating_sub(1))..width)
                .step_by(step as usize)
                .map(move |x| (x, y))
        })
        .collect()
}

impl CostModel {
    /// Measure the costs on every `step`-th pixel of every `step`-th row of
    /// `base` (ref-f316 of the untuned description) and `sources` (its Jack
    /// program).
    pub fn calibrate(base: &Described, sources: &JackSources, step: u32) -> anyhow::Result<Self> {
        let runner = Runner::profiled(sources, hack_vm::Profile::Desktop)
            .context("running the untuned scene's Jack program")?;
        let (width, height) = scene_jack::drawn(base.program());
        let pixels = sample(width, height, step);
        let measured: Vec<(Vec<(String, u64)>, OpCounts)> = pixels
            .par_iter()
            .map(|&(x, y)| {
                let (_, counts) = base.pixel_counted(x, y)?;
                Ok((runner.pixel_profile(x, y), counts))
            })
            .collect::<anyhow::Result<_>>()?;
        let mut by_op = [0u64; Op::ALL.len()];
        let mut counts = OpCounts::default();
        let mut total = 0u64;
        for (profile, c) in &measured {
            counts.add(c);
            for (function, n) in profile {
                total += n;
                if let Some(op) = operation(function) {
                    by_op[op as usize] += n;
                }
            }
        }
        let mut per_op = [0.0; Op::ALL.len()];
        for op in Op::ALL {
            let (spent, calls) = (by_op[op as usize], counts.of(op));
            match (spent, calls) {
                (0, _) => {}
                (_, 0) => bail!(
                    "the Jack program spends {spent} VM instructions in {op} on the sample, \
                     where the reference counts no call"
                ),
                _ => per_op[op as usize] = spent as f64 / calls as f64,
            }
        }
        let own = total - by_op.iter().sum::<u64>();
        let outer = counts.outer_total();
        let mut model = CostModel {
            per_op,
            per_outer_call: own as f64 / outer.max(1) as f64,
            init_instructions: runner.init_instructions,
            pixels: u64::from(width) * u64::from(height),
            sample: pixels.len(),
            sample_measured: total,
            sample_modelled: 0.0,
        };
        model.sample_modelled = model.pixels_cost(&counts);
        Ok(model)
    }

    /// The VM instructions of the pixels whose operations are `counts`.
    pub fn pixels_cost(&self, counts: &OpCounts) -> f64 {
        let ops: f64 = Op::ALL
            .iter()
            .map(|&op| counts.of(op) as f64 * self.per_op[op as usize])
            .sum();
        ops + counts.outer_total() as f64 * self.per_outer_call
    }

    /// VM instructions per pixel of an image whose operations are `counts`.
    pub fn per_pixel(&self, counts: &OpCounts) -> f64 {
        self.pixels_cost(counts) / self.pixels.max(1) as f64
    }

    /// VM instructions of the whole image (`Main.init` and every pixel).
    pub fn whole_image(&self, counts: &OpCounts) -> f64 {
        self.init_instructions as f64 + self.pixels_cost(counts)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn float316_subroutines_and_their_variants_are_their_operations() {
        assert_eq!(operation("Float316.invSqrt"), Some(Op::InvSqrt));
        assert_eq!(operation("Float316.invSqrtNewton1"), Some(Op::InvSqrt));
        assert_eq!(operation("Float316.sqrtNewton1"), Some(Op::Sqrt));
        assert_eq!(operation("Float316.add"), Some(Op::Add));
        assert_eq!(operation("Float316.copy"), None);
        assert_eq!(operation("Ops.double"), None);
    }

    #[test]
    fn the_sample_starts_inside_small_images() {
        assert_eq!(sample(16, 8, 8), [(4, 4), (12, 4)]);
        assert_eq!(sample(3, 2, 8), [(2, 1)]);
    }
}
