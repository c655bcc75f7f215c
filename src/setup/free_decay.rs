//! A free-decay run (`excitation.kind = "free"`): the primary's displacement is collected from
//! t = 0 at [`SAMPLES_PER_PERIOD`] samples per period of the run's clock (f0 by default), and
//! its decay envelope per cycle — amplitude, logarithmic decrement, equivalent damping ratio
//! ζ(amplitude), [`crate::analysis::decay`] — goes into the summary's `decay` block
//! (`decay.csv` in a run folder). The caller's own samples are passed on unchanged.

use crate::analysis::decay::{decay_envelope, DecayOptions};
use crate::error::SimError;
use crate::model::{RunOptions, RunSummary, StrobePoint};
use crate::observe::{GrainState, Observer, Sample, SampleKind, Tee};

/// Samples of the primary's displacement per period of the clock: the envelope's peaks are
/// refined by a parabola through three samples, whose error at 64 samples per period is
/// ~(2π/64)²/24 ≈ 4e-4 of the amplitude and cancels in the ratio of successive peaks.
pub const SAMPLES_PER_PERIOD: f64 = 64.0;

/// Runs a free decay with `run` (the simulation, given its observer and sampling), collecting
/// the primary's displacement from t = 0 at the clock `frequency_hz` (Hz) ×
/// [`SAMPLES_PER_PERIOD`] for the envelope; `obs` receives the samples `opts` asks for.
///
/// # Errors
/// The simulation's errors. An envelope that cannot be measured (fewer than two cycles above
/// its floor: an overdamped primary, a bed that stops it at once) is a warning of the summary,
/// not an error.
pub(super) fn simulate_free(
    frequency_hz: f64,
    obs: &mut dyn Observer,
    opts: &RunOptions,
    run: impl FnOnce(&mut dyn Observer, &RunOptions) -> Result<RunSummary, SimError>,
) -> Result<RunSummary, SimError> {
    let clock = 1.0 / (SAMPLES_PER_PERIOD * frequency_hz);
    // the collector's interval: the clock, or the caller's interval divided into whole steps
    let (interval, stride) = match opts.sample_interval_s {
        None => (clock, None),
        Some(d) => {
            let k = (d / clock).ceil().max(1.0);
            (d / k, Some(k as u64))
        }
    };
    let mut caller = Thinned {
        inner: obs,
        stride,
        from_s: opts.sample_from_s,
        count: 0,
    };
    let mut primary = PrimaryTrace::default();
    let mut tee = Tee {
        observers: vec![&mut caller, &mut primary],
    };
    let mut s = run(&mut tee, &RunOptions::full_series(interval))?;
    drop(tee);
    match decay_envelope(&primary.t_s, &primary.z_m, &DecayOptions::default()) {
        Ok(env) => s.decay = Some(env),
        Err(e) => s
            .warnings
            .push(format!("free decay: no decay envelope measured: {e}")),
    }
    Ok(s)
}

/// The primary's displacement z(t) (s, m) of every sample.
#[derive(Default)]
struct PrimaryTrace {
    t_s: Vec<f64>,
    z_m: Vec<f64>,
}

impl Observer for PrimaryTrace {
    fn sample(&mut self, s: &Sample) -> Result<(), SimError> {
        self.t_s.push(s.time_s);
        self.z_m.push(s.box_z_m);
        Ok(())
    }
}

/// Passes everything on to `inner`, the samples only every `stride`-th from `from_s` on (none
/// when `stride` is `None`: the caller asked for no samples).
struct Thinned<'a> {
    inner: &'a mut dyn Observer,
    stride: Option<u64>,
    from_s: f64,
    count: u64,
}

impl Observer for Thinned<'_> {
    fn start(&mut self, kind: SampleKind) -> Result<(), SimError> {
        self.inner.start(kind)
    }
    fn sample(&mut self, s: &Sample) -> Result<(), SimError> {
        let Some(stride) = self.stride else {
            return Ok(());
        };
        let keep = self.count.is_multiple_of(stride);
        self.count += 1;
        if keep && s.time_s >= self.from_s {
            self.inner.sample(s)
        } else {
            Ok(())
        }
    }
    fn strobe(&mut self, p: &StrobePoint) -> Result<(), SimError> {
        self.inner.strobe(p)
    }
    fn snapshot(&mut self, g: &GrainState<'_>) -> Result<(), SimError> {
        self.inner.snapshot(g)
    }
    fn progress(&mut self, t: f64, d: f64) -> Result<(), SimError> {
        self.inner.progress(t, d)
    }
    fn finish(&mut self) -> Result<(), SimError> {
        self.inner.finish()
    }
}
