//! Fault injection: a catalogue of deliberate faults, each run against its
//! clean counterpart on a small committed set. A fault passes when the
//! harness detects it (the comparison diverges), localizes the first
//! divergence to the operation the fault lives in, and the clean pair shows
//! no divergence on the same set (no false alarm).

use crate::cast::Cast;
use crate::localize::localize;
use crate::runner::{diff_set, RunOptions};
use common::Op;
use serde::{Deserialize, Serialize};
use std::fmt;
use vectors::VectorSet;

/// What a detected fault must look like.
#[derive(Clone, Copy, Debug)]
pub enum Expect {
    /// Localized to one of these operations.
    Op(&'static [Op]),
    /// Both traces agree but the answers differ after their last
    /// operation, which is this one (a fault in the logic that uses it).
    After(Op),
    /// Reported as a set-level finding containing this text.
    Finding(&'static str),
}

/// One deliberate fault.
pub struct Fault {
    /// The fault's name (`sqrt-floor-div`).
    pub name: &'static str,
    /// What it changes.
    pub description: &'static str,
    /// The labels of the subject and the oracle, one with the fault.
    pub faulty: [&'static str; 2],
    /// The same pair without the fault: the control, which must agree.
    pub clean: [&'static str; 2],
    /// The set it runs on: a committed set, or a TestFloat set by its name
    /// (`testfloat-2-add`).
    pub set: &'static str,
    /// What detection must show.
    pub expect: Expect,
}

/// The control of a reference fault: the clean ref-f316 against the Jack
/// program, an independent implementation (ref-f316 against itself could
/// never raise a false alarm, so it would control nothing).
const REF_CLEAN: [&str; 2] = ["ref-f316", "jack"];

/// The catalogue of faults.
pub fn catalogue() -> Vec<Fault> {
    vec![
        Fault {
            name: "sqrt-floor-div",
            description: "reference: sqrt's start exponent as (e-127)/2+127 with a floor division",
            faulty: ["ref-f316+sqrt-floor-div", "ref-f316"],
            clean: REF_CLEAN,
            set: "ops-small",
            expect: Expect::Op(&[Op::Sqrt]),
        },
        Fault {
            name: "jack-web-divide",
            description: "emulator: the web IDE's Math.divide, which floors instead of truncating",
            faulty: ["jack+web-divide", "ref-f316"],
            clean: ["jack", "ref-f316"],
            set: "ops-small",
            // The first divergent vector of ops-small is a sqrt.
            expect: Expect::Op(&[Op::Sqrt]),
        },
        Fault {
            name: "add-align-off-by-one",
            description: "reference: add shifts the smaller mantissa once too often",
            faulty: ["ref-f316+add-align-off-by-one", "ref-f316"],
            clean: REF_CLEAN,
            set: "ops-small",
            expect: Expect::Op(&[Op::Add]),
        },
        Fault {
            name: "mul-keep-low",
            description: "reference: mul keeps the low*low partial product",
            faulty: ["ref-f316+mul-keep-low", "ref-f316"],
            clean: REF_CLEAN,
            set: "ops-small",
            expect: Expect::Op(&[Op::Mul]),
        },
        Fault {
            name: "dither-threshold",
            description: "reference: a pixel is white when its dithered value is not below 0.5",
            faulty: ["ref-f316+dither-threshold", "ref-f316"],
            clean: REF_CLEAN,
            set: "pixels-small",
            expect: Expect::After(Op::Gt),
        },
        Fault {
            name: "add-carry-bit",
            description: "reference: add tests its carry by bit 14 (missed by the committed sets)",
            faulty: ["ref-f316+add-carry-bit", "ref-f316"],
            clean: REF_CLEAN,
            set: "testfloat-2-add",
            expect: Expect::Op(&[Op::Add]),
        },
        Fault {
            name: "add-drop-far",
            description: "reference: add drops an operand 14 exponents below (missed by the committed sets)",
            faulty: ["ref-f316+add-drop-far", "ref-f316"],
            clean: REF_CLEAN,
            set: "testfloat-2-add",
            expect: Expect::Op(&[Op::Add]),
        },
        Fault {
            name: "div-normalise-once",
            description: "reference: div normalises its quotient by one doubling (missed by the committed sets)",
            faulty: ["ref-f316+div-normalise-once", "ref-f316"],
            clean: REF_CLEAN,
            set: "testfloat-2-div",
            expect: Expect::Op(&[Op::Div]),
        },
        Fault {
            name: "f32-oracle",
            description: "the error policy's oracle computes in f32 while it is taken for ref-f64",
            faulty: ["ref-f32", "ref-f64+f32-oracle"],
            clean: ["ref-f32", "ref-f64"],
            set: "sdf-small",
            expect: Expect::Finding("is not f64"),
        },
    ]
}

/// How one fault fared.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FaultResult {
    pub fault: String,
    pub set: String,
    /// Differences the faulty run showed.
    pub differences: usize,
    /// Whether the comparison with the fault diverged.
    pub detected: bool,
    /// Whether the clean control diverged (a false alarm).
    pub clean_diverged: bool,
    /// The operation the first divergence was localized to.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub localized_to: Option<Op>,
    /// The first finding, for set-level faults.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub finding: Option<String>,
    /// Why the fault could not be run, if so.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
    pub passed: bool,
}

impl fmt::Display for FaultResult {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let verdict = if self.passed { "PASS" } else { "FAIL" };
        write!(f, "{verdict} {:22} on {:13}", self.fault, self.set)?;
        if let Some(e) = &self.error {
            return write!(f, " error: {e}");
        }
        write!(
            f,
            " detected: {} ({} differences)",
            if self.detected { "yes" } else { "no" },
            self.differences
        )?;
        if let Some(op) = self.localized_to {
            write!(f, ", localized to {op}")?;
        }
        if let Some(finding) = &self.finding {
            write!(f, ", finding: {finding}")?;
        }
        if self.clean_diverged {
            write!(f, ", FALSE ALARM on the clean pair")?;
        }
        Ok(())
    }
}

fn failed(fault: &Fault, error: String) -> FaultResult {
    FaultResult {
        fault: fault.name.to_string(),
        set: fault.set.to_string(),
        differences: 0,
        detected: false,
        clean_diverged: false,
        localized_to: None,
        finding: None,
        error: Some(error),
        passed: false,
    }
}

/// Run one fault: detect, localize, and check the clean control.
pub fn run_fault(cast: &Cast, fault: &Fault) -> FaultResult {
    let opened = (|| {
        let open = |label: &str| cast.open(label).map_err(|e| format!("{label}: {e}"));
        let pair = |[a, b]: [&str; 2]| Ok::<_, String>((open(a)?, open(b)?));
        let set: VectorSet = match vectors::gen::testfloat::named(fault.set) {
            Some(set) => set,
            None => vectors::load_named(fault.set).map_err(|e| e.to_string())?,
        };
        let faulty = pair(fault.faulty)?;
        let clean = pair(fault.clean)?;
        let tracer = open(&cast.tracer().name)?;
        Ok::<_, String>((set, faulty, clean, tracer))
    })();
    let (set, (subject, oracle), (clean_subject, clean_oracle), tracer) = match opened {
        Ok(o) => o,
        Err(e) => return failed(fault, e),
    };
    let options = RunOptions::default();
    let report = diff_set(&[subject.as_ref(), oracle.as_ref()], &set, options);
    let Some(comparison) = report.comparisons.first() else {
        let why = report
            .failures()
            .map(|(l, e)| format!("{l}: {e}"))
            .collect::<Vec<_>>()
            .join("; ");
        return failed(fault, why);
    };
    let clean_diverged = diff_set(
        &[clean_subject.as_ref(), clean_oracle.as_ref()],
        &set,
        options,
    )
    .diverged();
    let mut result = FaultResult {
        fault: fault.name.to_string(),
        set: fault.set.to_string(),
        differences: comparison.groups.iter().map(|g| g.count).sum(),
        detected: comparison.diverged,
        clean_diverged,
        localized_to: None,
        finding: comparison.findings.first().cloned(),
        error: None,
        passed: false,
    };
    let located = match fault.expect {
        Expect::Finding(text) => result.finding.as_deref().is_some_and(|f| f.contains(text)),
        Expect::Op(_) | Expect::After(_) => {
            let first = comparison.divergences.iter().find(|d| !d.tolerated);
            match first
                .map(|d| localize(subject.as_ref(), oracle.as_ref(), tracer.as_ref(), &d.input))
            {
                Some(Ok(l)) => {
                    if let Expect::After(op) = fault.expect {
                        result.localized_to = l.after_last.as_ref().map(|r| r.op);
                        result.localized_to == Some(op)
                    } else {
                        result.localized_to = l.blamed_op();
                        matches!(fault.expect, Expect::Op(ops) if result.localized_to.is_some_and(|op| ops.contains(&op)))
                    }
                }
                Some(Err(e)) => {
                    result.error = Some(format!("localize: {e}"));
                    false
                }
                None => false,
            }
        }
    };
    result.passed = result.detected && located && !clean_diverged;
    result
}

/// Run every fault of the catalogue.
pub fn run_all(cast: &Cast) -> Vec<FaultResult> {
    catalogue().iter().map(|f| run_fault(cast, f)).collect()
}
