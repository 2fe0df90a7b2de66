//! Superinstructions: common sequences of the Jack compiler's output fused
//! into one instruction, written over the first command's slot (the other
//! slots keep their plain form, so a jump into the middle still works).

use crate::program::Op;

/// The most VM commands one fused instruction stands for.
pub(crate) const MAX_FUSED_STEPS: u64 = 1;

/// The fused instruction array (same indexing as `plain`).
pub(crate) fn fuse(plain: &[Op]) -> Vec<Op> {
    plain.to_vec()
}
