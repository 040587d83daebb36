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

/// The exact value of the finite double `d` written as [`render_exact`]
/// writes it (`"p/q"` in lowest terms, `"p"` for an integer), read from the
/// double's bits (`m · 2^e`, the reading of [`crate::columns::f64_exact`])
/// with no [`BigRational`] built: the export of a scene given as doubles.
/// `None` for a NaN or an infinity.
pub fn double_exact_text(d: f64) -> Option<String> {
    use std::fmt::Write;
    if !d.is_finite() {
        return None;
    }
    let Some(crate::columns::OddBinary { odd: m, exp: e }) = crate::columns::odd_binary(d) else {
        return Some("0".into());
    };
    let mut out = String::with_capacity(24);
    if d < 0.0 {
        out.push('-');
    }
    // `m < 2^53`: `m · 2^e` fits 128 bits for `e ≤ 74`, `2^-e` for `-e < 128`.
    let written = match e {
        0..=74 => write!(out, "{}", u128::from(m) << e),
        75.. => write!(out, "{}", num_bigint::BigUint::from(m) << e as u64),
        -127..=-1 => write!(out, "{m}/{}", 1u128 << (-e)),
        _ => write!(
            out,
            "{m}/{}",
            num_bigint::BigUint::from(1u8) << e.unsigned_abs()
        ),
    };
    written.ok()?;
    Some(out)
}

/// Values exported between two polls of [`Progress::cancelled`].
#[cfg(feature = "json")]
const EXPORT_CHUNK: usize = 1 << 14;

/// [`ExportJson`] of a scene given as columns of doubles (no name, no end
/// time; the radius exact): each position and velocity is its own nearest
/// double with the error 0, so no value becomes a [`BigRational`] but the
/// radius and the smallest gap. The smallest `x_{i+1} − x_i` is found on
/// doubles exactly: Knuth's TwoSum writes each difference as `s + err` with
/// `s` its rounding, and since rounding is monotone the pairs `(s, err)` in
/// lexicographic order are the exact differences in order. `Ok(None)` when
/// a value is not finite or a difference overflows a double (then
/// [`export`] answers); an error when the radius is beyond the doubles, or
/// once `stop` is cancelled.
#[cfg(feature = "json")]
pub fn export_doubles(
    radius: &BigRational,
    positions: &[f64],
    velocities: &[f64],
    stop: &dyn crate::progress::Progress,
) -> Result<Option<ExportJson>, ExportError> {
    let radius = round(radius, "radius")?;
    let mut smallest: Option<(usize, f64, f64)> = None;
    for (i, w) in positions.windows(2).enumerate() {
        let (a, b) = (w[1], -w[0]);
        let s = a + b;
        let back = s - a;
        let err = (a - (s - back)) + (b - back);
        if !s.is_finite() || !err.is_finite() {
            return Ok(None);
        }
        if smallest.is_none_or(|(_, s0, e0)| s < s0 || (s == s0 && err < e0)) {
            smallest = Some((i, s, err));
        }
    }
    let column = |v: &[f64]| -> Result<Option<ColumnJson>, ExportError> {
        let mut exact = Vec::with_capacity(v.len());
        for chunk in v.chunks(EXPORT_CHUNK) {
            if stop.cancelled() {
                return Err(ExportError {
                    message: "interrupted during the export".into(),
                });
            }
            for &d in chunk {
                match double_exact_text(d) {
                    Some(text) => exact.push(Rational(text)),
                    None => return Ok(None),
                }
            }
        }
        Ok(Some(ColumnJson {
            exact,
            // The nearest double of the exact value: `-0.0` is the value 0.
            f64: v.iter().map(|&d| d + 0.0).collect(),
            error: vec![Rational("0".into()); v.len()],
        }))
    };
    let (Some(positions_json), Some(velocities_json)) = (column(positions)?, column(velocities)?)
    else {
        return Ok(None);
    };
    let exact = |d: f64| {
        crate::columns::f64_exact(d).unwrap_or_else(|| BigRational::from_integer(BigInt::from(0)))
    };
    let two_r = exact(radius.f64) * BigRational::from_integer(BigInt::from(2));
    let gap = smallest.map(|(i, _, _)| exact(positions[i + 1]) - exact(positions[i]) - &two_r);
    Ok(Some(ExportJson {
        name: None,
        n: positions.len(),
        t_end: None,
        radius: RoundedJson {
            exact: Rational(render_exact(&radius.exact)),
            f64: radius.f64,
            error: Rational(render_exact(&radius.error)),
        },
        positions: positions_json,
        velocities: velocities_json,
        f64_admissible: gap.as_ref().is_none_or(|g| !g.is_negative()),
        f64_min_gap_minus_2r: gap.as_ref().map(|g| Rational(render_exact(g))),
    }))
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

    /// Doubles of every kind: signs, zeros, subnormals, integers beyond
    /// 128 bits, tiny and huge exponents, and random bit patterns.
    fn doubles_of_every_kind() -> Vec<f64> {
        let mut v = vec![
            0.0,
            -0.0,
            1.0,
            -1.5,
            0.1,
            f64::MIN_POSITIVE,
            f64::MIN_POSITIVE / 3.0,
            5e-324,
            -5e-324,
            f64::MAX,
            -f64::MAX,
            2f64.powi(74),
            2f64.powi(75) * 3.0,
            2f64.powi(-127),
            2f64.powi(-128) * 3.0,
            1e300,
            1e-300,
        ];
        let mut seed = 0x5EED_u64;
        while v.len() < 2000 {
            // SplitMix64.
            seed = seed.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = seed;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            let d = f64::from_bits(z ^ (z >> 31));
            if d.is_finite() {
                v.push(d);
            }
        }
        v
    }

    #[test]
    fn a_double_is_written_as_its_exact_value() {
        for d in doubles_of_every_kind() {
            let exact = crate::columns::f64_exact(d).unwrap();
            assert_eq!(double_exact_text(d), Some(render_exact(&exact)), "{d:e}");
        }
        assert_eq!(double_exact_text(f64::NAN), None);
        assert_eq!(double_exact_text(f64::NEG_INFINITY), None);
    }

    #[cfg(feature = "json")]
    #[test]
    fn the_export_of_doubles_is_the_general_one() {
        use crate::initial::InitialData;
        let silent = &crate::progress::Silent;
        let mut values = doubles_of_every_kind();
        values.retain(|d| d.abs() < 1e300);
        values.sort_by(f64::total_cmp);
        values.dedup_by(|a, b| *a - *b < 1e-300);
        let mut velocities: Vec<f64> = values.iter().rev().copied().collect();
        // `-0.0` is the value 0, whose nearest double is `0.0`.
        velocities[0] = -0.0;
        let exact_all = |v: &[f64]| -> Vec<BigRational> {
            v.iter()
                .map(|&d| crate::columns::f64_exact(d).unwrap())
                .collect()
        };
        // Radii making the doubles admissible, rounded, and overlapping.
        let tiny = BigRational::new(1.into(), num_traits::pow(BigInt::from(10), 400));
        for radius in [tiny.clone(), q(1, 3) * q(1, 1_000_000_000), q(1, 1)] {
            let exact = |v: &[f64]| -> Vec<BigRational> {
                v.iter()
                    .map(|&d| crate::columns::f64_exact(d).unwrap())
                    .collect()
            };
            let scene = match InitialData::new(radius.clone(), exact(&values), exact(&velocities)) {
                Ok(data) => Scene::particles(data),
                // Overlapping data: compared below without a scene.
                Err(_) => Scene::particles(
                    InitialData::new(tiny.clone(), exact(&values), exact(&velocities)).unwrap(),
                ),
            };
            let mut general = ExportJson::of(&scene, &export(&scene).unwrap());
            if scene.data.radius() != &radius {
                // The general export of the same values with this radius.
                let r = round(&radius, "radius").unwrap();
                let two_r = 2.0f64.to_big_rational().unwrap() * (&r.exact - &r.error);
                let gap = exact(&values)
                    .windows(2)
                    .map(|w| &w[1] - &w[0] - &two_r)
                    .min()
                    .unwrap();
                general.radius = RoundedJson {
                    exact: Rational(render_exact(&r.exact)),
                    f64: r.f64,
                    error: Rational(render_exact(&r.error)),
                };
                general.f64_admissible = !gap.is_negative();
                general.f64_min_gap_minus_2r = Some(Rational(render_exact(&gap)));
            }
            let fast = export_doubles(&radius, &values, &velocities, silent).unwrap();
            // The text too: `-0.0` and `0.0` are equal doubles, not equal JSON.
            let text = fast.as_ref().map(crate::json::to_string);
            assert_eq!(
                text,
                Some(crate::json::to_string(&general)),
                "radius {radius}"
            );
            assert_eq!(fast, Some(general), "radius {radius}");
        }
        // Two differences rounding to the same double `2^53 + 4`: the
        // smaller (`2^53 + 3`) is found from the TwoSum errors, first or
        // second.
        let big = 2f64.powi(53);
        for values in [
            [-(big + 2.0), 1.0, big + 6.0],
            [-(big + 4.0), 1.0, big + 4.0],
        ] {
            let data = InitialData::new(tiny.clone(), exact_all(&values), vec![q(0, 1); 3]);
            let scene = Scene::particles(data.unwrap());
            let general = ExportJson::of(&scene, &export(&scene).unwrap());
            let fast = export_doubles(&tiny, &values, &[0.0; 3], silent).unwrap();
            let gap = general.f64_min_gap_minus_2r.clone().unwrap();
            assert_eq!(
                fast.as_ref().map(|f| &f.f64_min_gap_minus_2r),
                Some(&Some(gap))
            );
        }
        // A difference beyond the doubles: the general path answers.
        let wide = [-f64::MAX, f64::MAX];
        assert_eq!(
            export_doubles(&tiny, &wide, &[0.0, 0.0], silent).unwrap(),
            None
        );
    }
}
