//! The two engines of the emulator (interpreter, Cranelift-compiled code)
//! on the raymarcher at every level (operations, SDF, pixels, under both OS
//! profiles) and on the seed program's `Main.main`: the same outcomes and
//! the same instruction counts, RAM and ends.

use common::{Op, F316};
use hack_vm::{Config, Engine, Exit, KeyScript, Machine};
use jack::{Budgets, Profile, Raymarcher};

fn pair(profile: Profile) -> [Raymarcher; 2] {
    [Engine::Interp, Engine::Native].map(|engine| {
        let config = Config {
            profile,
            engine,
            ..Config::default()
        };
        Raymarcher::with_config(config, Budgets::default()).expect("the raymarcher builds")
    })
}

/// A deterministic spread of Float316 triples, normalised and not.
fn numbers(n: usize) -> Vec<F316> {
    let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
    (0..n)
        .map(|_| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let e = 100 + (x >> 8) % 60;
            let m = if x.is_multiple_of(7) {
                (x >> 20) % 16384
            } else {
                8192 + (x >> 20) % 8192
            };
            F316::new((x % 2) as i16, e as i16, m as i16)
        })
        .collect()
}

#[test]
fn operations_sdf_and_pixels_agree_on_both_engines() {
    for profile in Profile::ALL {
        let [interp, native] = pair(profile);
        let xs = numbers(64);
        for op in Op::ALL {
            for k in 0..16 {
                let args: Vec<F316> = (0..op.arity())
                    .map(|i| xs[(k * 3 + i) % xs.len()])
                    .collect();
                assert_eq!(
                    interp.op(op, &args).unwrap(),
                    native.op(op, &args).unwrap(),
                    "{op:?} {args:?} under {profile}"
                );
            }
        }
        for k in 0..8 {
            let p = [xs[k], xs[k + 8], xs[k + 16]];
            assert_eq!(interp.sdf(p).unwrap(), native.sdf(p).unwrap(), "sdf {p:?}");
        }
        for (x, y) in [(256, 128), (10, 10), (400, 200), (0, 255)] {
            assert_eq!(
                interp.pixel(x, y).unwrap(),
                native.pixel(x, y).unwrap(),
                "pixel ({x},{y}) under {profile}"
            );
        }
    }
}

/// `Main.main` with SPACE scripted on both engines, compared after each
/// slice of `slice` instructions (so key changes and budgets fall inside
/// compiled stretches), until `total` instructions or the end.
fn main_agrees(total: u64, slice: u64) {
    let program = jack::sources::program(Profile::Desktop).unwrap();
    let keys = KeyScript::parse("SPACE", 1_000_000).unwrap();
    let [mut a, mut b] = [Engine::Interp, Engine::Native].map(|engine| {
        let config = Config {
            keys: keys.clone(),
            engine,
            ..Config::default()
        };
        Machine::new(program.clone(), config)
    });
    assert_eq!(b.engine(), Engine::Native);
    while a.steps() < total {
        let (ea, eb) = (a.run(Some(slice)), b.run(Some(slice)));
        assert_eq!(ea, eb);
        assert_eq!(a.steps(), b.steps());
        assert!(a.ram() == b.ram(), "RAM differs after {} steps", a.steps());
        if !matches!(ea, Exit::Budget { .. }) {
            return;
        }
    }
}

#[test]
fn the_seed_program_starts_the_same_on_both_engines() {
    main_agrees(60_000_000, 7_777_777);
}

/// The whole of `Main.main` (about 21 G instructions on each engine:
/// `cargo test --release -p jack -- --ignored`). Ignored under `cargo
/// test`: the interpreter's run alone takes about 30 s.
#[test]
#[ignore = "Main.main on both engines (about 45 CPU s): scripts/nightly.sh"]
fn the_whole_seed_program_is_the_same_on_both_engines() {
    main_agrees(u64::MAX, 1_000_000_007);
}
