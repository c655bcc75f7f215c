//! Threads inside one DEM run: a persistent team that runs each phase of a step on every
//! thread, and the executors the step's phases are written against.
//!
//! A step has three phases (kick–drift, pairs, grains), each a set of fixed *units* (grain
//! chunks, blocks, cross-pair chunks) whose results go to one slot per unit and are summed by
//! the caller in unit order. Which thread runs a unit never changes a result, so a run is
//! bit-identical on one thread, on the rayon pool and on a [`Team`] of any size.
//!
//! Why a team and not only the rayon pool: a step of a few thousand grains lasts ~100 µs and
//! has three phases; rayon's idle workers go to sleep between them and are woken by the
//! kernel (measured: ~5 context switches and ~30 µs of system time per step on 2 threads at
//! N = 4000). The team's workers spin for a short while ([`SPIN`]) before parking, so a phase
//! starts within a microsecond of the previous one. The team is used for a run stepped from
//! outside any rayon pool (one `pdamp simulate`); inside a pool (sweep points, tests'
//! `install`) the rayon path runs, which shares the pool's threads with the other points.

use std::cell::UnsafeCell;
use std::ops::Range;
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::Arc;
use std::thread::{JoinHandle, Thread};
use std::time::{Duration, Instant};

use rayon::prelude::*;

/// How long an idle team thread spins (and then yields) before it parks.
pub const SPIN: Duration = Duration::from_micros(50);

/// One unit of work of a phase (its index).
type Job<'a> = dyn Fn(usize) + Sync + 'a;

/// What the team threads share: the job of the current generation.
struct Shared {
    generation: AtomicU64,
    pending: AtomicUsize,
    panicked: AtomicBool,
    stop: AtomicBool,
    /// The job of the current generation: written by the leader before it publishes the
    /// generation (Release), read by the workers after they see it (Acquire).
    job: UnsafeCell<Option<*const Job<'static>>>,
    /// Per thread and per list of units ([`Team::claimed`]), the next unit of its share not
    /// yet claimed: set by the leader before it publishes a generation, then advanced by
    /// `fetch_add` by whichever thread claims a unit.
    cursors: Box<[Cursor]>,
}

/// One claim cursor on its own cache line (two threads claim from it).
#[repr(align(128))]
struct Cursor(AtomicUsize);

// SAFETY: `job` is written only by the leader while no worker reads it (between
// generations, all workers having decremented `pending`), and read by workers only after the
// Acquire load of the generation that published it.
unsafe impl Sync for Shared {}
// SAFETY: as above; the pointer is only dereferenced while the leader keeps the job alive.
unsafe impl Send for Shared {}

/// A leader (the thread that steps the world) and `threads − 1` worker threads.
pub struct Team {
    shared: Arc<Shared>,
    workers: Vec<(Thread, Option<JoinHandle<()>>)>,
}

impl std::fmt::Debug for Team {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Team({} threads)", self.threads())
    }
}

impl Team {
    /// A team of `threads` (≥ 1) threads: the caller and `threads − 1` workers.
    ///
    /// # Errors
    /// The operating system's refusal to start a thread.
    pub fn new(threads: usize) -> std::io::Result<Team> {
        let shared = Arc::new(Shared {
            generation: AtomicU64::new(0),
            pending: AtomicUsize::new(0),
            panicked: AtomicBool::new(false),
            stop: AtomicBool::new(false),
            job: UnsafeCell::new(None),
            cursors: (0..2 * threads.max(1))
                .map(|_| Cursor(AtomicUsize::new(0)))
                .collect(),
        });
        let mut workers = Vec::new();
        for index in 1..threads.max(1) {
            let s = Arc::clone(&shared);
            let h = std::thread::Builder::new()
                .name(format!("pdamp-dem-{index}"))
                .spawn(move || worker(&s, index))?;
            workers.push((h.thread().clone(), Some(h)));
        }
        Ok(Team { shared, workers })
    }

    /// Number of threads, the caller included.
    pub fn threads(&self) -> usize {
        self.workers.len() + 1
    }

    /// Runs every unit of one or two lists of units (`(count, job)`, at most two), each
    /// exactly once, and returns when all have run.
    ///
    /// Each thread first runs its own share of each list (thread t of n: units
    /// `t·count/n .. (t+1)·count/n`, the same grains every step, so they stay in its cache),
    /// then claims the units still unclaimed in the other threads' shares, list by list.
    /// A unit is claimed by a `fetch_add` on its share's cursor, so a thread that finishes
    /// early (a lighter block, a worker woken late) takes over work instead of waiting.
    /// Which thread runs a unit changes no result: every unit writes only its own slot.
    pub fn claimed(&self, lists: &[(usize, &Job<'_>)]) {
        let n = self.threads();
        assert!(lists.len() <= 2, "at most two lists of units");
        let s = &*self.shared;
        for (l, &(count, _)) in lists.iter().enumerate() {
            for t in 0..n {
                s.cursors[l * n + t]
                    .0
                    .store(share(t, n, count).start, Ordering::Relaxed);
            }
        }
        // the cursors' stores are published by the Release of the generation in `run`
        let claim = |l: usize, owner: usize| {
            let (count, job) = lists[l];
            let end = share(owner, n, count).end;
            loop {
                let u = s.cursors[l * n + owner].0.fetch_add(1, Ordering::Relaxed);
                if u >= end {
                    break;
                }
                job(u);
            }
        };
        self.run(&|t| {
            for l in 0..lists.len() {
                claim(l, t);
            }
            for l in 0..lists.len() {
                for k in 1..n {
                    claim(l, (t + k) % n);
                }
            }
        });
    }

    /// Runs `job(t)` on every thread t of the team (t = 0 on the caller) and returns when all
    /// have finished.
    ///
    /// # Panics
    /// When the job panicked on any thread (after every thread has finished with it).
    pub fn run(&self, job: &Job<'_>) {
        if self.workers.is_empty() {
            job(0);
            return;
        }
        let s = &*self.shared;
        // SAFETY: the lifetime is erased only for the duration of this call: every worker
        // has finished with the job (pending == 0) before `run` returns.
        let ptr: *const Job<'static> = unsafe { std::mem::transmute(job as *const Job<'_>) };
        // SAFETY: no worker reads `job` now (the previous generation is complete).
        unsafe { *s.job.get() = Some(ptr) };
        s.pending.store(self.workers.len(), Ordering::Relaxed);
        s.generation.fetch_add(1, Ordering::Release);
        for (t, _) in &self.workers {
            t.unpark();
        }
        // the leader's share may panic (an index out of bounds): the workers still run the
        // job, so wait for them before unwinding out of the job's lifetime
        let leader = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| job(0)));
        wait_until(|| s.pending.load(Ordering::Acquire) == 0, false);
        let worker_panicked = s.panicked.swap(false, Ordering::Relaxed);
        if let Err(payload) = leader {
            std::panic::resume_unwind(payload);
        }
        if worker_panicked {
            panic!("a DEM team thread panicked");
        }
    }
}

impl Drop for Team {
    fn drop(&mut self) {
        self.shared.stop.store(true, Ordering::Release);
        self.shared.generation.fetch_add(1, Ordering::Release);
        for (t, h) in &mut self.workers {
            t.unpark();
            if let Some(h) = h.take() {
                let _ = h.join();
            }
        }
    }
}

/// Spins, then yields, for up to [`SPIN`]; then parks (if `park`) or keeps yielding, until
/// `ready()`.
fn wait_until(ready: impl Fn() -> bool, park: bool) {
    let t0 = Instant::now();
    let mut k = 0u32;
    while !ready() {
        k = k.wrapping_add(1);
        if k < 64 {
            std::hint::spin_loop();
            continue;
        }
        if !k.is_multiple_of(256) || t0.elapsed() < SPIN {
            std::hint::spin_loop();
        } else if park {
            std::thread::park_timeout(Duration::from_millis(50));
        } else {
            std::thread::yield_now();
        }
    }
}

fn worker(s: &Shared, index: usize) {
    let mut seen = 0u64;
    loop {
        wait_until(|| s.generation.load(Ordering::Acquire) != seen, true);
        seen = s.generation.load(Ordering::Acquire);
        if s.stop.load(Ordering::Acquire) {
            return;
        }
        // SAFETY: published by the leader before this generation; alive until pending == 0.
        let job = unsafe { (*s.job.get()).expect("a job with every generation") };
        let ok = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            // SAFETY: see above.
            unsafe { (*job)(index) }
        }));
        if ok.is_err() {
            s.panicked.store(true, Ordering::Relaxed);
        }
        s.pending.fetch_sub(1, Ordering::Release);
    }
}

/// Who runs the units of a phase.
#[derive(Clone, Copy)]
pub enum Exec<'a> {
    /// The calling thread, units in order.
    Serial,
    /// The rayon pool the caller is in.
    Rayon,
    /// A [`Team`]: thread t runs a contiguous share of the units, then claims the units the
    /// others have not reached ([`Team::claimed`]).
    Team(&'a Team),
}

impl Exec<'_> {
    /// Runs `f(u)` for every unit u of `0..units`.
    pub fn units(self, units: usize, f: &Job<'_>) {
        if units == 0 {
            // (no phase at all: a team would otherwise wake its threads for nothing — the
            // cross-pair phase of a step is empty whenever cross pairs are done from both
            // sides)
            return;
        }
        match self {
            Exec::Serial => (0..units).for_each(f),
            Exec::Rayon => (0..units).into_par_iter().for_each(f),
            Exec::Team(team) => team.claimed(&[(units, f)]),
        }
    }

    /// Runs `f(u)` for every unit of `0..a` and `g(u)` for every unit of `0..b`, as one phase
    /// (each thread of a team takes its share of both, then claims what is left of either).
    pub fn units2(self, (a, f): (usize, &Job<'_>), (b, g): (usize, &Job<'_>)) {
        if a + b == 0 {
            return;
        }
        match self {
            Exec::Serial => {
                (0..a).for_each(f);
                (0..b).for_each(g);
            }
            Exec::Rayon => {
                rayon::join(
                    || (0..a).into_par_iter().for_each(f),
                    || (0..b).into_par_iter().for_each(g),
                );
            }
            Exec::Team(team) => team.claimed(&[(a, f), (b, g)]),
        }
    }
}

/// Thread t's contiguous share of `units` among `n` threads.
fn share(t: usize, n: usize, units: usize) -> Range<usize> {
    t * units / n..(t + 1) * units / n
}

/// Element-by-element read access to a slice whose pieces the units of a phase may be
/// writing through [`Parts`] (a unit reads an element only when no other unit writes it, as
/// the callers of [`Parts::get`] promise). No reference to the whole slice is held, so a unit
/// may write its own piece and read other elements in the same phase.
pub struct View<'a, T> {
    ptr: *const T,
    len: usize,
    _life: std::marker::PhantomData<&'a [T]>,
}

impl<T> Clone for View<'_, T> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<T> Copy for View<'_, T> {}

// SAFETY: a `View` only reads, and its users guarantee that no element is written while it
// is read; T itself is Sync.
unsafe impl<T: Sync> Sync for View<'_, T> {}
// SAFETY: as above.
unsafe impl<T: Sync> Send for View<'_, T> {}

impl<'a, T> View<'a, T> {
    /// A view of `s`, for reading while no unit writes it.
    pub fn of(s: &'a [T]) -> Self {
        View {
            ptr: s.as_ptr(),
            len: s.len(),
            _life: std::marker::PhantomData,
        }
    }
}

impl<T: Copy> View<'_, T> {
    /// Element `i`.
    ///
    /// # Panics
    /// When `i` is out of bounds.
    #[inline(always)]
    pub fn at(&self, i: usize) -> T {
        assert!(i < self.len, "index {i} out of {} elements", self.len);
        // SAFETY: in bounds; no unit writes element i while it is read (the users' promise).
        unsafe { *self.ptr.add(i) }
    }
}

/// A mutable slice handed out in disjoint pieces to the units of a phase. It holds the slice's
/// mutable borrow for its whole life (`'a`), so the slice can neither be read, moved nor
/// dropped behind its back:
///
/// ```compile_fail
/// use pdamp::dem::team::Parts;
/// let mut v = vec![1.0f64; 4];
/// let parts = Parts::new(&mut v);
/// drop(v); // error: `v` is still borrowed by `parts`
/// let _ = parts.view().at(0);
/// ```
pub struct Parts<'a, T> {
    ptr: *mut T,
    len: usize,
    _borrow: std::marker::PhantomData<&'a mut [T]>,
}

// SAFETY: `Parts` only gives out pieces through the unsafe `get`, whose callers guarantee
// that concurrently used pieces are disjoint; T itself is Send.
unsafe impl<T: Send> Sync for Parts<'_, T> {}
// SAFETY: as above.
unsafe impl<T: Send> Send for Parts<'_, T> {}

impl<'a, T> Parts<'a, T> {
    /// The pieces of `s`, which stays borrowed mutably for as long as the `Parts` lives.
    pub fn new(s: &'a mut [T]) -> Parts<'a, T> {
        Parts {
            ptr: s.as_mut_ptr(),
            len: s.len(),
            _borrow: std::marker::PhantomData,
        }
    }

    /// A [`View`] of the whole slice, for reading elements no unit is writing.
    pub fn view(&self) -> View<'_, T> {
        View {
            ptr: self.ptr,
            len: self.len,
            _life: std::marker::PhantomData,
        }
    }

    /// Elements `r` (clamped to the slice).
    ///
    /// # Safety
    /// Pieces in use at the same time must not overlap, and no piece may be used while a
    /// [`View`] of the same elements is read (the borrow checker keeps the slice itself alive
    /// and untouched).
    #[allow(clippy::mut_from_ref)]
    pub unsafe fn get(&self, r: Range<usize>) -> &mut [T] {
        let (a, b) = (r.start.min(self.len), r.end.min(self.len));
        // SAFETY: in bounds; disjointness is the caller's promise.
        unsafe { std::slice::from_raw_parts_mut(self.ptr.add(a), b.saturating_sub(a)) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_unit_runs_once_on_any_executor() {
        for threads in [1, 2, 3, 5] {
            let team = Team::new(threads).unwrap();
            for units in [0, 1, 2, 7, 100] {
                for exec in [Exec::Serial, Exec::Rayon, Exec::Team(&team)] {
                    let mut hits = vec![0u32; units];
                    let parts = Parts::new(&mut hits);
                    // SAFETY: unit u touches element u only.
                    exec.units(units, &|u| unsafe { parts.get(u..u + 1)[0] += 1 });
                    assert!(
                        hits.iter().all(|&h| h == 1),
                        "{threads} threads, {units} units"
                    );
                }
            }
            // many short phases in a row (the step's pattern)
            let mut total = vec![0u64; 8];
            for _ in 0..2000 {
                let parts = Parts::new(&mut total);
                // SAFETY: unit u of the first list writes slot u, of the second slot 4 + u:
                // every unit runs once, no two touch the same slot.
                Exec::Team(&team).units2(
                    (4, &|u| unsafe { parts.get(u..u + 1)[0] += 1 }),
                    (4, &|u| unsafe { parts.get(4 + u..5 + u)[0] += 2 }),
                );
            }
            assert_eq!(total, [2000, 2000, 2000, 2000, 4000, 4000, 4000, 4000]);
        }
    }

    #[test]
    fn a_panic_in_the_leaders_share_waits_for_the_workers() {
        // the job borrows `done` from this frame: `run` may unwind out of it only after every
        // worker has finished with the job
        let team = Team::new(3).unwrap();
        let done = AtomicUsize::new(0);
        let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            team.run(&|t| {
                if t == 0 {
                    panic!("the leader's share");
                }
                std::thread::sleep(Duration::from_millis(20));
                done.fetch_add(1, Ordering::SeqCst);
            })
        }));
        assert!(r.is_err());
        assert_eq!(
            done.load(Ordering::SeqCst),
            2,
            "both workers finished first"
        );
        // and the team still works
        let again = AtomicUsize::new(0);
        team.run(&|_| {
            again.fetch_add(1, Ordering::SeqCst);
        });
        assert_eq!(again.load(Ordering::SeqCst), 3);
    }

    #[test]
    fn a_phase_of_no_units_does_not_wake_the_team() {
        let team = Team::new(2).unwrap();
        let generation = || team.shared.generation.load(Ordering::Acquire);
        let before = generation();
        Exec::Team(&team).units(0, &|_| panic!("no unit to run"));
        Exec::Team(&team).units2((0, &|_| panic!("no unit")), (0, &|_| panic!("no unit")));
        assert_eq!(generation(), before);
        // one unit does start a generation
        Exec::Team(&team).units(1, &|_| {});
        assert_eq!(generation(), before + 1);
    }

    #[test]
    fn a_panicking_worker_is_reported_to_the_leader() {
        let team = Team::new(2).unwrap();
        let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            team.run(&|t| assert!(t == 0, "worker fails"));
        }));
        assert!(r.is_err());
        // the team still works afterwards
        let mut x = [0u8; 2];
        let parts = Parts::new(&mut x);
        // SAFETY: thread t writes slot t alone.
        team.run(&|t| unsafe { parts.get(t..t + 1)[0] = 1 });
        assert_eq!(x, [1, 1]);
    }
}
