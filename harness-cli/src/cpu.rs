//! The CPU time this process has used (every thread, user and system), for
//! the cost of the nightly's steps where wall time on a shared machine says
//! little.

/// CPU seconds this process has used so far; `None` where it cannot be
/// read (a system other than Linux).
pub fn process_seconds() -> Option<f64> {
    #[cfg(target_os = "linux")]
    {
        let t = rustix::time::clock_gettime(rustix::time::ClockId::ProcessCPUTime);
        Some(t.tv_sec as f64 + t.tv_nsec as f64 * 1e-9)
    }
    #[cfg(not(target_os = "linux"))]
    {
        None
    }
}

#[cfg(all(test, target_os = "linux"))]
mod tests {
    /// Work on this thread shows as CPU time.
    #[test]
    fn busy_work_takes_cpu_time() {
        let before = super::process_seconds().unwrap();
        let mut x = 0u64;
        let start = std::time::Instant::now();
        while start.elapsed().as_millis() < 50 {
            x = std::hint::black_box(x.wrapping_mul(6364136223846793005).wrapping_add(1));
        }
        let used = super::process_seconds().unwrap() - before;
        assert!(used > 0.01, "{used} s for {x}");
    }
}
