//! Columnar particle data: the two columns `position, velocity` of a big
//! scene, kept in a file beside its TOML (docs/guide/scenes.md, `[particles] data =
//! "…"`), the way numerical users hold them.
//!
//! * **CSV** — a header `position,velocity`, then one particle per line,
//!   each value an exact decimal, scientific or fraction string read by
//!   [`parse_exact`] (`"0.125"`, `"1.5e-3"`, `"-7/4"`); blank lines and a
//!   final newline are allowed, nothing else is.
//! * **NPY** — NumPy's format, version 1.0–3.0, dtype `<f8` (little-endian
//!   `f64`), shape `(N, 2)`, C or Fortran order. Every double is read
//!   *exactly* as the binary rational it is (`0.1` in a `.npy` file is
//!   `3602879701896397/36028797018963968`): nothing is rounded, and the
//!   scene is exactly the data the user's numpy program held.
//!
//! Errors name the line and column (CSV) or the byte offset (NPY) of the
//! first bad value; reading never panics on any input.

use std::fmt::Write as _;

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::Zero;

use crate::rational::{parse_exact, render_exact};

mod small;

pub(crate) use small::{csv_header_small, csv_line_small, small_of, trim_ascii, CsvLine};
pub use small::{f64_small, parse_small, read_csv_small, read_npy_small, Small, SmallColumns};

/// The two columns of a particle file, exact.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Columns {
    /// `x⁰_1 … x⁰_N`.
    pub positions: Vec<BigRational>,
    /// `u⁰_1 … u⁰_N`.
    pub velocities: Vec<BigRational>,
}

/// Why a particle file was refused: the place and the reason.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ColumnsError {
    /// Where: `line L, column C` (CSV) or `byte B` (NPY).
    pub at: String,
    /// What is wrong there.
    pub message: String,
}

impl std::fmt::Display for ColumnsError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.at.is_empty() {
            write!(f, "{}", self.message)
        } else {
            write!(f, "{}: {}", self.at, self.message)
        }
    }
}

impl std::error::Error for ColumnsError {}

fn csv_err(line: usize, column: usize, message: impl Into<String>) -> ColumnsError {
    ColumnsError {
        at: format!("line {line}, column {column}"),
        message: message.into(),
    }
}

/// The CSV header a particle file starts with.
pub const CSV_HEADER: &str = "position,velocity";

/// Reads a CSV particle file (see the module documentation).
pub fn read_csv(text: &str) -> Result<Columns, ColumnsError> {
    let mut lines = text.lines().enumerate();
    let header = lines
        .by_ref()
        .find(|(_, l)| !l.trim().is_empty())
        .map(|(k, l)| (k + 1, l.trim()));
    match header {
        Some((_, h)) if h.split(',').map(str::trim).eq(CSV_HEADER.split(',')) => {}
        Some((line, h)) => {
            return Err(csv_err(
                line,
                1,
                format!("the header must be `{CSV_HEADER}`, found `{h}`"),
            ))
        }
        None => {
            return Err(ColumnsError {
                at: String::new(),
                message: format!("empty file: expected the header `{CSV_HEADER}`"),
            })
        }
    }
    let mut positions = Vec::new();
    let mut velocities = Vec::new();
    for (k, line) in lines {
        let number = k + 1;
        if line.trim().is_empty() {
            continue;
        }
        let mut column = 1;
        let mut fields = line.split(',');
        for (name, out) in [("position", &mut positions), ("velocity", &mut velocities)] {
            let Some(field) = fields.next() else {
                return Err(csv_err(
                    number,
                    line.chars().count() + 1,
                    format!("missing the {name}"),
                ));
            };
            let value = parse_exact(field.trim()).map_err(|e| {
                csv_err(
                    number,
                    column,
                    format!("{name} {:?} is refused: {e}", field.trim()),
                )
            })?;
            out.push(value);
            column += field.chars().count() + 1;
        }
        if fields.next().is_some() {
            return Err(csv_err(
                number,
                column,
                "a third value: the file has two columns, position and velocity",
            ));
        }
    }
    Ok(Columns {
        positions,
        velocities,
    })
}

/// Writes the columns as a CSV particle file, every value exact.
pub fn write_csv(positions: &[BigRational], velocities: &[BigRational]) -> String {
    let mut out = String::with_capacity(16 * positions.len() + 32);
    out.push_str(CSV_HEADER);
    out.push('\n');
    for (x, u) in positions.iter().zip(velocities) {
        let _ = writeln!(out, "{},{}", render_exact(x), render_exact(u));
    }
    out
}

/// The exact value of a finite double (the binary rational it is); `None`
/// for NaN and infinities. Built in lowest terms from the double's fields
/// (`m 2^e` with `m` odd), with no gcd: `BigRational::from_float`'s
/// reduction was most of the cost of reading a column.
pub fn f64_exact(v: f64) -> Option<BigRational> {
    if !v.is_finite() {
        return None;
    }
    let Some(OddBinary { odd, exp }) = odd_binary(v) else {
        return Some(BigRational::from_integer(BigInt::from(0)));
    };
    let m = if v < 0.0 {
        -BigInt::from(odd)
    } else {
        BigInt::from(odd)
    };
    // `m` odd: `m / 2^−exp` is in lowest terms.
    Some(if exp >= 0 {
        BigRational::from_integer(m << exp as u64)
    } else {
        BigRational::new_raw(m, BigInt::from(1) << exp.unsigned_abs())
    })
}

/// The magnitude of a finite nonzero double as `odd · 2^exp`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct OddBinary {
    /// Odd, below `2^53`.
    pub odd: u64,
    /// The power of two.
    pub exp: i64,
}

/// The magnitude of the finite double `v` read from its fields as
/// `odd · 2^exp` with `odd` odd; `None` for ±0. `v` must be finite.
pub fn odd_binary(v: f64) -> Option<OddBinary> {
    debug_assert!(v.is_finite());
    let bits = v.to_bits();
    let field = ((bits >> 52) & 0x7ff) as i64;
    let fraction = bits & ((1u64 << 52) - 1);
    let (m, e) = match field {
        0 => (fraction, -1074),
        _ => (fraction | (1 << 52), field - 1075),
    };
    if m == 0 {
        return None;
    }
    let z = m.trailing_zeros();
    let b = OddBinary {
        odd: m >> z,
        exp: e + i64::from(z),
    };
    debug_assert!(b.odd % 2 == 1 && b.odd < 1 << 53);
    Some(b)
}

fn npy_err(byte: usize, message: impl Into<String>) -> ColumnsError {
    ColumnsError {
        at: format!("byte {byte}"),
        message: message.into(),
    }
}

/// The value of `key` in a NumPy header dictionary (`{'descr': '<f8', …}`),
/// as the text up to the next top-level comma.
fn header_value<'a>(header: &'a str, key: &str) -> Option<&'a str> {
    let start = header.find(&format!("'{key}'"))? + key.len() + 2;
    let rest = header[start..].trim_start().strip_prefix(':')?.trim_start();
    let mut depth = 0usize;
    for (i, c) in rest.char_indices() {
        match c {
            '(' | '[' => depth += 1,
            ')' | ']' => depth = depth.saturating_sub(1),
            ',' | '}' if depth == 0 => return Some(rest[..i].trim()),
            _ => {}
        }
    }
    None
}

/// The layout of a `.npy` particle file: `(N, Fortran order?, offset of the data)`,
/// the header checked (see the module documentation).
fn npy_layout(bytes: &[u8]) -> Result<(usize, bool, usize), ColumnsError> {
    npy_layout_of(bytes, bytes.len() as u64)
}

/// [`npy_layout`] from the first bytes of a `.npy` file (`head`, at least
/// through the end of its header) and the file's length: what a reader in
/// chunks needs before it reads the data.
pub(crate) fn npy_layout_of(
    bytes: &[u8],
    file_len: u64,
) -> Result<(usize, bool, usize), ColumnsError> {
    const MAGIC: &[u8] = b"\x93NUMPY";
    if bytes.len() < 10 || &bytes[..6] != MAGIC {
        return Err(npy_err(
            0,
            "not a NumPy .npy file (the magic string \\x93NUMPY is missing)",
        ));
    }
    let major = bytes[6];
    let (len, start): (usize, usize) = match major {
        1 => (usize::from(u16::from_le_bytes([bytes[8], bytes[9]])), 10),
        2 | 3 if bytes.len() >= 12 => (
            u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]) as usize,
            12,
        ),
        _ => {
            return Err(npy_err(
                6,
                format!("unsupported .npy format version {major}"),
            ))
        }
    };
    let end = start
        .checked_add(len)
        .filter(|e| *e <= bytes.len())
        .ok_or_else(|| npy_err(8, "the header runs past the end of the file"))?;
    let header = std::str::from_utf8(&bytes[start..end])
        .map_err(|_| npy_err(start, "the header is not text"))?;
    let descr =
        header_value(header, "descr").ok_or_else(|| npy_err(start, "the header has no 'descr'"))?;
    if !matches!(descr, "'<f8'" | "'float64'") {
        return Err(npy_err(
            start,
            format!("dtype {descr} is refused: the columns must be little-endian f64 ('<f8')"),
        ));
    }
    let fortran = match header_value(header, "fortran_order") {
        Some("False") => false,
        Some("True") => true,
        _ => return Err(npy_err(start, "the header has no valid 'fortran_order'")),
    };
    let shape =
        header_value(header, "shape").ok_or_else(|| npy_err(start, "the header has no 'shape'"))?;
    let dims: Vec<&str> = shape
        .trim_start_matches('(')
        .trim_end_matches(')')
        .split(',')
        .map(str::trim)
        .filter(|d| !d.is_empty())
        .collect();
    let n = match dims.as_slice() {
        [n, "2"] => n
            .parse::<usize>()
            .map_err(|_| npy_err(start, format!("shape {shape}: {n} is not a count")))?,
        _ => {
            return Err(npy_err(
                start,
                format!("shape {shape} is refused: it must be (N, 2), one row per particle"),
            ))
        }
    };
    let body = file_len.saturating_sub(end as u64);
    let need = n
        .checked_mul(16)
        .ok_or_else(|| npy_err(start, format!("shape {shape} is too large")))?;
    if body != need as u64 {
        return Err(npy_err(
            end,
            format!("{body} bytes of data for shape ({n}, 2), expected {need}"),
        ));
    }
    Ok((n, fortran, end))
}

/// The two columns of an `(N, 2)` array whose element `k` (in file order)
/// is `value(k)`: C order `x⁰_1, u⁰_1, x⁰_2, …`, Fortran order all the
/// positions first; the first failure stops it.
fn npy_columns<T, E>(
    n: usize,
    fortran: bool,
    value: impl Fn(usize) -> Result<T, E>,
) -> Result<(Vec<T>, Vec<T>), E> {
    let mut positions = Vec::with_capacity(n);
    let mut velocities = Vec::with_capacity(n);
    for i in 0..n {
        let (kx, ku) = if fortran {
            (i, n + i)
        } else {
            (2 * i, 2 * i + 1)
        };
        positions.push(value(kx)?);
        velocities.push(value(ku)?);
    }
    Ok((positions, velocities))
}

/// Reads a NumPy `.npy` particle file (see the module documentation).
pub fn read_npy(bytes: &[u8]) -> Result<Columns, ColumnsError> {
    let (n, fortran, end) = npy_layout(bytes)?;
    let body = &bytes[end..];
    let value = |k: usize| -> Result<BigRational, ColumnsError> {
        let at = k * 8;
        let mut b = [0u8; 8];
        b.copy_from_slice(&body[at..at + 8]);
        let v = f64::from_le_bytes(b);
        f64_exact(v).ok_or_else(|| {
            let (row, col) = if fortran {
                (k % n, k / n)
            } else {
                (k / 2, k % 2)
            };
            npy_err(
                end + at,
                format!(
                    "particle {} (from 0) has a non-finite {} ({v})",
                    row,
                    ["position", "velocity"][col]
                ),
            )
        })
    };
    let (positions, velocities) = npy_columns(n, fortran, value)?;
    Ok(Columns {
        positions,
        velocities,
    })
}

/// The header of a `.npy` file of little-endian doubles (`<f8`, C order)
/// of the given shape (version 1.0, padded to 64 bytes).
pub fn npy_header(shape: &[usize]) -> Vec<u8> {
    let dims: Vec<String> = shape.iter().map(ToString::to_string).collect();
    let shape = match dims.len() {
        1 => format!("({},)", dims[0]),
        _ => format!("({})", dims.join(", ")),
    };
    let mut header = format!("{{'descr': '<f8', 'fortran_order': False, 'shape': {shape}, }}");
    // Magic (6) + version (2) + length (2) + header + '\n', padded to 64.
    let unpadded = 10 + header.len() + 1;
    header.push_str(&" ".repeat((64 - unpadded % 64) % 64));
    header.push('\n');
    let mut out = Vec::with_capacity(10 + header.len());
    out.extend_from_slice(b"\x93NUMPY\x01\x00");
    out.extend_from_slice(
        &u16::try_from(header.len())
            .unwrap_or(u16::MAX)
            .to_le_bytes(),
    );
    out.extend_from_slice(header.as_bytes());
    out
}

/// Writes doubles as an `(N, 2)` `<f8` `.npy` file (C order).
pub fn write_npy(rows: &[(f64, f64)]) -> Vec<u8> {
    let mut out = npy_header(&[rows.len(), 2]);
    out.reserve(16 * rows.len());
    for (x, u) in rows {
        out.extend_from_slice(&x.to_le_bytes());
        out.extend_from_slice(&u.to_le_bytes());
    }
    out
}

/// `true` when `q` is exactly a double (so a `.npy` file can hold it).
pub fn is_f64(q: &BigRational) -> bool {
    let v = crate::scalar::Scalar::to_f64_lossy(q);
    f64_exact(v).is_some_and(|e| &e == q) || (q.is_zero() && v == 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_bigint::BigInt;
    use num_traits::One;

    use crate::rational::ratio as q;

    #[test]
    fn csv_round_trip_is_exact() {
        let x = vec![q(-7, 4), q(1, 3), q(5, 1)];
        let u = vec![q(0, 1), q(-1, 1000), q(22, 7)];
        let text = write_csv(&x, &u);
        let c = read_csv(&text).expect("reads back");
        assert_eq!((c.positions, c.velocities), (x, u));
        let c = read_csv("position, velocity\n0.125, 1.5e-3\n\n-7/4,2\n").expect("valid");
        assert_eq!(c.positions, vec![q(1, 8), q(-7, 4)]);
        assert_eq!(c.velocities, vec![q(3, 2000), q(2, 1)]);
    }

    #[test]
    fn csv_errors_name_line_and_column() {
        let e = read_csv("position,velocity\n1,2\n3,abc\n").unwrap_err();
        assert_eq!(e.at, "line 3, column 3", "{e}");
        assert!(e.to_string().contains("velocity \"abc\""), "{e}");
        let e = read_csv("x,u\n1,2\n").unwrap_err();
        assert_eq!(e.at, "line 1, column 1");
        let e = read_csv("position,velocity\n1\n").unwrap_err();
        assert!(
            e.to_string().contains("line 2") && e.message.contains("velocity"),
            "{e}"
        );
        let e = read_csv("position,velocity\n1,2,3\n").unwrap_err();
        assert!(e.message.contains("third value"), "{e}");
        assert!(read_csv("").is_err());
        let e = read_csv("position,velocity\n1/0,2\n").unwrap_err();
        assert_eq!(e.at, "line 2, column 1");
    }

    #[test]
    fn doubles_are_read_exactly() {
        assert_eq!(
            f64_exact(0.1),
            Some(q(3_602_879_701_896_397, 36_028_797_018_963_968))
        );
        assert_eq!(f64_exact(-2.5), Some(q(-5, 2)));
        assert_eq!(f64_exact(0.0), Some(q(0, 1)));
        assert_eq!(f64_exact(-0.0), Some(q(0, 1)));
        assert_eq!(f64_exact(f64::NAN), None);
        assert_eq!(f64_exact(f64::INFINITY), None);
        let tiny = f64::from_bits(1); // the smallest subnormal, 2^-1074
        let want = BigRational::new(BigInt::one(), BigInt::one() << 1074usize);
        assert_eq!(f64_exact(tiny), Some(want));
        assert_eq!(
            f64_exact(f64::MAX),
            Some(BigRational::from_integer(
                (BigInt::from((1u64 << 53) - 1)) << 971usize
            ))
        );
        for v in [1.0, 1e300, 3.25e-310, 123_456.789] {
            let e = f64_exact(v).expect("finite");
            assert_eq!(crate::scalar::Scalar::to_f64_lossy(&e), v);
            assert!(is_f64(&e));
        }
        assert!(!is_f64(&q(1, 3)));
    }

    /// Random bit patterns (every exponent field, subnormals, both signs):
    /// the same numerator and denominator as `BigRational::from_float`'s
    /// reduced value, field by field (lowest terms, positive denominator).
    #[test]
    fn doubles_equal_from_float_field_by_field() {
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        for k in 0..20_000u64 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            // Every fourth value a subnormal or a small integer's pattern.
            let bits = match k % 4 {
                0 => state & ((1 << 52) - 1) | (state & (1 << 63)),
                1 => (k as f64 - 5000.0).to_bits(),
                _ => state,
            };
            let v = f64::from_bits(bits);
            match (f64_exact(v), BigRational::from_float(v)) {
                (Some(a), Some(b)) => {
                    assert_eq!((a.numer(), a.denom()), (b.numer(), b.denom()), "{v:e}");
                }
                (a, b) => assert_eq!(a, b, "{v:e}"),
            }
        }
    }

    #[test]
    fn npy_round_trip_and_errors() {
        let rows = [(0.1, -1.0), (1.5, 0.0), (2.0, 1e-3)];
        let bytes = write_npy(&rows);
        assert_eq!(
            (10 + usize::from(u16::from_le_bytes([bytes[8], bytes[9]]))) % 64,
            0
        );
        let c = read_npy(&bytes).expect("reads back");
        for (k, (x, u)) in rows.iter().enumerate() {
            assert_eq!(Some(c.positions[k].clone()), f64_exact(*x));
            assert_eq!(Some(c.velocities[k].clone()), f64_exact(*u));
        }
        // Fortran order: all positions, then all velocities.
        let header = "{'descr': '<f8', 'fortran_order': True, 'shape': (2, 2), }";
        let mut f = b"\x93NUMPY\x01\x00".to_vec();
        f.extend_from_slice(&(header.len() as u16).to_le_bytes());
        f.extend_from_slice(header.as_bytes());
        for v in [1.0f64, 2.0, -1.0, -2.0] {
            f.extend_from_slice(&v.to_le_bytes());
        }
        let c = read_npy(&f).expect("fortran order");
        assert_eq!(c.positions, vec![q(1, 1), q(2, 1)]);
        assert_eq!(c.velocities, vec![q(-1, 1), q(-2, 1)]);
        // A NaN is named with its particle and column.
        let bytes = write_npy(&[(0.0, 1.0), (f64::NAN, 2.0)]);
        let e = read_npy(&bytes).unwrap_err();
        assert!(
            e.message
                .contains("particle 1 (from 0) has a non-finite position"),
            "{e}"
        );
        // Truncated data, wrong dtype, wrong shape, garbage.
        let bytes = write_npy(&rows);
        assert!(read_npy(&bytes[..bytes.len() - 1])
            .unwrap_err()
            .message
            .contains("bytes of data"));
        let replace = |from: &[u8], to: &[u8]| {
            let at = bytes
                .windows(from.len())
                .position(|w| w == from)
                .expect("present");
            let mut b = bytes.clone();
            b[at..at + from.len()].copy_from_slice(to);
            b
        };
        let e = read_npy(&replace(b"<f8", b"<f4")).unwrap_err();
        assert!(e.message.contains("'<f4' is refused"), "{e}");
        let e = read_npy(&replace(b"(3, 2)", b"(6,)  ")).unwrap_err();
        assert!(e.message.contains("(N, 2)"), "{e}");
        assert!(read_npy(b"hello").is_err());
        for cut in 0..bytes.len() {
            let _ = read_npy(&bytes[..cut]); // never panics
        }
    }
}
