//! Reading another solver's answer exactly: the SOLUTION of `sticky compare`
//! (docs/guide/json.md).
//!
//! Two formats, told apart by the first character that is not white space:
//!
//! * **JSON** (`{` or `[`): the `sticky run --json` shape, one object per
//!   line or one array of objects. Per object `t` and `positions` are
//!   required; `velocities`, `multipliers` (`λ_1 … λ_{N−1}`), `clusters`
//!   (`[[first, size], …]`, the solver's own contact clusters) and `n` are
//!   optional; other keys are ignored. A number is either a string holding
//!   an exact number (`"3"`, `"-7/4"`, `"0.125"`, `"1.5e-3"`), read exactly,
//!   or a JSON number, read as the double it denotes: the nearest `f64` of
//!   its decimal text (what any JSON reader of the solver's side does), then
//!   that double's exact binary value. `NaN`, `Infinity` and numbers beyond
//!   the `f64` range are refused.
//! * **CSV** (anything else): rows `t,i,position[,velocity]`, `i` 0-based, an
//!   optional header row (first field not a number), every value read
//!   exactly as the text it is (a CSV has no doubles: `0.1` is `1/10`). The
//!   rows of one time need not be contiguous; each `i` in `0..N` must appear
//!   once per time.
//!
//! Every error names the line: [`SolutionError`] prints as
//! `LINE: message`, and the command prefixes the file name.
//!
//! The JSON reader is this module's own, small and exact: it never turns a
//! number into anything but the rational it denotes.

mod json;

use std::fmt;

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, Zero};

use crate::rational::parse_exact;
use crate::scalar::Scalar;

/// One time of a solution, exact.
#[derive(Debug, Clone, PartialEq)]
pub struct Frame {
    /// The line where this time's object (or first CSV row) starts, 1-based.
    pub line: usize,
    /// The time `t ≥ 0`.
    pub t: BigRational,
    /// Positions `x_1 … x_N`.
    pub positions: Vec<BigRational>,
    /// Velocities, if given.
    pub velocities: Option<Vec<BigRational>>,
    /// `λ_1 … λ_{N−1}`, if given.
    pub multipliers: Option<Vec<BigRational>>,
    /// The solver's contact set from its `clusters` (`contacts[j]` for the
    /// pair `(j, j + 1)`), if given.
    pub contacts: Option<Vec<bool>>,
}

impl Frame {
    /// A frame not read from a file (`line` 0): positions at time `t`, no
    /// velocities, multipliers or clusters (set the public fields to add
    /// them).
    pub fn new(t: BigRational, positions: Vec<BigRational>) -> Frame {
        Frame {
            line: 0,
            t,
            positions,
            velocities: None,
            multipliers: None,
            contacts: None,
        }
    }

    /// This time of the solution as what [`compare`] scores against the
    /// exact state.
    ///
    /// [`compare`]: crate::reference::measure::compare
    pub fn candidate(&self) -> crate::reference::measure::Candidate<'_> {
        crate::reference::measure::Candidate {
            positions: &self.positions,
            velocities: self.velocities.as_deref(),
            multipliers: self.multipliers.as_deref(),
            contacts: self.contacts.as_deref(),
        }
    }
}

/// A bad solution: the 1-based line and what is wrong there.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SolutionError {
    /// 1-based line number.
    pub line: usize,
    /// The message.
    pub message: String,
}

impl fmt::Display for SolutionError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.line, self.message)
    }
}

impl std::error::Error for SolutionError {}

fn err<T>(line: usize, message: impl Into<String>) -> Result<T, SolutionError> {
    Err(SolutionError {
        line,
        message: message.into(),
    })
}

/// Reads a solution for a scene of `n` particles. Every frame has exactly
/// `n` positions (and velocities), `n − 1` multipliers, clusters that
/// partition `0..n`, a time `t ≥ 0`, and no two frames share a time.
pub fn parse(text: &str, n: usize) -> Result<Vec<Frame>, SolutionError> {
    let first = text.trim_start().chars().next();
    let frames = match first {
        None => return err(1, "empty solution: no time in it"),
        Some('{') | Some('[') => json::parse_json(text, n)?,
        Some(_) => parse_csv(text, n)?,
    };
    if frames.is_empty() {
        return err(1, "empty solution: no time in it");
    }
    for (k, f) in frames.iter().enumerate() {
        if let Some(g) = frames[..k].iter().find(|g| g.t == f.t) {
            return err(
                f.line,
                format!("time t = {} already given at line {}", f.t.render(), g.line),
            );
        }
    }
    Ok(frames)
}
fn cut(s: &str) -> String {
    if s.chars().count() > 40 {
        format!("{}…", s.chars().take(40).collect::<String>())
    } else {
        s.to_string()
    }
}

// ----------------------------------------------------------------- CSV ----

fn parse_csv(text: &str, n: usize) -> Result<Vec<Frame>, SolutionError> {
    struct Partial {
        line: usize,
        t: BigRational,
        x: Vec<Option<BigRational>>,
        u: Vec<Option<BigRational>>,
        has_u: Option<bool>,
    }
    let mut frames: Vec<Partial> = Vec::new();
    let mut header_allowed = true;
    for (k, raw) in text.lines().enumerate() {
        let line = k + 1;
        let row = raw.trim();
        if row.is_empty() || row.starts_with('#') {
            continue;
        }
        let cols: Vec<&str> = row.split(',').map(str::trim).collect();
        if header_allowed {
            header_allowed = false;
            if parse_exact(cols[0]).is_err() && cols[0].chars().any(|c| c.is_alphabetic()) {
                let names: Vec<String> = cols.iter().map(|c| c.to_lowercase()).collect();
                let ok = names.len() >= 3
                    && names.len() <= 4
                    && names[0] == "t"
                    && names[1] == "i"
                    && names[2] == "position"
                    && (names.len() == 3 || names[3] == "velocity");
                if !ok {
                    return err(
                        line,
                        format!("CSV header {row:?}: expected t,i,position[,velocity]"),
                    );
                }
                continue;
            }
        }
        if cols.len() != 3 && cols.len() != 4 {
            return err(
                line,
                format!(
                    "{} columns, expected 3 or 4 (t,i,position[,velocity])",
                    cols.len()
                ),
            );
        }
        let num = |s: &str, what: &str| {
            parse_exact(s).map_err(|e| SolutionError {
                line,
                message: format!("{what}: {:?} is not an exact number ({e})", cut(s)),
            })
        };
        let t = num(cols[0], "t")?;
        if t.is_negative() {
            return err(line, format!("t = {} is negative", t.render()));
        }
        let i: usize = match cols[1].parse() {
            Ok(i) if i < n => i,
            _ => {
                return err(
                    line,
                    format!(
                        "i = {:?}: expected a particle index in 0..{n} (0-based, N = {n})",
                        cut(cols[1])
                    ),
                )
            }
        };
        let x = num(cols[2], &format!("position of i = {i}"))?;
        let u = match cols.get(3) {
            Some(s) => Some(num(s, &format!("velocity of i = {i}"))?),
            None => None,
        };
        let fi = match frames.iter().position(|f| f.t == t) {
            Some(fi) => fi,
            None => {
                frames.push(Partial {
                    line,
                    t,
                    x: vec![None; n],
                    u: vec![None; n],
                    has_u: None,
                });
                frames.len() - 1
            }
        };
        let f = &mut frames[fi];
        if f.x[i].is_some() {
            return err(
                line,
                format!("particle i = {i} at t = {} given twice", f.t.render()),
            );
        }
        match f.has_u {
            Some(h) if h != u.is_some() => {
                return err(
                    line,
                    "some rows of this time give a velocity and others do not",
                )
            }
            _ => f.has_u = Some(u.is_some()),
        }
        f.x[i] = Some(x);
        f.u[i] = u;
    }
    frames
        .into_iter()
        .map(|f| {
            if let Some(i) = f.x.iter().position(Option::is_none) {
                return err(
                    f.line,
                    format!(
                        "t = {}: no row for particle i = {i} (the scene has N = {n})",
                        f.t.render()
                    ),
                );
            }
            let positions: Vec<BigRational> = f.x.into_iter().flatten().collect();
            let velocities = (f.has_u == Some(true)).then(|| f.u.into_iter().flatten().collect());
            Ok(Frame {
                line: f.line,
                t: f.t,
                positions,
                velocities,
                multipliers: None,
                contacts: None,
            })
        })
        .collect()
}

/// `√q` as a decimal with `digits` significant digits, truncated (the exact
/// value lies in `[shown, shown + 1 ulp of the last digit)`), or the exact
/// root when `q` is the square of a rational. For reports of `L²` errors,
/// whose squares are what is exact.
pub fn sqrt_text(q: &BigRational, digits: u32) -> String {
    if q.is_negative() {
        return "NaN".into();
    }
    if Zero::is_zero(q) {
        return "0".into();
    }
    let (a, b) = (q.numer(), q.denom());
    let (ra, rb) = (a.sqrt(), b.sqrt());
    if &ra * &ra == *a && &rb * &rb == *b {
        return BigRational::new(ra, rb).render();
    }
    format!("≈{}", decimal(q, digits, Shown::SquareRoot))
}

/// What [`decimal`] prints of its rational: the number, or the root of a
/// squared figure (an `L²` norm kept squared to stay rational).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Shown {
    /// `q` itself.
    Itself,
    /// `√q` (`q ≥ 0`).
    SquareRoot,
}

/// `q` (or `√q` for [`Shown::SquareRoot`]) in scientific notation with
/// `digits` significant digits, truncated toward zero; integer arithmetic
/// only.
pub fn decimal(q: &BigRational, digits: u32, shown: Shown) -> String {
    if Zero::is_zero(q) {
        return "0".into();
    }
    let neg = q.is_negative();
    let q = q.abs();
    let sqrt = shown == Shown::SquareRoot;
    let ten = BigInt::from(10u32);
    // Find e with 10^e ≤ v < 10^(e+1), v = q or √q, then m = ⌊v·10^(d−1−e)⌋.
    let value_scaled = |k: i64| -> BigInt {
        // ⌊v · 10^k⌋
        let (n, d) = (q.numer().clone(), q.denom().clone());
        let kk = if sqrt { 2 * k } else { k };
        let (n, d) = if kk >= 0 {
            (n * num_traits::pow(ten.clone(), kk as usize), d)
        } else {
            (n, d * num_traits::pow(ten.clone(), (-kk) as usize))
        };
        let f = n / d;
        if sqrt {
            f.sqrt()
        } else {
            f
        }
    };
    // Estimate the exponent from the bit lengths, then correct.
    let bits = q.numer().bits() as i64 - q.denom().bits() as i64;
    let mut e = bits * 30_103 / 100_000; // log10(2) ≈ 0.30103: an estimate only
    if sqrt {
        e /= 2;
    }
    let d = i64::from(digits.max(1));
    let lo = num_traits::pow(ten.clone(), (d - 1) as usize);
    let hi = &lo * &ten;
    let mut m = value_scaled(d - 1 - e);
    for _ in 0..64 {
        if m >= hi {
            e += 1;
        } else if m < lo {
            e -= 1;
        } else {
            break;
        }
        m = value_scaled(d - 1 - e);
    }
    let s = m.to_string();
    let (head, tail) = s.split_at(1);
    let tail = tail.trim_end_matches('0');
    let mantissa = if tail.is_empty() {
        head.to_string()
    } else {
        format!("{head}.{tail}")
    };
    format!("{}{mantissa}e{e}", if neg { "-" } else { "" })
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::rational::ratio as q;

    #[test]
    fn json_numbers_are_the_doubles_they_denote() {
        let f = parse(r#"{"t": 0.1, "positions": ["1/3", 0.5]}"#, 2).unwrap();
        assert_eq!(f[0].t, 0.1f64.to_big_rational().unwrap());
        assert_ne!(f[0].t, q(1, 10));
        assert_eq!(f[0].positions, vec![q(1, 3), q(1, 2)]);
    }

    #[test]
    fn array_and_lines_agree() {
        let a = parse(
            "[{\"t\": \"1\", \"positions\": [\"0\"]},\n {\"t\": \"2\", \"positions\": [\"1\"]}]",
            1,
        )
        .unwrap();
        let b = parse(
            "{\"t\": \"1\", \"positions\": [\"0\"]}\n{\"t\": \"2\", \"positions\": [\"1\"]}\n",
            1,
        )
        .unwrap();
        assert_eq!(a, b);
        assert_eq!(b[1].line, 2);
    }

    #[test]
    fn decimals_are_truncated_not_rounded() {
        assert_eq!(decimal(&q(2, 3), 3, Shown::Itself), "6.66e-1");
        assert_eq!(decimal(&q(-12345, 1), 2, Shown::Itself), "-1.2e4");
        assert_eq!(decimal(&q(1, 1000), 3, Shown::Itself), "1e-3");
        assert_eq!(sqrt_text(&q(2, 1), 4), "≈1.414e0");
        assert_eq!(sqrt_text(&q(9, 4), 4), "3/2");
    }

    #[test]
    fn csv_rows_in_any_order() {
        let f = parse("t,i,position,velocity\n1,1,2,0\n1,0,0.5,1\n", 2).unwrap();
        assert_eq!(f[0].positions, vec![q(1, 2), q(2, 1)]);
        assert_eq!(f[0].velocities, Some(vec![q(1, 1), q(0, 1)]));
    }
}
