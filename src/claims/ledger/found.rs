//! A failure counts only inside its statement's domain: finding one on a
//! case (at two times of one open interval for an a.e.-in-`t` statement).

use num_rational::BigRational;

use crate::claims::domain::{open_intervals, Domain, InTime, OpenInterval};
use crate::claims::{Case, CaseCheck, Violation};
use crate::fast::kernel;

/// A failure of a checker inside its statement's domain: the violation
/// at each time where it is shown (two times of one open interval between
/// collisions for an a.e.-in-`t` statement; the checker's own probe times
/// otherwise).
#[derive(Debug, Clone)]
pub struct Found {
    /// The violation at each time, in order.
    pub violations: Vec<Violation>,
    /// The times (empty when the checker ran on all its probe times).
    pub times: Vec<BigRational>,
    /// The open interval holding `times`.
    pub interval: Option<OpenInterval<BigRational>>,
}

/// The first failure of `check` on `case` inside `domain`, or `None`. A
/// datum outside the domain's hypotheses (`N`, `u⁰ ∈ H`) is skipped; an
/// a.e.-in-`t` statement is run at two times of each open interval between
/// collisions, one time alone at a time, and fails only if it fails at
/// both. Every returned witness passes [`Domain::admits`].
pub fn failure_in_domain(
    check: CaseCheck<BigRational>,
    case: &Case<BigRational>,
    domain: &Domain,
) -> Option<Found> {
    domain.admits_datum(&case.traj).ok()?;
    if domain.time != InTime::AlmostEvery {
        return check(case).err().map(|v| Found {
            violations: vec![v],
            times: Vec::new(),
            interval: None,
        });
    }
    let at = |t: &BigRational| {
        check(
            &Case::with_times(case.traj.clone(), vec![t.clone()])
                .with_engine(kernel::state_of_data),
        )
        .err()
    };
    let intervals = open_intervals(&case.traj);
    // One run over every interval's first time first: most cases pass.
    let firsts: Vec<BigRational> = intervals.iter().map(|iv| iv.times[0].clone()).collect();
    check(&Case::with_times(case.traj.clone(), firsts).with_engine(kernel::state_of_data)).err()?;
    for iv in intervals {
        let Some(a) = at(&iv.times[0]) else { continue };
        let Some(b) = at(&iv.times[1]) else { continue };
        let times = iv.times.to_vec();
        debug_assert!(domain.admits(&case.traj, &times).is_ok());
        domain.admits(&case.traj, &times).ok()?;
        return Some(Found {
            violations: vec![a, b],
            times,
            interval: Some(iv),
        });
    }
    None
}
