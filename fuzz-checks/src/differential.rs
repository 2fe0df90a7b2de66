//! Random Float316 operands through ref-f316 and through the Jack
//! program's Float316 class on the emulator, whose integer arithmetic is
//! the Jack OS's (`common::jack_int`): the two must agree bit for bit.

use common::{Op, F316};
use jack::{Budgets, Profile, Raymarcher};
use std::sync::OnceLock;

/// The raymarcher after `Main.init`, built once per process.
fn jack() -> &'static Raymarcher {
    static JACK: OnceLock<Raymarcher> = OnceLock::new();
    JACK.get_or_init(|| {
        Raymarcher::new(Profile::Desktop, Budgets::default()).expect("the raymarcher loads")
    })
}

/// An operation and its operands from the fuzzer's bytes: one byte picks
/// the operation, then 6 bytes per operand (s, e, m as little-endian
/// words; any word, normalised or not).
pub fn decode(data: &[u8]) -> Option<(Op, Vec<F316>)> {
    let (&pick, rest) = data.split_first()?;
    let op = Op::ALL[usize::from(pick) % Op::ALL.len()];
    let word = |b: &[u8]| i16::from_le_bytes([b[0], b[1]]);
    let args: Vec<F316> = rest
        .chunks_exact(6)
        .take(op.arity())
        .map(|c| F316::new(word(&c[0..2]), word(&c[2..4]), word(&c[4..6])))
        .collect();
    (args.len() == op.arity()).then_some((op, args))
}

/// ref-f316 and the Jack program give the same outcome (value, Sys.error
/// code, hang or out of domain) for the operation the bytes encode.
pub fn f316_vs_jack(data: &[u8]) {
    let Some((op, args)) = decode(data) else {
        return;
    };
    let reference =
        reference::op(op, &args, reference::Arith::default()).expect("the arity is right");
    let on_jack = jack()
        .op(op, &args)
        .unwrap_or_else(|e| panic!("{op}{args:?}: the Jack program failed: {e}"))
        .outcome;
    assert_eq!(
        reference, on_jack,
        "{op}{args:?}: ref-f316 (left) against jack (right)"
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bytes_decode_to_an_operation_and_its_operands() {
        let mut bytes = vec![3u8]; // Op::ALL[3] = mul
        for w in [0i16, 128, 8192, 1, -2, 16383] {
            bytes.extend(w.to_le_bytes());
        }
        let (op, args) = decode(&bytes).unwrap();
        assert_eq!(op, Op::Mul);
        assert_eq!(args, [F316::new(0, 128, 8192), F316::new(1, -2, 16383)]);
        assert_eq!(decode(&bytes[..12]), None, "a missing operand");
        assert_eq!(decode(&[]), None);
        // One operand is enough for sqrt (index 7); extra bytes are unused.
        assert_eq!(decode(&[7, 0, 0, 128, 0, 0, 32, 9]).unwrap().1.len(), 1);
    }
}
