//! Library classes cut down to what a generated program calls: the
//! hand-written Float316 class (`impls/jack/raymarcher/Float316.jack`,
//! whose subroutines are kept character for character) and `Ops`
//! (`src/jack/Ops.jack`, the IR statements that are several Float316
//! operations), with the variants of tuned call sites
//! (`src/jack/Float316Variants.jack`) added to Float316. A subroutine is kept when a kept text names it after a dot
//! or calls it on `this`; a static is kept when a kept subroutine other
//! than `init` names it, and `init` keeps the statements that make kept
//! statics (with the locals they need).

use std::collections::BTreeSet;

/// The hand-written Float316 class.
pub const FLOAT316: &str = include_str!("../../jack/raymarcher/Float316.jack");
/// Variants of Float316's subroutines for tuned call sites, appended to
/// the class by [`float316`].
pub const FLOAT316_VARIANTS: &str = include_str!("jack/Float316Variants.jack");
/// The vector and composite helpers.
pub const OPS: &str = include_str!("jack/Ops.jack");

/// The hand-written Float316 class with the variants' subroutines added
/// before its closing brace (a program keeps them only when it calls them).
pub fn float316() -> String {
    let end = FLOAT316.rfind('}').expect("the class ends with a brace");
    format!(
        "{}\n{FLOAT316_VARIANTS}{}",
        &FLOAT316[..end],
        &FLOAT316[end..]
    )
}

/// A library class split into its parts.
struct Class<'a> {
    name: &'a str,
    /// `static` declaration lines.
    statics: Vec<&'a str>,
    /// `field` declaration lines (kept as they are).
    fields: Vec<&'a str>,
    /// Each subroutine with its doc comment: (name, text).
    subs: Vec<(String, String)>,
}

/// The identifiers of `text`, comments and strings left out.
pub fn identifiers(text: &str) -> BTreeSet<&str> {
    text.lines()
        .map(|l| l.split("//").next().unwrap_or(""))
        .filter(|l| !l.trim_start().starts_with('*') && !l.trim_start().starts_with("/**"))
        .flat_map(|l| l.split(|c: char| !(c.is_alphanumeric() || c == '_')))
        .filter(|w| !w.is_empty() && !w.starts_with(|c: char| c.is_ascii_digit()))
        .collect()
}

/// The names called as `X.name(` or `name(` in `text`.
pub fn called(text: &str) -> BTreeSet<&str> {
    let mut out = BTreeSet::new();
    for l in text.lines() {
        let code = l.split("//").next().unwrap_or("");
        let t = code.trim_start();
        if t.starts_with('*') || t.starts_with("/**") {
            continue;
        }
        let bytes = code.as_bytes();
        let mut start = None;
        for (i, &b) in bytes.iter().enumerate() {
            let word = b.is_ascii_alphanumeric() || b == b'_';
            match (word, start) {
                (true, None) => start = Some(i),
                (false, Some(s)) => {
                    if b == b'(' {
                        out.insert(&code[s..i]);
                    }
                    start = None;
                }
                _ => {}
            }
        }
    }
    out
}

fn parse(text: &str) -> Class<'_> {
    let mut name = "";
    let mut statics = Vec::new();
    let mut fields = Vec::new();
    let mut subs = Vec::new();
    let mut doc = String::new();
    let mut current: Option<(String, String)> = None;
    for line in text.lines() {
        if let Some((_, body)) = current.as_mut() {
            body.push_str(line);
            body.push('\n');
            if line == "    }" {
                subs.extend(current.take());
            }
            continue;
        }
        let t = line.trim_start();
        if let Some(rest) = line.strip_prefix("class ") {
            name = rest.split_whitespace().next().unwrap_or("");
        } else if t.starts_with("static ") {
            statics.push(line);
        } else if t.starts_with("field ") {
            fields.push(line);
        } else if line.starts_with("    /**") || (!doc.is_empty() && line.starts_with("     *")) {
            doc.push_str(line);
            doc.push('\n');
        } else if ["function ", "method ", "constructor "]
            .iter()
            .any(|k| t.starts_with(k))
        {
            let sub = t
                .split('(')
                .next()
                .and_then(|h| h.split_whitespace().last())
                .unwrap_or("")
                .to_string();
            current = Some((sub, format!("{doc}{line}\n")));
            doc.clear();
        }
    }
    Class {
        name,
        statics,
        fields,
        subs,
    }
}

/// `init`'s body cut down to the statements that make `needed` statics.
fn shake_init(text: &str, needed: &BTreeSet<&str>) -> String {
    let mut lines = text.lines();
    let mut head = String::new();
    for l in lines.by_ref() {
        head.push_str(l);
        head.push('\n');
        if l.trim_end().ends_with('{') {
            break;
        }
    }
    // The body's statements: a line at the body's indent, with the lines
    // of the block it opens.
    let mut vars: Vec<&str> = Vec::new();
    let mut stmts: Vec<String> = Vec::new();
    for l in lines {
        if l == "    }" {
            break;
        }
        if l.trim_start().starts_with("var ") {
            vars.push(l);
        } else if l.starts_with("        ") && !l.starts_with("         ") && l.trim() != "}" {
            stmts.push(format!("{l}\n"));
        } else if let Some(last) = stmts.last_mut() {
            last.push_str(l);
            last.push('\n');
        }
    }
    let locals: BTreeSet<&str> = vars.iter().flat_map(|v| declared(v)).collect();
    let mut want: BTreeSet<&str> = needed.clone();
    let mut keep = vec![false; stmts.len()];
    loop {
        let before = want.len();
        for (i, s) in stmts.iter().enumerate() {
            if s.trim_start().starts_with("return") {
                keep[i] = true;
            } else if !keep[i] && identifiers(s).iter().any(|w| want.contains(w)) {
                keep[i] = true;
                want.extend(identifiers(s).intersection(&locals));
            }
        }
        if want.len() == before {
            break;
        }
    }
    let mut out = head;
    for v in vars {
        if let Some(l) = keep_names(v, &want) {
            out.push_str(&l);
        }
    }
    for (s, k) in stmts.iter().zip(keep) {
        if k {
            out.push_str(s);
        }
    }
    out.push_str("    }\n");
    out
}

/// The names a declaration line (`static T a, b; // note`) declares.
fn declared(line: &str) -> Vec<&str> {
    let code = line.split("//").next().unwrap_or("");
    let decl = code.trim().trim_end_matches(';');
    decl.splitn(3, ' ')
        .nth(2)
        .map(|names| names.split(',').map(str::trim).collect())
        .unwrap_or_default()
}

/// A declaration line (`static T a, b; // note`) with only the names in
/// `keep`, or `None` when it keeps none. The note goes when a name does.
fn keep_names(line: &str, keep: &BTreeSet<&str>) -> Option<String> {
    let (code, note) = match line.split_once("//") {
        Some((c, n)) => (c.trim_end(), Some(n)),
        None => (line.trim_end(), None),
    };
    let indent = &code[..code.len() - code.trim_start().len()];
    let decl = code.trim().trim_end_matches(';');
    let mut words = decl.splitn(3, ' ');
    let (kind, ty, names) = (words.next()?, words.next()?, words.next()?);
    let all: Vec<&str> = names.split(',').map(str::trim).collect();
    let kept: Vec<&str> = all.iter().copied().filter(|n| keep.contains(n)).collect();
    if kept.is_empty() {
        return None;
    }
    let mut l = format!("{indent}{kind} {ty} {};", kept.join(", "));
    if let (Some(n), true) = (note, kept.len() == all.len()) {
        l = format!("{l} //{n}");
    }
    Some(l + "\n")
}

/// `text`'s class with the subroutines `roots` name (and what they call),
/// under the doc comment `doc`; `None` when nothing is kept.
pub fn shake(text: &str, roots: &BTreeSet<&str>, doc: &str) -> Option<String> {
    let class = parse(text);
    let names: Vec<&str> = class.subs.iter().map(|(n, _)| n.as_str()).collect();
    let mut keep = vec![false; names.len()];
    let mut work: Vec<usize> = (0..names.len())
        .filter(|&i| roots.contains(names[i]) && names[i] != "init")
        .collect();
    while let Some(i) = work.pop() {
        if keep[i] {
            continue;
        }
        keep[i] = true;
        for w in called(&class.subs[i].1) {
            if let Some(j) = names.iter().position(|n| *n == w) {
                if !keep[j] && names[j] != "init" {
                    work.push(j);
                }
            }
        }
    }
    if !keep.contains(&true) {
        return None;
    }
    let declared: BTreeSet<&str> = class.statics.iter().flat_map(|l| declared(l)).collect();
    let used: BTreeSet<&str> = class
        .subs
        .iter()
        .zip(&keep)
        .filter(|(_, k)| **k)
        .flat_map(|((_, t), _)| identifiers(t))
        .filter(|w| declared.contains(w))
        .collect();
    let mut out = format!("{doc}class {} {{\n", class.name);
    for f in &class.fields {
        out.push_str(f);
        out.push('\n');
    }
    let statics: Vec<String> = class
        .statics
        .iter()
        .filter_map(|l| keep_names(l, &used))
        .collect();
    if !class.fields.is_empty() || !statics.is_empty() {
        if !class.fields.is_empty() && !statics.is_empty() {
            out.push('\n');
        }
        statics.iter().for_each(|l| out.push_str(l));
        out.push('\n');
    }
    let mut parts = Vec::new();
    for ((name, text), k) in class.subs.iter().zip(&keep) {
        if name == "init" && !statics.is_empty() {
            parts.push(shake_init(text, &used));
        } else if *k {
            parts.push(text.clone());
        }
    }
    out.push_str(&parts.join("\n"));
    out.push_str("}\n");
    Some(out)
}

/// Whether the class text has an `init` function.
pub fn has_init(text: &str) -> bool {
    text.contains("function void init()")
}
