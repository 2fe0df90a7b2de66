//! The statement language of bindings: `[target =] callee(arg, ...)`, where
//! the callee is `Class.function` or `var.method` (a method on a variable,
//! whose class is the variable's), an argument is a variable, an integer,
//! `true`, `false`, or `_` (an argument whose value is ignored, in capture
//! statements only), and the target names the variable the return value
//! becomes. Variables are the roles of a context ([`Context`]): `a`, `b`,
//! `result` for an operation, `p`, `hit`, ... for an SDF query.

use super::error::BindError;
use super::signatures::Signatures;
use hack_vm::{FnId, Program};

/// The type of a variable.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Ty {
    /// A float object.
    Float,
    /// A 3-vector object.
    Vec3,
    /// An SDF result object.
    Hit,
    /// A Jack int.
    Int,
    /// A Jack boolean (0 false, anything else true).
    Bool,
}

/// The variables a statement may use.
pub(crate) struct Context {
    /// Names and types; a variable's index here is its register.
    pub vars: Vec<(&'static str, Ty)>,
    /// Whether `_` may stand for an argument.
    pub skip: bool,
}

impl Context {
    /// The register of `name`.
    pub fn var(&self, name: &str) -> Option<usize> {
        self.vars.iter().position(|(n, _)| *n == name)
    }

    /// The type of register `v`.
    pub fn ty(&self, v: usize) -> Ty {
        self.vars[v].1
    }

    /// The variable names, for messages.
    fn names(&self) -> String {
        let names: Vec<&str> = self.vars.iter().map(|(n, _)| *n).collect();
        names.join(", ")
    }
}

/// One argument of a compiled call.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Slot {
    /// The value of a register.
    Var(usize),
    /// A constant.
    Lit(i16),
    /// Any value (capture statements: an argument the harness ignores).
    Skip,
}

/// A statement resolved against the program.
#[derive(Clone, Debug)]
pub(crate) struct Call {
    /// The function called.
    pub function: FnId,
    /// Its name, for messages.
    pub name: String,
    /// The arguments in VM order (the receiver first for a method).
    pub args: Vec<Slot>,
    /// The register the return value goes to.
    pub target: Option<usize>,
}

impl Call {
    /// The register of argument `var`, if the call passes it.
    pub fn arg_position(&self, var: usize) -> Option<usize> {
        self.args.iter().position(|s| *s == Slot::Var(var))
    }

    /// Whether the call reads or writes register `var`.
    pub fn uses(&self, var: usize) -> bool {
        self.target == Some(var) || self.arg_position(var).is_some()
    }
}

/// The class of each object-typed variable.
pub(crate) struct Classes<'a> {
    pub float: &'a str,
    pub vec3: Option<&'a str>,
    pub hit: Option<&'a str>,
}

impl Classes<'_> {
    fn of(&self, ty: Ty) -> Option<&str> {
        match ty {
            Ty::Float => Some(self.float),
            Ty::Vec3 => self.vec3,
            Ty::Hit => self.hit,
            Ty::Int | Ty::Bool => None,
        }
    }
}

/// Split `[target =] callee(args)` into its parts.
fn split(text: &str) -> Result<(Option<&str>, &str, Vec<&str>), String> {
    let text = text.trim();
    let (target, call) = match text.split_once('=') {
        Some((t, c)) => (Some(t.trim()), c.trim()),
        None => (None, text),
    };
    let open = call
        .find('(')
        .ok_or_else(|| format!("`{text}` is not a call: expected `Class.function(...)`"))?;
    let inner = call[open + 1..]
        .strip_suffix(')')
        .ok_or_else(|| format!("`{text}` does not end with `)`"))?;
    let callee = call[..open].trim();
    let args: Vec<&str> = if inner.trim().is_empty() {
        Vec::new()
    } else {
        inner.split(',').map(str::trim).collect()
    };
    if let Some(t) = target {
        if !is_ident(t) {
            return Err(format!("`{t}` is not a variable name"));
        }
    }
    Ok((target, callee, args))
}

fn is_ident(s: &str) -> bool {
    let mut chars = s.chars();
    chars
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// Parse and resolve `text` in `context`; errors name `field`.
pub(crate) fn compile(
    field: &str,
    text: &str,
    context: &Context,
    classes: &Classes,
    program: &Program,
    signatures: &Signatures,
) -> Result<Call, BindError> {
    let err = |message: String| BindError::new(field, message);
    let (target, callee, arg_texts) = split(text).map_err(err)?;
    let (owner, method) = callee
        .split_once('.')
        .filter(|(o, m)| is_ident(o) && is_ident(m))
        .ok_or_else(|| {
            err(format!(
                "`{callee}` is not `Class.function` or `variable.method`"
            ))
        })?;
    let mut args = Vec::new();
    let name = match context.var(owner) {
        Some(v) => {
            let class = classes.of(context.ty(v)).ok_or_else(|| {
                err(format!(
                    "`{owner}` is not an object: `{owner}.{method}` calls no method"
                ))
            })?;
            args.push(Slot::Var(v));
            format!("{class}.{method}")
        }
        None => callee.to_string(),
    };
    for a in &arg_texts {
        args.push(slot(a, context).map_err(err)?);
    }
    let target = target
        .map(|t| {
            context.var(t).ok_or_else(|| {
                err(format!(
                    "`{t}` is not a variable here (expected one of {})",
                    context.names()
                ))
            })
        })
        .transpose()?;
    let function = program
        .function_id(&name)
        .ok_or_else(|| err(signatures.missing(&name)))?;
    signatures
        .check(
            &name,
            args.len(),
            target.is_some(),
            context.var(owner).is_some(),
        )
        .map_err(err)?;
    Ok(Call {
        function,
        name,
        args,
        target,
    })
}

fn slot(text: &str, context: &Context) -> Result<Slot, String> {
    match text {
        "true" => return Ok(Slot::Lit(-1)),
        "false" => return Ok(Slot::Lit(0)),
        "_" if context.skip => return Ok(Slot::Skip),
        _ => {}
    }
    if let Ok(n) = text.parse::<i16>() {
        return Ok(Slot::Lit(n));
    }
    let digits = text.strip_prefix('-').unwrap_or(text);
    if !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()) {
        return Err(format!(
            "argument `{text}` is an integer outside Jack's 16-bit range (-32768..=32767)"
        ));
    }
    context.var(text).map(Slot::Var).ok_or_else(|| {
        format!(
            "argument `{text}` is not a variable here (expected one of {}, or an integer)",
            context.names()
        )
    })
}

#[cfg(test)]
mod tests {
    use super::split;

    #[test]
    fn statements_split_into_target_callee_and_arguments() {
        assert_eq!(
            split(" r = F.add(a, b) ").unwrap(),
            (Some("r"), "F.add", vec!["a", "b"])
        );
        assert_eq!(split("a.halve()").unwrap(), (None, "a.halve", vec![]));
        assert!(split("F.add(a, b").unwrap_err().contains("does not end"));
        assert!(split("F.add").unwrap_err().contains("not a call"));
        assert!(split("1x = F.f()").unwrap_err().contains("not a variable"));
    }
}
