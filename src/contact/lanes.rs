//! Numbers the contact kernels compute with: one contact (`f64`) or eight at once ([`F64x8`]).
//!
//! Every kernel of this module's siblings is written once, generic over [`Real`], and is
//! branch-free: where a law branches (Coulomb cap, no slip), both sides are computed and the
//! result is chosen with [`Real::select`]. The tests check the kernels on `f64`; the engine
//! runs the same functions on [`F64x8`], eight contacts per call, which the compiler turns into
//! vector instructions (AVX2 where the processor has it, see [`crate::simd`]).
//!
//! Every lane operation is the IEEE operation of `f64` (`+ − × ÷ √`, `f64::min`/`max`/`abs`;
//! no fused multiply–add), so a contact computed in a lane of [`F64x8`] is bitwise the contact
//! computed on `f64` (unit test `lanes_are_bitwise_scalar` and `tests/contact_lanes.rs`).

use std::ops::{Add, Div, Mul, Neg, Sub};

/// A real number or a vector of them, lane by lane.
pub trait Real:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// A truth value per lane.
    type Mask: Copy;
    /// Every lane `x`.
    fn splat(x: f64) -> Self;
    /// √x per lane (IEEE, correctly rounded).
    fn sqrt(self) -> Self;
    /// `f64::min` per lane.
    fn min(self, o: Self) -> Self;
    /// `f64::max` per lane.
    fn max(self, o: Self) -> Self;
    /// |x| per lane.
    fn abs(self) -> Self;
    /// `self > o` per lane.
    fn gt(self, o: Self) -> Self::Mask;
    /// `self != o` per lane.
    fn ne(self, o: Self) -> Self::Mask;
    /// Both masks true.
    fn and(a: Self::Mask, b: Self::Mask) -> Self::Mask;
    /// `a` where `m`, else `b`, per lane.
    fn select(m: Self::Mask, a: Self, b: Self) -> Self;
}

impl Real for f64 {
    type Mask = bool;
    #[inline(always)]
    fn splat(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
    #[inline(always)]
    fn min(self, o: Self) -> Self {
        f64::min(self, o)
    }
    #[inline(always)]
    fn max(self, o: Self) -> Self {
        f64::max(self, o)
    }
    #[inline(always)]
    fn abs(self) -> Self {
        f64::abs(self)
    }
    #[inline(always)]
    fn gt(self, o: Self) -> bool {
        self > o
    }
    #[inline(always)]
    fn ne(self, o: Self) -> bool {
        self != o
    }
    #[inline(always)]
    fn and(a: bool, b: bool) -> bool {
        a & b
    }
    #[inline(always)]
    fn select(m: bool, a: Self, b: Self) -> Self {
        if m {
            a
        } else {
            b
        }
    }
}

/// A vector of `f64` lanes the contact loops gather contacts into.
pub trait Lanes: Real + Default {
    /// Number of lanes.
    const N: usize;
    /// Lane `l`.
    fn get(&self, l: usize) -> f64;
    /// Sets lane `l`.
    fn set(&mut self, l: usize, x: f64);
    /// The first [`Lanes::N`] numbers of `x`.
    fn load(x: &[f64]) -> Self;
    /// Writes the lanes to the first [`Lanes::N`] numbers of `x`.
    fn store(self, x: &mut [f64]);
}

macro_rules! lanes_type {
    ($name:ident, $n:expr, $align:expr, $doc:expr) => {
        #[doc = $doc]
        #[derive(Debug, Clone, Copy, PartialEq, Default)]
        #[repr(C, align($align))]
        pub struct $name(pub [f64; $n]);

        impl $name {
            #[inline(always)]
            fn map(self, f: impl Fn(f64) -> f64) -> Self {
                let mut o = [0.0; $n];
                for k in 0..$n {
                    o[k] = f(self.0[k]);
                }
                $name(o)
            }
            #[inline(always)]
            fn zip(self, b: Self, f: impl Fn(f64, f64) -> f64) -> Self {
                let mut o = [0.0; $n];
                for k in 0..$n {
                    o[k] = f(self.0[k], b.0[k]);
                }
                $name(o)
            }
            #[inline(always)]
            fn test(self, b: Self, f: impl Fn(f64, f64) -> bool) -> [bool; $n] {
                let mut o = [false; $n];
                for k in 0..$n {
                    o[k] = f(self.0[k], b.0[k]);
                }
                o
            }
        }

        impl Add for $name {
            type Output = $name;
            #[inline(always)]
            fn add(self, b: $name) -> $name {
                self.zip(b, |x, y| x + y)
            }
        }
        impl Sub for $name {
            type Output = $name;
            #[inline(always)]
            fn sub(self, b: $name) -> $name {
                self.zip(b, |x, y| x - y)
            }
        }
        impl Mul for $name {
            type Output = $name;
            #[inline(always)]
            fn mul(self, b: $name) -> $name {
                self.zip(b, |x, y| x * y)
            }
        }
        impl Div for $name {
            type Output = $name;
            #[inline(always)]
            fn div(self, b: $name) -> $name {
                self.zip(b, |x, y| x / y)
            }
        }
        impl Neg for $name {
            type Output = $name;
            #[inline(always)]
            fn neg(self) -> $name {
                self.map(|x| -x)
            }
        }

        impl Real for $name {
            type Mask = [bool; $n];
            #[inline(always)]
            fn splat(x: f64) -> Self {
                $name([x; $n])
            }
            #[inline(always)]
            fn sqrt(self) -> Self {
                self.map(f64::sqrt)
            }
            #[inline(always)]
            fn min(self, o: Self) -> Self {
                self.zip(o, f64::min)
            }
            #[inline(always)]
            fn max(self, o: Self) -> Self {
                self.zip(o, f64::max)
            }
            #[inline(always)]
            fn abs(self) -> Self {
                self.map(f64::abs)
            }
            #[inline(always)]
            fn gt(self, o: Self) -> Self::Mask {
                self.test(o, |x, y| x > y)
            }
            #[inline(always)]
            fn ne(self, o: Self) -> Self::Mask {
                self.test(o, |x, y| x != y)
            }
            #[inline(always)]
            fn and(a: Self::Mask, b: Self::Mask) -> Self::Mask {
                let mut o = [false; $n];
                for k in 0..$n {
                    o[k] = a[k] & b[k];
                }
                o
            }
            #[inline(always)]
            fn select(m: Self::Mask, a: Self, b: Self) -> Self {
                let mut o = [0.0; $n];
                for k in 0..$n {
                    o[k] = if m[k] { a.0[k] } else { b.0[k] };
                }
                $name(o)
            }
        }

        impl Lanes for $name {
            const N: usize = $n;
            #[inline(always)]
            fn get(&self, l: usize) -> f64 {
                self.0[l]
            }
            #[inline(always)]
            fn set(&mut self, l: usize, x: f64) {
                self.0[l] = x;
            }
            #[inline(always)]
            fn load(x: &[f64]) -> Self {
                let mut o = [0.0; $n];
                o.copy_from_slice(&x[..$n]);
                $name(o)
            }
            #[inline(always)]
            fn store(self, x: &mut [f64]) {
                x[..$n].copy_from_slice(&self.0);
            }
        }
    };
}

lanes_type!(
    F64x8,
    8,
    64,
    "Eight `f64` lanes: two AVX2 registers (two independent chains per operation: measured \
     faster on the DEM loops than four lanes, and than eight or sixteen AVX-512 lanes)."
);

/// Sets lane `l` of each of `K` lane vectors to the components of `x`.
#[inline(always)]
pub fn set_lane<L: Lanes, const K: usize>(v: &mut [L; K], l: usize, x: [f64; K]) {
    for (v, x) in v.iter_mut().zip(x) {
        v.set(l, x);
    }
}

/// Lane `l` of each of `K` lane vectors.
#[inline(always)]
pub fn get_lane<L: Lanes, const K: usize>(v: &[L; K], l: usize) -> [f64; K] {
    std::array::from_fn(|c| v[c].get(l))
}

/// `a · b` of two 3-vectors.
#[inline(always)]
pub fn dot<R: Real>(a: [R; 3], b: [R; 3]) -> R {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `s a` of a 3-vector.
#[inline(always)]
pub fn scale<R: Real>(s: R, a: [R; 3]) -> [R; 3] {
    [s * a[0], s * a[1], s * a[2]]
}

/// `a − b` of two 3-vectors.
#[inline(always)]
pub fn sub3<R: Real>(a: [R; 3], b: [R; 3]) -> [R; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `a × b` of two 3-vectors.
#[inline(always)]
pub fn cross<R: Real>(a: [R; 3], b: [R; 3]) -> [R; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `a` where `m`, else `b`, per component.
#[inline(always)]
pub fn select3<R: Real>(m: R::Mask, a: [R; 3], b: [R; 3]) -> [R; 3] {
    [
        R::select(m, a[0], b[0]),
        R::select(m, a[1], b[1]),
        R::select(m, a[2], b[2]),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    const LANES: usize = 8;

    fn lanes(v: [f64; LANES]) -> F64x8 {
        F64x8(v)
    }

    #[test]
    fn lanes_are_bitwise_scalar() {
        let a = [1.5, -0.0, 0.0, f64::INFINITY, 3e-300, -7.25, f64::NAN, 2.0];
        let b = [0.3, 0.0, -0.0, 1.0, 1e10, -7.25, 1.0, f64::NAN];
        let (x, y) = (
            std::hint::black_box(lanes(a)),
            std::hint::black_box(lanes(b)),
        );
        type Op = fn(f64, f64) -> f64;
        let ops: [(F64x8, Op); 8] = [
            (x + y, |p, q| p + q),
            (x - y, |p, q| p - q),
            (x * y, |p, q| p * q),
            (x / y, |p, q| p / q),
            (x.min(y), f64::min),
            (x.max(y), f64::max),
            (Real::sqrt(x.abs()), |p, _| p.abs().sqrt()),
            (
                R8::select(x.gt(y), x, -y),
                |p, q| if p > q { p } else { -q },
            ),
        ];
        for (v, f) in ops {
            for k in 0..LANES {
                // NaN: any NaN (its sign and payload depend on where the compiler folded it)
                let (x, y) = (v.0[k], f(a[k], b[k]));
                assert!(
                    x.to_bits() == y.to_bits() || (x.is_nan() && y.is_nan()),
                    "lane {k}"
                );
            }
        }
    }

    type R8 = F64x8;
}
