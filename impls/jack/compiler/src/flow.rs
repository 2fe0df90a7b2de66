//! The return checks of the web IDE's control-flow pass (spec §4.2): every
//! subroutine, void included, must end in a return on every path, and
//! `return;` is refused in a non-void subroutine.
//!
//! The official pass builds a graph in which a `while` body loops back and
//! the code after the loop is a separate path; reduced to its meaning, a
//! `while` never returns by itself, an `if` returns when both branches (the
//! missing else is empty) return or fall through into code that does, and a
//! `return` anywhere in a straight run of statements makes that run return.

use crate::ast::{Statement, Subroutine};
use crate::error::{ErrorKind, Pos};

/// The return errors of one subroutine, in source order.
pub fn check(sub: &Subroutine) -> Vec<(Pos, ErrorKind)> {
    let mut errors = Vec::new();
    if !sub.is_void() {
        bare_returns(&sub.body, &mut errors);
    }
    if !returns(&sub.body, false) {
        errors.push((
            sub.name.pos,
            ErrorKind::MissingReturn(sub.name.text.clone()),
        ));
    }
    errors
}

fn bare_returns(stmts: &[Statement], errors: &mut Vec<(Pos, ErrorKind)>) {
    for s in stmts {
        match s {
            Statement::Return { pos, value: None } => {
                errors.push((*pos, ErrorKind::ReturnWithoutValue));
            }
            Statement::If { then, els, .. } => {
                bare_returns(then, errors);
                bare_returns(els, errors);
            }
            Statement::While { body, .. } => bare_returns(body, errors),
            _ => {}
        }
    }
}

/// Whether every path through `stmts` returns, given whether the code that
/// follows them (`after`) does.
/// Walks backwards, so recursion is as deep as the nesting, not the length.
fn returns(stmts: &[Statement], after: bool) -> bool {
    stmts.iter().rev().fold(after, |cont, s| match s {
        Statement::Return { .. } => true,
        Statement::If { then, els, .. } => returns(then, cont) && returns(els, cont),
        _ => cont,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parser::parse_class;

    fn errors(ret: &str, body: &str) -> Vec<String> {
        let src = format!("class A {{ function {ret} f() {{ var int x; {body} }} }}");
        let class = parse_class(&src).unwrap();
        check(&class.subroutines[0])
            .into_iter()
            .map(|(_, k)| k.to_string())
            .collect()
    }

    const MISSING: &str = "Subroutine f: not all code paths return a value";

    #[test]
    fn straight_and_branching_code() {
        assert_eq!(errors("void", "return;"), Vec::<String>::new());
        assert_eq!(errors("void", "let x = 1;"), vec![MISSING]);
        assert_eq!(
            errors("int", "if (x) { return 1; } else { return 2; }"),
            Vec::<String>::new()
        );
        assert_eq!(errors("int", "if (x) { return 1; }"), vec![MISSING]);
        assert_eq!(
            errors("int", "if (x) { return 1; } return 2;"),
            Vec::<String>::new()
        );
        assert_eq!(
            errors("int", "if (x) { let x = 1; } else { return 1; } return 2;"),
            Vec::<String>::new()
        );
        // A return before later statements still counts (unreachable code is fine).
        assert_eq!(errors("int", "return 1; let x = 2;"), Vec::<String>::new());
        assert_eq!(
            errors("int", "if (x) { if (x) { return 1; } } else { return 2; }"),
            vec![MISSING]
        );
    }

    #[test]
    fn loops_never_return_by_themselves() {
        assert_eq!(errors("void", "while (true) { }"), vec![MISSING]);
        assert_eq!(errors("int", "while (x) { return 1; }"), vec![MISSING]);
        assert_eq!(
            errors("int", "while (x) { let x = 1; } return 0;"),
            Vec::<String>::new()
        );
    }

    #[test]
    fn bare_return_in_non_void() {
        assert_eq!(
            errors("int", "if (x) { return; } return;"),
            vec!["A non void subroutine must return a value"; 2]
        );
        assert_eq!(errors("void", "return x;"), Vec::<String>::new());
    }
}
