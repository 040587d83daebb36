//! The files of the convergence study (`sticky converge`): the CSV tables
//! of a [`ConvergenceReport`] computed by [`crate::limit::converge()`].

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use super::io::csv_field;
use crate::error::Error;
use crate::limit::converge::{ConvergenceReport, Quantity};
use crate::scalar::Scalar;

/// Writes `contents` to `dir/name` whole ([`super::io::write_whole`]),
/// creating `dir` if needed; returns the path written.
fn write_whole(dir: &Path, name: &str, contents: &str) -> Result<PathBuf, Error> {
    let path = dir.join(name);
    let io = |e: std::io::Error| Error::Io {
        message: format!("{}: {e}", path.display()),
    };
    std::fs::create_dir_all(dir).map_err(io)?;
    super::io::write_whole(&path, contents.as_bytes()).map_err(io)?;
    Ok(path)
}

/// Writes `convergence.csv` (one row per N: every quantity with its bound
/// and exact form), `rates.csv`, `continuum.csv` (per sample time) and
/// `residuals.csv` (per test function: the continuum residuals and
/// `R_mom^N` for every N) into `dir`; returns the paths written.
pub fn write_csv(report: &ConvergenceReport, dir: &Path) -> Result<Vec<PathBuf>, Error> {
    let mut out = Vec::new();
    let mut c = String::from("n,engine,exact_comparisons,seconds,collisions");
    for q in Quantity::ALL {
        let _ = write!(c, ",{k},{k}_bound,{k}_exact", k = q.key());
    }
    c.push('\n');
    for r in &report.rows {
        let _ = write!(
            c,
            "{},{},{},{:.6},{}",
            r.n,
            r.engine.name(),
            r.exact_comparisons,
            r.seconds,
            r.collisions
        );
        for q in Quantity::ALL {
            match r.get(q) {
                Some(m) => {
                    let _ = write!(
                        c,
                        ",{:e},{:e},{}",
                        m.value,
                        m.bound,
                        csv_field(m.exact.as_deref().unwrap_or(""))
                    );
                }
                None => c.push_str(",,,"),
            }
        }
        c.push('\n');
    }
    out.push(write_whole(dir, "convergence.csv", &c)?);
    let mut r = String::from("quantity,label,points,slope_all,slope_tail,verdict\n");
    for rate in &report.rates {
        let _ = writeln!(
            r,
            "{},{},{},{},{},{}",
            rate.quantity.key(),
            csv_field(rate.quantity.label()),
            rate.points,
            rate.slope_all,
            rate.slope_tail,
            csv_field(&rate.verdict)
        );
    }
    out.push(write_whole(dir, "rates.csv", &r)?);
    let cs = &report.continuum;
    let mut t = String::from("t,plateaus,spread,tv_u,lambda_integral\n");
    for (j, time) in report.times.iter().enumerate() {
        let _ = writeln!(
            t,
            "{},{},{:e},{:e},{:e}",
            time.render(),
            cs.plateaus.get(j).copied().unwrap_or(0),
            cs.spread.get(j).copied().unwrap_or(f64::NAN),
            cs.tv_u.get(j).copied().unwrap_or(f64::NAN),
            cs.lambda_integral.get(j).copied().unwrap_or(f64::NAN)
        );
    }
    out.push(write_whole(dir, "continuum.csv", &t)?);
    let mut s = String::from("test_function,continuum_mass,continuum_mass_error,continuum_momentum,continuum_momentum_error");
    for row in &report.rows {
        let _ = write!(s, ",particles_N{}", row.n);
    }
    s.push('\n');
    for (k, name) in report.test_functions.iter().enumerate() {
        let (m, p) = cs
            .residuals
            .get(k)
            .map_or((f64::NAN, f64::NAN), |r| (r.0.value, r.1.value));
        let (me, pe) = cs
            .residuals
            .get(k)
            .map_or((f64::NAN, f64::NAN), |r| (r.0.error, r.1.error));
        let _ = write!(s, "{},{m:e},{me:e},{p:e},{pe:e}", csv_field(name));
        for v in report.particle_residuals.get(k).into_iter().flatten() {
            let _ = write!(s, ",{v:e}");
        }
        s.push('\n');
    }
    out.push(write_whole(dir, "residuals.csv", &s)?);
    Ok(out)
}
