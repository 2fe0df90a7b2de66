//! The `pipe` kind: a program of any language that speaks the JSON-lines
//! protocol of `docs/protocol.md` (the protocol and the process are in
//! [`crate::pipe`]). A project file declares one with
//!
//! ```toml
//! [impl.my-port]
//! kind = "pipe"
//! numbers = "float316"      # float316, f64 or f32: its group and policy
//! levels = ["ops", "pixels"]
//! trace = true              # optional: it answers trace requests
//! checks_domain = true      # optional: it answers out_of_domain where the
//!                           # reference does (else such inputs are counted,
//!                           # not compared)
//! command = "python3"
//! args = ["adapter.py"]     # optional
//! dir = "ports/python"      # optional, relative to the project file
//! watchdog_s = 60           # optional: seconds per batch before a hang
//! ```
//!
//! When it is opened, its handshake must agree with the declaration.

use crate::cast::entry::{Entry, Kind, Opener, Request};
use crate::cast::file::{FieldError, Fields};
use crate::contain::Watchdog;
use crate::implementation::{Failure, FailureKind};
use crate::implementation::{ImplError, Implementation, Numbers};
use crate::pipe::{Pipe, PipeConfig};
use std::path::PathBuf;
use vectors::Level;

/// The `pipe` kind (no built-in entries).
pub struct PipeKind;

impl Kind for PipeKind {
    fn name(&self) -> &'static str {
        "pipe"
    }

    fn declare(&self, name: &str, fields: &mut Fields<'_>) -> Result<Entry, FieldError> {
        let numbers: Numbers = match fields.parsed("numbers")? {
            Some(n) => n,
            None => return Err(fields.error("numbers", "missing (required: float316, f64 or f32)")),
        };
        let levels = fields
            .strings("levels")?
            .iter()
            .map(|l| l.parse::<Level>().map_err(|e| fields.error("levels", e)))
            .collect::<Result<Vec<_>, _>>()?;
        if levels.is_empty() {
            return Err(fields.error(
                "levels",
                "missing or empty (the levels the adapter answers)",
            ));
        }
        let trace = fields.bool("trace")?.unwrap_or(false);
        let checks_domain = fields.bool("checks_domain")?.unwrap_or(false);
        let command = fields.required_string("command")?.to_string();
        let args = fields
            .strings("args")?
            .iter()
            .map(|a| a.to_string())
            .collect();
        let dir = Some(
            fields
                .path("dir")?
                .unwrap_or_else(|| fields.dir().to_path_buf()),
        );
        let watchdog = match fields.raw("watchdog_s").map(|v| v.get_ref()) {
            None => Watchdog::default(),
            Some(v) => {
                let seconds = match v {
                    toml::de::DeValue::Integer(i) => i.as_str().parse::<f64>().ok(),
                    toml::de::DeValue::Float(f) => f.as_str().parse::<f64>().ok(),
                    _ => None,
                }
                .and_then(crate::contain::user_seconds)
                .ok_or_else(|| {
                    fields.error(
                        "watchdog_s",
                        format!(
                            "expected a positive number of seconds, at most {} (one day)",
                            crate::contain::MAX_DURATION_S
                        ),
                    )
                })?;
                Watchdog::fixed(seconds)
            }
        };
        let origin = format!("{}:{}", fields.file().display(), fields.line());
        let mut entry = Entry::new(
            name,
            "pipe",
            numbers,
            PipeOpener {
                program: command.clone(),
                args,
                dir,
                watchdog,
                numbers,
                levels: levels.clone(),
                trace,
                checks_domain,
                origin,
            },
        )
        .about(format!("a pipe adapter: `{command}`"))
        .levels(&levels)
        .own_process();
        if trace {
            entry = entry.traces();
        }
        Ok(entry)
    }
}

/// Starts the adapter and checks its handshake against the declaration.
struct PipeOpener {
    program: String,
    args: Vec<String>,
    dir: Option<PathBuf>,
    watchdog: Watchdog,
    numbers: Numbers,
    levels: Vec<Level>,
    trace: bool,
    checks_domain: bool,
    /// Where it was declared, for messages.
    origin: String,
}

impl Opener for PipeOpener {
    fn open(&self, request: &Request<'_>) -> Result<Box<dyn Implementation>, ImplError> {
        request.seed_scene_only()?;
        if let Some(v) = request.label.variants.first() {
            return Err(ImplError::Unsupported(format!(
                "variant `{v}` (a pipe adapter has none)"
            )));
        }
        let label = request.label.name.clone();
        let mut config = PipeConfig::new(&label, &self.program, &[]);
        config.args = self.args.clone();
        config.dir = self.dir.clone();
        config.watchdog = self.watchdog;
        config.checks_domain = self.checks_domain;
        let pipe = Pipe::open(&config)?;
        let hello = pipe.handshake();
        let disagreement = if hello.numbers != self.numbers {
            Some(format!(
                "numbers {}, declared {}",
                hello.numbers, self.numbers
            ))
        } else if let Some(l) = self.levels.iter().find(|l| !hello.levels.contains(l)) {
            Some(format!("no level {l}, declared in `levels`"))
        } else if self.trace && !hello.trace {
            Some("no trace support, declared with `trace = true`".into())
        } else {
            None
        };
        match disagreement {
            None => Ok(Box::new(pipe)),
            Some(d) => Err(Failure::new(
                &label,
                FailureKind::Protocol,
                format!("its handshake says {d} at {}", self.origin),
                &[],
            )
            .into()),
        }
    }
}
