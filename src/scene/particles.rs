//! The `[particles]` table: explicit positions and velocities, inline or
//! from a column file (CSV or NPY).

use std::path::Path;

use num_rational::BigRational;
use toml::Value;

use super::values::{as_table, check_keys, exact, exact_array, required, Budget};
use super::MAX_DATA_BYTES;
use crate::error::Error;
use crate::initial::InitialData;

/// `[particles]`: `radius` (optional), `positions`, `velocities`.
pub(super) fn particles_table(
    value: &Value,
    budget: &Budget,
    dir: Option<&Path>,
) -> Result<InitialData<BigRational>, Error> {
    const P: &str = "particles";
    let table = as_table(value, P)?;
    check_keys(table, P, &["radius", "positions", "velocities", "data"])?;
    let (positions, velocities) = match table.get("data") {
        Some(file) => {
            for key in ["positions", "velocities"] {
                if table.contains_key(key) {
                    return Err(Error::SceneKind {
                        message: format!(
                            "[particles] gives both `data` and `{key}`: the columns come from one place"
                        ),
                    });
                }
            }
            let Value::String(file) = file else {
                return Err(Error::WrongType {
                    field: "particles.data".to_string(),
                    expected: "a file name (a string)",
                });
            };
            read_columns(file, dir, budget)?
        }
        None => (
            exact_array(
                required(table, P, "positions")?,
                "particles.positions",
                budget,
            )?,
            exact_array(
                required(table, P, "velocities")?,
                "particles.velocities",
                budget,
            )?,
        ),
    };
    match table.get("radius") {
        Some(r) => {
            let radius = exact(r, "particles.radius", budget)?;
            InitialData::new(radius, positions, velocities)
        }
        None => InitialData::with_paper_radius(positions, velocities),
    }
}

/// Reads the column file `file` of a `[particles]` table (CSV or NPY, by its
/// extension), relative to the scene's folder `dir`.
pub(super) fn read_columns(
    file: &str,
    dir: Option<&Path>,
    budget: &Budget,
) -> Result<(Vec<BigRational>, Vec<BigRational>), Error> {
    let fail = |message: String| Error::DataFile {
        file: file.to_string(),
        message,
    };
    let Some(dir) = dir else {
        return Err(fail(
            "a scene given as text has no folder to read its column file from: load the scene from a file".to_string(),
        ));
    };
    let path = dir.join(file);
    let meta = std::fs::metadata(&path).map_err(|e| fail(format!("{}: {e}", path.display())))?;
    if meta.len() > MAX_DATA_BYTES {
        return Err(fail(format!(
            "larger than the {} GiB limit for column files",
            MAX_DATA_BYTES >> 30
        )));
    }
    let bytes = std::fs::read(&path).map_err(|e| fail(format!("{}: {e}", path.display())))?;
    let columns = match path.extension().and_then(|e| e.to_str()) {
        Some("csv") => {
            let text = std::str::from_utf8(&bytes).map_err(|e| {
                fail(format!(
                    "not UTF-8 text (invalid byte at offset {})",
                    e.valid_up_to()
                ))
            })?;
            crate::columns::read_csv(text)
        }
        Some("npy") => crate::columns::read_npy(&bytes),
        _ => {
            return Err(fail(
                "the file name must end in .csv (exact strings) or .npy (f64, shape (N, 2))"
                    .to_string(),
            ))
        }
    }
    .map_err(|e| fail(e.to_string()))?;
    for q in columns.positions.iter().chain(&columns.velocities) {
        budget.charge(q, "particles.data")?;
    }
    Ok((columns.positions, columns.velocities))
}
