//! Target `tst_script`: a `.tst` script of any text, run beside a small
//! program that loops for ever (`Count.vm`) and a compare file.

use hack_vm::{run_script, Profile};
use std::sync::atomic::{AtomicU64, Ordering};

/// The program a script may load: push, pop, goto, for ever.
const COUNT_VM: &str = "label L\npush constant 1\npop temp 0\ngoto L\n";

/// Whether the script's run is short enough to fuzz: at most two `repeat`
/// loops, each with a count of at most 1,000, and no `while` (a legitimate
/// script may run two billion steps, or loop until the program ends).
fn short(text: &str) -> bool {
    let words: Vec<&str> = text
        .split(|c: char| c.is_whitespace() || ",;!{}".contains(c))
        .filter(|w| !w.is_empty())
        .collect();
    let repeats: Vec<usize> = (0..words.len()).filter(|&i| words[i] == "repeat").collect();
    repeats.len() <= 2
        && !words.contains(&"while")
        && repeats.iter().all(|&i| {
            words
                .get(i + 1)
                .and_then(|n| n.parse::<u64>().ok())
                .is_some_and(|n| n <= 1000)
        })
}

/// Any UTF-8 text as `F.tst`, under both profiles: the script runs to a
/// report, or fails with an error that names `F.tst` at a line and column
/// inside the text (line 0 never), and never panics.
pub fn tst_script(data: &[u8]) {
    static RUN: AtomicU64 = AtomicU64::new(0);
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if !short(text) {
        return;
    }
    let dir = std::env::temp_dir().join(format!(
        "fuzz-tst-{}-{}",
        std::process::id(),
        RUN.fetch_add(1, Ordering::Relaxed)
    ));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("Count.vm"), COUNT_VM).unwrap();
    std::fs::write(dir.join("Count.cmp"), "|RAM[5]|\n|   1 |\n").unwrap();
    let script = dir.join("F.tst");
    std::fs::write(&script, text).unwrap();
    let lines = text.lines().count().max(1) + 1;
    for profile in Profile::ALL {
        if let Err(e) = run_script(&script, profile) {
            assert_eq!(e.file, script.display().to_string(), "{e}");
            assert!((1..=lines).contains(&e.line) && e.col >= 1, "{e}");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
