//! `sticky.isotonic`: exact isotonic regression (increasing, equal
//! weights), the exact counterpart of `scipy.optimize.isotonic_regression`
//! — the projection onto the monotone cone that `P_K` becomes in shifted
//! coordinates (`df:translat-x`, `prop:proj-micro`).

use num_rational::BigRational;
use num_traits::Zero;
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray1};
use pyo3::prelude::*;

use crate::{convert, interrupt};

/// Values as the nearest doubles (a numpy array) or, with `exact`, as a
/// list of `fractions.Fraction`.
pub fn output<'py>(py: Python<'py>, v: &[BigRational], exact: bool) -> PyResult<Bound<'py, PyAny>> {
    if exact {
        Ok(crate::bulk::fractions(py, v)?.into_any())
    } else {
        Ok(PyArray1::from_vec(py, convert::nearest(v)).into_any())
    }
}

/// isotonic(z, exact=False): the exact isotonic regression of z
/// (non-decreasing, equal weights; pool-adjacent-violators on exact
/// rationals), each input read exactly (a float as its binary value). A
/// numpy float64 array of the nearest doubles, or with exact=True a list of
/// fractions.Fraction.
#[pyfunction]
#[pyo3(signature = (z, exact=false))]
pub fn isotonic<'py>(
    py: Python<'py>,
    z: &Bound<'py, PyAny>,
    exact: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let zero = BigRational::zero();
    let mut refused = false;
    if !exact {
        match filtered(py, z, &zero)? {
            Filtered::Proved(fitted) => return Ok(fitted.into_any()),
            Filtered::Refused => refused = true,
            Filtered::NotTried => {}
        }
    }
    let z = convert::column(z, "z")?;
    if let (false, convert::Column::Doubles(d)) = (exact, &z) {
        if d.iter().all(|v| v.is_finite()) {
            return nearest_of_doubles(py, d.clone(), zero, refused);
        }
    }
    let z = z.into_exact("z")?;
    let steps = z.len();
    let fitted = interrupt::run_sized(py, steps, move |_| sticky::projection::isotonic(&z))?;
    output(py, &fitted, exact)
}

/// `P_K(d)` (`radius` `0`: the isotonic regression) of finite doubles as
/// a numpy array of the nearest doubles, on a worker thread (Ctrl-C): the
/// Solver's choice of path ([`sticky::solver::project_doubles`]), or the
/// exact paths alone when the certified filter has refused these values
/// already (`refused`, [`filtered`]).
pub fn nearest_of_doubles<'py>(
    py: Python<'py>,
    d: Vec<f64>,
    radius: BigRational,
    refused: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let steps = d.len();
    let x = interrupt::run_sized(py, steps, move |_| {
        if refused {
            sticky::solver::project_doubles_exactly(&d, &radius)
        } else {
            sticky::solver::project_doubles(&d, &radius)
        }
    })?
    .map_err(crate::errors::py_error)?;
    Ok(PyArray1::from_vec(py, x).into_any())
}

/// What [`filtered`] made of a column.
pub enum Filtered<'py> {
    /// The certified answer.
    Proved(Bound<'py, PyArray1<f64>>),
    /// A column of doubles the filter did not prove: the exact paths answer
    /// ([`sticky::solver::project_doubles_exactly`]).
    Refused,
    /// Not a contiguous `float64` numpy array: not tried.
    NotTried,
}

/// `P_K(z)` for the radius `radius` (`0`: the isotonic regression) by the
/// certified path ([`sticky::solver::project_doubles_certified`]), read
/// from a contiguous `float64` numpy array where it lies and written into a
/// new one, the GIL released (a few milliseconds at `N = 10⁶`).
pub fn filtered<'py>(
    py: Python<'py>,
    z: &Bound<'py, PyAny>,
    radius: &BigRational,
) -> PyResult<Filtered<'py>> {
    let Ok(z) = z.extract::<PyReadonlyArray1<'_, f64>>() else {
        return Ok(Filtered::NotTried);
    };
    let Ok(z) = z.as_slice() else {
        return Ok(Filtered::NotTried);
    };
    let out = convert::empty(py, z.len())?;
    let proved = {
        let mut written = out.readwrite();
        let x = written.as_slice_mut()?;
        py.detach(|| sticky::solver::project_doubles_certified(z, radius, x))
    };
    Ok(if proved {
        Filtered::Proved(out)
    } else {
        Filtered::Refused
    })
}
