//! Where the instructions go: per-function (exclusive) VM instruction
//! counts over a set of pixels.

use crate::{JackError, Raymarcher};
use rayon::prelude::*;
use std::collections::HashMap;

impl Raymarcher {
    /// Instructions per Jack function (exclusive of its callees) summed over
    /// `pixels`, largest first. Needs a raymarcher made with
    /// `Config::profile_functions` (see [`Raymarcher::with_config`]);
    /// otherwise the list is empty.
    pub fn profile_pixels(
        &self,
        pixels: &[(usize, usize)],
    ) -> Result<Vec<(String, u64)>, JackError> {
        let base: HashMap<String, u64> = self.machine().function_profile().into_iter().collect();
        let totals = pixels
            .par_iter()
            .map(|&(x, y)| {
                let args = Raymarcher::pixel_args(x, y)?;
                let mut m = self.machine();
                self.run_call(&mut m, "Image.pixel", &args, self.budgets().pixel)?;
                Ok(m.function_profile())
            })
            .try_fold(
                HashMap::new,
                |mut acc: HashMap<String, u64>, p: Result<_, JackError>| {
                    for (f, n) in p? {
                        *acc.entry(f).or_default() += n;
                    }
                    Ok::<_, JackError>(acc)
                },
            )
            .try_reduce(HashMap::new, |mut a, b| {
                for (f, n) in b {
                    *a.entry(f).or_default() += n;
                }
                Ok(a)
            })?;
        let mut list: Vec<(String, u64)> = totals
            .into_iter()
            .map(|(f, n)| {
                let before = base.get(&f).copied().unwrap_or(0) * pixels.len() as u64;
                (f, n - before)
            })
            .filter(|(_, n)| *n > 0)
            .collect();
        list.sort_by(|a, b| b.1.cmp(&a.1).then_with(|| a.0.cmp(&b.0)));
        Ok(list)
    }
}
