//! The word encoding every Float316 kernel shares: op codes, triples as
//! three sign-extended words, and the status word around an answer.

use common::{Op, Outcome, F316};

/// The op code the kernel switches on: the index in [`Op::ALL`].
pub(crate) fn op_code(op: Op) -> u32 {
    Op::ALL
        .iter()
        .position(|&o| o == op)
        .expect("Op::ALL lists every op") as u32
}

/// Append a triple as three input words (each field sign-extended).
pub(crate) fn push_triple(words: &mut Vec<u32>, v: F316) {
    words.extend([v.s, v.e, v.m].map(|field| field as i32 as u32));
}

/// A triple from three output words (each a sign-extended Jack word).
pub(crate) fn triple(words: &[u32]) -> F316 {
    F316::new(words[0] as i16, words[1] as i16, words[2] as i16)
}

/// Decode a status word (`kind | code << 4`, see f316.wgsl) around `value`.
pub(crate) fn outcome<T>(status: u32, value: impl FnOnce() -> T) -> Outcome<T> {
    let status = status as i32;
    match status & 15 {
        0 => Outcome::Value(value()),
        1 => Outcome::SysError((status >> 4) as i16),
        2 => Outcome::Hang,
        _ => Outcome::OutOfDomain,
    }
}
