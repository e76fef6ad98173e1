//! Work of a solve spread over threads: runs of items, one run a thread.

/// `f` of `items` in consecutive runs, one run per thread (of `threads`),
/// in order: one result per run; a single run for one thread or item.
pub(super) fn in_runs<T: Sync, R: Send>(items: &[T], threads: usize, f: impl Fn(&[T]) -> R + Sync) -> Vec<R> {
    if threads < 2 || items.len() < 2 {
        return vec![f(items)];
    }
    let run = items.len().div_ceil(threads);
    std::thread::scope(|scope| {
        let f = &f;
        let handles: Vec<_> = items.chunks(run).map(|c| scope.spawn(move || f(c))).collect();
        handles.into_iter().map(|h| h.join().unwrap_or_else(|e| std::panic::resume_unwind(e))).collect()
    })
}

/// `f` of each of `items`, in order, in [`in_runs`] where there are two
/// items a thread or more (a junction's tie and its forces are small dense
/// problems of its own: 0.01-0.03 s of a contact iteration at 512 to 1,000
/// blocks).
pub(super) fn in_threads<T: Sync, R: Send>(items: &[T], threads: usize, f: impl Fn(&T) -> R + Sync) -> Vec<R> {
    let threads = if items.len() < 2 * threads { 1 } else { threads };
    in_runs(items, threads, |run| run.iter().map(&f).collect::<Vec<R>>()).into_iter().flatten().collect()
}
