//! The engine's worker threads: one pool for the process, built on first use, with as many threads as
//! `RAYON_NUM_THREADS` says or the machine has cores. A time integration runs on it as a whole ([`run`]), so
//! that its parallel loops (the rod's assembly, the contact's nodes, the block LU's halves) split work
//! between threads that are already awake rather than waking the pool twice per assembly.
use std::sync::OnceLock;

/// Elements (or nodes) a parallel loop takes in one run, without splitting further: below it a task costs
/// more to hand out than to do.
pub const SERIAL_RUN: usize = 128;

/// The pool, or `None` if its threads could not be started (the work then runs on the calling thread).
fn pool() -> Option<&'static rayon::ThreadPool> {
    static POOL: OnceLock<Option<rayon::ThreadPool>> = OnceLock::new();
    POOL.get_or_init(|| {
        rayon::ThreadPoolBuilder::new()
            .thread_name(|i| format!("pipelay-{i}"))
            .build()
            .ok()
    })
    .as_ref()
}

/// Runs `work` on the pool when `worth_it` (a model large enough for the parallel loops), directly when
/// already on it or not worth it: handing work to the pool wakes one of its threads, which costs more than a
/// small model's whole run.
pub fn run<R: Send>(worth_it: bool, work: impl FnOnce() -> R + Send) -> R {
    match pool() {
        Some(pool) if worth_it && pool.current_thread_index().is_none() => pool.install(work),
        _ => work(),
    }
}

/// Whether a rod of `elements` elements has work for the pool: more than one serial run ([`SERIAL_RUN`]).
pub fn worth_it(elements: usize) -> bool {
    elements > SERIAL_RUN
}

/// Runs `a` and `b`, in parallel when `worth_it` and called from the pool (else one after the other, on the
/// calling thread: a join from outside would wake the pool and put this thread to sleep for each call).
pub fn join<RA: Send, RB: Send>(
    worth_it: bool,
    a: impl FnOnce() -> RA + Send,
    b: impl FnOnce() -> RB + Send,
) -> (RA, RB) {
    if worth_it && rayon::current_thread_index().is_some() {
        rayon::join(a, b)
    } else {
        (a(), b())
    }
}
