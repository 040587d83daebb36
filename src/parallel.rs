//! Work cut into pieces done on every core: two halves at once
//! ([`join`], what the engines' two-core passes use), or many pieces with
//! the results taken back in the pieces' order ([`in_order`], what the
//! streaming writers use to format exact values on several threads and
//! still write them one after the other).

use std::sync::mpsc::sync_channel;

/// Results computed ahead of the one being taken, per worker.
const AHEAD: usize = 2;

/// The number of worker threads: the cores this process may use.
pub fn workers() -> usize {
    std::thread::available_parallelism().map_or(1, std::num::NonZeroUsize::get)
}

/// `(left(), right())`, `right` on a second thread while `left` runs on
/// this one, or on this one after `left` when no thread can be had; a
/// panic of either is passed on.
pub fn join<A, B: Send>(left: impl FnOnce() -> A, right: impl FnOnce() -> B + Send) -> (A, B) {
    // Whichever thread takes `right` out of the slot runs it: the second
    // one, or this one when the second could not be started.
    let slot = std::sync::Mutex::new(Some(right));
    let run = || slot.lock().ok().and_then(|mut r| r.take()).map(|f| f());
    std::thread::scope(|s| {
        let worker = std::thread::Builder::new().spawn_scoped(s, run);
        let a = left();
        let b = match worker.map(|w| w.join()) {
            Ok(Ok(b)) => b,
            Ok(Err(panic)) => std::panic::resume_unwind(panic),
            Err(_) => None,
        };
        match b.or_else(run) {
            Some(b) => (a, b),
            None => unreachable!("`right` is taken once, by one of the two threads"),
        }
    })
}

/// Calls `take(work(item))` for every item in order, `work` running on
/// `workers` threads (item `k` on worker `k mod workers`, at most
/// two results waiting per worker) while `take` runs on this one.
/// With one worker or fewer than two items, everything runs here. Stops at
/// the first error of `take` and returns it (the workers then stop).
pub fn in_order<T: Sync, R: Send, E>(
    items: &[T],
    workers: usize,
    work: impl Fn(&T) -> R + Sync,
    mut take: impl FnMut(R) -> Result<(), E>,
) -> Result<(), E> {
    let workers = workers.min(items.len());
    if workers < 2 {
        return items.iter().try_for_each(|item| take(work(item)));
    }
    std::thread::scope(|scope| {
        let work = &work;
        let results: Vec<_> = (0..workers)
            .map(|w| {
                let (send, receive) = sync_channel(AHEAD);
                scope.spawn(move || {
                    for item in items.iter().skip(w).step_by(workers) {
                        // The receiver is gone: `take` failed, stop.
                        if send.send(work(item)).is_err() {
                            break;
                        }
                    }
                });
                receive
            })
            .collect();
        for k in 0..items.len() {
            // A worker that panicked: the scope passes its panic on.
            let Ok(r) = results[k % workers].recv() else {
                break;
            };
            take(r)?;
        }
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Both halves are computed, each once, with the borrows they take
    /// (one of them mutable) given back after.
    #[test]
    fn join_runs_both_halves() {
        let mut data = vec![0u64; 100];
        let (lo, hi) = data.split_at_mut(40);
        let (a, b) = join(
            || {
                lo.fill(1);
                lo.len()
            },
            || {
                hi.fill(2);
                hi.len()
            },
        );
        assert_eq!((a, b), (40, 60));
        assert_eq!(data.iter().sum::<u64>(), 40 + 120);
    }

    /// The results come back in the items' order, whatever the number of
    /// workers, and the first error of `take` stops the walk.
    #[test]
    fn results_in_order_and_errors_stop() {
        let items: Vec<u64> = (0..1000).collect();
        for workers in [1, 2, 3, 8] {
            let mut got = Vec::new();
            let r: Result<(), ()> = in_order(
                &items,
                workers,
                |&i| i * i,
                |v| {
                    got.push(v);
                    Ok(())
                },
            );
            assert!(r.is_ok());
            assert_eq!(got, items.iter().map(|i| i * i).collect::<Vec<_>>());
            let mut seen = 0;
            let r = in_order(
                &items,
                workers,
                |&i| i,
                |v| {
                    seen += 1;
                    if v == 10 {
                        Err(v)
                    } else {
                        Ok(())
                    }
                },
            );
            assert_eq!((r, seen), (Err(10), 11));
        }
    }
}
