//! The `[macro]` table: a block datum, its particle count, and the check
//! that sampling it stays within the size limits.

use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive, Zero};
use toml::Value;

use super::values::{as_table, bits, check_keys, exact, join, required, Budget};
use super::{SceneKind, MAX_MACRO_BLOCKS, MAX_MACRO_PARTICLES, MAX_SAMPLE_BYTES};
use crate::error::Error;
use crate::initial::InitialData;
use crate::quantile::{render_short, Block, BlockVelocity, MacroDatum};

/// `[macro]`: `particles` and `blocks`, sampled at the quantiles.
pub(super) fn macro_table(
    value: &Value,
    budget: &Budget,
) -> Result<(SceneKind, InitialData<BigRational>), Error> {
    const M: &str = "macro";
    let table = as_table(value, M)?;
    check_keys(table, M, &["particles", "blocks"])?;
    let n = particle_count(required(table, M, "particles")?, budget)?;
    let blocks_value = required(table, M, "blocks")?;
    let Value::Array(items) = blocks_value else {
        return Err(Error::WrongType {
            field: "macro.blocks".to_string(),
            expected: "an array of tables { from, to, density, velocity }",
        });
    };
    check_block_count(items.len())?;
    let blocks = items
        .iter()
        .enumerate()
        .map(|(k, v)| block(v, &format!("macro.blocks[{k}]"), budget))
        .collect::<Result<Vec<_>, _>>()?;
    macro_data(blocks, n)
}

/// Refuses more than [`MAX_MACRO_BLOCKS`] blocks.
fn check_block_count(blocks: usize) -> Result<(), Error> {
    if blocks > MAX_MACRO_BLOCKS {
        return Err(Error::Unsupported {
            message: format!(
                "field `macro.blocks`: {blocks} blocks is more than the limit of {MAX_MACRO_BLOCKS}"
            ),
        });
    }
    Ok(())
}

/// A `[macro]` datum of `blocks` (left to right) sampled with `n`
/// particles at the quantiles (`thm:main`): the checks and limits of the
/// TOML table, for blocks a program built (Python's `Scene.from_macro`).
pub fn macro_data(
    blocks: Vec<Block>,
    n: usize,
) -> Result<(SceneKind, InitialData<BigRational>), Error> {
    check_block_count(blocks.len())?;
    if n == 0 {
        return Err(Error::NoParticles);
    }
    if n > MAX_MACRO_PARTICLES {
        return Err(Error::Unsupported {
            message: format!(
                "field `macro.particles`: {n} particles is more than the limit of {MAX_MACRO_PARTICLES}"
            ),
        });
    }
    let datum = MacroDatum::new(blocks)?;
    check_sample_size(&datum, n)?;
    let data = datum.sample(n)?;
    Ok((
        SceneKind::Macro {
            datum,
            particles: n,
        },
        data,
    ))
}

/// `macro.particles`: an integer N with `1 ≤ N ≤ MAX_MACRO_PARTICLES`.
pub(super) fn particle_count(value: &Value, budget: &Budget) -> Result<usize, Error> {
    const FIELD: &str = "macro.particles";
    let wrong = || Error::WrongType {
        field: FIELD.to_string(),
        expected: "a positive integer (the particle count N)",
    };
    let n = exact(value, FIELD, budget).map_err(|e| match e {
        Error::WrongType { .. } => wrong(),
        other => other,
    })?;
    if !n.is_integer() || n.is_negative() {
        return Err(wrong());
    }
    if n.is_zero() {
        return Err(Error::NoParticles);
    }
    match n.to_integer().to_usize() {
        Some(k) if k <= MAX_MACRO_PARTICLES => Ok(k),
        _ => Err(Error::Unsupported {
            message: format!(
                "field `{FIELD}`: {} particles is more than the limit of {MAX_MACRO_PARTICLES}",
                render_short(&n)
            ),
        }),
    }
}

/// One block `{ from, to, density, velocity }`.
pub(super) fn block(value: &Value, field: &str, budget: &Budget) -> Result<Block, Error> {
    let Value::Table(t) = value else {
        return Err(Error::WrongType {
            field: field.to_string(),
            expected: "a table { from, to, density, velocity }",
        });
    };
    check_keys(t, field, &["from", "to", "density", "velocity"])?;
    let get = |key: &str| -> Result<BigRational, Error> {
        exact(required(t, field, key)?, &join(field, key), budget)
    };
    let from = get("from")?;
    let to = get("to")?;
    let density = get("density")?;
    let vfield = join(field, "velocity");
    let velocity = match required(t, field, "velocity")? {
        Value::Array(ab) => match ab.as_slice() {
            [a, b] => BlockVelocity::Affine(
                exact(a, &format!("{vfield}[0]"), budget)?,
                exact(b, &format!("{vfield}[1]"), budget)?,
            ),
            _ => {
                return Err(Error::WrongType {
                    field: vfield,
                    expected: "an exact number, or an array of two exact numbers [a, b] (affine: a at `from`, b at `to`)",
                })
            }
        },
        v => BlockVelocity::Constant(exact(v, &vfield, budget).map_err(|e| match e {
            Error::WrongType { field, .. } => Error::WrongType {
                field,
                expected: "an exact number, or an array of two exact numbers [a, b] (affine: a at `from`, b at `to`)",
            },
            other => other,
        })?),
    };
    Ok(Block {
        from,
        to,
        density,
        velocity,
    })
}

/// Refuses a sampling whose numbers would need more than
/// [`MAX_SAMPLE_BYTES`]: each `x_i = from_b + (i/N − m_{b−1})/ρ_b` and `u_i`
/// has at most about the bits of the block's data, of `m_{b−1}` and of `N`.
pub(super) fn check_sample_size(datum: &MacroDatum, n: usize) -> Result<(), Error> {
    let breakpoints = datum.mass_breakpoints();
    let n_bits = u64::from(usize::BITS - n.leading_zeros());
    let per_particle_bits = datum
        .blocks()
        .iter()
        .zip(&breakpoints)
        .map(|(b, m)| {
            let v = match &b.velocity {
                BlockVelocity::Constant(c) => bits(c),
                BlockVelocity::Affine(a, c) => bits(a) + bits(c),
            };
            let x = bits(&b.from) + bits(&b.to) + bits(&b.density) + bits(m) + 2 * n_bits;
            // Position and velocity (the affine one involves x).
            x.saturating_mul(2).saturating_add(v)
        })
        .max()
        .unwrap_or(0);
    // 8 bits per byte, plus a fixed overhead of 256 bytes per particle for
    // the big-integer headers and allocations.
    let bytes = (n as u64).saturating_mul(per_particle_bits / 8 + 256);
    if bytes > MAX_SAMPLE_BYTES {
        return Err(Error::Unsupported {
            message: format!(
                "field `macro.particles`: sampling {n} particles from blocks with numbers this large would need about {} MiB; use fewer particles or simpler numbers",
                bytes / (1024 * 1024)
            ),
        });
    }
    Ok(())
}
