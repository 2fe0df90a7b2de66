//! What a configuration costs on the Jack VM, estimated from the Float316
//! operations the reference counts: each operation, and each variant of an
//! operation, at its measured cost in the scene's generated Jack programs,
//! and the program's own code at its measured cost per operation it calls.
//!
//! The costs are measured once, on a sample of pixels of two programs under
//! the function profile of the emulator. On the untuned scene's: the VM
//! instructions spent in each `Float316` subroutine (exclusive of the
//! subroutines it calls) over the calls of its operation the reference
//! counts on the same pixels (the op-trace convention makes the two equal),
//! and everything else (`Shade.pixel`, `Scene.sdf`, `Ops`, `Float316.copy`,
//! ...) over the operations the program calls itself. On the scene's with
//! every operation site at its variant: each variant's subroutine
//! (`sqrtNewton1`, `mulTruncated`, `floorDirect`) over the calls the
//! reference counts of it. `Main.init` is measured on the untuned program; the
//! set-up's operations in it are charged as counted, so that a tuned set-up
//! site costs what it saves. A variant that no sampled pixel calls is
//! charged as its operation.

use anyhow::{bail, Context};
use common::Op;
use rayon::prelude::*;
use reference::{Described, OpCounts};
use scene::ir::Tuning;
use scene_jack::cost::Runner;
use scene_jack::JackSources;
use serde::Serialize;

/// The cost of each operation (indexed as [`Op::ALL`]).
type PerOp = [f64; Op::ALL.len()];

/// Measured costs, VM instructions.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CostModel {
    /// One call of each operation as the spec computes it, exclusive of the
    /// operations it calls.
    pub per_op: PerOp,
    /// One call of each operation as each variant (indexed as
    /// [`Tuning::ALL`]), exclusive of the operations it calls.
    pub per_variant: [PerOp; Tuning::ALL.len()],
    /// The program's own code per operation it calls.
    pub per_outer_call: f64,
    /// `Main.init` without the set-up's operations, once per image.
    pub init_instructions: f64,
    /// Pixels of the image.
    pub pixels: u64,
    /// Pixels the costs were measured on, in each of the two programs.
    pub sample: usize,
    /// What the sample took on the untuned program and what the model says
    /// of it.
    pub sample_measured: u64,
    pub sample_modelled: f64,
}

/// The operation a `Float316` subroutine computes (`Float316.invSqrt`,
/// `Float316.sqrtNewton1`) and the variant it is, if any.
fn operation(function: &str) -> Option<(Op, Option<Tuning>)> {
    let name = function.strip_prefix("Float316.")?;
    for t in Tuning::ALL {
        if let Some(op) = name.strip_suffix(t.suffix()) {
            return op.parse().ok().map(|op| (op, Some(t)));
        }
    }
    name.parse().ok().map(|op| (op, None))
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

/// What the sampled pixels of a calibration program spent and counted.
#[derive(Default)]
struct Spent {
    /// VM instructions in each operation's subroutine: the spec's (index 0)
    /// and each variant's (index 1 + its place in [`Tuning::ALL`]).
    by_op: [[u64; Op::ALL.len()]; Tuning::ALL.len() + 1],
    counts: OpCounts,
    total: u64,
}

impl Spent {
    /// Add `runner`'s profile and `reference`'s counts on `pixels`.
    fn measure(
        &mut self,
        reference: &Described,
        runner: &Runner,
        pixels: &[(u32, u32)],
    ) -> anyhow::Result<()> {
        let measured: Vec<(Vec<(String, u64)>, OpCounts)> = pixels
            .par_iter()
            .map(|&(x, y)| {
                let (_, counts) = reference.pixel_counted(x, y)?;
                Ok((runner.pixel_profile(x, y), counts))
            })
            .collect::<anyhow::Result<_>>()?;
        for (profile, c) in &measured {
            self.counts.add(c);
            for (function, n) in profile {
                self.total += n;
                if let Some((op, variant)) = operation(function) {
                    let row = variant.map_or(0, |t| 1 + t as usize);
                    self.by_op[row][op as usize] += n;
                }
            }
        }
        Ok(())
    }

    /// Instructions per call of each operation in `row` of `by_op`, over
    /// `calls(op)`; `what` names the row in errors.
    fn per_call(&self, row: usize, calls: impl Fn(Op) -> u64, what: &str) -> anyhow::Result<PerOp> {
        let mut per_op = [0.0; Op::ALL.len()];
        for op in Op::ALL {
            match (self.by_op[row][op as usize], calls(op)) {
                (0, _) => {}
                (spent, 0) => bail!(
                    "the Jack programs spend {spent} VM instructions in {op}{what} on the \
                     sample, where the reference counts no call"
                ),
                (spent, n) => per_op[op as usize] = spent as f64 / n as f64,
            }
        }
        Ok(per_op)
    }
}

impl CostModel {
    /// Measure the costs on every `step`-th pixel of every `step`-th row of
    /// `base` (ref-f316 of the untuned description) with `sources` (its
    /// Jack program), and of `variants` (ref-f316 and the Jack program of
    /// the description with every operation site at its variant).
    pub fn calibrate(
        base: (&Described, &JackSources),
        variants: (&Described, &JackSources),
        step: u32,
    ) -> anyhow::Result<Self> {
        let runner = |sources: &JackSources, what: &str| {
            Runner::profiled(sources, hack_vm::Profile::Desktop)
                .with_context(|| format!("running the {what} scene's Jack program"))
        };
        let untuned = runner(base.1, "untuned")?;
        let tuned = runner(variants.1, "fully tuned")?;
        let (width, height) = scene_jack::drawn(base.0.program());
        let pixels = sample(width, height, step);
        let mut spent = Spent::default();
        spent.measure(base.0, &untuned, &pixels)?;
        let mut tuned_spent = Spent::default();
        tuned_spent.measure(variants.0, &tuned, &pixels)?;
        let counts = spent.counts;
        let per_op = spent.per_call(0, |op| counts.of_spec(op), "")?;
        let mut per_variant = [per_op; Tuning::ALL.len()];
        for t in Tuning::ALL {
            let calls = |op| tuned_spent.counts.of_variant(op, t);
            let measured = tuned_spent.per_call(1 + t as usize, calls, &format!(" ({t})"))?;
            for op in Op::ALL.into_iter().filter(|&op| calls(op) > 0) {
                per_variant[t as usize][op as usize] = measured[op as usize];
            }
        }
        let in_ops: u64 = spent.by_op.iter().flatten().sum();
        let outer = counts.outer_total();
        let mut model = CostModel {
            per_op,
            per_variant,
            per_outer_call: (spent.total - in_ops) as f64 / outer.max(1) as f64,
            init_instructions: 0.0,
            pixels: u64::from(width) * u64::from(height),
            sample: pixels.len(),
            sample_measured: spent.total,
            sample_modelled: 0.0,
        };
        model.sample_modelled = model.pixels_cost(&counts);
        let setup = model.pixels_cost(&base.0.setup_counted()?);
        model.init_instructions = untuned.init_instructions as f64 - setup;
        Ok(model)
    }

    /// The VM instructions of the operations `counts` (pixels, or a
    /// set-up), and of the program's own code around them.
    pub fn pixels_cost(&self, counts: &OpCounts) -> f64 {
        let ops: f64 = Op::ALL
            .iter()
            .map(|&op| {
                let spec = counts.of_spec(op) as f64 * self.per_op[op as usize];
                let variants: f64 = Tuning::ALL
                    .iter()
                    .map(|&t| {
                        counts.of_variant(op, t) as f64 * self.per_variant[t as usize][op as usize]
                    })
                    .sum();
                spec + variants
            })
            .sum();
        ops + counts.outer_total() as f64 * self.per_outer_call
    }

    /// VM instructions per pixel of an image whose operations are `counts`.
    pub fn per_pixel(&self, counts: &OpCounts) -> f64 {
        self.pixels_cost(counts) / self.pixels.max(1) as f64
    }

    /// VM instructions of the whole image (`Main.init` and every pixel)
    /// whose operations (set-up included) are `counts`.
    pub fn whole_image(&self, counts: &OpCounts) -> f64 {
        self.init_instructions + self.pixels_cost(counts)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn float316_subroutines_and_their_variants_are_their_operations() {
        assert_eq!(operation("Float316.invSqrt"), Some((Op::InvSqrt, None)));
        let newton1 = Some(Tuning::Newton1);
        assert_eq!(
            operation("Float316.invSqrtNewton1"),
            Some((Op::InvSqrt, newton1))
        );
        assert_eq!(operation("Float316.sqrtNewton1"), Some((Op::Sqrt, newton1)));
        assert_eq!(
            operation("Float316.mulTruncated"),
            Some((Op::Mul, Some(Tuning::TruncatedProduct)))
        );
        assert_eq!(
            operation("Float316.floorDirect"),
            Some((Op::Floor, Some(Tuning::FloorDirect)))
        );
        assert_eq!(operation("Float316.add"), Some((Op::Add, None)));
        assert_eq!(operation("Float316.copy"), None);
        assert_eq!(operation("Ops.double"), None);
    }

    #[test]
    fn the_sample_starts_inside_small_images() {
        assert_eq!(sample(16, 8, 8), [(4, 4), (12, 4)]);
        assert_eq!(sample(3, 2, 8), [(2, 1)]);
    }
}
