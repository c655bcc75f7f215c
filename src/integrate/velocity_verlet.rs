//! Velocity Verlet (kick–drift–kick) on structure-of-arrays `[f64; 3]` buffers (2.2.4–2.2.5).
//!
//! One step: v ← v + (dt/2) F/m; x ← x + dt v; forces F(x, v); v ← v + (dt/2) F/m.
//! Velocity-dependent (damping) forces are evaluated with the half-step velocity, as in
//! LAMMPS's `fix nve/sphere`. The same kernels advance ω with τ/I.

use crate::simd::WritePrefetch;

/// Half kick v ← v + h · f · inv_m for every grain (h = dt/2).
///
/// # Formula
/// v(t + dt/2) = v(t) + (dt/2) F(t)/m  (2.2.5)
///
/// # Units
/// `v` m/s (or rad/s), `f` N (or N m), `inv_m` 1/kg (or 1/(kg m²)), `h` s.
#[inline]
pub fn half_kick(v: &mut [[f64; 3]], f: &[[f64; 3]], inv_m: &[f64], h: f64) {
    for ((v, f), &im) in v.iter_mut().zip(f).zip(inv_m) {
        let s = h * im;
        v[0] += s * f[0];
        v[1] += s * f[1];
        v[2] += s * f[2];
    }
}

/// Drift x ← x + dt · v.
///
/// # Formula
/// x(t + dt) = x(t) + dt v(t + dt/2)  (2.2.4)
#[inline]
pub fn drift(x: &mut [[f64; 3]], v: &[[f64; 3]], dt: f64) {
    for (x, v) in x.iter_mut().zip(v) {
        x[0] += dt * v[0];
        x[1] += dt * v[1];
        x[2] += dt * v[2];
    }
}

/// Fused half kick + drift: v ← v + h f inv_m; x ← x + dt v, returning the largest squared
/// displacement |x − x_ref − shift|² (m²) for the Verlet-list validity check, in one pass.
/// Also writes the predicted full-step velocity v_pred = v(t + dt/2) + h f(t)/m (an O(dt²)
/// estimate of v(t + dt)) used by the velocity-dependent (dissipative) contact forces.
/// With `prefetch`, the lines of `x` and `v_pred` that the loop will store into
/// [`WritePrefetch::AHEAD`] grains later are asked for first (no value changes).
#[allow(clippy::too_many_arguments)]
#[inline]
pub fn kick_drift(
    x: &mut [[f64; 3]],
    v: &mut [[f64; 3]],
    v_pred: &mut [[f64; 3]],
    f: &[[f64; 3]],
    inv_m: &[f64],
    (h, dt): (f64, f64),
    reference: &[[f64; 3]],
    shift: [f64; 3],
    prefetch: Option<WritePrefetch>,
) -> f64 {
    let mut worst = 0.0f64;
    let tracked = reference.len() == x.len();
    for k in 0..x
        .len()
        .min(v.len())
        .min(v_pred.len())
        .min(f.len())
        .min(inv_m.len())
    {
        if let Some(p) = prefetch {
            p.element(x, k + WritePrefetch::AHEAD);
            p.element(v_pred, k + WritePrefetch::AHEAD);
        }
        let (x, v, vp, f, im) = (&mut x[k], &mut v[k], &mut v_pred[k], &f[k], inv_m[k]);
        let s = h * im;
        v[0] += s * f[0];
        v[1] += s * f[1];
        v[2] += s * f[2];
        *vp = [v[0] + s * f[0], v[1] + s * f[1], v[2] + s * f[2]];
        x[0] += dt * v[0];
        x[1] += dt * v[1];
        x[2] += dt * v[2];
        if tracked {
            let r = reference[k];
            let d = [
                x[0] - r[0] - shift[0],
                x[1] - r[1] - shift[1],
                x[2] - r[2] - shift[2],
            ];
            // a plain select, not `f64::max` (whose NaN handling costs three more
            // instructions on the loop's dependency chain); NaN is skipped by both
            let d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            worst = if d2 > worst { d2 } else { worst };
        }
    }
    if tracked {
        worst
    } else {
        f64::INFINITY
    }
}

/// Half kick of ω with the predicted full-step value (and the prefetch), as in
/// [`kick_drift`].
#[inline]
pub fn half_kick_predict(
    v: &mut [[f64; 3]],
    v_pred: &mut [[f64; 3]],
    f: &[[f64; 3]],
    inv_m: &[f64],
    h: f64,
    prefetch: Option<WritePrefetch>,
) {
    for k in 0..v.len().min(v_pred.len()).min(f.len()).min(inv_m.len()) {
        if let Some(p) = prefetch {
            p.element(v_pred, k + WritePrefetch::AHEAD);
        }
        let (v, vp, f, im) = (&mut v[k], &mut v_pred[k], &f[k], inv_m[k]);
        let s = h * im;
        v[0] += s * f[0];
        v[1] += s * f[1];
        v[2] += s * f[2];
        *vp = [v[0] + s * f[0], v[1] + s * f[1], v[2] + s * f[2]];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn free_fall_is_exact() {
        // constant force: velocity Verlet is exact (x = ½ g t²)
        let (mut x, mut v) = (vec![[0.0; 3]], vec![[0.0; 3]]);
        let f = vec![[0.0, 0.0, -9.8]];
        let dt = 0.01;
        for _ in 0..100 {
            half_kick(&mut v, &f, &[1.0], dt / 2.0);
            drift(&mut x, &v, dt);
            half_kick(&mut v, &f, &[1.0], dt / 2.0);
        }
        assert!((x[0][2] + 0.5 * 9.8).abs() < 1e-12);
        assert!((v[0][2] + 9.8).abs() < 1e-12);
    }

    #[test]
    fn the_write_prefetch_changes_no_value() {
        // 40 grains (more than WritePrefetch::AHEAD, so that the prefetch runs and stops
        // at the end); with and without it the same bits
        let n = 40;
        let x0: Vec<[f64; 3]> = (0..n)
            .map(|i| [i as f64 * 0.1, 0.3, -0.2 * i as f64])
            .collect();
        let v0: Vec<[f64; 3]> = (0..n).map(|i| [0.01 * i as f64, -1.0, 0.5]).collect();
        let f: Vec<[f64; 3]> = (0..n).map(|i| [1.0, i as f64, -9.8]).collect();
        let im: Vec<f64> = (0..n).map(|i| 1.0 / (1.0 + i as f64)).collect();
        let run = |p: Option<WritePrefetch>| {
            let (mut x, mut v, mut vp) = (x0.clone(), v0.clone(), vec![[0.0; 3]; n]);
            let worst = kick_drift(
                &mut x,
                &mut v,
                &mut vp,
                &f,
                &im,
                (0.5e-3, 1e-3),
                &x0,
                [0.0; 3],
                p,
            );
            let (mut w, mut wp) = (v0.clone(), vec![[0.0; 3]; n]);
            half_kick_predict(&mut w, &mut wp, &f, &im, 0.5e-3, p);
            (x, v, vp, worst, w, wp)
        };
        let plain = run(None);
        assert!(
            plain.3 > 0.0 && plain.0 != x0,
            "the kernel moved the grains"
        );
        if let Some(p) = WritePrefetch::detect() {
            assert_eq!(run(Some(p)), plain);
        }
    }
}
