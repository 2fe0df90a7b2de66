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
//! reference counts of it. The code outside the operations is fitted, by
//! least squares over the sampled pixels of both programs, as a cost per
//! operation the program calls itself plus a cost per operation of any
//! kind: the second is the `Float316.set` and `absOf` an operation ends
//! with, which the profile counts apart from it, so that an operation
//! made inside another (an `add` of `sqrt`'s second Newton step) saves its
//! own `set` too when a variant leaves it out. `Main.init` is measured on
//! the untuned program; the
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
    /// The code outside the operations per operation of any kind (the
    /// `set` each ends with).
    pub per_call: f64,
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
    /// Each pixel's instructions outside the operations' subroutines, its
    /// operations called by the program, and all its operations.
    outside: Vec<(f64, f64, f64)>,
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
            let mut outside = 0;
            for (function, n) in profile {
                self.total += n;
                match operation(function) {
                    Some((op, variant)) => {
                        let row = variant.map_or(0, |t| 1 + t as usize);
                        self.by_op[row][op as usize] += n;
                    }
                    None => outside += n,
                }
            }
            let all: u64 = c.all.iter().sum();
            self.outside
                .push((outside as f64, c.outer_total() as f64, all as f64));
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

/// The costs `(a, b)` that fit `outside ≈ a * outer + b * all` over the
/// pixels `(outside, outer, all)` by least squares, both at least 0; `b`
/// is 0 (and `a` the ratio of the sums) where the pixels cannot tell the
/// two apart.
fn fit_outside(pixels: &[(f64, f64, f64)]) -> (f64, f64) {
    let sum = |f: &dyn Fn(&(f64, f64, f64)) -> f64| pixels.iter().map(f).sum::<f64>();
    let (oo, oa, aa) = (
        sum(&|p| p.1 * p.1),
        sum(&|p| p.1 * p.2),
        sum(&|p| p.2 * p.2),
    );
    let (yo, ya) = (sum(&|p| p.0 * p.1), sum(&|p| p.0 * p.2));
    let det = oo * aa - oa * oa;
    if det > 1e-9 * oo * aa {
        let a = (yo * aa - ya * oa) / det;
        let b = (ya * oo - yo * oa) / det;
        if a >= 0.0 && b >= 0.0 {
            return (a, b);
        }
    }
    (sum(&|p| p.0) / sum(&|p| p.1).max(1.0), 0.0)
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
        let (per_outer_call, per_call) =
            fit_outside(&[spent.outside.as_slice(), &tuned_spent.outside].concat());
        let mut model = CostModel {
            per_op,
            per_variant,
            per_outer_call,
            per_call,
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
        let all: u64 = counts.all.iter().sum();
        ops + counts.outer_total() as f64 * self.per_outer_call + all as f64 * self.per_call
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
    fn the_code_outside_the_operations_is_fitted_per_outer_and_per_any_call() {
        // 30 per operation the program calls, 10 per operation of any kind.
        let pixels: Vec<(f64, f64, f64)> = [(10.0, 40.0), (20.0, 25.0), (5.0, 50.0)]
            .iter()
            .map(|&(outer, all)| (30.0 * outer + 10.0 * all, outer, all))
            .collect();
        let (a, b) = fit_outside(&pixels);
        assert!(
            (a - 30.0).abs() < 1e-6 && (b - 10.0).abs() < 1e-6,
            "{a} {b}"
        );
        // Proportional pixels cannot tell the two apart: all per outer.
        let (a, b) = fit_outside(&[(70.0, 1.0, 2.0), (140.0, 2.0, 4.0)]);
        assert_eq!((a, b), (70.0, 0.0));
    }

    #[test]
    fn the_sample_starts_inside_small_images() {
        assert_eq!(sample(16, 8, 8), [(4, 4), (12, 4)]);
        assert_eq!(sample(3, 2, 8), [(2, 1)]);
    }
}
