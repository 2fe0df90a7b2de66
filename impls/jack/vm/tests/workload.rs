//! The benchmark workload computes what a direct Rust model of it computes
//! (so the fused instructions it exercises are checked), and every budget
//! split of its run counts the same instructions.

use hack_vm::{Config, Exit, Machine, Program};

fn model_mul(a: (i16, i16, i16), b: (i16, i16, i16)) -> (i16, i16, i16) {
    let mut mm = (a.2 / 128).wrapping_mul(b.2 / 128);
    let mut ee = a.1.wrapping_add(b.1).wrapping_sub(140);
    while mm < 8192 {
        mm = mm.wrapping_add(mm);
        ee = ee.wrapping_sub(1);
    }
    (a.0, ee, mm)
}

fn model_run(n: i16) -> i16 {
    let (mut a, b) = ((0, 140, 12345), (0, 139, 9000));
    let mut acc: i16 = 0;
    for _ in 0..n {
        let r = model_mul(a, b);
        a = model_mul(r, b);
        acc = acc.wrapping_add(a.1);
    }
    acc
}

fn machine() -> Machine {
    let p = Program::from_sources(&[
        ("Bench.vm", include_str!("../benches/workload/Bench.vm")),
        ("Main.vm", include_str!("../benches/workload/Main.vm")),
    ])
    .unwrap();
    Machine::new(p, Config::default())
}

#[test]
fn workload_matches_the_model() {
    let m = machine();
    for n in [0, 1, 2, 10, 300] {
        assert_eq!(
            m.clone().call("Main.run", &[n], None).unwrap(),
            Exit::Returned(model_run(n)),
            "n={n}"
        );
    }
}

#[test]
fn budget_splits_do_not_change_the_count() {
    let mut whole = machine();
    assert_eq!(whole.run(None), Exit::Halted);
    for chunk in [1, 2, 3, 5, 97] {
        let mut m = machine();
        let mut runs = 0;
        while let Exit::Budget { .. } = m.run(Some(chunk)) {
            runs += 1;
        }
        assert_eq!(m.steps(), whole.steps(), "chunk {chunk}");
        assert_eq!(m.ram(), whole.ram(), "chunk {chunk}");
        assert!(runs as u64 >= whole.steps() / chunk);
    }
}
