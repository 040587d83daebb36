//! Work cut into pieces done on every core, the results taken back in the
//! pieces' order: what the streaming writers use to format exact values on
//! several threads and still write them one after the other.

use std::sync::mpsc::sync_channel;

/// Results computed ahead of the one being taken, per worker.
const AHEAD: usize = 2;

/// The number of worker threads: the cores this process may use.
pub fn workers() -> usize {
    std::thread::available_parallelism().map_or(1, std::num::NonZeroUsize::get)
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
