use reference::{Described, RefImpl, Reference, Settings};
use std::time::Instant;
fn main() {
    let seed = scene::load(std::path::Path::new("vectors/scenes/seed.json")).unwrap();
    let d = Described::new(RefImpl::F316, &seed, Settings::default()).unwrap();
    let h = Reference::seed(RefImpl::F316);
    for _ in 0..3 {
        let t = Instant::now(); std::hint::black_box(h.render()); let a = t.elapsed();
        let t = Instant::now(); std::hint::black_box(d.render()); let b = t.elapsed();
        println!("hand {:?} described {:?} ratio {:.2}", a, b, b.as_secs_f64()/a.as_secs_f64());
    }
}
