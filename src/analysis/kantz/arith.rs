//! The arithmetic of the kernel of [`super::kantz`]: running products of the per-reference
//! sums (mantissa and binary exponent, so that `Σ ln(a/c) = ln Π a − Σ ln c` takes one
//! logarithm per (m, ε, Δn) and chunk), and the pair loops over squared coordinate
//! differences `e_t = (s_{i+t} − s_{j+t})²` (contiguous, they vectorise).

/// Running products of one chunk's per-reference sums, so that the logarithm is taken once
/// per chunk instead of once per reference: `Σ_r ln(a_r/c_r) = ln Π_r a_r − Σ_r ln c_r`.
/// A product is kept as a mantissa `p` and a binary exponent `exp2` (value `p·2^exp2`);
/// `p` is renormalised to [1, 2) after every [`RENORM_EVERY`] factors, and only factors in
/// [`PROD_LO`, `PROD_HI`] enter it (others take the direct path), so it never leaves the
/// normal f64 range. Rounding: ~1e-16 relative per factor, as for a sum of logarithms.
pub(super) struct Products {
    /// Mantissa products, [row][Δn] (row = dimension slot × ε).
    pub(super) p: Vec<f64>,
    /// Binary exponents taken out of `p`, same layout.
    exp2: Vec<i64>,
    /// Factors multiplied into each row since its last renormalisation.
    pub(super) since: Vec<u32>,
    /// Σ ln c_r of the references in each row's product (c_r: neighbour count, the same
    /// at every Δn for these references).
    pub(super) ln_count: Vec<f64>,
    /// Number of references in each row's product.
    pub(super) refs: Vec<u64>,
}

/// Smallest factor admitted to a running product (2^-100).
pub(super) const PROD_LO: f64 = 7.888_609_052_210_118e-31;
/// Largest factor admitted to a running product (2^100).
pub(super) const PROD_HI: f64 = 1.267_650_600_228_229_4e30;
/// Renormalise a product after this many factors: 8 factors in [2^-100, 2^100] times a
/// mantissa in [1, 2) stay inside 2^±808.
pub(super) const RENORM_EVERY: u32 = 8;
/// Mantissa bits of an f64.
pub(super) const MANTISSA: u64 = 0x000f_ffff_ffff_ffff;
/// Bits of 1.0 (biased exponent 1023, zero mantissa).
pub(super) const ONE_BITS: u64 = 0x3ff0_0000_0000_0000;

impl Products {
    pub(super) fn new(rows: usize, len: usize) -> Self {
        Self {
            p: vec![1.0; rows * len],
            exp2: vec![0; rows * len],
            since: vec![0; rows],
            ln_count: vec![0.0; rows],
            refs: vec![0; rows],
        }
    }

    /// Multiplies the factors `a` (all in [PROD_LO, PROD_HI]) of one reference with `c`
    /// neighbours into row `r`.
    #[inline(always)]
    pub(super) fn multiply(&mut self, r: usize, a: &[f64], c: u32) {
        let len = a.len();
        let p = &mut self.p[r * len..(r + 1) * len];
        for (x, y) in p.iter_mut().zip(a) {
            *x *= y;
        }
        self.ln_count[r] += f64::from(c).ln();
        self.refs[r] += 1;
        self.since[r] += 1;
        if self.since[r] == RENORM_EVERY {
            self.since[r] = 0;
            let exp2 = &mut self.exp2[r * len..(r + 1) * len];
            for (x, e) in p.iter_mut().zip(exp2) {
                let b = x.to_bits();
                *e += ((b >> 52) & 0x7ff) as i64 - 1023;
                *x = f64::from_bits((b & MANTISSA) | ONE_BITS);
            }
        }
    }

    /// Adds `half·(ln Π a − Σ ln c)` and the reference counts to `totals`.
    pub(super) fn fold_into(&self, totals: &mut Totals, half: f64, len: usize) {
        for (r, &refs) in self.refs.iter().enumerate() {
            if refs == 0 {
                continue;
            }
            let span = r * len..(r + 1) * len;
            let (p, exp2) = (&self.p[span.clone()], &self.exp2[span.clone()]);
            let (lyap, count) = (&mut totals.lyap[span.clone()], &mut totals.count[span]);
            for t in 0..len {
                let ln_prod = p[t].ln() + exp2[t] as f64 * std::f64::consts::LN_2;
                lyap[t] += half * (ln_prod - self.ln_count[r]);
                count[t] += refs;
            }
        }
    }
}

/// Whether every value is in [`PROD_LO`, `PROD_HI`] (no early exit: the loop vectorises).
#[inline(always)]
pub(super) fn in_product_range(a: &[f64]) -> bool {
    a.iter()
        .fold(true, |ok, &v| ok & (PROD_LO..=PROD_HI).contains(&v))
}

/// `e_t = (a_t − b_t)²`; returns the number of exact zeros.
#[inline(always)]
pub(super) fn squared_differences(a: &[f64], b: &[f64], e: &mut [f64]) -> usize {
    let mut zeros = 0;
    for ((e, x), y) in e.iter_mut().zip(a).zip(b) {
        let v = (x - y) * (x - y);
        *e = v;
        zeros += usize::from(v == 0.0);
    }
    zeros
}

/// `d += e` (the pair's squared distance gains one coordinate, every Δn at once).
#[inline(always)]
pub(super) fn extend(d: &mut [f64], e: &[f64]) {
    for (x, y) in d.iter_mut().zip(e) {
        *x += y;
    }
}

/// `d += e` (unless `e` is empty) and `acc += d` (TISEAN: squared distances) or
/// `acc += √d` (pdamp: distances), fused.
pub(super) fn extend_and_accumulate(d: &mut [f64], e: &[f64], acc: &mut [f64], tisean: bool) {
    match (e.is_empty(), tisean) {
        (true, true) => acc.iter_mut().zip(d.iter()).for_each(|(a, x)| *a += x),
        (true, false) => acc
            .iter_mut()
            .zip(d.iter())
            .for_each(|(a, x)| *a += x.sqrt()),
        (false, true) => {
            for ((x, y), a) in d.iter_mut().zip(e).zip(acc) {
                let v = *x + y;
                *x = v;
                *a += v;
            }
        }
        (false, false) => {
            for ((x, y), a) in d.iter_mut().zip(e).zip(acc) {
                let v = *x + y;
                *x = v;
                *a += v.sqrt();
            }
        }
    }
}

/// Sums of ln-terms and reference counts, laid out [dim][eps][Δn].
pub(super) struct Totals {
    pub(super) lyap: Vec<f64>,
    pub(super) count: Vec<u64>,
}

impl Totals {
    pub(super) fn new(n: usize) -> Self {
        Self {
            lyap: vec![0.0; n],
            count: vec![0; n],
        }
    }
    pub(super) fn add(&mut self, other: &Totals) {
        for (a, b) in self.lyap.iter_mut().zip(&other.lyap) {
            *a += b;
        }
        for (a, b) in self.count.iter_mut().zip(&other.count) {
            *a += b;
        }
    }
}
