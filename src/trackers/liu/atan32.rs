//! atan in f32 by a polynomial, for the curve's orientation per far row in liu-ppf's
//! parabolic sums (eq. 7: theta(y) = atan(-2 e y - d)): an approximation, within 2e-7 rad of
//! the exact atan (tested against f64 atan: 1.3e-7 on [-1, 1] in f32, 1.6e-7 beyond), against
//! `libm::atanf`'s 6e-8. The kernels use the orientation in f32 and take the nodes' orientation
//! to first order from the row's (below 1e-6 rad off), so 2e-7 rad is below what they already
//! neglect; the point is speed (no range reduction into four intervals and a division per row
//! as `atanf` does; one division only for |x| > 1, which the top view's curves rarely reach).
//!
//! atan(x) = x P(x^2) on [-1, 1] with P of degree 7, fitted for the least largest absolute
//! error (Lawson's iteration, coefficients rounded to f32); beyond, atan(x) = sign(x) pi/2 -
//! atan(1/x).

use super::lanes::F32x4;

/// atan(x) ~= x (A[0] + z (A[1] + ... + z A[7])), z = x^2, on [-1, 1].
const A: [f32; 8] = [
    0.999_999_34,
    -0.333_298_6,
    0.199_465_65,
    -0.139_086_28,
    0.096_421_935,
    -0.055_912_275,
    0.021_862_92,
    -0.004_054_556_6,
];

/// atan(x) within 2e-7 rad (NaN for NaN).
#[inline]
pub fn atan32(x: f32) -> f32 {
    let t = x.abs();
    // atan(x) = sign(x) atan(|x|); beyond 1, atan(|x|) = pi/2 - atan(1/|x|) (inf: pi/2 - 0).
    let r = if t <= 1.0 {
        odd(t)
    } else {
        std::f32::consts::FRAC_PI_2 - odd(1.0 / t)
    };
    r.copysign(x)
}

/// x P(x^2) for |x| <= 1.
#[inline]
fn odd(x: f32) -> f32 {
    let z = x * x;
    let p = A[0]
        + z * (A[1] + z * (A[2] + z * (A[3] + z * (A[4] + z * (A[5] + z * (A[6] + z * A[7]))))));
    x * p
}

/// [`atan32`] of four lanes, by the same operations lane by lane (both branches computed,
/// the lane's taken by a select).
#[inline]
pub fn atan32_x4(x: F32x4) -> F32x4 {
    Atan32Lanes::splat().eval(x)
}

/// The constants of [`atan32_x4`] as lanes, made once before a loop and passed through
/// [`std::hint::black_box`] (otherwise they are constants at every use, which WebAssembly
/// engines may build anew in each iteration). The same operations, so the same bits.
#[derive(Clone, Copy, Debug)]
pub struct Atan32Lanes {
    a: [F32x4; 8],
    sign: F32x4,
    abs: F32x4,
    one: F32x4,
    half_pi: F32x4,
}

impl Atan32Lanes {
    /// The constants, as values the compiler cannot see through.
    #[inline]
    pub fn opaque() -> Self {
        std::hint::black_box(Self::splat())
    }

    #[inline]
    fn splat() -> Self {
        Self {
            a: A.map(F32x4::splat),
            sign: F32x4::splat(-0.0),
            abs: F32x4::splat(f32::from_bits(0x7fff_ffff)),
            one: F32x4::splat(1.0),
            half_pi: F32x4::splat(std::f32::consts::FRAC_PI_2),
        }
    }

    /// [`atan32`] of each lane.
    #[inline]
    pub fn eval(&self, x: F32x4) -> F32x4 {
        let t = x & self.abs;
        let small = t.le(self.one);
        // 1 / t only where a lane needs it (the selects below give the same lanes).
        let all_small = small.all();
        let u = if all_small {
            t
        } else {
            small.select(t, self.one / t)
        };
        let z = u * u;
        let a = self.a;
        let p = a[0]
            + z * (a[1]
                + z * (a[2] + z * (a[3] + z * (a[4] + z * (a[5] + z * (a[6] + z * a[7]))))));
        let q = u * p;
        let r = if all_small {
            q
        } else {
            small.select(q, self.half_pi - q)
        };
        r | (x & self.sign)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math;

    #[test]
    fn within_its_bound_of_atan() {
        let mut worst: f64 = 0.0;
        let mut check = |x: f32| {
            let exact = math::atan(f64::from(x));
            worst = worst.max((f64::from(atan32(x)) - exact).abs());
        };
        for k in -400_000..=400_000 {
            check(k as f32 * 2.5e-6);
        }
        for k in -100_000..=100_000 {
            check(k as f32 * 1e-3);
        }
        for x in [1e-30, 1e10, -1e10, 3e38, f32::MAX, f32::MIN_POSITIVE] {
            check(x);
        }
        assert!(worst <= 2e-7, "{worst}");
        assert_eq!(atan32(0.0), 0.0);
        assert_eq!(atan32(f32::INFINITY), std::f32::consts::FRAC_PI_2);
        assert_eq!(atan32(f32::NEG_INFINITY), -std::f32::consts::FRAC_PI_2);
        assert!(atan32(f32::NAN).is_nan());
        // Odd, and increasing across the switch at 1.
        assert_eq!(atan32(-0.3).to_bits(), (-atan32(0.3)).to_bits());
        let one = 1.0f32;
        assert!(atan32(f32::from_bits(one.to_bits() + 1)) >= atan32(one));
    }

    #[test]
    fn the_lanes_give_the_scalar_bits() {
        let mut xs: Vec<f32> = (-30_000..30_000).map(|k| k as f32 * 1.7e-4).collect();
        xs.extend([
            0.0,
            -0.0,
            1.0,
            -1.0,
            1e10,
            -1e-30,
            f32::INFINITY,
            f32::NEG_INFINITY,
        ]);
        for four in xs.chunks_exact(4) {
            let four = [four[0], four[1], four[2], four[3]];
            let v = atan32_x4(F32x4::from_array(four)).to_array();
            for (x, v) in four.iter().zip(v) {
                assert_eq!(v.to_bits(), atan32(*x).to_bits(), "{x}");
            }
        }
    }
}
