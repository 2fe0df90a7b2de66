//! The Jack-level interface of the built-in OS (spec §3) as the compiler sees
//! it: kind, parameter types and return type of every subroutine. Calls are
//! validated against it before the compiled classes (spec §4.2).

use crate::ast::SubroutineKind;

/// One OS subroutine's Jack signature.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct OsSubroutine {
    /// Class name, e.g. `Math`.
    pub class: &'static str,
    /// Subroutine name, e.g. `divide`.
    pub name: &'static str,
    /// Function, constructor or method.
    pub kind: SubroutineKind,
    /// Parameter types, `this` excluded for methods.
    pub params: &'static [&'static str],
    /// Return type (`void` for none).
    pub ret: &'static str,
}

impl OsSubroutine {
    /// The interface as Jack would declare it, e.g.
    /// `function int divide(int, int)`.
    pub fn interface(&self) -> String {
        format!(
            "{} {} {}({})",
            self.kind.keyword(),
            self.ret,
            self.name,
            self.params.join(", ")
        )
    }
}

/// The 8 OS classes.
pub const OS_CLASSES: [&str; 8] = [
    "Sys", "Screen", "Output", "Keyboard", "String", "Array", "Memory", "Math",
];

const F: SubroutineKind = SubroutineKind::Function;
const C: SubroutineKind = SubroutineKind::Constructor;
const M: SubroutineKind = SubroutineKind::Method;

const fn os(
    class: &'static str,
    name: &'static str,
    kind: SubroutineKind,
    params: &'static [&'static str],
    ret: &'static str,
) -> OsSubroutine {
    OsSubroutine {
        class,
        name,
        kind,
        params,
        ret,
    }
}

/// Every OS subroutine of spec §3, in the spec's order.
pub const OS_SUBROUTINES: &[OsSubroutine] = &[
    os("Math", "init", F, &[], "void"),
    os("Math", "multiply", F, &["int", "int"], "int"),
    os("Math", "divide", F, &["int", "int"], "int"),
    os("Math", "min", F, &["int", "int"], "int"),
    os("Math", "max", F, &["int", "int"], "int"),
    os("Math", "sqrt", F, &["int"], "int"),
    os("Math", "abs", F, &["int"], "int"),
    os("Memory", "init", F, &[], "void"),
    os("Memory", "peek", F, &["int"], "int"),
    os("Memory", "poke", F, &["int", "int"], "void"),
    os("Memory", "alloc", F, &["int"], "Array"),
    os("Memory", "deAlloc", F, &["Array"], "void"),
    os("Array", "init", F, &[], "void"),
    os("Array", "new", C, &["int"], "Array"),
    os("Array", "dispose", M, &[], "void"),
    os("String", "init", F, &[], "void"),
    os("String", "new", C, &["int"], "String"),
    os("String", "dispose", M, &[], "void"),
    os("String", "length", M, &[], "int"),
    os("String", "charAt", M, &["int"], "char"),
    os("String", "setCharAt", M, &["int", "char"], "void"),
    os("String", "appendChar", M, &["char"], "String"),
    os("String", "eraseLastChar", M, &[], "void"),
    os("String", "intValue", M, &[], "int"),
    os("String", "setInt", M, &["int"], "void"),
    os("String", "backSpace", F, &[], "char"),
    os("String", "doubleQuote", F, &[], "char"),
    os("String", "newLine", F, &[], "char"),
    os("Output", "init", F, &[], "void"),
    os("Output", "moveCursor", F, &["int", "int"], "void"),
    os("Output", "printChar", F, &["char"], "void"),
    os("Output", "printString", F, &["String"], "void"),
    os("Output", "printInt", F, &["int"], "void"),
    os("Output", "println", F, &[], "void"),
    os("Output", "backSpace", F, &[], "void"),
    os("Screen", "init", F, &[], "void"),
    os("Screen", "clearScreen", F, &[], "void"),
    os("Screen", "setColor", F, &["boolean"], "void"),
    os("Screen", "drawPixel", F, &["int", "int"], "void"),
    os(
        "Screen",
        "drawLine",
        F,
        &["int", "int", "int", "int"],
        "void",
    ),
    os(
        "Screen",
        "drawRectangle",
        F,
        &["int", "int", "int", "int"],
        "void",
    ),
    os("Screen", "drawCircle", F, &["int", "int", "int"], "void"),
    os("Keyboard", "init", F, &[], "void"),
    os("Keyboard", "keyPressed", F, &[], "char"),
    os("Keyboard", "readChar", F, &[], "char"),
    os("Keyboard", "readLine", F, &["String"], "String"),
    os("Keyboard", "readInt", F, &["String"], "int"),
    os("Sys", "halt", F, &[], "void"),
    os("Sys", "error", F, &["int"], "void"),
    os("Sys", "wait", F, &["int"], "void"),
];

/// The OS subroutine `class.name`, if there is one.
pub fn lookup(class: &str, name: &str) -> Option<&'static OsSubroutine> {
    OS_SUBROUTINES
        .iter()
        .find(|s| s.class == class && s.name == name)
}

/// Whether `name` is one of the 8 OS classes.
pub fn is_os_class(name: &str) -> bool {
    OS_CLASSES.contains(&name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_covers_every_os_class_and_is_unique() {
        for class in OS_CLASSES {
            assert!(OS_SUBROUTINES.iter().any(|s| s.class == class));
        }
        for (i, a) in OS_SUBROUTINES.iter().enumerate() {
            assert!(is_os_class(a.class));
            for b in &OS_SUBROUTINES[i + 1..] {
                assert!((a.class, a.name) != (b.class, b.name));
            }
        }
        assert_eq!(OS_SUBROUTINES.len(), 50);
        assert!(lookup("Sys", "init").is_none());
        assert!(lookup("Math", "bit").is_none());
        assert_eq!(
            lookup("Math", "divide").unwrap().interface(),
            "function int divide(int, int)"
        );
    }
}
