//! The contact loops' kernels, each compiled once per instruction set (a baseline build and
//! an AVX2 one, bitwise the same results): the pair pass of a block's own pairs and of the
//! cross pairs (`pair.rs`), a block's side of its cross pairs (`cross.rs`), and the per-grain
//! pass of the wall contacts and the second half kick (`grain.rs`); here what they share.

mod cross;
mod grain;
mod pair;

pub(crate) use cross::{cross_side, CrossSide};
pub(crate) use grain::{grain_chunk, init_forces, GrainChunk, GrainCtx, Weight};
pub(crate) use pair::{pair_chunk, PairChunk, PairCtx};

use std::mem::MaybeUninit;

/// Own pairs of a block per call of the pair kernel (a block's own pairs are run in these
/// chunks, in order, by the block's thread).
pub const PAIR_CHUNK: usize = 1024;

/// Per cross pair (across grain blocks): the contact's force on i (N) and torque arm from
/// the force pass, gathered per grain afterwards.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct PairResponse {
    pub(crate) force: [f64; 3],
    pub(crate) torque_arm: [f64; 3],
}

/// Pair `a`'s tangential spring at force evaluation `eval` (m): the stored elongation if the
/// pair touched at the evaluation before, else zero (a new contact starts unstretched). The
/// springs of pairs that stop touching are left stale rather than cleared: which candidates
/// touch is unpredictable, and a conditional store per candidate cost a quarter of a step.
#[inline(always)]
pub(crate) fn spring(history: &[[f64; 3]], touch: &[u64], a: usize, eval: u64) -> [f64; 3] {
    if touch[a] + 1 == eval {
        history[a]
    } else {
        [0.0; 3]
    }
}

/// The first `m` entries of a scratch array filled front to back, as a slice.
///
/// # Safety
/// Entries `0..m` must have been written, and `m ≤ a.len()`.
#[inline(always)]
pub(crate) unsafe fn written<T>(a: &[MaybeUninit<T>], m: usize) -> &[T] {
    debug_assert!(m <= a.len());
    // SAFETY: the caller's promise; `MaybeUninit<T>` has the layout of `T`.
    unsafe { std::slice::from_raw_parts(a.as_ptr().cast::<T>(), m) }
}
