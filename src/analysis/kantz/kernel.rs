//! The kernel of [`super::kantz`]: neighbours from a kd-tree on the first two delay
//! coordinates, the per-pair squared coordinate differences reused for every dimension m and
//! radius ε, and the running products that take one logarithm per (m, ε, Δn) and chunk (the
//! module documentation of [`super`] explains why this is fast). References run in fixed
//! chunks in parallel and are combined in chunk order, so results do not depend on the
//! thread count.

use kiddo::{ImmutableKdTree, SquaredEuclidean};
use rayon::prelude::*;

use super::arith::*;
use super::buffers::{Grouped, Job, Scratch};
use super::options::{KantzCurve, KantzDefinition, KantzResult};
use super::rms::{finish_reference, reference_rms};
use crate::analysis::outside_theiler_window;
use crate::error::AnalysisError;
use crate::simd::Simd;

/// References per parallel work unit (fixed, so that sums do not depend on thread count).
const CHUNK: usize = 1024;

pub(super) fn run<const K: usize>(job: &Job) -> Result<Totals, AnalysisError> {
    let tau = job.opts.tau;
    let s = job.s;
    let pts: Vec<[f64; K]> = (0..job.n_cand)
        .map(|i| std::array::from_fn(|k| s[i + k * tau]))
        .collect();
    let tree: ImmutableKdTree<f64, K> = ImmutableKdTree::new_from_slice(&pts)
        .map_err(|e| AnalysisError::NoResult(format!("kd-tree construction failed: {e:?}")))?;
    let n_chunks = job.n_ref.div_ceil(CHUNK);
    let partials: Vec<Totals> = (0..n_chunks)
        .into_par_iter()
        .map(|c| {
            chunk::<K>(
                job,
                &tree,
                &pts,
                c * CHUNK..((c + 1) * CHUNK).min(job.n_ref),
            )
        })
        .collect();
    let mut totals = Totals::new(job.total_len());
    for p in &partials {
        totals.add(p);
    }
    Ok(totals)
}

fn chunk<const K: usize>(
    job: &Job,
    tree: &ImmutableKdTree<f64, K>,
    pts: &[[f64; K]],
    refs: std::ops::Range<usize>,
) -> Totals {
    let o = job.opts;
    let span = o.steps + (o.m_max - 1) * o.tau;
    let rows = job.n_dims() * job.eps2.len();
    let mut sc = Scratch {
        nb: Vec::with_capacity(256),
        e: vec![0.0; span + 1],
        d: vec![0.0; job.len()],
        acc: vec![0.0; job.total_len()],
        pairs: vec![0; rows],
        zeros: vec![0; job.total_len()],
        zero_slot: vec![false; job.n_dims()],
        first_bin: vec![usize::MAX; job.n_dims()],
        grouped: Grouped::new(job, span + 1),
    };
    let tisean = o.definition == KantzDefinition::TiseanRms;
    let simd = Simd::detect();
    let mut totals = Totals::new(job.total_len());
    let mut products = Products::new(rows, job.len());
    // Query radius slightly above ε_max² so that kiddo's rounding cannot drop a pair that the
    // exact test below accepts; the test below is the definition.
    let r2 = job.eps2[job.eps2.len() - 1] * (1.0 + 1e-9);
    for i in refs {
        sc.nb.clear();
        tree.query(&pts[i])
            .within::<SquaredEuclidean<f64>>(r2)
            .unsorted()
            .visit(|r| {
                let j = r.item as usize;
                if outside_theiler_window(i, j, job.theiler) {
                    sc.nb.push(r.item);
                }
            });
        if sc.nb.is_empty() {
            continue;
        }
        sc.nb.sort_unstable();
        if tisean {
            reference_rms(job, i, &mut sc, simd);
        } else {
            reference(job, i, &mut sc);
        }
        finish_reference(job, &mut sc, &mut products, &mut totals, simd);
    }
    products.fold_into(&mut totals, job.half(), job.len());
    totals
}

/// Bins the pairs of reference `i` (its neighbours are in `sc.nb`) into `sc.acc`/`sc.pairs`.
fn reference(job: &Job, i: usize, sc: &mut Scratch) {
    let o = job.opts;
    let s = job.s;
    let (tau, len) = (o.tau, job.len());
    let n_eps = job.eps2.len();
    let eps2_max = job.eps2[n_eps - 1];
    let tisean = o.definition == KantzDefinition::TiseanRms;
    sc.first_bin.fill(usize::MAX);
    sc.zero_slot.fill(false);
    for idx in 0..sc.nb.len() {
        let j = sc.nb[idx] as usize;
        // Squared distance in dimension m, extended coordinate by coordinate (TISEAN order).
        let mut d2 = 0.0;
        let mut m_top = 0;
        for k in 0..o.m_max {
            let dk = s[i + k * tau] - s[j + k * tau];
            d2 += dk * dk;
            if d2 > eps2_max {
                break;
            }
            m_top = k + 1;
        }
        if m_top < o.m_min {
            continue;
        }
        // e_t for t = 0 ..= steps + (m_top−1)τ
        let t_max = o.steps + (m_top - 1) * tau;
        let e = &mut sc.e[..=t_max];
        let has_zero = squared_differences(&s[i..=i + t_max], &s[j..=j + t_max], e) > 0;
        let e = &sc.e[..=t_max];
        sc.d.copy_from_slice(&e[..len]);
        // the same additions in the same order as a direct sum over k (bitwise equal)
        let mut d2 = e[0];
        for m in 1..=m_top {
            let off = (m - 1) * tau;
            let shifted: &[f64] = if m > 1 { &e[off..off + len] } else { &[] };
            if m > 1 {
                d2 += e[off];
            }
            if m < o.m_min {
                extend(&mut sc.d, shifted);
                continue;
            }
            // smallest ε containing this pair in dimension m
            let l0 = job.eps2.partition_point(|&e2| e2 < d2);
            if l0 >= n_eps {
                break;
            }
            let slot = m - o.m_min;
            sc.first_bin[slot] = sc.first_bin[slot].min(l0);
            let r = slot * n_eps + l0;
            sc.pairs[r] += 1;
            let acc = &mut sc.acc[r * len..(r + 1) * len];
            extend_and_accumulate(&mut sc.d, shifted, acc, tisean);
            if has_zero {
                sc.zero_slot[slot] = true;
                for (z, &dv) in sc.zeros[r * len..(r + 1) * len].iter_mut().zip(&sc.d) {
                    *z += u32::from(dv == 0.0);
                }
            }
        }
    }
}

pub(super) fn assemble(job: &Job, eps: &[f64], range: f64, totals: Totals) -> KantzResult {
    let o = job.opts;
    let mut curves = Vec::with_capacity(eps.len() * job.n_dims());
    for (l, &e) in eps.iter().enumerate() {
        for m in o.m_min..=o.m_max {
            let row = job.row(m - o.m_min, l);
            let count = totals.count[row..row + job.len()].to_vec();
            let s = (0..job.len())
                .map(|t| (count[t] > 0).then(|| totals.lyap[row + t] / count[t] as f64))
                .collect();
            curves.push(KantzCurve {
                m,
                eps: e * range,
                s,
                count,
            });
        }
    }
    KantzResult {
        curves,
        range,
        definition: o.definition,
    }
}
