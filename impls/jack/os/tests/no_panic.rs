//! Every built-in, any arguments, either profile: the call returns.

mod support;

use jack_os::{subroutines, KeyScript, Os, Profile, Ram};
use proptest::prelude::*;

/// Any word, with small values and the boundary values of the spec favoured.
fn arg() -> impl Strategy<Value = i16> {
    prop_oneof![
        any::<i16>(),
        -3i16..300,
        2048i16..2100,
        Just(64),
        Just(181),
        Just(182),
        Just(256),
        Just(512),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn any_call_sequence_completes(
        calls in proptest::collection::vec(
            (0..subroutines().len(), proptest::collection::vec(arg(), 4)),
            1..12,
        ),
        web in any::<bool>(),
    ) {
        let profile = if web { Profile::Web } else { Profile::Desktop };
        let keys = KeyScript::parse("A,BACKSPACE,1,ENTER", 7).unwrap();
        let mut os = Os::new(profile, keys);
        let mut ram = Ram::new();
        os.reset(&mut ram);
        let mut clock = 0;
        for (index, args) in &calls {
            let f = subroutines()[*index].builtin;
            os.call(f, &args[..f.vm_arity()], &mut ram, &mut clock);
            let (row, col) = os.cursor();
            prop_assert!((0..=22).contains(&row) && (0..=64).contains(&col));
        }
    }
}
