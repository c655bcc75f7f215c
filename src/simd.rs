//! Instruction sets the hot loops are compiled for, chosen once at run time.
//!
//! A loop written once (`#[inline(always)]`) is compiled a second time inside a
//! `#[target_feature(enable = "avx2")]` function and called through a `match` on [`Simd`].
//! Neither variant enables fused multiply–add, so both compute bitwise the same numbers: only
//! the speed depends on the machine. (AVX-512 was measured on the DEM loops, 8 and 16 lanes:
//! no faster than AVX2 on the development machine, so it has no variant.)

/// The widest instruction set this processor offers to the pdamp loops.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Simd {
    /// The target's baseline (SSE2 on x86-64).
    Baseline,
    /// AVX2 (256-bit vectors).
    #[cfg(target_arch = "x86_64")]
    Avx2,
}

impl Simd {
    /// The widest set the processor running this program has.
    pub fn detect() -> Self {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            return Simd::Avx2;
        }
        Simd::Baseline
    }

    /// Every set this processor can run, narrowest first (for tests that compare them).
    pub fn available() -> Vec<Simd> {
        match Simd::detect() {
            Simd::Baseline => vec![Simd::Baseline],
            #[cfg(target_arch = "x86_64")]
            Simd::Avx2 => vec![Simd::Baseline, Simd::Avx2],
        }
    }
}
