//! A candidate pair of grains ([`Pair`]) and the per-grain index of a pair list
//! ([`index_by_grain`]).

/// One candidate pair of grains (indices into the grain arrays), i ≠ j.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Pair {
    /// First grain.
    pub i: u32,
    /// Second grain.
    pub j: u32,
}

/// Bit set in the entries of [`index_by_grain`] where the grain is the pair's `j`.
pub const J_ROLE: u32 = 1 << 31;

/// Per-grain index of `pairs` of `n` grains (counting sort, pair order kept): grain g's
/// entries are `items[start[g]..start[g + 1]]`, each a pair index with [`J_ROLE`] set where g
/// is the pair's `j`. Reuses the buffers.
pub fn index_by_grain(pairs: &[Pair], n: usize, start: &mut Vec<u32>, items: &mut Vec<u32>) {
    start.clear();
    start.resize(n + 1, 0);
    for p in pairs {
        start[p.i as usize + 1] += 1;
        start[p.j as usize + 1] += 1;
    }
    for g in 0..n {
        start[g + 1] += start[g];
    }
    items.clear();
    items.resize(2 * pairs.len(), 0);
    // fill, using start[g] as g's cursor, then shift the ends back into starts
    for (k, p) in pairs.iter().enumerate() {
        let (i, j) = (p.i as usize, p.j as usize);
        items[start[i] as usize] = k as u32;
        start[i] += 1;
        items[start[j] as usize] = k as u32 | J_ROLE;
        start[j] += 1;
    }
    // start[g] now holds the end of g = the start of g + 1: shift back
    for g in (1..=n).rev() {
        start[g] = start[g - 1];
    }
    start[0] = 0;
}
