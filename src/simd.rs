//! Instruction sets the hot loops are compiled for, chosen once at run time.
//!
//! A loop written once (`#[inline(always)]`) is compiled a second and third time inside a
//! `#[target_feature]` function (AVX2, AVX-512) and called through a `match` on [`Simd`]. No
//! variant enables fused multiply–add, so every variant computes bitwise the same numbers:
//! only the speed depends on the machine.

/// The widest instruction set this processor offers to the pdamp loops.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Simd {
    /// The target's baseline (SSE2 on x86-64).
    Baseline,
    /// AVX2 (256-bit vectors).
    #[cfg(target_arch = "x86_64")]
    Avx2,
    /// AVX-512 F (512-bit vectors; detected only with AVX2).
    #[cfg(target_arch = "x86_64")]
    Avx512,
}

impl Simd {
    /// The widest set the processor running this program has.
    pub fn detect() -> Self {
        #[cfg(target_arch = "x86_64")]
        {
            let avx2 = std::arch::is_x86_feature_detected!("avx2");
            if avx2 && std::arch::is_x86_feature_detected!("avx512f") {
                return Simd::Avx512;
            }
            if avx2 {
                return Simd::Avx2;
            }
        }
        Simd::Baseline
    }

    /// Every set this processor can run, narrowest first (for tests that compare them).
    pub fn available() -> Vec<Simd> {
        let mut v = vec![Simd::Baseline];
        #[cfg(target_arch = "x86_64")]
        {
            if std::arch::is_x86_feature_detected!("avx2") {
                v.push(Simd::Avx2);
                if std::arch::is_x86_feature_detected!("avx512f") {
                    v.push(Simd::Avx512);
                }
            }
        }
        v
    }
}
