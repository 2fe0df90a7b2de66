//! One Jack class per IR function: its constants and register slots as
//! statics made at start-up, and one Jack function whose statements map
//! the IR statements one for one (see [`crate::alloc`] for where registers
//! live).

use crate::alloc::{plan, Place, Plan};
use crate::EmitError;
use common::F316;
use scene::ir::{Binary, FuncId, Function, Logic, Program, Stmt, Tuning, Unary, VecOp};
use std::collections::BTreeSet;
use std::fmt::Write;

/// The Jack class and function an IR function becomes.
#[derive(Clone, Debug)]
pub struct Names {
    pub class: String,
    pub function: String,
}

/// The Jack names of every function of `p`: the SDF is `Scene.sdf`, the
/// set-up `Camera.setup`, the pixel function `Shade.pixel`; any other is a
/// class of its own named after it.
pub fn names(p: &Program) -> Vec<Names> {
    (0..p.functions.len() as FuncId)
        .map(|id| {
            let f = p.function(id);
            let (class, function) = if id == p.sdf {
                ("Scene".to_string(), "sdf".to_string())
            } else if id == p.setup {
                ("Camera".to_string(), "setup".to_string())
            } else if id == p.pixel {
                ("Shade".to_string(), "pixel".to_string())
            } else {
                let word: String = f.name.chars().filter(char::is_ascii_alphanumeric).collect();
                let mut c = word.chars();
                let class = c.next().map_or(String::new(), |h| {
                    h.to_ascii_uppercase().to_string() + c.as_str()
                });
                (format!("Fn{id}{class}"), "run".to_string())
            };
            Names { class, function }
        })
        .collect()
}

/// What a role's class says of itself.
fn role(p: &Program, id: FuncId) -> &'static str {
    if id == p.sdf {
        "The scene's signed distance: its shapes, combinations and materials' colours"
    } else if id == p.setup {
        "The camera set-up, run once per image; its results are the uniforms"
    } else if id == p.pixel {
        "A pixel's shade: the view ray, the march, the normal, lighting, shadows and the output level"
    } else {
        "A helper function of the scene"
    }
}

/// A generated class.
pub struct FunctionClass {
    pub text: String,
}

/// The Jack text of a constant.
pub fn literal(value: f64, origin: &str) -> Result<F316, EmitError> {
    F316::from_f64_truncating(value).ok_or_else(|| EmitError::Constant {
        origin: origin.to_string(),
        value,
    })
}

/// Writes the statements of one function.
struct Emitter<'a> {
    f: &'a Function,
    names: &'a [Names],
    plan: Plan,
    out: String,
    indent: usize,
    /// Open loops: (counter, count).
    loops: Vec<(usize, u32)>,
    /// Loop counters declared.
    counters: usize,
    consts: BTreeSet<u16>,
    uses_uniforms: bool,
    /// The variant of the tuned call site being written, if any.
    tuning: Option<Tuning>,
}

impl Emitter<'_> {
    fn unsupported(&self, what: impl Into<String>) -> EmitError {
        EmitError::Unsupported {
            function: self.f.name.clone(),
            what: what.into(),
        }
    }

    fn line(&mut self, s: &str) {
        for _ in 0..self.indent {
            self.out.push_str("    ");
        }
        self.out.push_str(s);
        self.out.push('\n');
    }

    /// A scalar register as a Jack expression (an object).
    fn r(&mut self, r: u16) -> String {
        match self.plan.scalars[usize::from(r)] {
            Place::Slot(s) => format!("r{s}"),
            Place::Const(i) => {
                self.consts.insert(i);
                format!("k{i}")
            }
            Place::Uniform(i) => {
                self.uses_uniforms = true;
                format!("u{i}")
            }
            Place::Param(k) => format!("p{k}"),
            Place::Unused => unreachable!("a mentioned register has a place"),
        }
    }

    /// The suffix of the subroutine that computes the tuned site's variant
    /// (`Newton1`: `sqrtNewton1`), empty outside a tuned site.
    fn variant(&self) -> &'static str {
        self.tuning.map_or("", Tuning::suffix)
    }

    /// Three consecutive registers, as Jack arguments.
    fn r3(&mut self, r: u16) -> String {
        format!("{}, {}, {}", self.r(r), self.r(r + 1), self.r(r + 2))
    }

    fn b(&self, b: u16) -> String {
        format!(
            "b{}",
            self.plan.bools[usize::from(b)].expect("a mentioned boolean")
        )
    }

    fn t(&self, t: u16) -> String {
        format!(
            "t{}",
            self.plan.tags[usize::from(t)].expect("a mentioned tag")
        )
    }

    /// A tag value as a Jack integer (tags are 16-bit words).
    fn tag_value(v: u16) -> String {
        (v as i16).to_string()
    }

    fn block(&mut self, stmts: &[Stmt]) -> Result<(), EmitError> {
        self.indent += 1;
        self.statements(stmts)?;
        self.indent -= 1;
        Ok(())
    }

    /// A block's statements; those after a statement that may leave the
    /// innermost loop run only while the loop goes on (Jack has no break).
    fn statements(&mut self, stmts: &[Stmt]) -> Result<(), EmitError> {
        for (i, s) in stmts.iter().enumerate() {
            self.stmt(s)?;
            let rest = &stmts[i + 1..];
            if breaks_out(s) && !rest.is_empty() {
                let (counter, count) = *self.loops.last().expect("a break is in a loop");
                self.line(&format!("if (i{counter} < {count}) {{"));
                self.block(rest)?;
                self.line("}");
                return Ok(());
            }
        }
        Ok(())
    }

    /// `dst` as a destination: its slot.
    fn dst(&mut self, r: u16) -> String {
        match self.plan.scalars[usize::from(r)] {
            Place::Slot(s) => format!("r{s}"),
            other => unreachable!("a written register is a slot, not {other:?}"),
        }
    }

    /// Whether `dst` is a read-only register written by its one statement
    /// at start-up instead.
    fn hoisted(&self, dst: u16) -> bool {
        matches!(
            self.plan.scalars[usize::from(dst)],
            Place::Const(_) | Place::Uniform(_)
        )
    }

    /// Vector statements write their result component by component:
    /// refuse a destination that overlaps an operand other than exactly.
    fn check_vector(&self, dst: u16, op: VecOp, a: u16, b: u16) -> Result<(), EmitError> {
        let overlaps = |x: u16, width: u16| x != dst && x < dst + 3 && dst < x + width;
        let b_bad = match op {
            VecOp::Normalize => false,
            VecOp::Scale => (dst..dst + 3).contains(&b),
            _ => overlaps(b, 3),
        };
        if overlaps(a, 3) || b_bad {
            return Err(self.unsupported(format!(
                "a vector statement whose result r{dst} overlaps its operands"
            )));
        }
        Ok(())
    }

    fn stmt(&mut self, s: &Stmt) -> Result<(), EmitError> {
        match s {
            Stmt::Const { dst, index } => {
                if !self.hoisted(*dst) {
                    self.consts.insert(*index);
                    let d = self.dst(*dst);
                    self.line(&format!("do {d}.copy(k{index});"));
                }
            }
            Stmt::Uniform { dst, index } => {
                if !self.hoisted(*dst) {
                    self.uses_uniforms = true;
                    let d = self.dst(*dst);
                    self.line(&format!("do {d}.copy(u{index});"));
                }
            }
            Stmt::Table { dst, table } => {
                let d = self.dst(*dst);
                self.line(&format!("do {d}.copy(Image.table{table}());"));
            }
            Stmt::Copy { dst, src } => {
                let (d, a) = (self.dst(*dst), self.r(*src));
                self.line(&format!("do {d}.copy({a});"));
            }
            Stmt::Unary { dst, op, a } => {
                let (d, a) = (self.dst(*dst), self.r(*a));
                let l = match op {
                    Unary::Sqrt => format!("do {a}.sqrt{}({d});", self.variant()),
                    Unary::Floor => format!("do {a}.floor{}({d});", self.variant()),
                    Unary::Mod2 => format!("do {a}.mod2({d});"),
                    Unary::Double => format!("do Ops.double({a}, {d});"),
                    Unary::Quarter => format!("do Ops.quarter({a}, {d});"),
                    Unary::Neg => format!("do {d}.negatedOf({a});"),
                    Unary::Abs => format!("do {d}.absOf({a});"),
                    Unary::Fract => format!("do Ops.fract({a}, {d});"),
                    Unary::Clamp01 => format!("do Ops.clamp01({a}, {d});"),
                };
                self.line(&l);
            }
            Stmt::Binary { dst, op, a, b } => {
                let (d, a, b) = (self.dst(*dst), self.r(*a), self.r(*b));
                let l = match op {
                    Binary::Add => format!("do {a}.add({b}, {d});"),
                    Binary::Sub => format!("do {a}.sub({b}, {d});"),
                    Binary::Mul => format!("do {a}.mul{}({b}, {d});", self.variant()),
                    Binary::Div => format!("do {a}.div({b}, {d});"),
                    Binary::Max => {
                        format!(
                            "if ({a}.gt({b})) {{ do {d}.copy({a}); }} else {{ do {d}.copy({b}); }}"
                        )
                    }
                    Binary::Min => {
                        format!(
                            "if ({b}.gt({a})) {{ do {d}.copy({a}); }} else {{ do {d}.copy({b}); }}"
                        )
                    }
                    Binary::Pow => return Err(self.unsupported("pow (IEEE programs only)")),
                };
                self.line(&l);
            }
            Stmt::Vector { dst, op, a, b } => {
                self.check_vector(*dst, *op, *a, *b)?;
                let (d, va) = (self.r3(*dst), self.r3(*a));
                let l = match op {
                    VecOp::Add => format!("do Ops.add3({va}, {}, {d});", self.r3(*b)),
                    VecOp::Sub => format!("do Ops.sub3({va}, {}, {d});", self.r3(*b)),
                    VecOp::Scale => format!("do Ops.scale3({va}, {}, {d});", self.r(*b)),
                    VecOp::Cross => format!("do Ops.cross3({va}, {}, {d});", self.r3(*b)),
                    VecOp::Normalize => {
                        format!("do Ops.normalize3{}({va}, {d});", self.variant())
                    }
                };
                self.line(&l);
            }
            Stmt::Dot { dst, a, b } => {
                let (d, va, vb) = (self.dst(*dst), self.r3(*a), self.r3(*b));
                self.line(&format!("do Ops.dot3({va}, {vb}, {d});"));
            }
            Stmt::Length { dst, a } => {
                let (d, va) = (self.dst(*dst), self.r3(*a));
                let v = self.variant();
                self.line(&format!("do Ops.length3{v}({va}, {d});"));
            }
            Stmt::Gt { dst, a, b } => {
                let (d, a, b) = (self.b(*dst), self.r(*a), self.r(*b));
                self.line(&format!("let {d} = {a}.gt({b});"));
            }
            Stmt::SignBit { dst, a } => {
                let (d, a) = (self.b(*dst), self.r(*a));
                self.line(&format!("let {d} = ({a}.sign() = 1);"));
            }
            Stmt::Bool { dst, value } => {
                let d = self.b(*dst);
                self.line(&format!("let {d} = {value};"));
            }
            Stmt::Logic { dst, op, a, b } => {
                let (d, a) = (self.b(*dst), self.b(*a));
                let l = match op {
                    Logic::And => format!("let {d} = {a} & {};", self.b(*b)),
                    Logic::Or => format!("let {d} = {a} | {};", self.b(*b)),
                    Logic::Not => format!("let {d} = ~{a};"),
                };
                self.line(&l);
            }
            Stmt::Select { dst, cond, a, b } => {
                let (d, c, a, b) = (self.dst(*dst), self.b(*cond), self.r(*a), self.r(*b));
                self.line(&format!(
                    "if ({c}) {{ do {d}.copy({a}); }} else {{ do {d}.copy({b}); }}"
                ));
            }
            Stmt::SetTag { dst, value } => {
                let d = self.t(*dst);
                self.line(&format!("let {d} = {};", Self::tag_value(*value)));
            }
            Stmt::TagIs { dst, tag, value } => {
                let (d, t) = (self.b(*dst), self.t(*tag));
                self.line(&format!("let {d} = ({t} = {});", Self::tag_value(*value)));
            }
            Stmt::SelectTag { dst, cond, a, b } => {
                let (d, c, a, b) = (self.t(*dst), self.b(*cond), self.t(*a), self.t(*b));
                self.line(&format!(
                    "if ({c}) {{ let {d} = {a}; }} else {{ let {d} = {b}; }}"
                ));
            }
            Stmt::If {
                cond,
                then,
                otherwise,
            } => {
                let c = self.b(*cond);
                self.line(&format!("if ({c}) {{"));
                self.block(then)?;
                if !otherwise.is_empty() {
                    self.line("} else {");
                    self.block(otherwise)?;
                }
                self.line("}");
            }
            Stmt::Switch { tag, cases } => self.switch(*tag, cases)?,
            Stmt::Loop { count, name, body } => {
                let i = self.counters;
                self.counters += 1;
                let count = i16::try_from(*count)
                    .map_err(|_| self.unsupported(format!("a loop of {count} steps")))?;
                if let Some(n) = name {
                    self.line(&format!("// {n}s"));
                }
                self.line(&format!("let i{i} = 0;"));
                self.line(&format!("while (i{i} < {count}) {{"));
                self.loops.push((i, count as u32));
                self.block(body)?;
                self.loops.pop();
                self.line(&format!("    let i{i} = i{i} + 1;"));
                self.line("}");
            }
            Stmt::Break { cond } => {
                let c = self.b(*cond);
                let (counter, count) = *self.loops.last().expect("validated: in a loop");
                self.line(&format!("if ({c}) {{ let i{counter} = {count}; }}"));
            }
            Stmt::Frame { name, body } => {
                self.line(&format!("// {name}"));
                self.statements(body)?;
            }
            Stmt::Tuned { variant, body } => {
                self.line(&format!("// {variant}"));
                let before = self.tuning.replace(*variant);
                self.statements(body)?;
                self.tuning = before;
            }
            // Only engines that explain runs take another side.
            Stmt::Decide { .. } => {}
            Stmt::Call {
                func,
                args,
                results,
                tags,
            } => self.call(*func, args, results, tags)?,
        }
        Ok(())
    }

    /// `switch` as a chain of `if`s on the tag; a tag with no case is out
    /// of domain, as in the reference.
    fn switch(&mut self, tag: u16, cases: &[Vec<Stmt>]) -> Result<(), EmitError> {
        let t = self.t(tag);
        let opened = self.indent;
        for (i, c) in cases.iter().enumerate() {
            self.line(&format!("if ({t} = {i}) {{"));
            self.block(c)?;
            self.line("} else {");
            self.indent += 1;
        }
        self.line(&format!("do Sys.error({});", crate::OUT_OF_DOMAIN));
        while self.indent > opened {
            self.indent -= 1;
            self.line("}");
        }
        Ok(())
    }

    fn call(
        &mut self,
        func: FuncId,
        args: &[u16],
        results: &[u16],
        tags: &[u16],
    ) -> Result<(), EmitError> {
        if results.iter().any(|r| args.contains(r)) {
            return Err(self.unsupported("a call whose result is one of its arguments"));
        }
        let n = &self.names[usize::from(func)];
        let head = format!("{}.{}", n.class, n.function);
        let mut list: Vec<String> = args.iter().map(|&a| self.r(a)).collect();
        list.extend(results.iter().map(|&r| self.dst(r)));
        let call = format!("{head}({})", list.join(", "));
        match tags {
            [] => self.line(&format!("do {call};")),
            [t] => {
                let t = self.t(*t);
                self.line(&format!("let {t} = {call};"));
            }
            _ => return Err(self.unsupported("a call with more than one tag result")),
        }
        Ok(())
    }
}

/// Whether `s` holds a `break` that leaves it (one not inside a loop of its own).
fn breaks_out(s: &Stmt) -> bool {
    match s {
        Stmt::Break { .. } => true,
        Stmt::Loop { .. } => false,
        _ => s.blocks().into_iter().flatten().any(breaks_out),
    }
}

/// Declarations of `names` of type `ty`, eight to a line.
fn declare(out: &mut String, kind: &str, ty: &str, prefix: &str, ids: &[String]) {
    for chunk in ids.chunks(8) {
        let list: Vec<String> = chunk.iter().map(|i| format!("{prefix}{i}")).collect();
        let _ = writeln!(out, "    {kind} {ty} {};", list.join(", "));
    }
}

fn numbered(n: usize) -> Vec<String> {
    (0..n).map(|i| i.to_string()).collect()
}

/// The class of function `id` of `p`.
pub fn class(p: &Program, id: FuncId, names: &[Names]) -> Result<FunctionClass, EmitError> {
    let f = p.function(id);
    let me = &names[usize::from(id)];
    let mut e = Emitter {
        f,
        names,
        plan: plan(f),
        out: String::new(),
        indent: 1,
        loops: Vec::new(),
        counters: 0,
        consts: BTreeSet::new(),
        uses_uniforms: false,
        tuning: None,
    };
    for (k, s) in e.plan.copied_params.clone() {
        e.line(&format!("do r{s}.copy(p{k});"));
    }
    e.statements(&f.body)?;
    for (j, &r) in f.results.iter().enumerate() {
        let v = e.r(r);
        e.line(&format!("do o{j}.copy({v});"));
    }
    let ret = match f.tag_results.as_slice() {
        [] => "void",
        [_] => "int",
        _ => return Err(e.unsupported("more than one tag result")),
    };
    match f.tag_results.first() {
        Some(&t) => {
            let t = e.t(t);
            e.line(&format!("return {t};"));
        }
        None => e.line("return;"),
    }
    let body = std::mem::take(&mut e.out);
    let uniforms = if e.uses_uniforms {
        p.function(p.setup).results.len()
    } else {
        0
    };

    // Declarations and start-up.
    let mut text = format!(
        "/**\n * {}\n * (the IR function `{}`, generated by scene-jack).\n */\nclass {} {{\n",
        role(p, id),
        f.name,
        me.class
    );
    let consts: Vec<String> = e.consts.iter().map(u16::to_string).collect();
    declare(&mut text, "static", "Float316", "k", &consts);
    declare(&mut text, "static", "Float316", "u", &numbered(uniforms));
    declare(
        &mut text,
        "static",
        "Float316",
        "r",
        &numbered(e.plan.scalar_slots),
    );
    declare(
        &mut text,
        "static",
        "boolean",
        "b",
        &numbered(e.plan.bool_slots),
    );
    declare(&mut text, "static", "int", "t", &numbered(e.plan.tag_slots));

    let _ = writeln!(
        text,
        "\n    /** Make the constants and registers; call once, after Float316.init and Ops.init. */\n    function void init() {{"
    );
    for &i in &e.consts {
        let c = &p.consts[usize::from(i)];
        let v = literal(c.value, &c.origin)?;
        let _ = writeln!(
            text,
            "        let k{i} = Float316.new({}, {}, {}); // {} = {}",
            v.s, v.e, v.m, c.origin, c.value
        );
    }
    for j in 0..uniforms {
        let _ = writeln!(text, "        let u{j} = Float316.new(0, 0, 0);");
    }
    for s in 0..e.plan.scalar_slots {
        let _ = writeln!(text, "        let r{s} = Float316.new(0, 0, 0);");
    }
    if uniforms > 0 {
        let setup = &names[usize::from(p.setup)];
        let outs: Vec<String> = (0..uniforms).map(|j| format!("u{j}")).collect();
        let _ = writeln!(
            text,
            "        do {}.{}({});",
            setup.class,
            setup.function,
            outs.join(", ")
        );
    }
    text.push_str("        return;\n    }\n\n");

    // The function.
    let mut params: Vec<String> = (0..f.params.len())
        .map(|k| format!("Float316 p{k}"))
        .collect();
    params.extend((0..f.results.len()).map(|j| format!("Float316 o{j}")));
    let _ = writeln!(
        text,
        "    /** The IR function `{}`: {} parameter(s) p, {} result(s) written into o{}. */",
        f.name,
        f.params.len(),
        f.results.len(),
        if ret == "int" {
            "; returns its tag"
        } else {
            ""
        }
    );
    let _ = writeln!(
        text,
        "    function {ret} {}({}) {{",
        me.function,
        params.join(", ")
    );
    if e.counters > 0 {
        let _ = writeln!(
            text,
            "        var int {};",
            (0..e.counters)
                .map(|i| format!("i{i}"))
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    for l in body.lines() {
        let _ = writeln!(text, "    {l}");
    }
    text.push_str("    }\n}\n");
    Ok(FunctionClass { text })
}
