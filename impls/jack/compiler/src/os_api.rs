//! The built-in OS (spec §3) as the compiler sees it, read from `jack-os`'s
//! table: calls are validated against it before the compiled classes, and a
//! class named like an OS class must keep its interface (spec §4.2).

use crate::ast::SubroutineKind;
use jack_os::OsSubroutine;

/// The OS subroutine `class.name`, if there is one.
pub fn lookup(class: &str, name: &str) -> Option<&'static OsSubroutine> {
    jack_os::subroutines()
        .iter()
        .find(|s| s.class == class && s.name == name)
}

/// Whether `name` is one of the OS classes.
pub fn is_os_class(name: &str) -> bool {
    jack_os::subroutines().iter().any(|s| s.class == name)
}

/// The kind of an OS subroutine in the compiler's terms.
pub fn kind(os: &OsSubroutine) -> SubroutineKind {
    match os.kind {
        jack_os::SubroutineKind::Function => SubroutineKind::Function,
        jack_os::SubroutineKind::Method => SubroutineKind::Method,
        jack_os::SubroutineKind::Constructor => SubroutineKind::Constructor,
    }
}

/// The interface as Jack declares it, e.g. `function int divide(int, int)`.
pub fn interface(os: &OsSubroutine) -> String {
    format!(
        "{} {} {}({})",
        kind(os).keyword(),
        os.return_type,
        os.name,
        os.param_types.join(", ")
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_eight_os_classes_and_nothing_else() {
        for class in [
            "Sys", "Screen", "Output", "Keyboard", "String", "Array", "Memory", "Math",
        ] {
            assert!(is_os_class(class), "{class}");
        }
        assert!(!is_os_class("Main"));
        assert!(lookup("Sys", "init").is_none());
        assert!(lookup("Math", "bit").is_none());
        let divide = lookup("Math", "divide").unwrap();
        assert_eq!(interface(divide), "function int divide(int, int)");
        assert_eq!(
            kind(lookup("String", "length").unwrap()),
            SubroutineKind::Method
        );
    }
}
