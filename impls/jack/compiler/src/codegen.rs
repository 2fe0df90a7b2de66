//! Semantic checks and VM code generation for one class (spec §4.2, §4.3).
//! Errors do not stop the class: each is recorded and compilation goes on,
//! so one run reports as many as it can. Output is kept only without errors.

use std::collections::HashMap;
use std::fmt::Write as _;

use crate::ast::*;
use crate::error::{ErrorKind, Pos};
use crate::os_api;
use crate::program::{Program, ProgramClass};
use jack_os::OsSubroutine;
use jack_os::Profile;

const PRIMITIVES: [&str; 3] = ["int", "char", "boolean"];

/// A class's VM text and the Jack position of each of its lines.
pub type ClassCode = (String, Vec<Pos>);

/// Compiles one class to VM text with the Jack position of each of its
/// lines, or returns every error found in it.
pub fn compile_class<'a>(
    class: &'a Class,
    program: &'a Program<'a>,
) -> Result<ClassCode, Vec<(Pos, ErrorKind)>> {
    let mut g = Gen::new(class, program);
    g.class_checks();
    for sub in &class.subroutines {
        g.subroutine(sub);
    }
    if g.errors.is_empty() {
        Ok((g.out, g.lines))
    } else {
        Err(g.errors)
    }
}

/// A variable's storage and declared type.
#[derive(Debug, Clone)]
struct Var {
    segment: &'static str,
    index: usize,
    ty: String,
}

struct Gen<'a> {
    class: &'a Class,
    program: &'a Program<'a>,
    class_vars: HashMap<&'a str, Var>,
    locals: HashMap<&'a str, Var>,
    n_fields: usize,
    next_label: usize,
    out: String,
    /// The Jack construct being compiled: the source of the next line.
    at: Pos,
    /// The Jack position of each line of `out`.
    lines: Vec<Pos>,
    errors: Vec<(Pos, ErrorKind)>,
}

fn capitalize(s: &str) -> String {
    let mut c = s.chars();
    match c.next() {
        Some(f) => f.to_uppercase().chain(c).collect(),
        None => String::new(),
    }
}

impl<'a> Gen<'a> {
    fn new(class: &'a Class, program: &'a Program<'a>) -> Self {
        let mut class_vars = HashMap::new();
        let (mut n_static, mut n_field) = (0, 0);
        for dec in &class.vars {
            for name in &dec.names {
                let (segment, counter) = match dec.kind {
                    ClassVarKind::Static => ("static", &mut n_static),
                    ClassVarKind::Field => ("this", &mut n_field),
                };
                let var = Var {
                    segment,
                    index: *counter,
                    ty: dec.ty.text.clone(),
                };
                *counter += 1;
                class_vars.insert(name.text.as_str(), var);
            }
        }
        Gen {
            class,
            program,
            class_vars,
            locals: HashMap::new(),
            n_fields: n_field,
            next_label: 0,
            out: String::new(),
            at: class.name.pos,
            lines: Vec::new(),
            errors: Vec::new(),
        }
    }

    fn error(&mut self, pos: Pos, kind: ErrorKind) {
        self.errors.push((pos, kind));
    }

    /// An indented VM command.
    fn emit(&mut self, cmd: &str) {
        self.out.push_str("    ");
        self.out.push_str(cmd);
        self.out.push('\n');
        self.lines.push(self.at);
    }

    fn label(&mut self) -> String {
        let l = format!("{}_{}", self.class.name.text, self.next_label);
        self.next_label += 1;
        l
    }

    fn emit_label(&mut self, l: &str) {
        let _ = writeln!(self.out, "label {l}");
        self.lines.push(self.at);
    }

    /// Duplicate subroutines, OS interface overrides, class variable types.
    fn class_checks(&mut self) {
        let mut seen: Vec<&str> = Vec::new();
        for sub in &self.class.subroutines {
            if seen.contains(&sub.name.text.as_str()) {
                self.error(
                    sub.name.pos,
                    ErrorKind::DuplicateSubroutine(sub.name.text.clone()),
                );
            }
            seen.push(&sub.name.text);
            if let Some(os) = os_api::lookup(&self.class.name.text, &sub.name.text) {
                if !same_signature(os, sub) {
                    self.error(
                        sub.name.pos,
                        ErrorKind::OsInterface {
                            class: os.class.to_string(),
                            name: os.name.to_string(),
                            interface: os_api::interface(os),
                        },
                    );
                }
            }
        }
        for dec in &self.class.vars {
            self.check_type(&dec.ty);
        }
    }

    /// In the web profile, a type must be primitive, an OS class or a class
    /// of the program.
    fn check_type(&mut self, ty: &Ident) {
        if self.program.profile == Profile::Desktop {
            return;
        }
        let t = ty.text.as_str();
        if PRIMITIVES.contains(&t) || os_api::is_os_class(t) || self.program.class(t).is_some() {
            return;
        }
        self.error(ty.pos, ErrorKind::UnknownType(ty.text.clone()));
    }

    fn subroutine(&mut self, sub: &'a Subroutine) {
        for (pos, kind) in crate::flow::check(sub) {
            self.error(pos, kind);
        }
        if !sub.is_void() {
            self.check_type(&sub.ret);
        }
        self.locals.clear();
        let offset = usize::from(sub.kind == SubroutineKind::Method);
        for (i, (ty, name)) in sub.params.iter().enumerate() {
            self.check_type(ty);
            let var = Var {
                segment: "argument",
                index: i + offset,
                ty: ty.text.clone(),
            };
            self.locals.insert(name.text.as_str(), var);
        }
        let mut n_locals = 0;
        for dec in &sub.locals {
            self.check_type(&dec.ty);
            for name in &dec.names {
                let var = Var {
                    segment: "local",
                    index: n_locals,
                    ty: dec.ty.text.clone(),
                };
                n_locals += 1;
                self.locals.insert(name.text.as_str(), var);
            }
        }
        self.at = sub.name.pos;
        let _ = writeln!(
            self.out,
            "function {}.{} {}",
            self.class.name.text, sub.name.text, n_locals
        );
        self.lines.push(self.at);
        match sub.kind {
            SubroutineKind::Method => {
                self.emit("push argument 0");
                self.emit("pop pointer 0");
            }
            SubroutineKind::Constructor if self.n_fields > 0 => {
                self.emit(&format!("push constant {}", self.n_fields));
                self.emit("call Memory.alloc 1");
                self.emit("pop pointer 0");
            }
            SubroutineKind::Constructor => {
                self.emit("push constant 0");
                self.emit("pop pointer 0");
            }
            SubroutineKind::Function => {}
        }
        self.statements(&sub.body);
    }

    fn lookup(&self, name: &str) -> Option<&Var> {
        self.locals.get(name).or_else(|| self.class_vars.get(name))
    }

    /// `segment index` of a variable, or an error (and `None`).
    fn var(&mut self, id: &Ident) -> Option<String> {
        match self.lookup(&id.text) {
            Some(v) => Some(format!("{} {}", v.segment, v.index)),
            None => {
                self.error(id.pos, ErrorKind::UndeclaredVariable(id.text.clone()));
                None
            }
        }
    }

    fn push_var(&mut self, id: &Ident) {
        self.at = id.pos;
        if let Some(v) = self.var(id) {
            self.emit(&format!("push {v}"));
        }
    }

    fn statements(&mut self, stmts: &[Statement]) {
        for s in stmts {
            self.statement(s);
        }
    }

    fn statement(&mut self, s: &Statement) {
        match s {
            Statement::Let {
                target,
                index: Some(index),
                value,
            } => {
                self.expr(index);
                self.push_var(target);
                self.emit("add");
                self.expr(value);
                for cmd in ["pop temp 0", "pop pointer 1", "push temp 0", "pop that 0"] {
                    self.emit(cmd);
                }
            }
            Statement::Let {
                target,
                index: None,
                value,
            } => {
                self.expr(value);
                self.at = target.pos;
                if let Some(v) = self.var(target) {
                    self.emit(&format!("pop {v}"));
                }
            }
            Statement::If { cond, then, els } => {
                let end = self.label();
                let otherwise = self.label();
                self.expr(cond);
                self.emit("not");
                self.emit(&format!("if-goto {otherwise}"));
                self.statements(then);
                self.emit(&format!("goto {end}"));
                self.emit_label(&otherwise);
                self.statements(els);
                self.emit_label(&end);
            }
            Statement::While { cond, body } => {
                let top = self.label();
                let exit = self.label();
                self.emit_label(&top);
                self.expr(cond);
                self.emit("not");
                self.emit(&format!("if-goto {exit}"));
                self.statements(body);
                self.emit(&format!("goto {top}"));
                self.emit_label(&exit);
            }
            Statement::Do(call) => {
                self.call(call);
                self.emit("pop temp 0");
            }
            Statement::Return { value, pos } => {
                self.at = *pos;
                match value {
                    Some(e) => self.expr(e),
                    None => self.emit("push constant 0"),
                }
                self.emit("return");
            }
        }
    }

    fn expr(&mut self, e: &Expr) {
        self.term(&e.first);
        for (op, t) in &e.rest {
            self.term(t);
            self.emit(match op {
                BinOp::Add => "add",
                BinOp::Sub => "sub",
                BinOp::Mul => "call Math.multiply 2",
                BinOp::Div => "call Math.divide 2",
                BinOp::And => "and",
                BinOp::Or => "or",
                BinOp::Lt => "lt",
                BinOp::Gt => "gt",
                BinOp::Eq => "eq",
            });
        }
    }

    fn term(&mut self, t: &Term) {
        match t {
            Term::Int(digits, pos) => {
                self.at = *pos;
                self.emit(&format!("push constant {digits}"));
            }
            Term::Str(s) => {
                let codes: Vec<u16> = s.encode_utf16().collect();
                self.emit(&format!("push constant {}", codes.len()));
                self.emit("call String.new 1");
                for c in codes {
                    self.emit(&format!("push constant {c}"));
                    self.emit("call String.appendChar 2");
                }
            }
            Term::Keyword(KeywordConst::True) => {
                self.emit("push constant 1");
                self.emit("neg");
            }
            Term::Keyword(KeywordConst::False | KeywordConst::Null) => self.emit("push constant 0"),
            Term::Keyword(KeywordConst::This) => self.emit("push pointer 0"),
            Term::Var(id) => self.push_var(id),
            Term::Index(id, index) => {
                self.expr(index);
                self.push_var(id);
                for cmd in ["add", "pop pointer 1", "push that 0"] {
                    self.emit(cmd);
                }
            }
            Term::Call(call) => self.call(call),
            Term::Paren(e) => self.expr(e),
            Term::Unary(op, inner) => {
                self.term(inner);
                self.emit(match op {
                    UnaryOp::Neg => "neg",
                    UnaryOp::Not => "not",
                });
            }
        }
    }

    fn call(&mut self, call: &Call) {
        self.at = call.pos();
        // (class, receiver to push): unqualified calls are methods on this.
        let (class_name, receiver) = match &call.receiver {
            None => (self.class.name.text.clone(), Some("pointer 0".to_string())),
            Some(r) => match self.lookup(&r.text) {
                Some(v) => (v.ty.clone(), Some(format!("{} {}", v.segment, v.index))),
                None => (r.text.clone(), None),
            },
        };
        let is_method = receiver.is_some();
        if let Err(kind) =
            self.validate_call(&class_name, &call.name.text, call.args.len(), is_method)
        {
            self.error(call.pos(), kind);
        }
        if !is_method && class_name == "Memory" && call.name.text == "deAlloc" && self.n_fields == 0
        {
            // The official compiler's quirk: in a class without fields the
            // call is replaced by discarding the argument and pushing 0.
            for a in &call.args {
                self.expr(a);
                self.emit("pop temp 0");
            }
            self.emit("push constant 0");
            return;
        }
        if let Some(r) = &receiver {
            self.emit(&format!("push {r}"));
        }
        for a in &call.args {
            self.expr(a);
        }
        let n = call.args.len() + usize::from(is_method);
        self.at = call.pos();
        self.emit(&format!("call {}.{} {}", class_name, call.name.text, n));
    }

    /// Checks a call against the OS first, then the program's classes.
    fn validate_call(
        &self,
        class: &str,
        name: &str,
        n_args: usize,
        is_method: bool,
    ) -> Result<(), ErrorKind> {
        let web = self.program.profile == Profile::Web;
        let (kind, n_params, kind_label) = if let Some(os) = os_api::lookup(class, name) {
            (
                os_api::kind(os),
                usize::from(os.params),
                capitalize(os_api::kind(os).keyword()),
            )
        } else {
            match self.program.class(class) {
                // A file that did not parse: its subroutines are unknown.
                Some(ProgramClass::Unparsed) => return Ok(()),
                Some(ProgramClass::Parsed(c)) => {
                    let Some(sub) = c.subroutines.iter().find(|s| s.name.text == name) else {
                        return Err(ErrorKind::UnknownSubroutine {
                            class: class.to_string(),
                            name: name.to_string(),
                        });
                    };
                    // The web IDE capitalises the subroutine's name here.
                    let label = capitalize(if web { name } else { sub.kind.keyword() });
                    (sub.kind, sub.params.len(), label)
                }
                None if !web && os_api::is_os_class(class) => {
                    return Err(ErrorKind::UnknownSubroutine {
                        class: class.to_string(),
                        name: name.to_string(),
                    })
                }
                // Desktop: a class outside the program may come as VM code.
                None if !web && !PRIMITIVES.contains(&class) => return Ok(()),
                None => return Err(ErrorKind::UnknownClass(class.to_string())),
            }
        };
        if kind == SubroutineKind::Method && !is_method {
            return Err(ErrorKind::MethodCalledAsFunction {
                class: class.to_string(),
                name: name.to_string(),
            });
        }
        if kind != SubroutineKind::Method && is_method {
            return Err(ErrorKind::FunctionCalledAsMethod {
                label: kind_label,
                class: class.to_string(),
                name: name.to_string(),
            });
        }
        if n_params != n_args {
            return Err(ErrorKind::ArgumentCount {
                class: class.to_string(),
                name: name.to_string(),
                expected: n_params,
                got: n_args,
            });
        }
        Ok(())
    }
}

/// Whether a user subroutine declares exactly the OS interface.
fn same_signature(os: &OsSubroutine, sub: &Subroutine) -> bool {
    os_api::kind(os) == sub.kind
        && os.return_type == sub.ret.text
        && os.param_types.len() == sub.params.len()
        && os
            .param_types
            .iter()
            .zip(&sub.params)
            .all(|(a, (b, _))| *a == b.text)
}
