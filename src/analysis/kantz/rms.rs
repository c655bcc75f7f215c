//! The per-reference work of the TISEAN (RMS) definition ([`reference_rms`]) and the finish
//! of every reference ([`finish_reference`]): the ε bins accumulated over increasing ε and
//! the ln(sum/count) terms of S(m, ε, Δn) (4.1.7) added, in rescaled units; each built for
//! AVX2 beside the baseline (no FMA: bitwise the same sums).

use super::arith::*;
use super::buffers::{accumulate_squared_differences, Job, Scratch, SpreadTarget};
use super::options::MAX_DIMENSION;
use crate::simd::Simd;

/// [`reference`] for the TISEAN (RMS) definition: the same bins and sums, but each pair's
/// `e` is added once into the sum of its bin pattern ([`Grouped`]) instead of once per
/// dimension, and the shifted sums `Σ_{k<m} e_{Δn+kτ}` are formed once per (m, ε) bin.
/// Exactly the same pairs and counts as [`reference`]; the sums differ only in the order of
/// the additions (rounding, ~1e-16 relative).
pub(super) fn reference_rms(job: &Job, i: usize, sc: &mut Scratch, simd: Simd) {
    match simd {
        #[cfg(target_arch = "x86_64")]
        // SAFETY: a `Simd::Avx2` carries the proof (`HasAvx2`) that this processor has AVX2.
        Simd::Avx2(_) => unsafe { reference_rms_avx2(job, i, sc) },
        Simd::Baseline => reference_rms_impl(job, i, sc),
    }
}

/// [`reference_rms_impl`] compiled for AVX2 (4 f64 lanes; no FMA, so the sums are bitwise
/// those of the baseline build).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn reference_rms_avx2(job: &Job, i: usize, sc: &mut Scratch) {
    reference_rms_impl(job, i, sc);
}

#[inline(always)]
fn reference_rms_impl(job: &Job, i: usize, sc: &mut Scratch) {
    let o = job.opts;
    let s = job.s;
    let (tau, len) = (o.tau, job.len());
    let n_eps = job.eps2.len();
    let n_dims = job.n_dims();
    let eps2_max = job.eps2[n_eps - 1];
    let g = &mut sc.grouped;
    let width = g.width;
    sc.first_bin.fill(usize::MAX);
    sc.zero_slot.fill(false);
    let mut bins = [0u16; MAX_DIMENSION];
    let use_table = !g.table.is_empty();
    for idx in 0..sc.nb.len() {
        let j = sc.nb[idx] as usize;
        // Squared distance in dimension m, extended coordinate by coordinate (TISEAN order),
        // and the pair's ε bin in each dimension slot.
        let mut d2 = 0.0;
        let mut m_top = 0;
        let mut code = 0usize;
        let mut weight = 1usize;
        for k in 0..o.m_max {
            let dk = s[i + k * tau] - s[j + k * tau];
            d2 += dk * dk;
            if d2 > eps2_max {
                break;
            }
            m_top = k + 1;
            if m_top >= o.m_min {
                let l = job.eps2.partition_point(|&e2| e2 < d2);
                bins[m_top - o.m_min] = l as u16;
                code += l * weight;
                weight *= n_eps + 1;
            }
        }
        if m_top < o.m_min {
            continue;
        }
        for b in &mut bins[m_top + 1 - o.m_min..n_dims] {
            *b = n_eps as u16;
            code += n_eps * weight;
            weight *= n_eps + 1;
        }
        let t_max = o.steps + (m_top - 1) * tau;
        let (a, b) = (&s[i..=i + t_max], &s[j..=j + t_max]);
        let zeros = if use_table {
            let slot = &mut g.table[code];
            if *slot == 0 {
                g.codes.push(code);
                g.bins.extend_from_slice(&bins[..n_dims]);
                g.m_top.push(m_top);
                g.npairs.push(0);
                g.sum.resize(g.sum.len() + width, 0.0);
                *slot = g.npairs.len() as u32;
            }
            let grp = *slot as usize - 1;
            g.npairs[grp] += 1;
            if job.distinct {
                // no zeros possible: added group by group after the loop
                g.batch.push((grp as u32, j as u32));
                continue;
            }
            let row = &mut g.sum[grp * width..grp * width + t_max + 1];
            accumulate_squared_differences(a, b, row, true)
        } else {
            let e = &mut sc.e[..=t_max];
            let z = squared_differences(a, b, e);
            let mut target = SpreadTarget {
                pairs: &mut sc.pairs,
                first_bin: &mut sc.first_bin,
            };
            g.spread(job, &bins[..n_dims], m_top, e, 1, &mut target);
            z
        };
        if zeros > 0 {
            // rare: a repeated value; count the Δn at which the pair's distance is exactly 0
            let e = &mut sc.e[..=t_max];
            squared_differences(a, b, e);
            sc.d.copy_from_slice(&e[..len]);
            for m in 1..=m_top {
                let off = (m - 1) * tau;
                if m > 1 {
                    extend(&mut sc.d, &e[off..off + len]);
                }
                if m < o.m_min {
                    continue;
                }
                let slot = m - o.m_min;
                let r = slot * n_eps + usize::from(bins[slot]);
                sc.zero_slot[slot] = true;
                for (z, &dv) in sc.zeros[r * len..(r + 1) * len].iter_mut().zip(&sc.d) {
                    *z += u32::from(dv == 0.0);
                }
            }
        }
    }
    if !g.batch.is_empty() {
        g.accumulate(job, i);
    }
    // spread the groups over the (slot, ε) bins, in the order they were first seen
    if use_table {
        let mut target = SpreadTarget {
            pairs: &mut sc.pairs,
            first_bin: &mut sc.first_bin,
        };
        let gsum = std::mem::take(&mut g.sum);
        let gbins = std::mem::take(&mut g.bins);
        for grp in 0..g.npairs.len() {
            let m_top = g.m_top[grp];
            let n = o.steps + (m_top - 1) * tau + 1;
            g.spread(
                job,
                &gbins[grp * n_dims..(grp + 1) * n_dims],
                m_top,
                &gsum[grp * width..grp * width + n],
                g.npairs[grp],
                &mut target,
            );
        }
        g.sum = gsum;
        g.bins = gbins;
        for &c in &g.codes {
            g.table[c] = 0;
        }
        g.codes.clear();
        g.bins.clear();
        g.m_top.clear();
        g.npairs.clear();
        g.sum.clear();
    }
    // per (slot, ε) bin: Σ over its pairs of ‖·‖²_m at every Δn = Σ_{k<m} bsum_{Δn+kτ}
    for slot in 0..n_dims {
        let m = o.m_min + slot;
        for l in 0..n_eps {
            let r = slot * n_eps + l;
            if !g.touched[r] {
                continue;
            }
            g.touched[r] = false;
            let n = o.steps + (m - 1) * tau + 1;
            let row = &mut g.bsum[r * width..r * width + n];
            let acc = &mut sc.acc[r * len..(r + 1) * len];
            acc.copy_from_slice(&row[..len]);
            for k in 1..m {
                extend(acc, &row[k * tau..k * tau + len]);
            }
            row.fill(0.0);
        }
    }
}

/// Accumulates the bins of the current reference over increasing ε and adds its
/// `ln(sum/count)` terms (through `products`, or directly), then clears the scratch rows.
pub(super) fn finish_reference(
    job: &Job,
    sc: &mut Scratch,
    products: &mut Products,
    totals: &mut Totals,
    simd: Simd,
) {
    match simd {
        #[cfg(target_arch = "x86_64")]
        // SAFETY: a `Simd::Avx2` carries the proof (`HasAvx2`) that this processor has AVX2.
        Simd::Avx2(_) => unsafe { finish_reference_avx2(job, sc, products, totals) },
        Simd::Baseline => finish_reference_impl(job, sc, products, totals),
    }
}

/// [`finish_reference_impl`] compiled for AVX2 (no FMA: bitwise the baseline's results).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn finish_reference_avx2(
    job: &Job,
    sc: &mut Scratch,
    products: &mut Products,
    totals: &mut Totals,
) {
    finish_reference_impl(job, sc, products, totals);
}

#[inline(always)]
fn finish_reference_impl(
    job: &Job,
    sc: &mut Scratch,
    products: &mut Products,
    totals: &mut Totals,
) {
    let len = job.len();
    let n_eps = job.eps2.len();
    let half = job.half();
    for slot in 0..job.n_dims() {
        let l_first = sc.first_bin[slot];
        if l_first == usize::MAX {
            continue;
        }
        let zero = sc.zero_slot[slot];
        let mut c = 0u32;
        for l in l_first..n_eps {
            let r = slot * n_eps + l;
            let row = r * len;
            c += sc.pairs[r];
            if l > l_first {
                let (lo, hi) = sc.acc.split_at_mut(row);
                extend(&mut hi[..len], &lo[row - len..]);
                if zero {
                    let (lo, hi) = sc.zeros.split_at_mut(row);
                    for (h, p) in hi[..len].iter_mut().zip(&lo[row - len..]) {
                        *h += p;
                    }
                }
            }
            let a = &sc.acc[row..row + len];
            let (lyap, count) = (
                &mut totals.lyap[row..row + len],
                &mut totals.count[row..row + len],
            );
            if zero {
                // exact per-Δn counts: pairs at distance 0 are skipped at that Δn
                for (t, (&z, &at)) in sc.zeros[row..row + len].iter().zip(a).enumerate() {
                    let ct = c - z;
                    if ct > 0 {
                        lyap[t] += half * (at / f64::from(ct)).ln();
                        count[t] += 1;
                    }
                }
            } else if in_product_range(a) {
                products.multiply(r, a, c);
            } else {
                for (t, &at) in a.iter().enumerate() {
                    lyap[t] += half * (at / f64::from(c)).ln();
                    count[t] += 1;
                }
            }
        }
        for l in l_first..n_eps {
            let r = slot * n_eps + l;
            sc.acc[r * len..(r + 1) * len].fill(0.0);
            sc.pairs[r] = 0;
            if zero {
                sc.zeros[r * len..(r + 1) * len].fill(0);
            }
        }
    }
}
