//! What the harness knows of a program's subroutines before calling them:
//! from Jack sources, each declaration (kind, parameters, return type,
//! fields); from VM code alone, the argument count of every call site.
//! Used to reject a statement with the wrong arity, a method called on a
//! function, or a target assigned from a `void` subroutine.

use jack_compiler::ast::{ClassVarKind, SubroutineKind};
use std::collections::BTreeMap;

/// One subroutine as declared or as called.
#[derive(Clone, Debug, PartialEq, Eq)]
struct Signature {
    /// Arguments in VM order (`this` counted for a method); `None` when
    /// the VM code never calls it.
    vm_args: Option<usize>,
    /// The declaration, from Jack sources.
    declared: Option<Declared>,
}

#[derive(Clone, Debug, PartialEq, Eq)]
struct Declared {
    kind: SubroutineKind,
    void: bool,
    /// `method Float316 add(Float316 b, Float316 r)`.
    text: String,
}

/// Subroutine signatures and class field counts of one program.
#[derive(Clone, Debug, Default)]
pub struct Signatures {
    functions: BTreeMap<String, Signature>,
    fields: BTreeMap<String, usize>,
}

impl Signatures {
    /// From Jack sources (parsed; sources that do not parse add nothing,
    /// since compiling them reports the error first).
    pub fn from_jack<N: AsRef<str>, S: AsRef<str>>(sources: &[(N, S)]) -> Signatures {
        let mut sig = Signatures::default();
        for (_, src) in sources {
            let Ok(class) = jack_compiler::parser::parse_class(src.as_ref()) else {
                continue;
            };
            let fields = class
                .vars
                .iter()
                .filter(|v| v.kind == ClassVarKind::Field)
                .map(|v| v.names.len())
                .sum();
            sig.fields.insert(class.name.text.clone(), fields);
            for sub in &class.subroutines {
                let params: Vec<String> = sub
                    .params
                    .iter()
                    .map(|(t, n)| format!("{} {}", t.text, n.text))
                    .collect();
                let this = usize::from(sub.kind == SubroutineKind::Method);
                sig.functions.insert(
                    format!("{}.{}", class.name.text, sub.name.text),
                    Signature {
                        vm_args: Some(sub.params.len() + this),
                        declared: Some(Declared {
                            kind: sub.kind,
                            void: sub.is_void(),
                            text: format!(
                                "{} {} {}({})",
                                sub.kind.keyword(),
                                sub.ret.text,
                                sub.name.text,
                                params.join(", ")
                            ),
                        }),
                    },
                );
            }
        }
        sig
    }

    /// From VM code: every `function` line, and the argument count of the
    /// `call` lines that name it.
    pub fn from_vm<N: AsRef<str>, S: AsRef<str>>(sources: &[(N, S)]) -> Signatures {
        let mut sig = Signatures::default();
        for (_, src) in sources {
            for line in src.as_ref().lines() {
                let line = line.split("//").next().unwrap_or("");
                let words: Vec<&str> = line.split_whitespace().collect();
                match words.as_slice() {
                    ["function", name, _] => {
                        sig.functions.entry(name.to_string()).or_insert(Signature {
                            vm_args: None,
                            declared: None,
                        });
                    }
                    ["call", name, n] => {
                        if let Ok(n) = n.parse() {
                            sig.functions
                                .entry(name.to_string())
                                .or_insert(Signature {
                                    vm_args: None,
                                    declared: None,
                                })
                                .vm_args = Some(n);
                        }
                    }
                    _ => {}
                }
            }
        }
        sig
    }

    /// Number of fields of `class`, when its Jack source is known.
    pub fn field_count(&self, class: &str) -> Option<usize> {
        self.fields.get(class).copied()
    }

    /// Whether the program has `class`, when its Jack sources are known
    /// (`None` from VM code alone, where a class without functions leaves
    /// no trace).
    pub fn has_class(&self, class: &str) -> Option<bool> {
        (!self.fields.is_empty()).then(|| self.fields.contains_key(class))
    }

    /// Why `name` cannot be called: it does not exist; the functions of its
    /// class, if any, are listed.
    pub fn missing(&self, name: &str) -> String {
        let class = name.split('.').next().unwrap_or(name);
        let prefix = format!("{class}.");
        let siblings: Vec<&str> = self
            .functions
            .keys()
            .filter_map(|f| f.strip_prefix(&prefix))
            .collect();
        if siblings.is_empty() {
            format!("the program has no function `{name}` (and no class `{class}`)")
        } else {
            format!(
                "the program has no function `{name}` ({class} has: {})",
                siblings.join(", ")
            )
        }
    }

    /// Check a call of `name` with `vm_args` arguments: its arity, that a
    /// target is assigned only from a non-void subroutine, that `var.f()`
    /// names a method and `Class.f()` a function or constructor (a method
    /// called that way would take its first argument as its object).
    pub fn check(
        &self,
        name: &str,
        vm_args: usize,
        has_target: bool,
        on_variable: bool,
    ) -> Result<(), String> {
        let Some(sig) = self.functions.get(name) else {
            return Ok(());
        };
        let declared = sig.declared.as_ref();
        if let Some(d) = declared {
            if on_variable && d.kind != SubroutineKind::Method {
                return Err(format!(
                    "`{name}` is a {}, not a method (`{}`): call it as `{name}(...)`",
                    d.kind.keyword(),
                    d.text
                ));
            }
            if !on_variable && d.kind == SubroutineKind::Method {
                let sub = name.rsplit('.').next().unwrap_or(name);
                return Err(format!(
                    "`{name}` is a method, not a function (`{}`): call it on an object, \
                     `a.{sub}(...)`",
                    d.text
                ));
            }
            if has_target && d.void {
                return Err(format!(
                    "`{name}` returns void (`{}`): it has no value to assign",
                    d.text
                ));
            }
        }
        if let Some(n) = sig.vm_args {
            if n != vm_args {
                let how = declared.map_or_else(
                    || format!("the program calls it with {n}"),
                    |d| format!("`{}`", d.text),
                );
                let this = if declared.is_some_and(|d| d.kind == SubroutineKind::Method) {
                    ", counting the object it is called on"
                } else {
                    ""
                };
                return Err(format!(
                    "wrong arity: `{name}` takes {n} argument(s){this} ({how}), the statement passes {vm_args}"
                ));
            }
        }
        Ok(())
    }
}
