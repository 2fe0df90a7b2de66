//! The course's VM emulator test scripts (`.tst`, spec §5.1): `load`,
//! `output-file`, `compare-to`, `output-list` with formats, `output`, `set`
//! on RAM, registers and segments, `vmstep`, `repeat`, `while`, `echo` and
//! `clear-echo`, `breakpoint` and `clear-breakpoints`; `currentFunction`
//! and `line` as output columns; a `!` terminator stops the script.
//! [`run_script`] runs one on a [`Machine`], writes the `.out` file and
//! compares each output line with the `.cmp` file as it is written, the way
//! the official tools do: the first differing line ends the script. The web
//! IDE compares lines with their spaces trimmed, the desktop compares them
//! exactly, a `*` in the compare file matching any one character
//! (`--profile` decides).

use crate::{Config, Machine, Profile, Program, Register};
use std::fmt;
use std::path::{Path, PathBuf};

/// A script that cannot be read, parsed or run (not a comparison failure).
#[derive(Debug, thiserror::Error)]
#[error("{file}:{line}:{col}: {message}")]
pub struct ScriptError {
    /// The script (or the file a command named).
    pub file: String,
    /// 1-based line.
    pub line: usize,
    /// 1-based column.
    pub col: usize,
    /// What is wrong.
    pub message: String,
}

/// The first output line that differs from the compare file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Mismatch {
    /// 1-based line of the output (and of the compare file).
    pub line: usize,
    /// The compare file's line (empty past its end).
    pub expected: String,
    /// The line the script wrote.
    pub actual: String,
}

impl fmt::Display for Mismatch {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "comparison failure at line {}:\n  expected: {}\n  actual:   {}",
            self.line, self.expected, self.actual
        )
    }
}

/// What a finished script did.
#[derive(Debug)]
pub struct ScriptReport {
    /// The output file written, if the script named one.
    pub output_file: Option<PathBuf>,
    /// The compare file, if the script named one.
    pub compare_file: Option<PathBuf>,
    /// Lines written to the output.
    pub lines: usize,
    /// The first line that differs from the compare file (the script stopped there).
    pub mismatch: Option<Mismatch>,
    /// The last `echo` text still shown (cleared by `clear-echo`).
    pub echo: Option<String>,
    /// Why the script stopped before its end without a mismatch: a
    /// breakpoint reached or a `!` terminator, in the desktop's words.
    pub stopped: Option<String>,
    /// VM steps run.
    pub steps: u64,
}

/// Most iterations of a `repeat` without a count or of a `while`: such a
/// loop also stops when the program has ended, and one that reaches this
/// many iterations first is an error (the official tools would run on for
/// ever).
const MAX_OPEN_LOOP: u64 = 100_000_000;

/// The largest `repeat` count: the desktop reads it as a Java `int`.
const MAX_REPEAT: u64 = i32::MAX as u64;

/// The deepest nesting of `repeat` and `while` blocks.
const MAX_NESTING: usize = 64;

/// Run the script at `path` under `profile`.
pub fn run_script(path: &Path, profile: Profile) -> Result<ScriptReport, ScriptError> {
    let name = path.display().to_string();
    let text = common::input::read_text(path).map_err(|e| ScriptError {
        file: name.clone(),
        line: 1,
        col: 1,
        message: format!("cannot read the script: {e}"),
    })?;
    let commands = parse(&name, &text)?;
    // `NAME.tst` run from its own folder has an empty parent: that folder.
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => Path::new(".").to_path_buf(),
    };
    let mut run = Run {
        file: name,
        dir,
        profile,
        machine: None,
        columns: Vec::new(),
        output: None,
        compare: None,
        written: Vec::new(),
        mismatch: None,
        echo: None,
        stopped: None,
        breakpoints: Vec::new(),
        last_command: None,
        script: path.file_name().map(PathBuf::from).unwrap_or_default(),
    };
    run.block(&commands)?;
    if let Some((out, line, col)) = &run.output {
        let mut text = run.written.join("\n");
        text.push('\n');
        std::fs::write(out, text)
            .map_err(|e| run.err_at(*line, *col, format!("cannot write {}: {e}", out.display())))?;
    }
    Ok(ScriptReport {
        output_file: run.output.map(|(path, _, _)| path),
        compare_file: run.compare.map(|(p, _)| p),
        lines: run.written.len(),
        mismatch: run.mismatch,
        echo: run.echo,
        stopped: run.stopped,
        steps: run.machine.as_ref().map_or(0, Machine::steps),
    })
}

/// Whether a block is the single command `vmstep`.
fn is_vmstep(body: &[Command]) -> bool {
    matches!(body, [Command { kind: Kind::Words(w), .. }] if w.len() == 1 && w[0] == "vmstep")
}

/// One parsed command, with the position of its first word.
#[derive(Debug, Clone)]
struct Command {
    line: usize,
    col: usize,
    kind: Kind,
    /// The terminator after it (`,` `;` `!`), if any.
    end: Option<char>,
}

#[derive(Debug, Clone)]
enum Kind {
    /// A simple command: its words (a quoted string is one word, unquoted).
    Words(Vec<String>),
    /// `repeat [N] { ... }`
    Repeat(Option<u64>, Vec<Command>),
    /// `while a OP b { ... }`
    While([String; 3], Vec<Command>),
}

/// A token with its position.
#[derive(Debug, Clone, PartialEq)]
enum Tok {
    Word(String),
    Quoted(String),
    /// `,` `;` `!`
    End(char),
    Open,
    Close,
}

fn tokenize(file: &str, text: &str) -> Result<Vec<(Tok, usize, usize)>, ScriptError> {
    let err = |line, col, message: &str| ScriptError {
        file: file.to_string(),
        line,
        col,
        message: message.to_string(),
    };
    let chars: Vec<char> = text.chars().collect();
    let mut toks = Vec::new();
    let (mut i, mut line, mut col) = (0, 1, 1);
    let advance = |i: &mut usize, line: &mut usize, col: &mut usize, c: char| {
        *i += 1;
        if c == '\n' {
            *line += 1;
            *col = 1;
        } else {
            *col += 1;
        }
    };
    while i < chars.len() {
        let c = chars[i];
        let (l0, c0) = (line, col);
        if c.is_whitespace() {
            advance(&mut i, &mut line, &mut col, c);
        } else if c == '/' && chars.get(i + 1) == Some(&'/') {
            while i < chars.len() && chars[i] != '\n' {
                let ch = chars[i];
                advance(&mut i, &mut line, &mut col, ch);
            }
        } else if c == '/' && chars.get(i + 1) == Some(&'*') {
            advance(&mut i, &mut line, &mut col, '/');
            advance(&mut i, &mut line, &mut col, '*');
            loop {
                if i >= chars.len() {
                    return Err(err(l0, c0, "unterminated /* comment"));
                }
                if chars[i] == '*' && chars.get(i + 1) == Some(&'/') {
                    advance(&mut i, &mut line, &mut col, '*');
                    advance(&mut i, &mut line, &mut col, '/');
                    break;
                }
                let ch = chars[i];
                advance(&mut i, &mut line, &mut col, ch);
            }
        } else if c == '"' {
            advance(&mut i, &mut line, &mut col, c);
            let mut s = String::new();
            loop {
                match chars.get(i) {
                    None | Some('\n') => return Err(err(l0, c0, "unterminated string")),
                    Some('"') => {
                        advance(&mut i, &mut line, &mut col, '"');
                        break;
                    }
                    Some(&ch) => {
                        s.push(ch);
                        advance(&mut i, &mut line, &mut col, ch);
                    }
                }
            }
            toks.push((Tok::Quoted(s), l0, c0));
        } else if matches!(c, ',' | ';' | '!' | '{' | '}') {
            advance(&mut i, &mut line, &mut col, c);
            let t = match c {
                '{' => Tok::Open,
                '}' => Tok::Close,
                end => Tok::End(end),
            };
            toks.push((t, l0, c0));
        } else {
            let mut s = String::new();
            while let Some(&ch) = chars.get(i) {
                if ch.is_whitespace() || matches!(ch, ',' | ';' | '!' | '{' | '}' | '"') {
                    break;
                }
                if ch == '/' && matches!(chars.get(i + 1), Some('/') | Some('*')) {
                    break;
                }
                s.push(ch);
                advance(&mut i, &mut line, &mut col, ch);
            }
            toks.push((Tok::Word(s), l0, c0));
        }
    }
    Ok(toks)
}

fn parse(file: &str, text: &str) -> Result<Vec<Command>, ScriptError> {
    let toks = tokenize(file, text)?;
    let mut pos = 0;
    let commands = parse_block(file, &toks, &mut pos, 0)?;
    Ok(commands)
}

/// The commands from `pos` to the end of the block `depth` blocks deep (0:
/// the script itself).
fn parse_block(
    file: &str,
    toks: &[(Tok, usize, usize)],
    pos: &mut usize,
    depth: usize,
) -> Result<Vec<Command>, ScriptError> {
    let nested = depth > 0;
    let err = |line, col, message: String| ScriptError {
        file: file.to_string(),
        line,
        col,
        message,
    };
    let mut out = Vec::new();
    loop {
        let Some((tok, line, col)) = toks.get(*pos).cloned() else {
            if nested {
                let (l, c) = toks.last().map_or((1, 1), |t| (t.1, t.2));
                return Err(err(l, c, "missing } at the end of the script".into()));
            }
            return Ok(out);
        };
        match tok {
            Tok::End(_) => *pos += 1,
            Tok::Close if nested => {
                *pos += 1;
                return Ok(out);
            }
            Tok::Close => return Err(err(line, col, "} without a matching {".into())),
            Tok::Open => return Err(err(line, col, "{ without repeat or while".into())),
            Tok::Word(_) | Tok::Quoted(_) => {
                let mut words = Vec::new();
                while let Some((t, _, _)) = toks.get(*pos) {
                    match t {
                        Tok::Word(w) | Tok::Quoted(w) => words.push(w.clone()),
                        _ => break,
                    }
                    *pos += 1;
                }
                let opens = matches!(toks.get(*pos), Some((Tok::Open, _, _)));
                if opens && depth == MAX_NESTING {
                    return Err(err(
                        line,
                        col,
                        format!("blocks nested deeper than {MAX_NESTING}"),
                    ));
                }
                let kind = match (words[0].as_str(), opens) {
                    ("repeat", true) => {
                        *pos += 1;
                        let count = match words.get(1) {
                            None => None,
                            Some(n) => Some(n.parse::<u64>().map_err(|_| {
                                err(line, col, format!("repeat count {n:?} is not a number"))
                            })?),
                        };
                        if let Some(n) = count.filter(|&n| n > MAX_REPEAT) {
                            return Err(err(
                                line,
                                col,
                                format!(
                                    "repeat count {n} is above {MAX_REPEAT}, the desktop's largest"
                                ),
                            ));
                        }
                        if words.len() > 2 {
                            return Err(err(line, col, "repeat takes at most one count".into()));
                        }
                        Kind::Repeat(count, parse_block(file, toks, pos, depth + 1)?)
                    }
                    ("while", true) => {
                        *pos += 1;
                        let cond: [String; 3] = words[1..].to_vec().try_into().map_err(|_| {
                            err(
                                line,
                                col,
                                "while needs a condition like RAM[0] <> 262".into(),
                            )
                        })?;
                        Kind::While(cond, parse_block(file, toks, pos, depth + 1)?)
                    }
                    (_, true) => {
                        return Err(err(
                            line,
                            col,
                            format!("{} does not take a {{ block", words[0]),
                        ))
                    }
                    _ => Kind::Words(words),
                };
                let end = match toks.get(*pos) {
                    Some((Tok::End(c), _, _)) if matches!(kind, Kind::Words(_)) => Some(*c),
                    _ => None,
                };
                out.push(Command {
                    line,
                    col,
                    kind,
                    end,
                });
            }
        }
    }
}

/// One `output-list` column: a variable and its `%Fa.b.c` format.
#[derive(Debug, Clone)]
struct Column {
    var: String,
    format: char,
    left: usize,
    width: usize,
    right: usize,
}

impl Column {
    fn parse(spec: &str) -> Result<Column, String> {
        let (var, fmt) = spec
            .split_once('%')
            .ok_or_else(|| format!("{spec:?}: an output-list entry is VAR%Fa.b.c"))?;
        let mut chars = fmt.chars();
        let format = chars.next().unwrap_or(' ');
        if !matches!(format, 'B' | 'D' | 'X' | 'S') {
            return Err(format!("{spec:?}: the format is one of B, D, X, S"));
        }
        let nums: Vec<usize> = chars
            .as_str()
            .split('.')
            .map(str::parse)
            .collect::<Result<_, _>>()
            .map_err(|_| format!("{spec:?}: the widths are a.b.c, three numbers"))?;
        let [left, width, right] = nums[..] else {
            return Err(format!("{spec:?}: the widths are a.b.c, three numbers"));
        };
        Ok(Column {
            var: var.to_string(),
            format,
            left,
            width,
            right,
        })
    }

    /// The header cell: the name centred (extra space on the right), or cut.
    fn header(&self) -> String {
        let total = self.left + self.width + self.right;
        let name: String = self.var.chars().take(total).collect();
        let n = name.chars().count();
        let left = (total - n) / 2;
        format!("{}{name}{}", " ".repeat(left), " ".repeat(total - n - left))
    }

    /// A text value (`currentFunction`): left-aligned, cut to the width.
    fn text_cell(&self, text: &str) -> String {
        let text: String = text.chars().take(self.width).collect();
        format!(
            "{}{text:<w$}{}",
            " ".repeat(self.left),
            " ".repeat(self.right),
            w = self.width
        )
    }

    fn cell(&self, v: i16) -> String {
        let text = match self.format {
            'D' | 'S' => v.to_string(),
            'X' => format!("{:04X}", v as u16),
            _ => format!("{:016b}", v as u16),
        };
        let n = text.chars().count();
        let text = if n > self.width {
            text.chars().skip(n - self.width).collect()
        } else if self.format == 'S' {
            format!("{text:<w$}", w = self.width)
        } else {
            format!("{text:>w$}", w = self.width)
        };
        format!("{}{text}{}", " ".repeat(self.left), " ".repeat(self.right))
    }
}

/// A script variable: where `set` writes and output reads.
enum Var {
    Ram(i32),
    Register(Register),
    /// segment base register (1..=4) or 0 for temp (base 5), plus index
    Segment {
        base: i32,
        index: i32,
    },
}

fn var(name: &str) -> Result<Var, String> {
    let reg = |r| Ok(Var::Register(r));
    match name {
        "sp" => return reg(Register::Sp),
        "local" => return reg(Register::Local),
        "argument" => return reg(Register::Argument),
        "this" => return reg(Register::This),
        "that" => return reg(Register::That),
        _ => {}
    }
    let (seg, rest) = name
        .split_once('[')
        .ok_or_else(|| format!("unknown variable {name:?}"))?;
    let index: i32 = rest
        .strip_suffix(']')
        .and_then(|i| i.parse().ok())
        .ok_or_else(|| format!("{name:?}: the index is a number in [ ]"))?;
    Ok(match seg {
        "RAM" => {
            let last = jack_os::RAM_SIZE as i32 - 1;
            if !(0..=last).contains(&index) {
                return Err(format!("{name:?}: RAM has addresses 0..{last}"));
            }
            Var::Ram(index)
        }
        "local" => Var::Segment { base: 1, index },
        "argument" => Var::Segment { base: 2, index },
        "this" => Var::Segment { base: 3, index },
        "that" => Var::Segment { base: 4, index },
        "temp" if (0..8).contains(&index) => Var::Segment { base: 0, index },
        "pointer" if (0..2).contains(&index) => Var::Ram(3 + index),
        _ => return Err(format!("unknown variable {name:?}")),
    })
}

/// The registers RAM[0..=4].
const REGISTERS: [Register; 5] = [
    Register::Sp,
    Register::Local,
    Register::Argument,
    Register::This,
    Register::That,
];

struct Run {
    file: String,
    dir: PathBuf,
    profile: Profile,
    machine: Option<Machine>,
    columns: Vec<Column>,
    /// The output file, with the line and column of its command.
    output: Option<(PathBuf, usize, usize)>,
    /// The compare file and its lines.
    compare: Option<(PathBuf, Vec<String>)>,
    written: Vec<String>,
    mismatch: Option<Mismatch>,
    echo: Option<String>,
    stopped: Option<String>,
    breakpoints: Vec<Breakpoint>,
    /// The command index, in its function, of the instruction the last
    /// `vmstep` ran (what `line` prints).
    last_command: Option<u32>,
    /// The script's own file name (an output file must not be it).
    script: PathBuf,
}

/// A `breakpoint VAR VALUE`: the script stops when VAR shows VALUE after a
/// step, once until VAR shows something else.
#[derive(Debug, Clone)]
struct Breakpoint {
    var: String,
    value: String,
    reached: bool,
}

/// Variables whose value is text.
const TEXT_VARS: [&str; 2] = ["currentFunction", "line"];

impl Run {
    fn err_at(&self, line: usize, col: usize, message: String) -> ScriptError {
        ScriptError {
            file: self.file.clone(),
            line,
            col,
            message,
        }
    }

    /// Run commands; stops early (Ok) once a line has mismatched.
    fn block(&mut self, commands: &[Command]) -> Result<(), ScriptError> {
        for c in commands {
            if self.done() {
                return Ok(());
            }
            let file = self.file.clone();
            let fail = |m: String| ScriptError {
                file: file.clone(),
                line: c.line,
                col: c.col,
                message: m,
            };
            match &c.kind {
                Kind::Words(words) => {
                    self.simple(words, c.line, c.col).map_err(fail)?;
                    // A `;` or `!` ends a step of the script: breakpoints
                    // are tested there, and `!` stops the script.
                    if matches!(c.end, Some(';' | '!')) {
                        self.test_breakpoints().map_err(fail)?;
                    }
                    if c.end == Some('!') && self.stopped.is_none() {
                        self.stopped = Some("Script reached a '!' terminator".into());
                    }
                }
                Kind::Repeat(count, body) if is_vmstep(body) && self.breakpoints.is_empty() => {
                    // `repeat N { vmstep; }`: N steps in one run, at the
                    // emulator's own speed (a run of N steps is N runs of
                    // one, step for step).
                    let n = count.unwrap_or(MAX_OPEN_LOOP);
                    if n > 0 && !self.done() {
                        self.vmsteps(n).map_err(fail)?;
                        if count.is_none() && !self.ended() {
                            return Err(fail(open_loop("repeat")));
                        }
                    }
                }
                Kind::Repeat(count, body) => {
                    let n = count.unwrap_or(MAX_OPEN_LOOP);
                    for _ in 0..n {
                        if self.done() || (count.is_none() && self.ended()) {
                            break;
                        }
                        self.block(body)?;
                    }
                    if count.is_none() && !self.done() && !self.ended() {
                        return Err(fail(open_loop("repeat")));
                    }
                }
                Kind::While(cond, body) => {
                    let mut n = 0;
                    while !self.done() && self.holds(cond).map_err(fail)? {
                        if self.ended() {
                            break;
                        }
                        if n == MAX_OPEN_LOOP {
                            return Err(fail(open_loop("while")));
                        }
                        self.block(body)?;
                        n += 1;
                    }
                }
            }
        }
        Ok(())
    }

    /// Run `n` (at least 1) steps, noting the command the last one runs
    /// (what `line` prints): a run of `n` steps is `n` runs of one.
    fn vmsteps(&mut self, n: u64) -> Result<(), String> {
        let m = self.machine()?;
        m.run(Some(n - 1));
        let last = m.next_command_index();
        m.run(Some(1));
        self.last_command = last;
        Ok(())
    }

    /// A mismatch, a breakpoint or a `!` stopped the script.
    fn done(&self) -> bool {
        self.mismatch.is_some() || self.stopped.is_some()
    }

    /// Stop at the first breakpoint whose variable now shows its value
    /// (each stops once until its variable shows something else), as the
    /// desktop's GUI does after each step of a script.
    fn test_breakpoints(&mut self) -> Result<(), String> {
        for k in 0..self.breakpoints.len() {
            let var = self.breakpoints[k].var.clone();
            let shows = self.text(&var)? == self.breakpoints[k].value;
            let b = &mut self.breakpoints[k];
            if shows && !b.reached {
                b.reached = true;
                if self.stopped.is_none() {
                    self.stopped = Some("Breakpoint reached".into());
                }
            } else if !shows {
                b.reached = false;
            }
        }
        Ok(())
    }

    /// A variable's value as the desktop prints it.
    fn text(&mut self, var: &str) -> Result<String, String> {
        let last = self.last_command;
        let m = self.machine()?;
        Ok(match var {
            "currentFunction" => m.current_function().to_string(),
            "line" => {
                let index = last.or_else(|| m.next_command_index()).unwrap_or(0);
                format!("{}.{index}", m.current_function())
            }
            _ => self.read(var)?.to_string(),
        })
    }

    fn ended(&self) -> bool {
        self.machine.as_ref().is_some_and(|m| m.exit().is_some())
    }

    fn machine(&mut self) -> Result<&mut Machine, String> {
        self.machine
            .as_mut()
            .ok_or_else(|| "no program loaded (use load first)".to_string())
    }

    /// Run the simple command `words`, written at `line` and `col`.
    fn simple(&mut self, words: &[String], line: usize, col: usize) -> Result<(), String> {
        let arg = |i: usize| words.get(i).map(String::as_str);
        let arity = |n: usize| {
            if words.len() == n + 1 {
                Ok(())
            } else {
                Err(format!("{} takes {n} argument(s)", words[0]))
            }
        };
        match words[0].as_str() {
            "load" => {
                let program = match arg(1) {
                    None => Program::load_dir(&self.dir),
                    Some(p) => {
                        let path = self.dir.join(p);
                        if path.is_dir() {
                            Program::load_dir(&path)
                        } else {
                            let text =
                                common::input::read_text(&path).map_err(|e| e.to_string())?;
                            Program::from_sources(&[(p, text)])
                        }
                    }
                }
                .and_then(|p| p.check_profile(self.profile).map(|()| p))
                .map_err(|e| e.to_string())?;
                let config = Config {
                    profile: self.profile,
                    ..Config::default()
                };
                self.machine = Some(Machine::new(program, config));
            }
            "output-file" => {
                arity(1)?;
                let name = self.output_name(&words[1])?;
                let path = self.dir.join(name);
                if self
                    .compare
                    .as_ref()
                    .is_some_and(|(c, _)| c.file_name() == Some(name) || same_file(c, &path))
                {
                    return Err(format!("output-file {name:?} is the compare file"));
                }
                self.output = Some((path, line, col));
            }
            "compare-to" => {
                arity(1)?;
                let path = self.dir.join(&words[1]);
                if self
                    .output
                    .as_ref()
                    .is_some_and(|(o, _, _)| same_file(o, &path))
                {
                    return Err(format!("compare-to {:?} is the output file", words[1]));
                }
                let text = common::input::read_text(&path).map_err(|e| e.to_string())?;
                let lines = text.lines().map(str::to_string).collect();
                self.compare = Some((path, lines));
            }
            "output-list" => {
                self.columns = words[1..]
                    .iter()
                    .map(|w| Column::parse(w))
                    .collect::<Result<_, _>>()?;
                for c in self
                    .columns
                    .iter()
                    .filter(|c| !TEXT_VARS.contains(&c.var.as_str()))
                {
                    var(&c.var)?;
                }
                let line = format!(
                    "|{}|",
                    self.columns
                        .iter()
                        .map(Column::header)
                        .collect::<Vec<_>>()
                        .join("|")
                );
                self.write(line);
            }
            "output" => {
                arity(0)?;
                let mut cells = Vec::new();
                for c in self.columns.clone() {
                    if TEXT_VARS.contains(&c.var.as_str()) {
                        let text = self.text(&c.var)?;
                        cells.push(c.text_cell(&text));
                        continue;
                    }
                    let v = self.read(&c.var)?;
                    cells.push(c.cell(v));
                }
                self.write(format!("|{}|", cells.join("|")));
            }
            "set" => {
                arity(2)?;
                let value: i32 = words[2]
                    .parse()
                    .map_err(|_| format!("{:?} is not a number", words[2]))?;
                if !(-32768..=65535).contains(&value) {
                    return Err(format!("{value} is not a 16-bit value"));
                }
                self.set(&words[1], value as i16)?;
            }
            "vmstep" => {
                arity(0)?;
                self.vmsteps(1)?;
            }
            "breakpoint" => {
                arity(2)?;
                if !TEXT_VARS.contains(&words[1].as_str()) {
                    var(&words[1])?;
                }
                let new = !self
                    .breakpoints
                    .iter()
                    .any(|b| b.var == words[1] && b.value == words[2]);
                if new {
                    self.breakpoints.push(Breakpoint {
                        var: words[1].clone(),
                        value: words[2].clone(),
                        reached: false,
                    });
                }
            }
            "clear-breakpoints" => {
                arity(0)?;
                self.breakpoints.clear();
            }
            "echo" => {
                arity(1)?;
                self.echo = Some(words[1].clone());
            }
            "clear-echo" => {
                arity(0)?;
                self.echo = None;
            }
            other => return Err(format!("unknown or unsupported command {other:?}")),
        }
        Ok(())
    }

    /// The file name an `output-file` may write: a plain name in the
    /// script's folder that is neither the script nor a program, script
    /// or compare file (`.vm`, `.tst`, `.cmp`).
    fn output_name<'a>(&self, name: &'a str) -> Result<&'a std::ffi::OsStr, String> {
        let path = Path::new(name);
        let plain = path.components().count() == 1
            && matches!(
                path.components().next(),
                Some(std::path::Component::Normal(_))
            );
        let Some(file) = path.file_name().filter(|_| plain) else {
            return Err(format!(
                "output-file {name:?} is not a file name in the script's folder"
            ));
        };
        let kept = path
            .extension()
            .is_some_and(|e| ["vm", "tst", "cmp", "jack"].iter().any(|k| e == *k));
        if kept || path == self.script {
            return Err(format!(
                "output-file {name:?} would overwrite a program, script or compare file"
            ));
        }
        Ok(file)
    }

    fn address(&mut self, v: &Var) -> Result<i32, String> {
        let m = self.machine()?;
        Ok(match *v {
            Var::Ram(a) => a,
            Var::Register(r) => r as i32,
            Var::Segment { base: 0, index } => 5 + index,
            Var::Segment { base, index } => i32::from(m.ram().read(base)) + index,
        })
    }

    fn read(&mut self, name: &str) -> Result<i16, String> {
        let v = var(name)?;
        let a = self.address(&v)?;
        Ok(self.machine()?.ram().read(a))
    }

    fn set(&mut self, name: &str, value: i16) -> Result<(), String> {
        let v = match var(name)? {
            // RAM[0..=4] are the registers: set them as such (this also
            // marks the segment initialised for the entry).
            Var::Ram(a) if a <= 4 => Var::Register(REGISTERS[a as usize]),
            other => other,
        };
        if let Var::Register(r) = v {
            self.machine()?.set_register(r, value);
            return Ok(());
        }
        let a = self.address(&v)?;
        self.machine()?.ram_mut().write(a, value);
        Ok(())
    }

    fn holds(&mut self, [a, op, b]: &[String; 3]) -> Result<bool, String> {
        let value = |run: &mut Run, s: &str| -> Result<i32, String> {
            match s.parse::<i32>() {
                Ok(n) => Ok(n),
                Err(_) => run.read(s).map(i32::from),
            }
        };
        let (x, y) = (value(self, a)?, value(self, b)?);
        Ok(match op.as_str() {
            "=" => x == y,
            "<>" => x != y,
            "<" => x < y,
            ">" => x > y,
            "<=" => x <= y,
            ">=" => x >= y,
            _ => return Err(format!("unknown comparison {op:?} (=, <>, <, >, <=, >=)")),
        })
    }

    /// Append an output line and compare it with the compare file's line.
    fn write(&mut self, line: String) {
        let n = self.written.len();
        if let Some((_, expected)) = &self.compare {
            let want = expected.get(n).cloned().unwrap_or_default();
            // The web IDE compares trimmed lines; the desktop compares
            // them as they are, so a line that differs only in spaces fails.
            let same = match self.profile {
                Profile::Web => want.trim() == line.trim(),
                Profile::Desktop => matches_template(&line, &want),
            };
            if !same {
                self.mismatch = Some(Mismatch {
                    line: n + 1,
                    expected: want,
                    actual: line.clone(),
                });
            }
        }
        self.written.push(line);
    }
}

/// The desktop's comparison of an output line with its compare line: the
/// same length, and every character the same except where the compare line
/// has a `*`, which matches any one.
fn matches_template(line: &str, template: &str) -> bool {
    line.chars().count() == template.chars().count()
        && line
            .chars()
            .zip(template.chars())
            .all(|(c, t)| t == '*' || c == t)
}

/// The error of an open loop that reached [`MAX_OPEN_LOOP`] iterations
/// with the program still running.
fn open_loop(what: &str) -> String {
    format!(
        "this {what} ran {MAX_OPEN_LOOP} times and the program has not ended: stopped (the harness's bound for a loop without a count)"
    )
}

/// Whether `a` and `b` name one file: the same path, or paths that resolve
/// to the same file (`sub/../Count.out`, a symbolic link to it), so that an
/// `output-file` never writes over the file a `compare-to` reads.
fn same_file(a: &Path, b: &Path) -> bool {
    a == b || matches!((a.canonicalize(), b.canonicalize()), (Ok(x), Ok(y)) if x == y)
}
