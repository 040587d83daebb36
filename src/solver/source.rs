//! Where a [`Solver`](crate::solver::Solver)'s validated data come from
//! when a fast path read the input and the general path needs them later.

use std::path::PathBuf;
use std::sync::Arc;

use num_rational::BigRational;

use crate::error::Error;
use crate::initial::InitialData;
use crate::scene::Scene;

/// The origin of the general path's data, built on first use.
pub(crate) enum Source {
    /// Given already validated (the Solver's scene is set).
    Built,
    /// Columns of doubles, kept until the general path needs them.
    Doubles {
        radius: Option<BigRational>,
        positions: Arc<Vec<f64>>,
        velocities: Arc<Vec<f64>>,
    },
    /// A scene file the streaming path read.
    File(PathBuf),
}

impl Source {
    /// The validated scene, read or converted now.
    pub(crate) fn scene(&self) -> Result<Scene, Error> {
        match self {
            // `Solver::from_scene` sets the scene with `Source::Built`.
            Source::Built => Err(Error::Unsupported {
                message: "a built scene without its data (a bug in sticky: please report it)"
                    .into(),
            }),
            Source::Doubles {
                radius,
                positions,
                velocities,
            } => {
                let exact = |v: &[f64]| -> Result<Vec<BigRational>, Error> {
                    v.iter()
                        .map(|&d| {
                            crate::columns::f64_exact(d).ok_or_else(|| Error::Unsupported {
                                message: format!("{d} is not a finite number"),
                            })
                        })
                        .collect()
                };
                let (x, u) = (exact(positions)?, exact(velocities)?);
                let data = match radius {
                    Some(r) => InitialData::new(r.clone(), x, u)?,
                    None => InitialData::with_paper_radius(x, u)?,
                };
                Ok(Scene::particles(data))
            }
            Source::File(path) => crate::scene::load(path),
        }
    }

    /// The scene file, when it is the source.
    pub(crate) fn path(&self) -> Option<&std::path::Path> {
        match self {
            Source::File(path) => Some(path),
            _ => None,
        }
    }

    /// The columns of doubles, when they are the source.
    pub(crate) fn doubles(&self) -> Option<(&[f64], &[f64])> {
        match self {
            Source::Doubles {
                positions,
                velocities,
                ..
            } => Some((positions, velocities)),
            _ => None,
        }
    }
}
