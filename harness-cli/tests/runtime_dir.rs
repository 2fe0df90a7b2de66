//! The binary gives Mesa's Vulkan driver the `XDG_RUNTIME_DIR` it asks for
//! (a private directory under the temporary one) when the environment has
//! none or a bad one, so that a headless machine's user does not see the
//! driver's "XDG_RUNTIME_DIR is invalid" error at every command that opens
//! a GPU. What the binary set is read back from a pipe adapter, its child,
//! that prints its environment; the driver's silence is checked by opening
//! gpu-f32 (lavapipe will do; F316_SKIP_GPU skips that one check where
//! there is no adapter).

#![cfg(target_os = "linux")]

use crate::binary;

use std::os::unix::fs::{MetadataExt, PermissionsExt};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The harness with `args`, `TMPDIR` set to `tmp` and `XDG_RUNTIME_DIR`
/// set to `runtime`, or removed.
fn harness(args: &[&str], tmp: &Path, runtime: Option<&str>) -> Output {
    let mut command = Command::new(env!("CARGO_BIN_EXE_harness"));
    command
        .args(args)
        .env("TMPDIR", tmp)
        .env_remove("XDG_RUNTIME_DIR");
    if let Some(dir) = runtime {
        command.env("XDG_RUNTIME_DIR", dir);
    }
    command.output().expect("the binary runs")
}

/// The `XDG_RUNTIME_DIR` the binary's children get (`unset` when none):
/// a pipe adapter prints it on stderr at its start, and the harness quotes
/// that line in the adapter's failure.
fn seen_by_a_child(tmp: &Path, runtime: Option<&str>) -> String {
    let cast = tmp.join("probe.toml");
    std::fs::write(
        &cast,
        "[impl.probe]\nkind = \"pipe\"\nnumbers = \"float316\"\nlevels = [\"ops\"]\n\
         command = \"sh\"\nargs = [\"-c\", \"echo runtime=${XDG_RUNTIME_DIR-unset}:end >&2\"]\n",
    )
    .unwrap();
    let cast = cast.to_str().unwrap();
    let o = harness(
        &[
            "--cast", cast, "diff", "ref-f316", "probe", "--level", "ops",
        ],
        tmp,
        runtime,
    );
    let log = binary::text(&o);
    let start = log
        .find("runtime=")
        .unwrap_or_else(|| panic!("the probe's line is quoted: {log}"));
    let rest = &log[start + "runtime=".len()..];
    rest[..rest.find(":end").expect("the line's end")].to_string()
}

fn the_private_dir(tmp: &Path) -> PathBuf {
    let uid = std::fs::metadata("/proc/self").expect("procfs").uid();
    tmp.join(format!("f316-harness-runtime-{uid}"))
}

#[test]
fn an_unset_or_invalid_runtime_dir_is_replaced_by_a_private_one() {
    for runtime in [
        None,
        Some("relative/dir"),
        Some("/nonexistent/f316-runtime"),
    ] {
        let tmp = tempfile::tempdir().unwrap();
        let private = the_private_dir(tmp.path());
        assert_eq!(
            seen_by_a_child(tmp.path(), runtime),
            private.display().to_string(),
            "{runtime:?}"
        );
        let meta = std::fs::symlink_metadata(&private).unwrap();
        assert!(meta.is_dir(), "{runtime:?}");
        assert_eq!(meta.permissions().mode() & 0o777, 0o700, "{runtime:?}");
    }
}

#[test]
fn a_valid_runtime_dir_is_kept() {
    let tmp = tempfile::tempdir().unwrap();
    let own = tempfile::tempdir().unwrap();
    let own = own.path().to_str().unwrap();
    assert_eq!(seen_by_a_child(tmp.path(), Some(own)), own);
    assert!(!the_private_dir(tmp.path()).exists());
}

#[test]
fn a_private_dir_that_others_may_enter_is_not_used() {
    let tmp = tempfile::tempdir().unwrap();
    let open = the_private_dir(tmp.path());
    std::fs::create_dir(&open).unwrap();
    std::fs::set_permissions(&open, std::fs::Permissions::from_mode(0o755)).unwrap();
    assert_eq!(seen_by_a_child(tmp.path(), None), "unset");
}

#[test]
fn the_driver_does_not_complain_when_a_gpu_is_opened_without_one() {
    let tmp = tempfile::tempdir().unwrap();
    let o = harness(
        &["diff", "ref-f32", "gpu-f32", "--level", "sdf"],
        tmp.path(),
        None,
    );
    let log = binary::text(&o);
    if o.status.code() == Some(2) && std::env::var_os(gpu::SKIP_ENV).is_some() {
        gpu::report_skipped(&log);
        return;
    }
    assert_eq!(o.status.code(), Some(0), "{log}");
    assert!(!log.contains("XDG_RUNTIME_DIR"), "{log}");
}
