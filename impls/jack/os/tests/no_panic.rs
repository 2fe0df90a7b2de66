//! Every built-in, any arguments, either profile: the call returns.

mod support;

use jack_os::{subroutines, KeyScript, Os, Profile, Ram};
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn any_call_sequence_completes(
        calls in proptest::collection::vec(
            (0..subroutines().len(), proptest::collection::vec(any::<i16>(), 4)),
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
