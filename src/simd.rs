//! Instruction sets the hot loops are compiled for, chosen once at run time.
//!
//! A loop written once (`#[inline(always)]`) is compiled a second time inside a
//! `#[target_feature(enable = "avx2")]` function and called through a `match` on [`Simd`].
//! Neither variant enables fused multiply–add, so both compute bitwise the same numbers: only
//! the speed depends on the machine. (AVX-512 was measured on the DEM loops, 8 and 16 lanes:
//! no faster than AVX2 on the development machine, so it has no variant.)

/// The widest instruction set this processor offers to the pdamp loops.
///
/// A value is a proof: [`Simd::Avx2`] carries a [`HasAvx2`], which only [`Simd::detect`] can
/// make, after asking the processor — so safe code holding any `Simd` may run the kernels it
/// names.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Simd {
    /// The target's baseline (SSE2 on x86-64).
    Baseline,
    /// AVX2 (256-bit vectors), which this processor has.
    #[cfg(target_arch = "x86_64")]
    Avx2(HasAvx2),
}

/// The processor running this program has AVX2 (made only by [`Simd::detect`]; the private
/// field keeps every other code from making one):
///
/// ```compile_fail
/// // error: the field of `HasAvx2` is private — no proof without asking the processor
/// let claim = pdamp::simd::Simd::Avx2(pdamp::simd::HasAvx2(()));
/// ```
#[cfg(target_arch = "x86_64")]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct HasAvx2(());

impl Simd {
    /// The widest set the processor running this program has.
    pub fn detect() -> Self {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            return Simd::Avx2(HasAvx2(()));
        }
        Simd::Baseline
    }

    /// Every set this processor can run, narrowest first (for tests that compare them).
    pub fn available() -> Vec<Simd> {
        match Simd::detect() {
            Simd::Baseline => vec![Simd::Baseline],
            #[cfg(target_arch = "x86_64")]
            avx2 @ Simd::Avx2(_) => vec![Simd::Baseline, avx2],
        }
    }
}

/// Write prefetches: a request for a cache line in the exclusive state some iterations
/// before a loop stores into it (x86-64 `PREFETCHW`). Only where the processor has the
/// instruction (CPUID 8000_0001h ECX bit 8, PRFCHW) can a value of this type be made.
///
/// Why: on several threads, the DEM step's drift writes the centres and predicted velocities
/// of a grain block whose boundary grains the other thread read in the previous phase (its
/// cross pairs). Each such line is then shared, and the store must first invalidate the other
/// core's copy; without a prefetch the stores wait on those invalidations one after another
/// (on the vibrated 4000-grain bed on two threads the drift took 3× its one-thread CPU time;
/// with the prefetch 1.1×). A prefetch is a hint: it changes no value.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct WritePrefetch(());

impl WritePrefetch {
    /// How many elements ahead of the store the loops prefetch (12 grains of 24 bytes are
    /// 4–5 cache lines).
    pub const AHEAD: usize = 12;

    /// The write prefetch, if this processor has it.
    pub fn detect() -> Option<Self> {
        #[cfg(target_arch = "x86_64")]
        {
            use std::arch::x86_64::__cpuid;
            // (`__cpuid` is safe on x86-64 from Rust 1.94 on; the block keeps older
            // compilers building)
            // (leaf 8000_0001h is read only where the processor has it; else no flags)
            #[allow(unused_unsafe)]
            // SAFETY: CPUID exists on every x86-64 processor.
            let ecx = unsafe {
                if __cpuid(0x8000_0000).eax >= 0x8000_0001 {
                    __cpuid(0x8000_0001).ecx
                } else {
                    0
                }
            };
            if ecx & (1 << 8) != 0 {
                return Some(WritePrefetch(()));
            }
        }
        None
    }

    /// Asks for the line of `s[k]` in the exclusive state (nothing when `k` is past the end).
    #[inline(always)]
    pub fn element<T>(self, s: &[T], k: usize) {
        #[cfg(target_arch = "x86_64")]
        if k < s.len() {
            let p = s.as_ptr().wrapping_add(k);
            // SAFETY: a prefetch reads and writes nothing and cannot fault; the address is
            // in bounds anyway, and the processor has the instruction (`detect`).
            unsafe {
                std::arch::asm!("prefetchw [{0}]", in(reg) p, options(nostack, preserves_flags, readonly));
            }
        }
        #[cfg(not(target_arch = "x86_64"))]
        let _ = (s, k);
    }
}
