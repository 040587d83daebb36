//! `sticky export`: a scene's data as another solver reads it.
//!
//! A peer solver works in `f64`. Each value `v` of the scene (the radius,
//! every position and velocity) is given as its nearest double `f` (round to
//! nearest, ties to even) together with the exact rounding error
//! `v − f` (so `f + error = v` exactly) and the exact value as a string:
//!
//! * **JSON**: one object
//!   `{"name", "n", "t_end", "radius": {"exact", "f64", "error"},
//!   "positions": {"exact": [...], "f64": [...], "error": [...]},
//!   "velocities": {...}, "f64_admissible": bool, "f64_min_gap_minus_2r"}`;
//!   doubles are JSON numbers written with the shortest decimal that reads
//!   back as the same double, exact values and errors are strings.
//!   `f64_admissible` says whether the doubles themselves satisfy
//!   `x_{i+1} − x_i ≥ 2r` exactly (rounding can break it by less than one
//!   ulp), with the exact worst margin.
//! * **CSV**: a comment line `# n=… radius=… radius_f64=… radius_error=…`,
//!   then `i,position,velocity,position_exact,velocity_exact,position_error,velocity_error`
//!   (`i` 0-based).
//! * **NPY**: the (N, 2) little-endian `f64` array of positions and
//!   velocities (NumPy format 1.0, `'<f8'`, C order) — the radius is not in
//!   it (it stays in the scene).

use num_bigint::BigInt;
use num_rational::BigRational;
#[cfg(feature = "json")]
use num_traits::Signed;

#[cfg(feature = "json")]
use crate::json::Rational;
use crate::rational::render_exact;
use crate::scalar::Scalar;
use crate::scene::Scene;

pub use crate::rational::nearest_f64;

/// A value of the scene as the peer gets it.
#[derive(Debug, Clone, PartialEq)]
pub struct Rounded {
    /// The exact value.
    pub exact: BigRational,
    /// Its nearest double.
    pub f64: f64,
    /// `exact − f64`, exact.
    pub error: BigRational,
}

/// Why a scene cannot be exported.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ExportError {
    /// The message (names the value).
    pub message: String,
}

impl std::fmt::Display for ExportError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for ExportError {}

/// Rounds one value (`what` names it in the error).
pub fn round(q: &BigRational, what: &str) -> Result<Rounded, ExportError> {
    let f = nearest_f64(q).ok_or_else(|| ExportError {
        message: format!("{what} = {} is beyond the range of a double", q.render()),
    })?;
    let fq = f.to_big_rational().ok_or_else(|| ExportError {
        message: format!("{what}: not finite"),
    })?;
    Ok(Rounded {
        exact: q.clone(),
        f64: f,
        error: q - fq,
    })
}

/// The scene's values rounded: radius, positions, velocities.
#[derive(Debug, Clone, PartialEq)]
pub struct Exported {
    /// The radius.
    pub radius: Rounded,
    /// Positions.
    pub positions: Vec<Rounded>,
    /// Velocities.
    pub velocities: Vec<Rounded>,
    /// `min_i (f(x_{i+1}) − f(x_i)) − 2 f(r)`, exact, over the doubles
    /// (`None` when `N = 1`): negative means the rounded data overlap.
    pub f64_min_gap_minus_2r: Option<BigRational>,
}

/// Rounds every value of `scene`.
pub fn export(scene: &Scene) -> Result<Exported, ExportError> {
    let d = &scene.data;
    let radius = round(d.radius(), "radius")?;
    let positions = d
        .positions()
        .iter()
        .enumerate()
        .map(|(i, x)| round(x, &format!("positions[{i}]")))
        .collect::<Result<Vec<_>, _>>()?;
    let velocities = d
        .velocities()
        .iter()
        .enumerate()
        .map(|(i, x)| round(x, &format!("velocities[{i}]")))
        .collect::<Result<Vec<_>, _>>()?;
    let two_r = (&radius.exact - &radius.error) * BigRational::from_integer(BigInt::from(2));
    let f64_min_gap_minus_2r = positions
        .windows(2)
        .map(|w| (&w[1].exact - &w[1].error) - (&w[0].exact - &w[0].error) - &two_r)
        .min();
    Ok(Exported {
        radius,
        positions,
        velocities,
        f64_min_gap_minus_2r,
    })
}

/// Shortest decimal that reads back as `f` (Rust's `{:e}` is the shortest
/// round-trip form), valid JSON.
fn double_text(f: f64) -> String {
    format!("{f:e}")
}

/// `sticky export --format json`: the scene as a floating-point solver
/// reads it.
#[cfg(feature = "json")]
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
#[cfg_attr(test, derive(schemars::JsonSchema))]
#[cfg_attr(test, schemars(rename = "Export"))]
pub struct ExportJson {
    /// The scene's name (`null` when absent).
    pub name: Option<String>,
    /// N.
    pub n: usize,
    /// The scene's end time (`null` when absent).
    pub t_end: Option<Rational>,
    /// `r`.
    pub radius: RoundedJson,
    /// `x⁰`, index `i` from 0 in each array.
    pub positions: ColumnJson,
    /// `u⁰`, index `i` from 0 in each array.
    pub velocities: ColumnJson,
    /// Whether the doubles themselves satisfy `x_{i+1} − x_i ≥ 2r` (with
    /// `2r` from `radius.f64`), exactly.
    pub f64_admissible: bool,
    /// The smallest `x_{i+1} − x_i − 2r` of the doubles, exact (`null` for
    /// N = 1).
    pub f64_min_gap_minus_2r: Option<Rational>,
}

/// One value: exact, its nearest double, the rounding error.
#[cfg(feature = "json")]
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
#[cfg_attr(test, derive(schemars::JsonSchema))]
#[cfg_attr(test, schemars(rename = "Rounded"))]
pub struct RoundedJson {
    /// The exact value.
    pub exact: Rational,
    /// Its nearest double (ties to even), written with the shortest decimal
    /// that reads back as it.
    pub f64: f64,
    /// `exact − f64`, exact: `f64 + error = exact`.
    pub error: Rational,
}

/// N values, as [`RoundedJson`] column by column.
#[cfg(feature = "json")]
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
#[cfg_attr(test, derive(schemars::JsonSchema))]
#[cfg_attr(test, schemars(rename = "RoundedColumn"))]
pub struct ColumnJson {
    /// The exact values.
    pub exact: Vec<Rational>,
    /// Their nearest doubles.
    pub f64: Vec<f64>,
    /// `exact − f64`, exact.
    pub error: Vec<Rational>,
}

#[cfg(feature = "json")]
impl ExportJson {
    /// The contract object of `scene`'s export `e`.
    pub fn of(scene: &Scene, e: &Exported) -> ExportJson {
        let exact = |q: &BigRational| Rational(render_exact(q));
        let column = |v: &[Rounded]| ColumnJson {
            exact: v.iter().map(|r| exact(&r.exact)).collect(),
            f64: v.iter().map(|r| r.f64).collect(),
            error: v.iter().map(|r| exact(&r.error)).collect(),
        };
        ExportJson {
            name: scene.name.clone(),
            n: scene.n(),
            t_end: scene.t_end.as_ref().map(exact),
            radius: RoundedJson {
                exact: exact(&e.radius.exact),
                f64: e.radius.f64,
                error: exact(&e.radius.error),
            },
            positions: column(&e.positions),
            velocities: column(&e.velocities),
            f64_admissible: e
                .f64_min_gap_minus_2r
                .as_ref()
                .is_none_or(|g| !g.is_negative()),
            f64_min_gap_minus_2r: e.f64_min_gap_minus_2r.as_ref().map(exact),
        }
    }
}

/// The JSON export (one line).
#[cfg(feature = "json")]
pub fn json(scene: &Scene, e: &Exported) -> String {
    crate::json::to_string(&ExportJson::of(scene, e))
}

/// The CSV export.
pub fn csv(scene: &Scene, e: &Exported) -> String {
    let mut s = format!(
        "# n={} radius={} radius_f64={} radius_error={}\n",
        scene.n(),
        render_exact(&e.radius.exact),
        double_text(e.radius.f64),
        render_exact(&e.radius.error)
    );
    s.push_str("i,position,velocity,position_exact,velocity_exact,position_error,velocity_error\n");
    for (i, (x, u)) in e.positions.iter().zip(&e.velocities).enumerate() {
        s.push_str(&format!(
            "{i},{},{},{},{},{},{}\n",
            double_text(x.f64),
            double_text(u.f64),
            render_exact(&x.exact),
            render_exact(&u.exact),
            render_exact(&x.error),
            render_exact(&u.error)
        ));
    }
    s
}

/// The NPY export: NumPy format 1.0, `'<f8'`, shape `(N, 2)`, C order
/// ([`crate::columns::write_npy`], the file a scene's `data` field reads).
pub fn npy(e: &Exported) -> Vec<u8> {
    let rows: Vec<(f64, f64)> = e
        .positions
        .iter()
        .zip(&e.velocities)
        .map(|(x, u)| (x.f64, u.f64))
        .collect();
    crate::columns::write_npy(&rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::rational::ratio as q;

    #[test]
    fn nearest_and_its_error() {
        let r = round(&q(1, 10), "x").unwrap();
        assert_eq!(r.f64, 0.1);
        assert_eq!(&r.error + 0.1f64.to_big_rational().unwrap(), q(1, 10));
        assert!(!r.error.is_zero());
        assert_eq!(round(&q(3, 8), "x").unwrap().error, BigRational::zero());
        // A tie: 1 + 2^-53 lies halfway between 1 and 1 + 2^-52; even wins.
        let two = BigInt::from(2);
        let tie = q(1, 1) + BigRational::new(1.into(), num_traits::pow(two, 53));
        assert_eq!(nearest_f64(&tie), Some(1.0));
        assert_eq!(nearest_f64(&q(1, 3)), Some(1.0 / 3.0));
        let huge = BigRational::from_integer(num_traits::pow(BigInt::from(2), 1100));
        assert_eq!(nearest_f64(&huge), None);
    }
}
