//! The battery's messages: the first difference between two answers,
//! formatted only there.

use std::fmt;

use num_rational::BigRational;

use crate::trajectory::Trajectory;

/// The first index where two lists differ, described (values are
/// formatted only there: the battery compares many and formats one).
pub(super) fn list_diff<T: PartialEq + fmt::Display>(
    field: &str,
    want: &[T],
    got: &[T],
    show: impl Fn(&T) -> T,
) -> Option<String> {
    if let Some(i) = (0..want.len().min(got.len())).find(|&i| want[i] != got[i]) {
        return Some(format!(
            "{field}[{i}] = {}, expected {}",
            got[i],
            show(&want[i])
        ));
    }
    (want.len() != got.len()).then(|| format!("{} {field}, expected {}", got.len(), want.len()))
}

/// [`list_diff`] for values shown with `Debug`.
pub(super) fn list_diff_debug<T: PartialEq + fmt::Debug>(
    field: &str,
    want: &[T],
    got: &[T],
) -> Option<String> {
    if let Some(i) = (0..want.len().min(got.len())).find(|&i| want[i] != got[i]) {
        return Some(format!(
            "{field}[{i}] = {:?}, expected {:?}",
            got[i], want[i]
        ));
    }
    (want.len() != got.len()).then(|| format!("{} {field}, expected {}", got.len(), want.len()))
}

/// The first difference between two histories.
pub(super) fn history_diff(
    want: &Trajectory<BigRational>,
    got: &Trajectory<BigRational>,
) -> Option<String> {
    if want.data() != got.data() {
        return Some("the rebuilt initial data differ".into());
    }
    list_diff_debug("impulses", want.impulses(), got.impulses())
        .or_else(|| list_diff_debug("join times", want.join_times(), got.join_times()))
}
