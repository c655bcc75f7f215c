//! The accumulators of a run: compensated sums of the base work, the viscous and impact
//! losses (whole run and steady state), the counts of impacts and events, and the extrema
//! of the box.

/// Compensated (Kahan–Babuška) sum, so that 1e6 forcing periods do not drift.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Sum {
    pub(super) s: f64,
    pub(super) c: f64,
}

impl Sum {
    #[inline]
    pub(super) fn add(&mut self, x: f64) {
        let t = self.s + x;
        if self.s.abs() >= x.abs() {
            self.c += (self.s - t) + x;
        } else {
            self.c += (x - t) + self.s;
        }
        self.s = t;
    }
    pub(super) fn value(&self) -> f64 {
        self.s + self.c
    }
}

/// Accumulators of a run.
#[derive(Debug, Default)]
pub(super) struct Ledger {
    pub(super) base_work: Sum,
    pub(super) viscous: Sum,
    pub(super) impact: Sum,
    pub(super) steady_base: Sum,
    pub(super) steady_viscous: Sum,
    pub(super) steady_impact: Sum,
    pub(super) impacts: u64,
    pub(super) steady_impacts: u64,
    pub(super) events: u64,
    pub(super) zmax: f64,
    pub(super) zmin: f64,
}
