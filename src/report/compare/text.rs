//! The report for people: every figure exact, a decimal beside it (4
//! significant digits, correctly rounded from the exact value by
//! [`decimal`](super::decimal)), `L²` errors as the square root of their
//! exact square, overlap depths also as a fraction of `2r`, and indices
//! from 0 (`positions[3]`, `pair (1, 2)`).

use std::fmt::Write;

use num_rational::BigRational;
use num_traits::Zero;

use super::decimal::{scientific, Value};
use super::{FrameReport, Report, Verdict};
use crate::cluster::Cluster;
use crate::reference::measure::MaxError;
use crate::scalar::Scalar;

/// Significant digits of the decimals.
const DIGITS: u32 = 4;
/// Longer exact values are shown only as their decimal (`--json` has them).
const LONGEST_EXACT: usize = 48;
/// Items listed per kind and time (then `… (K in all)`).
const SHOWN: usize = 8;

/// An exact figure with its decimal: `1/1000 (1.000e-3)`; small integers
/// alone (`0`, `3`); a value too long to read as `≈1.234e-5 (exact: 812
/// characters, in --json)`.
pub fn figure(q: &BigRational) -> String {
    let exact = q.render();
    if q.is_integer() && q.numer().magnitude() < &num_bigint::BigUint::from(10_000u32) {
        return exact;
    }
    let d = scientific(Value::Rational(q), DIGITS);
    if exact.len() > LONGEST_EXACT {
        format!("≈{d} (exact: {} characters, in --json)", exact.len())
    } else {
        format!("{exact} ({d})")
    }
}

/// A root known by its exact square `s`: the exact root when `s` is the
/// square of a rational (`1/2000 (5.000e-4)`), else `√(9/30000) (1.732e-2)`.
pub fn root(s: &BigRational) -> String {
    if let Some(r) = exact_root(s) {
        return figure(&r);
    }
    let d = scientific(Value::SquareRoot(s), DIGITS);
    let exact = s.render();
    if exact.len() > LONGEST_EXACT {
        format!("≈{d} (exact square: {} characters, in --json)", exact.len())
    } else {
        format!("√({exact}) ({d})")
    }
}

/// `√s` when it is rational.
pub fn exact_root(s: &BigRational) -> Option<BigRational> {
    if s < &<BigRational as Zero>::zero() {
        return None;
    }
    let (a, b) = (s.numer(), s.denom());
    let (ra, rb) = (a.sqrt(), b.sqrt());
    (&ra * &ra == *a && &rb * &rb == *b).then(|| BigRational::new(ra, rb))
}

fn list<T>(items: &[T], f: impl Fn(&T) -> String) -> String {
    if items.is_empty() {
        return "none".into();
    }
    let mut s: Vec<String> = items.iter().take(SHOWN).map(f).collect();
    if items.len() > SHOWN {
        s.push(format!("… ({} in all)", items.len()));
    }
    s.join(", ")
}

fn cluster(k: &Cluster) -> String {
    format!("[{}, {}]", k.first, k.size)
}

/// Where one time's maximum error of a kind is, if given.
type Figure = fn(&FrameReport) -> Option<&MaxError>;

/// The worst value of a figure over the times, and its time.
fn worst<'a>(
    r: &'a Report,
    f: impl Fn(&'a FrameReport) -> Option<&'a MaxError>,
) -> Option<(&'a BigRational, &'a BigRational)> {
    r.frames
        .iter()
        .filter_map(|fr| f(fr).map(|m| (&m.value, &fr.comparison.t)))
        .fold(None, |best, (v, t)| match best {
            Some((bv, _)) if bv >= v => best,
            _ => Some((v, t)),
        })
}

/// The one-line verdict (see [`Report::summary`]).
pub fn summary(r: &Report) -> String {
    if r.verdict == Verdict::Exact {
        return format!(
            "exact: the solution equals sticky's answer at all {} time(s), and breaks no constraint",
            r.frames.len()
        );
    }
    let mut parts = Vec::new();
    let labels: [(&str, Figure); 3] = [
        ("max position error", |f| Some(&f.comparison.position_max)),
        ("max velocity error", |f| f.comparison.velocity_max.as_ref()),
        ("max λ error", |f| f.comparison.multiplier_max.as_ref()),
    ];
    for (label, get) in labels {
        if let Some((v, t)) = worst(r, get) {
            parts.push(format!("{label} {} (t = {})", figure(v), figure(t)));
        }
    }
    let sum = |f: &dyn Fn(&FrameReport) -> usize| r.frames.iter().map(f).sum::<usize>();
    let wrong = sum(&|f| f.comparison.missed_clusters.len() + f.comparison.spurious_clusters.len());
    let overlaps = sum(&|f| f.comparison.overlaps.len());
    let deep = sum(&|f| {
        f.comparison
            .overlaps
            .iter()
            .filter(|o| o.depth > f.tolerances.length)
            .count()
    });
    let neg = sum(&|f| f.comparison.negative_multipliers.len());
    let comp = sum(&|f| f.comparison.complementarity.len());
    let ole = sum(&|f| f.comparison.oleinik.as_ref().map_or(0, Vec::len));
    parts.push(format!("{wrong} wrong contact cluster(s)"));
    if overlaps > deep {
        parts.push(format!(
            "{overlaps} overlap(s), {} within the rounding bound",
            overlaps - deep
        ));
    } else {
        parts.push(format!("{overlaps} overlap(s)"));
    }
    parts.push(format!("{neg} λ < 0"));
    parts.push(format!("{comp} complementarity error(s)"));
    parts.push(format!("{ole} Oleinik violation(s)"));
    format!(
        "{} ({}): {}",
        r.verdict.name(),
        r.verdict.meaning(),
        parts.join(", ")
    )
}

/// The whole text report (see [`Report::text`]).
pub fn report(r: &Report) -> String {
    let mut out = String::new();
    // Writing to a String cannot fail.
    let _ = write_report(&mut out, r);
    out
}

fn write_report(out: &mut String, r: &Report) -> std::fmt::Result {
    let two_r = r.two_r();
    match (&r.scene, &r.solution) {
        (Some(scene), Some(sol)) => write!(out, "compare {sol} against {scene} ")?,
        _ => write!(out, "compare ")?,
    }
    writeln!(
        out,
        "(N = {}, r = {}, {} time(s)); errors exact with a 4-digit decimal, L² = ((1/N) Σ e_i²)^(1/2); indices from 0",
        r.n,
        figure(&r.radius),
        r.frames.len()
    )?;
    if !Zero::is_zero(&r.contact_tol) || !Zero::is_zero(&r.options.overlap_tol) {
        writeln!(
            out,
            "tolerances: contact when gap ≤ 2r + {}; rounding TOL = {} (overlaps and position errors ≤ TOL·2r = {}, velocity errors ≤ TOL·max|u⁰|, λ ≤ TOL·max λ(t))",
            figure(&r.contact_tol),
            figure(&r.options.overlap_tol),
            figure(&(&r.options.overlap_tol * &two_r)),
        )?;
    }
    for f in &r.frames {
        let c = &f.comparison;
        write!(out, "t = {}", figure(&c.t))?;
        if f.line > 0 {
            write!(out, "  (line {})", f.line)?;
        }
        writeln!(out)?;
        writeln!(
            out,
            "  position error   max {} at positions[{}]   L² {}",
            figure(&c.position_max.value),
            c.position_max.index,
            root(&c.position_l2_squared)
        )?;
        match (&c.velocity_max, &c.velocity_l2_squared) {
            (Some(m), Some(l2)) => writeln!(
                out,
                "  velocity error   max {} at velocities[{}]   L² {}",
                figure(&m.value),
                m.index,
                root(l2)
            )?,
            _ => writeln!(out, "  velocity error   — (no velocities given)")?,
        }
        writeln!(
            out,
            "  overlaps         {}",
            list(&c.overlaps, |o| {
                let within = if o.depth <= f.tolerances.length {
                    " (within the rounding bound)"
                } else {
                    ""
                };
                format!(
                    "pair ({}, {}) depth {} = {} × 2r{within}",
                    o.pair,
                    o.pair + 1,
                    figure(&o.depth),
                    figure(&(&o.depth / &two_r))
                )
            })
        )?;
        writeln!(
            out,
            "  contact clusters {} missed pair(s), {} spurious pair(s); exact clusters [first, size] missed: {}; solver's wrong clusters: {}",
            c.missed_contacts,
            c.spurious_contacts,
            list(&c.missed_clusters, cluster),
            list(&c.spurious_clusters, cluster)
        )?;
        match &c.multiplier_max {
            None => writeln!(out, "  multipliers      — (no multipliers given)")?,
            Some(m) => writeln!(
                out,
                "  multipliers      max error {} at pair ({}, {}); λ < 0: {}; complementarity λ·(gap − 2r) ≠ 0: {}",
                figure(&m.value),
                m.index,
                m.index + 1,
                list(&c.negative_multipliers, |p| format!(
                    "pair ({}, {}) λ = {}",
                    p.pair,
                    p.pair + 1,
                    figure(&p.value)
                )),
                list(&c.complementarity, |p| format!(
                    "pair ({}, {}) product {}",
                    p.pair,
                    p.pair + 1,
                    figure(&p.value)
                ))
            )?,
        }
        match &c.oleinik {
            None => writeln!(out, "  Oleinik          — (no velocities, or t = 0)")?,
            Some(o) => writeln!(
                out,
                "  Oleinik          (u_i − u_(i−1))/(x_i − x_(i−1)) < 1/t fails at: {}",
                list(o, |i| format!("pair ({}, {i})", i - 1))
            )?,
        }
        writeln!(out, "  this time        {}", f.verdict.name())?;
    }
    writeln!(out, "verdict: {}", summary(r))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rational::ratio as q;
    use num_bigint::BigInt;

    #[test]
    fn figures_carry_their_decimal() {
        assert_eq!(figure(&q(1, 1000)), "1/1000 (1.000e-3)");
        assert_eq!(figure(&q(-3, 1)), "-3");
        assert_eq!(figure(&q(12345, 1)), "12345 (1.234e4)");
        assert_eq!(root(&q(1, 4_000_000)), "1/2000 (5.000e-4)");
        assert_eq!(root(&q(9, 30000)), "√(3/10000) (1.732e-2)");
        let long = BigRational::new(1.into(), BigInt::from(3).pow(100u32));
        assert!(figure(&long).starts_with("≈1.940e-48 (exact: "));
    }
}
