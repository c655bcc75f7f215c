//! The integer machinery of the cell list: Morton (Z-order) bit interleaving of cell
//! coordinates (21 bits per axis), the open-addressing hash tables of the occupied cells and
//! columns, and the half stencil of forward neighbour cells.

/// The height bits of a [`Curve::Columns`] key.
pub(super) const Z_MASK: u64 = 0x1f_ffff;

/// An open-addressing hash table of the distinct `keys` (a power of two ≥ 2 × keys slots):
/// a slot holds 1 + the key's index in `keys`, 0 when empty.
pub(super) fn fill_hash(keys: &[u64], table: &mut Vec<u32>) {
    let slots = (2 * keys.len()).next_power_of_two().max(2);
    table.clear();
    table.resize(slots, 0);
    let mask = slots - 1;
    for (c, &k) in keys.iter().enumerate() {
        let mut s = slot_of(k, mask);
        while table[s] != 0 {
            s = (s + 1) & mask;
        }
        table[s] = c as u32 + 1;
    }
}

/// Index in `keys` of `key` through its [`fill_hash`] table, if present.
#[inline]
pub(super) fn find_hashed(keys: &[u64], table: &[u32], key: u64) -> Option<usize> {
    let mask = table.len() - 1;
    let mut s = slot_of(key, mask);
    loop {
        match table[s] {
            0 => return None,
            e if keys[e as usize - 1] == key => return Some(e as usize - 1),
            _ => s = (s + 1) & mask,
        }
    }
}

/// Home slot of cell key `key` in a table of `mask + 1` slots (Fibonacci hashing: the high
/// bits of key × 2⁶⁴/φ, which spread the Morton codes of neighbouring cells).
#[inline]
pub(super) fn slot_of(key: u64, mask: usize) -> usize {
    (key.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 32) as usize & mask
}

/// The 21 low bits of `x` spread to every second bit (from bit 0).
#[inline]
pub(super) fn spread2(x: u64) -> u64 {
    let mut x = x & 0x1f_ffff;
    x = (x | (x << 16)) & 0x0000_ffff_0000_ffff;
    x = (x | (x << 8)) & 0x00ff_00ff_00ff_00ff;
    x = (x | (x << 4)) & 0x0f0f_0f0f_0f0f_0f0f;
    x = (x | (x << 2)) & 0x3333_3333_3333_3333;
    x = (x | (x << 1)) & 0x5555_5555_5555_5555;
    x
}

/// Inverse of [`spread2`]: every second bit of `x` (from bit 0) packed into 21 bits.
#[inline]
pub(super) fn compact2(x: u64) -> u64 {
    let mut x = x & 0x5555_5555_5555_5555;
    x = (x | (x >> 1)) & 0x3333_3333_3333_3333;
    x = (x | (x >> 2)) & 0x0f0f_0f0f_0f0f_0f0f;
    x = (x | (x >> 4)) & 0x00ff_00ff_00ff_00ff;
    x = (x | (x >> 8)) & 0x0000_ffff_0000_ffff;
    x = (x | (x >> 16)) & 0x0000_0000_ffff_ffff;
    x & 0x1f_ffff
}

/// The low 21 bits of `x` spread to every third bit (bit k → bit 3k).
#[inline]
pub(super) fn spread3(x: u64) -> u64 {
    let mut x = x & 0x1f_ffff;
    x = (x | (x << 32)) & 0x001f_0000_0000_ffff;
    x = (x | (x << 16)) & 0x001f_0000_ff00_00ff;
    x = (x | (x << 8)) & 0x100f_00f0_0f00_f00f;
    x = (x | (x << 4)) & 0x10c3_0c30_c30c_30c3;
    x = (x | (x << 2)) & 0x1249_2492_4924_9249;
    x
}

/// Inverse of [`spread3`]: every third bit of `x` (from bit 0) packed into 21 bits.
#[inline]
pub(super) fn compact3(x: u64) -> u64 {
    let mut x = x & 0x1249_2492_4924_9249;
    x = (x | (x >> 2)) & 0x10c3_0c30_c30c_30c3;
    x = (x | (x >> 4)) & 0x100f_00f0_0f00_f00f;
    x = (x | (x >> 8)) & 0x001f_0000_ff00_00ff;
    x = (x | (x >> 16)) & 0x001f_0000_0000_ffff;
    x = (x | (x >> 32)) & 0x1f_ffff;
    x
}

/// Own cell plus the 13 forward neighbours: each unordered cell pair is visited once.
pub(super) const HALF_STENCIL: [(isize, isize, isize); 14] = [
    (0, 0, 0),
    (1, 0, 0),
    (-1, 1, 0),
    (0, 1, 0),
    (1, 1, 0),
    (-1, -1, 1),
    (0, -1, 1),
    (1, -1, 1),
    (-1, 0, 1),
    (0, 0, 1),
    (1, 0, 1),
    (-1, 1, 1),
    (0, 1, 1),
    (1, 1, 1),
];
