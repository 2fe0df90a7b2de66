//! WGSL generated from a scene's intermediate form (`scene::ir`): one WGSL
//! function per IR function, one WGSL statement per IR statement, so the
//! kernel performs the reference interpreter's operations in its order.
//! The arithmetic comes from the hand-written kernels' libraries
//! (shaders/f316.wgsl for Float316, shaders/f32.wgsl plus a few helpers for
//! f32), of which the generated text keeps only the items it refers to.

use common::F316;
use scene::ir::{
    Binary, Dither, Formulation, FuncId, Function, Logic, Program, Stmt, Tuning, Unary, VecOp,
};
use std::collections::{BTreeSet, HashMap};
use std::fmt::Write;

const F316_LIBRARY: &str = concat!(
    include_str!("shaders/f316.wgsl"),
    include_str!("shaders/scene_f316.wgsl")
);
const F32_LIBRARY: &str = concat!(
    include_str!("shaders/f32.wgsl"),
    include_str!("shaders/scene_f32.wgsl")
);

/// Input and output words per item of the generated kernels.
pub(crate) fn strides(form: Formulation) -> (usize, usize, usize, usize) {
    match form {
        // pixels: x, y -> status, value, level; sdf: p -> status, sd, col
        Formulation::Float316 => (2, 5, 9, 7),
        // pixels: x, y -> value, level; sdf: p -> sd, col
        Formulation::Ieee => (2, 2, 3, 2),
    }
}

/// The kernel source (without the prelude every kernel gets) for `p`, with
/// the entry points `pixels_main` and `sdf_main`.
pub fn generate(p: &Program) -> String {
    let t = Target(p.formulation);
    let mut code = String::new();
    for (i, f) in p.functions.iter().enumerate() {
        function(&mut code, t, p, i, f);
    }
    constants(&mut code, t, p);
    entries(&mut code, t, p);
    let library = match p.formulation {
        Formulation::Float316 => F316_LIBRARY,
        Formulation::Ieee => F32_LIBRARY,
    };
    format!("{}\n{code}", shake(library, &code))
}

/// The number type's spelling.
#[derive(Clone, Copy)]
struct Target(Formulation);

impl Target {
    fn num(self) -> &'static str {
        match self.0 {
            Formulation::Float316 => "F",
            Formulation::Ieee => "f32",
        }
    }

    fn vector(self, r: u16) -> String {
        match self.0 {
            Formulation::Float316 => format!("V(r{r}, r{}, r{})", r + 1, r + 2),
            Formulation::Ieee => format!("vec3<f32>(r{r}, r{}, r{})", r + 1, r + 2),
        }
    }

    fn literal(self, v: f64) -> String {
        match self.0 {
            Formulation::Float316 => {
                let t = F316::from_f64_truncating(v).unwrap_or(F316::ZERO);
                format!("F({}, {}, {})", t.s, t.e, t.m)
            }
            Formulation::Ieee => format!("{:?}f", v as f32),
        }
    }

    fn unary(self, op: Unary, a: &str) -> String {
        let f316 = self.0 == Formulation::Float316;
        match (op, f316) {
            (Unary::Sqrt, true) => format!("sqrt316({a})"),
            (Unary::Sqrt, false) => format!("sqrt({a})"),
            (Unary::Floor, true) => format!("floor316({a})"),
            (Unary::Floor, false) => format!("floor({a})"),
            (Unary::Mod2, true) => format!("mod2({a})"),
            (Unary::Mod2, false) => format!("mod2_f32({a})"),
            (Unary::Double, true) => format!("double316({a})"),
            (Unary::Double, false) => format!("(2.0 * {a})"),
            (Unary::Quarter, true) => format!("quarter({a})"),
            (Unary::Quarter, false) => format!("({a} * 0.25)"),
            (Unary::Neg, true) => format!("negated({a})"),
            (Unary::Neg, false) => format!("(-{a})"),
            (Unary::Abs, true) => format!("F(0, {a}.e, {a}.m)"),
            (Unary::Abs, false) => format!("abs({a})"),
            (Unary::Fract, true) => format!("sub({a}, floor316({a}))"),
            (Unary::Fract, false) => format!("({a} - floor({a}))"),
            (Unary::Clamp01, true) => format!("clamp01_316({a})"),
            (Unary::Clamp01, false) => format!("clamp01_f32({a})"),
        }
    }

    fn binary(self, op: Binary, a: &str, b: &str) -> String {
        let f316 = self.0 == Formulation::Float316;
        let gt = |x: &str, y: &str| {
            if f316 {
                format!("gt({x}, {y})")
            } else {
                format!("({x} > {y})")
            }
        };
        match (op, f316) {
            (Binary::Add, true) => format!("add({a}, {b})"),
            (Binary::Sub, true) => format!("sub({a}, {b})"),
            (Binary::Mul, true) => format!("mul({a}, {b})"),
            (Binary::Div, true) => format!("div({a}, {b})"),
            (Binary::Add, false) => format!("({a} + {b})"),
            (Binary::Sub, false) => format!("({a} - {b})"),
            (Binary::Mul, false) => format!("({a} * {b})"),
            (Binary::Div, false) => format!("({a} / {b})"),
            (Binary::Max, _) => format!("{}({b}, {a}, {})", self.select(), gt(a, b)),
            (Binary::Min, _) => format!("{}({b}, {a}, {})", self.select(), gt(b, a)),
            (Binary::Pow, false) => format!("pow({a}, {b})"),
            (Binary::Pow, true) => unreachable!("Float316 programs have no pow"),
        }
    }

    /// WGSL's `select` for this number type.
    fn select(self) -> &'static str {
        match self.0 {
            Formulation::Float316 => "select316",
            Formulation::Ieee => "select",
        }
    }

    fn vec_op(self, op: VecOp, a: &str, b: &str) -> String {
        match (op, self.0) {
            (VecOp::Add, Formulation::Float316) => format!("vadd({a}, {b})"),
            (VecOp::Sub, Formulation::Float316) => format!("vsub({a}, {b})"),
            (VecOp::Scale, Formulation::Float316) => format!("scale({a}, {b})"),
            (VecOp::Cross, Formulation::Float316) => format!("vcross({a}, {b})"),
            (VecOp::Normalize, Formulation::Float316) => format!("vnormalize({a})"),
            (VecOp::Add, Formulation::Ieee) => format!("({a} + {b})"),
            (VecOp::Sub, Formulation::Ieee) => format!("({a} - {b})"),
            (VecOp::Scale, Formulation::Ieee) => format!("({a} * {b})"),
            (VecOp::Cross, Formulation::Ieee) => format!("cross3({a}, {b})"),
            (VecOp::Normalize, Formulation::Ieee) => format!("normalize3({a})"),
        }
    }

    fn dot(self, a: &str, b: &str) -> String {
        match self.0 {
            Formulation::Float316 => format!("vdot({a}, {b})"),
            Formulation::Ieee => format!("dot3({a}, {b})"),
        }
    }

    fn length(self, a: &str) -> String {
        match self.0 {
            Formulation::Float316 => format!("vlength({a})"),
            Formulation::Ieee => format!("length3({a})"),
        }
    }

    fn sign_bit(self, a: &str) -> String {
        match self.0 {
            Formulation::Float316 => format!("({a}.s == 1)"),
            Formulation::Ieee => format!("((bitcast<u32>({a}) >> 31u) == 1u)"),
        }
    }
}

/// Writes one function's statements.
struct Emitter<'a> {
    out: &'a mut String,
    t: Target,
    p: &'a Program,
    indent: usize,
    loops: usize,
    /// The variant of the tuned call site being written, if any.
    tuning: Option<Tuning>,
}

impl Emitter<'_> {
    fn line(&mut self, s: &str) {
        for _ in 0..self.indent {
            self.out.push_str("    ");
        }
        self.out.push_str(s);
        self.out.push('\n');
    }

    fn block(&mut self, stmts: &[Stmt]) {
        self.indent += 1;
        self.statements(stmts);
        self.indent -= 1;
    }

    /// A block's statements. Where it calls one function more than once
    /// (the normal's four samples, the occlusion's five), the calls
    /// become one call in a loop (see [`Emitter::one_call_site`]).
    fn statements(&mut self, stmts: &[Stmt]) {
        match repeated_call(stmts) {
            Some((func, calls)) => self.one_call_site(stmts, func, &calls),
            None => stmts.iter().for_each(|s| self.stmt(s)),
        }
    }

    /// `stmts` with its calls of `func` (at positions `calls`) made through
    /// one call site: a loop whose iteration `j` runs the statements before
    /// call `j` (after taking call `j - 1`'s results), then the call. Every
    /// operation runs once and in the same order as written, so the
    /// results (and the first failure recorded) are the same; the kernel
    /// holds one inlined copy of `func` instead of one per call, which is
    /// what the device compiler's time grows with.
    fn one_call_site(&mut self, stmts: &[Stmt], func: FuncId, calls: &[usize]) {
        let Stmt::Call { args, .. } = &stmts[calls[0]] else {
            unreachable!("positions of calls")
        };
        let n = self.t.num();
        let i = self.loops;
        self.loops += 1;
        self.line("{");
        self.indent += 1;
        for k in 0..args.len() {
            self.line(&format!("var a{i}_{k}: {n};"));
        }
        self.line(&format!("var c{i}: R{func};"));
        self.line(&format!(
            "for (var i{i}: u32 = 0u; i{i} < {}u; i{i} = i{i} + 1u) {{",
            calls.len()
        ));
        self.indent += 1;
        self.line(&format!("switch i{i} {{"));
        let mut from = 0;
        for (j, &at) in calls.iter().enumerate() {
            self.indent += 1;
            self.line(&format!("case {j}u: {{"));
            self.indent += 1;
            if j > 0 {
                self.results(i, &stmts[calls[j - 1]]);
            }
            stmts[from..at].iter().for_each(|s| self.stmt(s));
            if let Stmt::Call { args, .. } = &stmts[at] {
                for (k, a) in args.iter().enumerate() {
                    self.line(&format!("a{i}_{k} = r{a};"));
                }
            }
            self.indent -= 1;
            self.line("}");
            self.indent -= 1;
            from = at + 1;
        }
        self.line("    default: {}");
        self.line("}");
        let params: Vec<String> = (0..args.len()).map(|k| format!("a{i}_{k}")).collect();
        self.line(&format!("c{i} = s_f{func}({});", params.join(", ")));
        self.indent -= 1;
        self.line("}");
        self.results(i, &stmts[calls[calls.len() - 1]]);
        self.indent -= 1;
        self.line("}");
        self.statements(&stmts[from..]);
    }

    /// Take the results of `call` from the loop's call value `c{i}`.
    fn results(&mut self, i: usize, call: &Stmt) {
        let Stmt::Call { results, tags, .. } = call else {
            unreachable!("a call")
        };
        let mut l = String::new();
        for (k, r) in results.iter().enumerate() {
            let _ = write!(l, "r{r} = c{i}.s{k}; ");
        }
        for (k, t) in tags.iter().enumerate() {
            let _ = write!(l, "t{t} = c{i}.t{k}; ");
        }
        self.line(l.trim_end());
    }

    /// `call` (a library call `f(...)`) as the tuned site's variant of `f`
    /// (`sqrt316_newton1(...)`, `mul_truncated(...)`,
    /// `floor316_direct(...)`); unchanged outside a tuned site, and in float
    /// programs, whose operations have no such variants.
    fn tuned(&self, call: String) -> String {
        let variant = match (self.tuning, self.t.0) {
            (Some(variant), Formulation::Float316) => variant,
            _ => return call,
        };
        match call.split_once('(') {
            Some((head, rest)) => {
                let suffix = variant.suffix().to_lowercase();
                format!("{head}_{suffix}({rest}")
            }
            None => call,
        }
    }

    fn stmt(&mut self, s: &Stmt) {
        let t = self.t;
        let r = |r: &u16| format!("r{r}");
        match s {
            Stmt::Const { dst, index } => self.line(&format!("r{dst} = K{index};")),
            Stmt::Uniform { dst, index } => self.line(&format!("r{dst} = U[{index}];")),
            Stmt::Table { dst, table } => self.line(&format!("r{dst} = T{table}[PIX];")),
            Stmt::Copy { dst, src } => self.line(&format!("r{dst} = r{src};")),
            Stmt::Unary { dst, op, a } => {
                let e = self.tuned(t.unary(*op, &r(a)));
                self.line(&format!("r{dst} = {e};"))
            }
            Stmt::Binary { dst, op, a, b } => {
                let e = self.tuned(t.binary(*op, &r(a), &r(b)));
                self.line(&format!("r{dst} = {e};"))
            }
            Stmt::Vector { dst, op, a, b } => {
                let bv = if *op == VecOp::Scale {
                    r(b)
                } else {
                    t.vector(*b)
                };
                let e = self.tuned(t.vec_op(*op, &t.vector(*a), &bv));
                self.line(&format!(
                    "{{ let v = {e}; r{dst} = v.x; r{} = v.y; r{} = v.z; }}",
                    dst + 1,
                    dst + 2
                ));
            }
            Stmt::Dot { dst, a, b } => self.line(&format!(
                "r{dst} = {};",
                t.dot(&t.vector(*a), &t.vector(*b))
            )),
            Stmt::Length { dst, a } => {
                let e = self.tuned(t.length(&t.vector(*a)));
                self.line(&format!("r{dst} = {e};"))
            }
            Stmt::Gt { dst, a, b } => {
                let e = match t.0 {
                    Formulation::Float316 => format!("gt(r{a}, r{b})"),
                    Formulation::Ieee => format!("(r{a} > r{b})"),
                };
                self.line(&format!("b{dst} = {e};"));
            }
            Stmt::SignBit { dst, a } => self.line(&format!("b{dst} = {};", t.sign_bit(&r(a)))),
            Stmt::Bool { dst, value } => self.line(&format!("b{dst} = {value};")),
            Stmt::Logic { dst, op, a, b } => self.line(&match op {
                Logic::And => format!("b{dst} = b{a} && b{b};"),
                Logic::Or => format!("b{dst} = b{a} || b{b};"),
                Logic::Not => format!("b{dst} = !b{a};"),
            }),
            Stmt::Select { dst, cond, a, b } => {
                self.line(&format!("r{dst} = {}(r{b}, r{a}, b{cond});", t.select()))
            }
            Stmt::SetTag { dst, value } => self.line(&format!("t{dst} = {value}u;")),
            Stmt::TagIs { dst, tag, value } => self.line(&format!("b{dst} = t{tag} == {value}u;")),
            Stmt::SelectTag { dst, cond, a, b } => {
                self.line(&format!("t{dst} = select(t{b}, t{a}, b{cond});"))
            }
            Stmt::If {
                cond,
                then,
                otherwise,
            } => {
                self.line(&format!("if (b{cond}) {{"));
                self.block(then);
                self.line("} else {");
                self.block(otherwise);
                self.line("}");
            }
            Stmt::Switch { tag, cases } => {
                self.line(&format!("switch t{tag} {{"));
                for (i, c) in cases.iter().enumerate() {
                    self.indent += 1;
                    self.line(&format!("case {i}u: {{"));
                    self.block(c);
                    self.line("}");
                    self.indent -= 1;
                }
                self.line("    default: {}");
                self.line("}");
            }
            Stmt::Loop { count, body, .. } => {
                let i = self.loops;
                self.loops += 1;
                self.line(&format!(
                    "for (var i{i}: u32 = 0u; i{i} < {count}u; i{i} = i{i} + 1u) {{"
                ));
                self.block(body);
                self.line("}");
            }
            Stmt::Break { cond } => self.line(&format!("if (b{cond}) {{ break; }}")),
            Stmt::Frame { body, .. } => {
                self.line("{");
                self.block(body);
                self.line("}");
            }
            Stmt::Tuned { variant, body } => {
                let before = self.tuning.replace(*variant);
                self.line("{");
                self.block(body);
                self.line("}");
                self.tuning = before;
            }
            // Only engines that explain runs take another side.
            Stmt::Decide { .. } => {}
            Stmt::Call {
                func,
                args,
                results,
                tags,
            } => {
                let args: Vec<String> = args.iter().map(r).collect();
                let mut l = format!("{{ let c = s_f{func}({});", args.join(", "));
                for (i, res) in results.iter().enumerate() {
                    let _ = write!(l, " r{res} = c.s{i};");
                }
                for (i, tag) in tags.iter().enumerate() {
                    let _ = write!(l, " t{tag} = c.t{i};");
                }
                l.push_str(" }");
                self.line(&l);
                let _ = self.p;
            }
        }
    }
}

/// The first function `stmts` calls more than once at its own level, with
/// the positions of those calls, when the statements before its last call
/// hold no `break` of an enclosing loop (a loop around them would catch it).
fn repeated_call(stmts: &[Stmt]) -> Option<(FuncId, Vec<usize>)> {
    let mut seen: Vec<FuncId> = Vec::new();
    for s in stmts {
        let Stmt::Call { func, .. } = s else { continue };
        if seen.contains(func) {
            let calls: Vec<usize> = (0..stmts.len())
                .filter(|&k| matches!(&stmts[k], Stmt::Call { func: g, .. } if g == func))
                .collect();
            let last = *calls.last().expect("two calls");
            return (!stmts[..last].iter().any(breaks_out)).then_some((*func, calls));
        }
        seen.push(*func);
    }
    None
}

/// Whether `s` holds a `break` that leaves it (one not inside a loop of its own).
fn breaks_out(s: &Stmt) -> bool {
    match s {
        Stmt::Break { .. } => true,
        Stmt::Loop { .. } => false,
        _ => s.blocks().into_iter().flatten().any(breaks_out),
    }
}

fn function(out: &mut String, t: Target, p: &Program, i: usize, f: &Function) {
    let n = t.num();
    let _ = writeln!(out, "struct R{i} {{");
    for k in 0..f.results.len() {
        let _ = writeln!(out, "    s{k}: {n},");
    }
    for k in 0..f.tag_results.len() {
        let _ = writeln!(out, "    t{k}: u32,");
    }
    let _ = writeln!(out, "    pad: u32,\n}}\n");
    let params: Vec<String> = (0..f.params.len()).map(|k| format!("a{k}: {n}")).collect();
    let _ = writeln!(
        out,
        "// {}\nfn s_f{i}({}) -> R{i} {{",
        f.name,
        params.join(", ")
    );
    for r in 0..f.scalars {
        let _ = writeln!(out, "    var r{r}: {n};");
    }
    for b in 0..f.bools {
        let _ = writeln!(out, "    var b{b}: bool;");
    }
    for tg in 0..f.tags {
        let _ = writeln!(out, "    var t{tg}: u32;");
    }
    for (k, r) in f.params.iter().enumerate() {
        let _ = writeln!(out, "    r{r} = a{k};");
    }
    let mut e = Emitter {
        out,
        t,
        p,
        indent: 0,
        loops: 0,
        tuning: None,
    };
    e.block(&f.body);
    let mut fields: Vec<String> = f.results.iter().map(|r| format!("r{r}")).collect();
    fields.extend(f.tag_results.iter().map(|t| format!("t{t}")));
    fields.push("0u".into());
    let _ = writeln!(out, "    return R{i}({});\n}}\n", fields.join(", "));
}

fn constants(out: &mut String, t: Target, p: &Program) {
    let n = t.num();
    for (i, c) in p.consts.iter().enumerate() {
        let _ = writeln!(
            out,
            "const K{i}: {n} = {}; // {} = {}",
            t.literal(c.value),
            c.origin,
            c.value
        );
    }
    for (i, table) in p.tables.iter().enumerate() {
        let items: Vec<String> = table.iter().map(|&v| t.literal(v)).collect();
        let _ = writeln!(
            out,
            "var<private> T{i}: array<{n}, {}> = array<{n}, {}>({});",
            table.len(),
            table.len(),
            items.join(", ")
        );
    }
    let uniforms = p.function(p.setup).results.len().max(1);
    let _ = writeln!(out, "var<private> U: array<{n}, {uniforms}>;");
    let _ = writeln!(out, "var<private> PIX: u32;\n");
}

/// The parts of the entry points that differ between the number types.
struct EntryParts {
    /// Items before the entry points.
    helpers: &'static str,
    zero: &'static str,
    /// The pixel function's arguments from the column `x` and the row
    /// counter `n`.
    pixel_args: &'static str,
    /// The output level of the pixel function's second result `r.s1`.
    level: &'static str,
    /// The pixel entry's stores of `value` and `level` (after the status).
    store_pixel: &'static str,
    /// The SDF entry: the call's arguments and its stores of `s`.
    sdf_args: &'static str,
    store_sdf: &'static str,
}

const F316_ENTRY: EntryParts = EntryParts {
    helpers: "fn level_of(a: F) -> i32 {
    if (a.e < 127) {
        return 0;
    }
    let k = min(a.e - 127, 13);
    let v = a.m >> u32(13 - k);
    return select(v, -v, a.s == 1);
}

",
    zero: "ZERO",
    pixel_args: "from_int(i32(x)), from_int(n)",
    level: "level_of(r.s1)",
    store_pixel: "    outp[i * 5u] = bitcast<u32>(status);
    store_f(i * 5u + 1u, value);
    outp[i * 5u + 4u] = u32(level);",
    sdf_args: "let p = load_v(i * 9u);\n    let s = s_f{sdf}(p.x, p.y, p.z);",
    store_sdf: "    outp[i * 7u] = bitcast<u32>(status);
    store_f(i * 7u + 1u, s.s0);
    store_f(i * 7u + 4u, s.s1);",
};

const F32_ENTRY: EntryParts = EntryParts {
    helpers: "",
    zero: "0.0",
    pixel_args: "f32(x), f32(n)",
    level: "i32(r.s1)",
    store_pixel: "    outp[i * 2u] = bitcast<u32>(value);
    outp[i * 2u + 1u] = u32(level);",
    sdf_args: "let s = s_f{sdf}(bitcast<f32>(inp[i * 3u]), bitcast<f32>(inp[i * 3u + 1u]), bitcast<f32>(inp[i * 3u + 2u]));",
    store_sdf: "    outp[i * 2u] = bitcast<u32>(s.s0);
    outp[i * 2u + 1u] = bitcast<u32>(s.s1);",
};

fn entries(out: &mut String, t: Target, p: &Program) {
    let px = &p.pixels;
    let setup = p.function(p.setup);
    let mut load_uniforms = format!("let su = s_f{}();", p.setup);
    for k in 0..setup.results.len() {
        let _ = write!(load_uniforms, " U[{k}] = su.s{k};");
    }
    let row = match px.row_origin {
        Some(o) => format!("{o} - i32(y)"),
        None => "i32(y)".into(),
    };
    let index = match px.dither {
        Dither::None => "0u".to_string(),
        Dither::Bayer8 => "(u32(n) % 8u) * 8u + x % 8u".into(),
        Dither::Bayer4 => "(u32(n) % 4u) * 4u + x % 4u".into(),
    };
    let levels = px.levels;
    let (lo, hi) = (px.rows[0], px.rows[1]);
    let e = match t.0 {
        Formulation::Float316 => &F316_ENTRY,
        Formulation::Ieee => &F32_ENTRY,
    };
    let (pixel, sdf) = (p.pixel, p.sdf);
    let _ = write!(
        out,
        "{helpers}@compute @workgroup_size(WG)
fn pixels_main(@builtin(global_invocation_id) gid: vec3<u32>) {{
    let i = gid.x;
    if (i >= params.count) {{
        return;
    }}
    let x = inp[i * 2u];
    let y = inp[i * 2u + 1u];
    let n = {row};
    var value = {zero};
    var level = 0;
    if (n >= {lo} && n <= {hi}) {{
        PIX = {index};
        {load_uniforms}
        let r = s_f{pixel}({pixel_args});
        value = r.s0;
        level = (({level} % {levels}) + {levels}) % {levels};
    }}
{store_pixel}
}}

@compute @workgroup_size(WG)
fn sdf_main(@builtin(global_invocation_id) gid: vec3<u32>) {{
    let i = gid.x;
    if (i >= params.count) {{
        return;
    }}
    {sdf_call}
{store_sdf}
}}
",
        helpers = e.helpers,
        pixel_args = e.pixel_args,
        zero = e.zero,
        level = e.level,
        store_pixel = e.store_pixel,
        sdf_call = e.sdf_args.replace("{sdf}", &sdf.to_string()),
        store_sdf = e.store_sdf,
    );
}

/// A top-level item of a WGSL library: its name and text (with the
/// comment lines above it).
struct Item {
    name: String,
    text: String,
}

/// Split a library into its top-level items (`fn`, `const`, `struct`,
/// `var<private>`, each with the column-0 comment lines above it); entry
/// points (`@compute ...`) are dropped.
fn items(library: &str) -> Vec<Item> {
    const HEADS: [&str; 4] = ["fn ", "const ", "struct ", "var<private> "];
    let mut items = Vec::new();
    let mut pending = String::new();
    let mut current: Option<Item> = None;
    let mut after_attribute = false;
    for line in library.lines() {
        if line.starts_with('@') {
            items.extend(current.take());
            pending.clear();
            current = Some(Item {
                name: String::new(),
                text: String::new(),
            });
            after_attribute = true;
            continue;
        }
        let head = HEADS.iter().find(|k| line.starts_with(**k));
        if let (Some(k), false) = (head, after_attribute) {
            items.extend(current.take());
            let name = line[k.len()..]
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            current = Some(Item {
                name,
                text: format!("{pending}{line}\n"),
            });
            pending.clear();
            continue;
        }
        after_attribute = false;
        if line.starts_with("//") {
            pending.push_str(line);
            pending.push('\n');
        } else if let Some(c) = current.as_mut() {
            c.text.push_str(&pending);
            c.text.push_str(line);
            c.text.push('\n');
            pending.clear();
        }
    }
    items.extend(current);
    items.retain(|i| !i.name.is_empty());
    items
}

/// The identifiers in `text`, comments left out.
fn identifiers(text: &str) -> BTreeSet<&str> {
    text.lines()
        .map(|l| l.split("//").next().unwrap_or(""))
        .flat_map(|l| l.split(|c: char| !(c.is_alphanumeric() || c == '_')))
        .filter(|w| !w.is_empty())
        .collect()
}

/// The library items `code` needs, transitively, in library order.
fn shake(library: &str, code: &str) -> String {
    let items = items(library);
    let index: HashMap<&str, usize> = items
        .iter()
        .enumerate()
        .map(|(i, it)| (it.name.as_str(), i))
        .collect();
    let mut keep = vec![false; items.len()];
    let mut work: Vec<usize> = identifiers(code)
        .into_iter()
        .filter_map(|w| index.get(w).copied())
        .collect();
    while let Some(i) = work.pop() {
        if keep[i] {
            continue;
        }
        keep[i] = true;
        for w in identifiers(&items[i].text) {
            if let Some(&j) = index.get(w) {
                if !keep[j] {
                    work.push(j);
                }
            }
        }
    }
    items
        .iter()
        .zip(&keep)
        .filter(|(_, &k)| k)
        .map(|(it, _)| it.text.as_str())
        .collect::<Vec<_>>()
        .join("\n")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn program(name: &str, form: Formulation) -> Program {
        let path = format!(
            "{}/../../vectors/scenes/{name}.json",
            env!("CARGO_MANIFEST_DIR")
        );
        let c = scene::load(std::path::Path::new(&path)).unwrap();
        scene::lower(&c, form)
    }

    /// The generated text holds the operations the scene uses and no other.
    #[test]
    fn only_what_the_scene_uses() {
        let seed = generate(&program("seed", Formulation::Float316));
        for used in [
            "fn add(",
            "fn mul(",
            "fn inv_sqrt(",
            "fn floor316(",
            "fn mod2(",
            "fn quarter(",
        ] {
            assert!(seed.contains(used), "{used}");
        }
        // The hand-written seed scene and the op kernel are not carried.
        for unused in [
            "fn scene(",
            "fn march(",
            "fn apply(",
            "fn torus",
            "SPHERE_CENTRE",
        ] {
            assert!(!seed.contains(unused), "{unused}");
        }
        let rtdemo = generate(&program("rtdemo", Formulation::Float316));
        for unused in [
            "fn inv_sqrt(",
            "fn vnormalize(",
            "fn quarter(",
            "fn double316(",
        ] {
            assert!(!rtdemo.contains(unused), "{unused}");
        }
        let f32 = generate(&program("toon", Formulation::Ieee));
        assert!(f32.contains("fn normalize3(") && !f32.contains("fn scene("));
    }

    /// A tuned site calls its variant, which only a tuned program carries.
    #[test]
    fn tuned_sites_call_their_variants() {
        let tuned = generate(&program("tests/seed-tuned", Formulation::Float316));
        for used in [
            "fn sqrt316_newton1(",
            "fn vlength_newton1(",
            "fn vnormalize_newton1(",
            "= sqrt316_newton1(r",
        ] {
            assert!(tuned.contains(used), "{used}");
        }
        let seed = generate(&program("seed", Formulation::Float316));
        assert!(!seed.contains("_newton1"));
        let ops = generate(&program("tests/seed-tuned-ops", Formulation::Float316));
        for used in [
            "fn mul_truncated(",
            "fn floor316_direct(",
            "= mul_truncated(r",
            "= floor316_direct(r",
        ] {
            assert!(ops.contains(used), "{used}");
        }
        assert!(!seed.contains("_truncated(") && !seed.contains("_direct("));
    }
}
