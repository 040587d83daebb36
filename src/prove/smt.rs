//! The SMT solver, driven over SMT-LIB text through a pipe: the `z3` binary
//! (Debian package `z3`), started once per exploration as `z3 -in
//! -memory:MB -T:S`, and restarted after a query it had to abandon.
//!
//! **Budget.** Every answer is awaited with a deadline (the output is read
//! by a thread of its own): a query's own limit plus [`QUERY_GRACE`], never
//! past the end of the attempt. A query past its limit, or one that hits the
//! memory cap, kills the process and answers `unknown`; the next query
//! starts a fresh one and re-asserts the path condition. Past the attempt's
//! end the error [`OUT_OF_TIME`] ends the exploration.
//!
//! Queries are in quantifier-free nonlinear real arithmetic (products `t·u`
//! of a time and a velocity, and cross-multiplied collision times), decided
//! by z3's complete `nlsat` procedure (`check-sat-using qfnra-nlsat`). The
//! path condition is kept on z3's assertion stack, one `push` per
//! constraint, and re-synchronised lazily when the explorer backtracks.
//! `STICKY_Z3_TACTIC` replaces the tactic (for experiments: on these
//! queries `qfnra-nlsat` alone was the fastest of those tried).

use std::io::{BufRead, BufReader, Write};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc::{self, Receiver, RecvTimeoutError};
use std::time::{Duration, Instant};

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::Zero;

/// The answer to a satisfiability query.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sat {
    /// Satisfiable: the path can be taken by some real datum.
    Sat,
    /// Unsatisfiable: no real datum takes it.
    Unsat,
    /// The solver gave up (time or memory limit): neither answer is known.
    Unknown,
}

/// The limits the solver runs under (the solver's share of a proof
/// attempt's budget).
#[derive(Debug, Clone, Copy)]
pub struct SolverLimits {
    /// Milliseconds per query before the query is abandoned (`unknown`):
    /// asked of z3 (`try-for`) and enforced here (the process is killed
    /// [`QUERY_GRACE`] later and restarted for the next query).
    pub query_ms: u64,
    /// The end of the whole attempt: no answer is awaited past it.
    pub deadline: Instant,
    /// z3's memory cap in megabytes (`-memory:`); a query that reaches it
    /// answers `unknown` and the process is restarted.
    pub memory_mb: u64,
}

/// How long past a query's own time limit its answer is awaited before the
/// process is killed (z3's `try-for` is not always honoured by `nlsat`).
pub const QUERY_GRACE: Duration = Duration::from_secs(2);

/// How long a non-query command (`get-value`) may take.
const COMMAND_LIMIT: Duration = Duration::from_secs(30);

/// One running `z3 -in` process: its input and the lines of its output, read
/// by a thread of their own so that an answer can be awaited with a
/// deadline.
struct Process {
    child: Child,
    stdin: ChildStdin,
    lines: Receiver<String>,
}

impl Process {
    fn kill(mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// A solver with the names of the declared real variables, started on first
/// use and restarted after a query it had to abandon.
pub struct Solver {
    process: Option<Process>,
    /// The declared variables.
    names: Vec<String>,
    /// Constraints currently asserted, one `push` level each.
    stack: Vec<String>,
    /// The limits.
    pub limits: SolverLimits,
    /// The program that is started.
    pub program: String,
    /// How many times the process was killed (a query past its limit, the
    /// memory cap).
    pub restarts: usize,
}

/// Why the solver could not be used.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SolverError(pub String);

impl std::fmt::Display for SolverError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

/// The message of the error that ends an attempt whose deadline passed
/// while the solver was working.
pub const OUT_OF_TIME: &str = "the time budget ran out during a solver query";

/// The solver binary: `$STICKY_Z3` or `z3`.
pub fn program() -> String {
    std::env::var("STICKY_Z3").unwrap_or_else(|_| "z3".into())
}

/// `Some(version line)` when the solver binary runs.
pub fn available() -> Option<String> {
    let out = Command::new(program()).arg("--version").output().ok()?;
    out.status
        .success()
        .then(|| String::from_utf8_lossy(&out.stdout).trim().to_string())
}

/// Appends `text` to the file named by `STICKY_Z3_LOG`, when it is set: a
/// transcript of everything sent to the solver, for finding the hard query
/// of an attempt (`z3 -in < file` replays it).
fn log(text: &str) {
    if let Some(path) = std::env::var_os("STICKY_Z3_LOG") {
        if let Ok(mut f) = std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(path)
        {
            let _ = f.write_all(text.as_bytes());
        }
    }
}

/// How a wait for the solver's answer ended without one.
enum NoAnswer {
    /// The wait's limit passed (the process was killed).
    Timeout,
    /// The process or the pipe failed.
    Failed(SolverError),
}

impl Solver {
    /// Starts the solver and declares the real variables `names`.
    pub fn start(names: &[String], limits: SolverLimits) -> Result<Self, SolverError> {
        let mut solver = Solver {
            process: None,
            names: names.to_vec(),
            stack: Vec::new(),
            limits,
            program: program(),
            restarts: 0,
        };
        solver.ensure_running()?;
        Ok(solver)
    }

    /// Starts the process when none runs (first use, or after a kill): the
    /// assertion stack is then empty.
    fn ensure_running(&mut self) -> Result<(), SolverError> {
        if self.process.is_some() {
            return Ok(());
        }
        let left = self
            .limits
            .deadline
            .saturating_duration_since(Instant::now());
        if left.is_zero() {
            return Err(SolverError(OUT_OF_TIME.into()));
        }
        let program = &self.program;
        // `-T:` is a backstop in whole seconds: the process ends by itself
        // shortly after the deadline even if this side were stuck.
        let mut child = Command::new(program)
            .arg("-in")
            .arg(format!("-memory:{}", self.limits.memory_mb.max(16)))
            .arg(format!("-T:{}", left.as_secs() + 2))
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .map_err(|e| {
                SolverError(format!(
                    "cannot start the SMT solver `{program}` ({e}); install it with `apt-get install z3` (or set STICKY_Z3)"
                ))
            })?;
        let stdin = child
            .stdin
            .take()
            .ok_or_else(|| SolverError("no stdin".into()))?;
        let stdout = child
            .stdout
            .take()
            .ok_or_else(|| SolverError("no stdout".into()))?;
        let (tx, lines) = mpsc::channel();
        std::thread::spawn(move || {
            for line in BufReader::new(stdout).lines() {
                let Ok(line) = line else { break };
                if tx.send(line).is_err() {
                    break;
                }
            }
        });
        self.process = Some(Process {
            child,
            stdin,
            lines,
        });
        self.stack.clear();
        let mut decl =
            String::from("(set-option :print-success false)\n(set-option :pp.decimal false)\n");
        for n in &self.names {
            decl.push_str(&format!("(declare-const {n} Real)\n"));
        }
        self.send(&decl)
    }

    /// Kills the process (it is restarted on next use).
    fn kill(&mut self) {
        if let Some(p) = self.process.take() {
            p.kill();
            self.restarts += 1;
        }
        self.stack.clear();
    }

    fn send(&mut self, text: &str) -> Result<(), SolverError> {
        log(text);
        let Some(p) = self.process.as_mut() else {
            return Err(SolverError("the solver is not running".into()));
        };
        p.stdin
            .write_all(text.as_bytes())
            .and_then(|()| p.stdin.flush())
            .map_err(|e| SolverError(format!("solver pipe: {e}")))
    }

    /// Reads one complete s-expression (or atom) from the solver, waiting
    /// until `limit` at most (then the process is killed).
    fn read_until(&mut self, limit: Instant) -> Result<String, NoAnswer> {
        let mut out = String::new();
        let mut depth: i64 = 0;
        loop {
            let Some(p) = self.process.as_ref() else {
                return Err(NoAnswer::Failed(SolverError(
                    "the solver is not running".into(),
                )));
            };
            let wait = limit.saturating_duration_since(Instant::now());
            let line = match p.lines.recv_timeout(wait) {
                Ok(line) => line,
                Err(RecvTimeoutError::Timeout) => {
                    self.kill();
                    return Err(NoAnswer::Timeout);
                }
                Err(RecvTimeoutError::Disconnected) => {
                    self.kill();
                    return Err(NoAnswer::Failed(SolverError("the solver exited".into())));
                }
            };
            for c in line.chars() {
                match c {
                    '(' => depth += 1,
                    ')' => depth -= 1,
                    _ => {}
                }
            }
            out.push_str(&line);
            out.push('\n');
            if depth <= 0 && !out.trim().is_empty() {
                return Ok(out.trim().to_string());
            }
        }
    }

    /// The answer to a command that is not a query (`get-value`).
    fn read_sexp(&mut self) -> Result<String, SolverError> {
        let limit = (Instant::now() + COMMAND_LIMIT).min(self.limits.deadline);
        match self.read_until(limit) {
            Ok(text) if text.starts_with("(error") => Err(SolverError(format!("solver: {text}"))),
            Ok(text) => Ok(text),
            Err(NoAnswer::Timeout) => Err(SolverError(OUT_OF_TIME.into())),
            Err(NoAnswer::Failed(e)) => Err(e),
        }
    }

    /// Makes the solver's assertion stack equal to `constraints`.
    fn sync(&mut self, constraints: &[String]) -> Result<(), SolverError> {
        self.ensure_running()?;
        let common = self
            .stack
            .iter()
            .zip(constraints)
            .take_while(|(a, b)| a == b)
            .count();
        let mut text = String::new();
        let pops = self.stack.len() - common;
        if pops > 0 {
            text.push_str(&format!("(pop {pops})\n"));
            self.stack.truncate(common);
        }
        for c in &constraints[common..] {
            text.push_str(&format!("(push 1)\n(assert {c})\n"));
            self.stack.push(c.clone());
        }
        if !text.is_empty() {
            self.send(&text)?;
        }
        Ok(())
    }

    /// Asks the current stack within `ms` milliseconds (at most the
    /// query's own limit).
    fn check_now(&mut self, ms: u64) -> Result<Sat, SolverError> {
        let ms = ms.min(self.limits.query_ms);
        let cmd = match std::env::var("STICKY_Z3_TACTIC") {
            Ok(t) if !t.is_empty() && ms == self.limits.query_ms => {
                format!("(check-sat-using {t})\n")
            }
            Ok(t) if !t.is_empty() => format!("(check-sat-using (try-for {t} {ms}))\n"),
            _ => format!("(check-sat-using (try-for qfnra-nlsat {ms}))\n"),
        };
        self.send(&cmd)?;
        let own = Instant::now() + Duration::from_millis(ms) + QUERY_GRACE;
        let limit = own.min(self.limits.deadline);
        match self.read_until(limit) {
            Ok(answer) => Ok(match answer.as_str() {
                "sat" => Sat::Sat,
                "unsat" => Sat::Unsat,
                a if a.starts_with("(error") && a.contains("memory") => {
                    // The memory cap: this query is abandoned, the process
                    // restarted for the next one.
                    self.kill();
                    Sat::Unknown
                }
                a if a.starts_with("(error") => {
                    return Err(SolverError(format!("solver: {a}")));
                }
                _ => Sat::Unknown,
            }),
            Err(NoAnswer::Timeout) if Instant::now() >= self.limits.deadline => {
                Err(SolverError(OUT_OF_TIME.into()))
            }
            Err(NoAnswer::Timeout) => Ok(Sat::Unknown),
            Err(NoAnswer::Failed(e)) => Err(e),
        }
    }

    /// Is `constraints ∧ extra` satisfiable?
    pub fn check(
        &mut self,
        constraints: &[String],
        extra: Option<&str>,
    ) -> Result<Sat, SolverError> {
        self.check_within(constraints, extra, self.limits.query_ms)
    }

    /// [`Solver::check`] given `ms` milliseconds (at most the query's own
    /// limit): a short first try, `unknown` when it does not suffice.
    pub fn check_within(
        &mut self,
        constraints: &[String],
        extra: Option<&str>,
        ms: u64,
    ) -> Result<Sat, SolverError> {
        self.sync(constraints)?;
        match extra {
            None => self.check_now(ms),
            Some(e) => {
                self.send(&format!("(push 1)\n(assert {e})\n"))?;
                let r = self.check_now(ms);
                self.pop_extra();
                r
            }
        }
    }

    /// Pops the level of an extra assertion (nothing to pop when the
    /// process was killed meanwhile: its stack is gone).
    fn pop_extra(&mut self) {
        if self.process.is_some() && self.send("(pop 1)\n").is_err() {
            self.kill();
        }
    }

    /// The current model's values of `names` (after a `sat` answer), when
    /// all are rational.
    pub fn model(&mut self, names: &[String]) -> Result<Option<Vec<BigRational>>, SolverError> {
        if names.is_empty() {
            return Ok(Some(Vec::new()));
        }
        self.send(&format!("(get-value ({}))\n", names.join(" ")))?;
        let answer = self.read_sexp()?;
        let Some(Sexp::List(pairs)) = parse_sexp(&answer) else {
            return Ok(None);
        };
        let mut out = Vec::with_capacity(names.len());
        for (pair, name) in pairs.iter().zip(names) {
            match pair {
                Sexp::List(kv) if kv.len() == 2 && kv[0] == Sexp::Atom(name.clone()) => {
                    match sexp_value(&kv[1]) {
                        Some(q) => out.push(q),
                        None => return Ok(None),
                    }
                }
                _ => return Ok(None),
            }
        }
        Ok((out.len() == names.len()).then_some(out))
    }

    /// Is `constraints ∧ extra` satisfiable? With `Sat`, also the model's
    /// rational values of `names` (when they are all rational).
    pub fn check_with_model(
        &mut self,
        constraints: &[String],
        extra: &str,
        names: &[String],
    ) -> Result<(Sat, Option<Vec<BigRational>>), SolverError> {
        self.check_with_model_within(constraints, extra, names, self.limits.query_ms)
    }

    /// [`Solver::check_with_model`] given `ms` milliseconds (at most the
    /// query's own limit).
    pub fn check_with_model_within(
        &mut self,
        constraints: &[String],
        extra: &str,
        names: &[String],
        ms: u64,
    ) -> Result<(Sat, Option<Vec<BigRational>>), SolverError> {
        self.sync(constraints)?;
        self.send(&format!("(push 1)\n(assert {extra})\n"))?;
        let r = self.check_now(ms);
        let model = match r {
            Ok(Sat::Sat) => self.model(names),
            _ => Ok(None),
        };
        self.pop_extra();
        Ok((r?, model?))
    }

    /// An exact rational point satisfying `constraints` (the variables
    /// `names`, in order), or `None`. The solver's model may hold algebraic
    /// numbers; the variables are then fixed one at a time to a rational
    /// value (the model's when rational, else nearby rationals), each step
    /// re-checked, so the point returned satisfies every constraint.
    pub fn rational_model(
        &mut self,
        constraints: &[String],
        names: &[String],
    ) -> Result<Option<Vec<BigRational>>, SolverError> {
        let mut fixed: Vec<String> = constraints.to_vec();
        let mut values = Vec::with_capacity(names.len());
        for n in names {
            if self.check(&fixed, None)? != Sat::Sat {
                return Ok(None);
            }
            self.send(&format!("(get-value ({n}))\n"))?;
            let answer = self.read_sexp()?;
            let text = answer
                .trim()
                .strip_prefix("((")
                .and_then(|s| s.strip_suffix("))"))
                .and_then(|s| s.trim().strip_prefix(n.as_str()))
                .unwrap_or("")
                .trim()
                .to_string();
            let mut candidates: Vec<BigRational> = Vec::new();
            if let Some(q) = parse_value(&text) {
                candidates.push(q);
            } else {
                self.send(
                    "(set-option :pp.decimal true)\n(set-option :pp.decimal_precision 40)\n",
                )?;
                self.send(&format!("(get-value ({n}))\n"))?;
                let approx = self.read_sexp()?;
                self.send("(set-option :pp.decimal false)\n")?;
                let digits: String = approx
                    .chars()
                    .filter(|c| c.is_ascii_digit() || *c == '.' || *c == '-')
                    .collect();
                if let Some(d) = parse_decimal(&digits) {
                    for places in [1u32, 2, 3, 5, 8, 12, 20, 30] {
                        let scale = BigRational::from_integer(BigInt::from(10u32).pow(places));
                        let r = (d.clone() * &scale).round() / scale;
                        candidates.push(r);
                    }
                }
            }
            let mut chosen = None;
            for q in candidates {
                let eq = format!("(= {n} {})", super::poly::smt_rational(&q));
                if self.check(&fixed, Some(&eq))? == Sat::Sat {
                    fixed.push(eq);
                    chosen = Some(q);
                    break;
                }
            }
            match chosen {
                Some(q) => values.push(q),
                None => return Ok(None),
            }
        }
        Ok(Some(values))
    }
}

impl Drop for Solver {
    fn drop(&mut self) {
        let _ = self.send("(exit)\n");
        if let Some(p) = self.process.take() {
            p.kill();
        }
    }
}

/// An s-expression of the solver's output.
#[derive(Debug, Clone, PartialEq)]
enum Sexp {
    Atom(String),
    List(Vec<Sexp>),
}

fn parse_sexp(text: &str) -> Option<Sexp> {
    let mut tokens: Vec<String> = Vec::new();
    let mut cur = String::new();
    for c in text.chars() {
        match c {
            '(' | ')' => {
                if !cur.is_empty() {
                    tokens.push(std::mem::take(&mut cur));
                }
                tokens.push(c.to_string());
            }
            c if c.is_whitespace() => {
                if !cur.is_empty() {
                    tokens.push(std::mem::take(&mut cur));
                }
            }
            c => cur.push(c),
        }
    }
    if !cur.is_empty() {
        tokens.push(cur);
    }
    let mut pos = 0;
    let e = sexp_at(&tokens, &mut pos)?;
    (pos == tokens.len()).then_some(e)
}

fn sexp_at(tokens: &[String], pos: &mut usize) -> Option<Sexp> {
    let t = tokens.get(*pos)?;
    *pos += 1;
    match t.as_str() {
        "(" => {
            let mut items = Vec::new();
            loop {
                if tokens.get(*pos)? == ")" {
                    *pos += 1;
                    return Some(Sexp::List(items));
                }
                items.push(sexp_at(tokens, pos)?);
            }
        }
        ")" => None,
        _ => Some(Sexp::Atom(t.clone())),
    }
}

fn sexp_value(e: &Sexp) -> Option<BigRational> {
    match e {
        Sexp::Atom(a) => parse_decimal(a),
        Sexp::List(items) => match items.as_slice() {
            [Sexp::Atom(op), x] if op == "-" => sexp_value(x).map(|q| -q),
            [Sexp::Atom(op), a, b] if op == "/" => {
                let b = sexp_value(b)?;
                (!b.is_zero()).then(|| sexp_value(a).map(|a| a / b))?
            }
            _ => None,
        },
    }
}

/// Parses a model value: `2.0`, `(- 2.0)`, `(/ 3.0 4.0)`, `(- (/ 3.0 4.0))`
/// (`None` for an algebraic number, `root-obj`).
pub fn parse_value(text: &str) -> Option<BigRational> {
    let t = text.trim();
    if let Some(inner) = t.strip_prefix("(-").and_then(|s| s.strip_suffix(')')) {
        return parse_value(inner).map(|q| -q);
    }
    if let Some(inner) = t.strip_prefix("(/").and_then(|s| s.strip_suffix(')')) {
        let inner = inner.trim();
        // Split at the top-level space between the two operands.
        let mut depth = 0;
        for (i, c) in inner.char_indices() {
            match c {
                '(' => depth += 1,
                ')' => depth -= 1,
                ' ' if depth == 0 => {
                    let a = parse_value(&inner[..i])?;
                    let b = parse_value(&inner[i + 1..])?;
                    if b.is_zero() {
                        return None;
                    }
                    return Some(a / b);
                }
                _ => {}
            }
        }
        return None;
    }
    parse_decimal(t)
}

/// Parses `123`, `123.0`, `-1.25` exactly.
fn parse_decimal(t: &str) -> Option<BigRational> {
    let t = t.trim().trim_end_matches('?');
    let (neg, t) = match t.strip_prefix('-') {
        Some(rest) => (true, rest),
        None => (false, t),
    };
    let (int, frac) = t.split_once('.').unwrap_or((t, ""));
    if int.is_empty()
        || !int.bytes().all(|b| b.is_ascii_digit())
        || !frac.bytes().all(|b| b.is_ascii_digit())
    {
        return None;
    }
    let digits: BigInt = format!("{int}{frac}").parse().ok()?;
    let scale = BigInt::from(10u32).pow(u32::try_from(frac.len()).ok()?);
    let q = BigRational::new(digits, scale);
    Some(if neg { -q } else { q })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_model_values() {
        let q = |n: i64, d: i64| BigRational::new(n.into(), d.into());
        assert_eq!(parse_value("2.0"), Some(q(2, 1)));
        assert_eq!(parse_value("(- 2.0)"), Some(q(-2, 1)));
        assert_eq!(parse_value("(/ 3.0 4.0)"), Some(q(3, 4)));
        assert_eq!(parse_value("(- (/ 3.0 4.0))"), Some(q(-3, 4)));
        assert_eq!(parse_value("(root-obj (+ (^ x 2) (- 2)) 1)"), None);
        assert_eq!(parse_decimal("-1.25"), Some(q(-5, 4)));
        let e = parse_sexp("((x1 (- (/ 1.0 2.0)))\n (t 3.0))").unwrap();
        let Sexp::List(pairs) = e else { panic!() };
        let Sexp::List(kv) = &pairs[0] else { panic!() };
        assert_eq!(sexp_value(&kv[1]), Some(q(-1, 2)));
    }
}
