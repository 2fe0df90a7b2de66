//! Memory and Array: the web IDE's free list, bugs included (spec 3.2,
//! 3.3), and the desktop VM emulator's built-in heap (issue 28).

mod support;

use jack_os::{Builtin, Profile, Stop};
use proptest::prelude::*;
use support::Machine;

#[test]
fn reset_lays_out_the_heap_header() {
    let m = Machine::new(Profile::Web);
    assert_eq!(m.ram.read(0), 256);
    assert_eq!(m.ram.read(2048), 0);
    assert_eq!(m.ram.read(2049), 14334);
    assert_eq!(m.os.heap_head(), 2048);
    assert_eq!(m.os.cursor(), (0, 0));
    assert!(m.os.color());
}

#[test]
fn first_alloc_returns_2050_and_blocks_are_contiguous() {
    let mut m = Machine::new(Profile::Web);
    assert_eq!(m.ok("Memory.alloc", &[3]), 2050);
    // The used block keeps its stale next pointer; its size word is n.
    assert_eq!((m.ram.read(2048), m.ram.read(2049)), (0, 3));
    // The remainder is the new head: next 0, size 14334-5.
    assert_eq!(m.os.heap_head(), 2053);
    assert_eq!((m.ram.read(2053), m.ram.read(2054)), (0, 14329));
    assert_eq!(m.ok("Memory.alloc", &[5]), 2055);
    assert_eq!(m.ok("Array.new", &[1]), 2062);
}

#[test]
fn the_largest_allocation_is_14332() {
    let mut m = Machine::new(Profile::Web);
    assert_eq!(m.ok("Memory.alloc", &[14332]), 2050);
    assert_eq!(m.err("Memory.alloc", &[1], 6), 0);
    let mut m = Machine::new(Profile::Web);
    assert_eq!(m.err("Memory.alloc", &[14333], 6), 0);
    assert!(m.shows_text(0, 0, "ERR6"));
}

#[test]
fn non_positive_sizes_are_err2_for_arrays_and_alloc_err2_web_err5_desktop() {
    for (profile, alloc_code) in [(Profile::Web, 2), (Profile::Desktop, 5)] {
        let mut m = Machine::new(profile);
        assert_eq!(m.err("Memory.alloc", &[0], alloc_code), 0);
        assert!(m.shows_text(0, 0, &format!("ERR{alloc_code}")));
        assert_eq!(m.err("Memory.alloc", &[-5], alloc_code), 0);
        assert_eq!(m.err("Array.new", &[0], 2), 0);
        assert_eq!(m.err("Array.new", &[-32768], 2), 0);
        assert_eq!(m.os.heap_head(), 2048, "nothing was allocated");
    }
}

#[test]
fn the_desktop_heap_header_is_14334_16384_and_blocks_cost_two_words() {
    let mut m = Machine::new(Profile::Desktop);
    assert_eq!((m.ram.read(2048), m.ram.read(2049)), (14334, 16384));
    // The used block's capacity word is 0 and it links to the rest, a new
    // block of 14334 - 3 - 2 words after its 3 data words.
    assert_eq!(m.ok("Memory.alloc", &[3]), 2050);
    assert_eq!((m.ram.read(2048), m.ram.read(2049)), (0, 2053));
    assert_eq!((m.ram.read(2053), m.ram.read(2054)), (14329, 16384));
    assert_eq!(m.ok("Array.new", &[1]), 2055);
    // Freeing a block merges the free block after it.
    m.ok("Memory.deAlloc", &[2055]);
    assert_eq!((m.ram.read(2053), m.ram.read(2054)), (14329, 16384));
    m.ok("Memory.deAlloc", &[2050]);
    assert_eq!((m.ram.read(2048), m.ram.read(2049)), (14334, 16384));
    // A freed block before a used one gets its own size back only.
    let a = m.ok("Memory.alloc", &[10]);
    let b = m.ok("Memory.alloc", &[10]);
    assert_eq!((a, b), (2050, 2062));
    m.ok("Memory.deAlloc", &[a]);
    assert_eq!((m.ram.read(2048), m.ram.read(2049)), (10, 2060));
    assert_eq!(m.ok("Memory.alloc", &[4]), 2050, "first fit, split");
    assert_eq!((m.ram.read(2054), m.ram.read(2055)), (4, 2060));
    assert_eq!(m.ram.read(2049), 2054);
}

#[test]
fn the_desktop_heap_overflows_with_err6_and_its_largest_block_is_14334() {
    let mut m = Machine::new(Profile::Desktop);
    assert_eq!(m.ok("Memory.alloc", &[14334]), 2050);
    assert_eq!(m.err("Memory.alloc", &[1], 6), 0);
}

#[test]
fn a_desktop_built_in_may_touch_only_the_heap_the_screen_and_word_0() {
    let outside = "A built-in function tried to access memory outside the Heap or Screen range";
    for (name, args) in [
        ("Memory.peek", &[1][..]),
        ("Memory.peek", &[2047]),
        ("Memory.poke", &[100, 5]),
        ("Memory.peek", &[-1]),
        ("String.length", &[5]),
    ] {
        let mut m = Machine::new(Profile::Desktop);
        let c = m.call(name, args);
        assert_eq!(
            c.stop,
            Some(Stop::RuntimeError(outside.into())),
            "{name}{args:?}"
        );
    }
    let mut m = Machine::new(Profile::Desktop);
    assert_eq!(m.ok("Memory.peek", &[0]), 256);
    m.ok("Memory.poke", &[2048, 7]);
    assert_eq!(m.ok("Memory.peek", &[2048]), 7);
    assert_eq!(m.ok("Memory.peek", &[24576]), 0);
    m.ok("Memory.poke", &[16384, -1]);
    assert_eq!(m.ram.read(16384), -1);
    // The web IDE checks nothing.
    let mut m = Machine::new(Profile::Web);
    assert_eq!(m.ok("Memory.peek", &[1]), 0);
}

#[test]
fn dealloc_appends_to_the_tail_and_reuses_only_when_the_head_is_too_small() {
    let mut m = Machine::new(Profile::Web);
    let a = m.ok("Memory.alloc", &[10]);
    let b = m.ok("Array.new", &[10]);
    assert_eq!((a, b), (2050, 2062));
    m.ok("Memory.deAlloc", &[a]);
    // RAM[a-2] = 0 and the head remainder (the only free block) links to it.
    let head = m.os.heap_head();
    assert_eq!(head, 2072);
    assert_eq!(m.ram.read(2048), 0);
    assert_eq!(m.ram.read(head), 2048);
    m.ok("Array.dispose", &[b]);
    assert_eq!(m.ram.read(2048), 2060, "appended after the freed a");
    // The head remainder still fits: freed blocks are not reused yet.
    assert_eq!(m.ok("Memory.alloc", &[10]), 2074);
    // Exhaust the remainder (14334 - 36 - 2 words left after headers).
    let rest = m.ram.read(m.os.heap_head() + 1);
    assert_eq!(rest, 14334 - 36);
    m.ok("Memory.alloc", &[rest - 2]);
    let head = m.os.heap_head();
    assert_eq!(m.ram.read(head + 1), 0, "the head is now empty");
    // Now the first fitting block is a's.
    assert_eq!(m.ok("Memory.alloc", &[4]), 2050);
}

#[test]
fn using_a_non_head_block_does_not_relink_its_predecessor() {
    let mut m = Machine::new(Profile::Web);
    let a = m.ok("Memory.alloc", &[10]);
    let rest = m.ram.read(m.os.heap_head() + 1);
    m.ok("Memory.alloc", &[rest - 2]); // the head is left with size 0
    m.ok("Memory.deAlloc", &[a]);
    let head = m.os.heap_head();
    assert_eq!(m.ram.read(head), 2048);
    // alloc(4) splits a's block (non-head): the remainder 2054 gets a's old
    // next (0) but the head still points at 2048, the now used block.
    assert_eq!(m.ok("Memory.alloc", &[4]), 2050);
    assert_eq!(m.ram.read(head), 2048, "predecessor not relinked (the bug)");
    assert_eq!((m.ram.read(2054), m.ram.read(2055)), (0, 4));
    assert_eq!(m.os.heap_head(), head);
    // So the same block is handed out again: size 4 is still >= 2+2.
    assert_eq!(m.ok("Memory.alloc", &[2]), 2050);
}

#[test]
fn a_double_free_makes_a_later_dealloc_hang_and_it_is_detected() {
    let mut m = Machine::new(Profile::Web);
    let a = m.ok("Memory.alloc", &[3]);
    let b = m.ok("Memory.alloc", &[3]);
    m.ok("Memory.deAlloc", &[a]);
    m.ok("Memory.deAlloc", &[a]); // a's next := a: a cycle
    let c = m.call("Memory.deAlloc", &[b]);
    assert!(matches!(c.stop, Some(Stop::Hang(_))), "{c:?}");
}

#[test]
fn peek_and_poke() {
    let mut m = Machine::new(Profile::Web);
    m.ok("Memory.poke", &[100, -7]);
    assert_eq!(m.ok("Memory.peek", &[100]), -7);
    assert_eq!(m.ok("Memory.peek", &[-1]), -1);
    m.ok("Memory.poke", &[-1, 5]);
    assert_eq!(m.ok("Memory.peek", &[24576]), 0);
}

#[test]
fn a_wrong_argument_count_is_a_runtime_error_not_a_panic() {
    let mut m = Machine::new(Profile::Desktop);
    let c =
        m.os.call(Builtin::MemoryAlloc, &[], &mut m.ram, &mut m.clock);
    assert_eq!(
        c.stop,
        Some(Stop::RuntimeError(
            "OS function Memory.alloc expects 1 arguments, not 0".into()
        ))
    );
}

#[derive(Debug, Clone)]
enum HeapOp {
    Alloc(i16),
    Free(usize),
    FreeRaw(i16),
}

fn heap_op() -> impl Strategy<Value = HeapOp> {
    prop_oneof![
        4 => (-3i16..3000).prop_map(HeapOp::Alloc),
        3 => any::<usize>().prop_map(HeapOp::Free),
        1 => any::<i16>().prop_map(HeapOp::FreeRaw),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Any sequence of allocations and frees (including bogus frees)
    /// completes every call; while nothing went wrong, every block lies in
    /// the heap. (Blocks may be handed out twice: that is the relink bug.)
    #[test]
    fn alloc_dealloc_sequences_never_panic(ops in proptest::collection::vec(heap_op(), 1..60)) {
        for profile in Profile::ALL {
            let mut m = Machine::new(profile);
            let mut live: Vec<i16> = Vec::new();
            let mut clean = true;
            for op in &ops {
                let c = match *op {
                    HeapOp::Alloc(n) => {
                        let c = m.call("Memory.alloc", &[n]);
                        if c.stop.is_none() && clean {
                            prop_assert!(n > 0 && (2050..16384).contains(&c.value));
                            live.push(c.value);
                        }
                        c
                    }
                    HeapOp::Free(i) if !live.is_empty() => {
                        let p = live.remove(i % live.len());
                        m.call("Memory.deAlloc", &[p])
                    }
                    HeapOp::Free(_) => continue,
                    HeapOp::FreeRaw(p) => {
                        clean = false;
                        m.call("Memory.deAlloc", &[p])
                    }
                };
                if c.stop.is_some() {
                    clean = false;
                }
            }
        }
    }
}
