//! Float functions, all through libm in one place, so that a no_std build
//! and a desktop build run the same code and give the same bits.

#[inline]
pub(crate) fn sqrt32(x: f32) -> f32 {
    libm::sqrtf(x)
}

#[inline]
pub(crate) fn tan32(x: f32) -> f32 {
    libm::tanf(x)
}

#[inline]
pub(crate) fn sin32(x: f32) -> f32 {
    libm::sinf(x)
}

#[inline]
pub(crate) fn cos32(x: f32) -> f32 {
    libm::cosf(x)
}

/// `libm::floor(x)`, bit for bit (NaN, infinities and -0.0 included),
/// without a call: the truncation toward zero, one lower where it rounded
/// a negative non-integer up. The terrain's noise floors two coordinates
/// per column, and the call was 7% of a large build.
#[inline]
pub(crate) fn floor64(x: f64) -> f64 {
    // From 2^52 on every f64 is a whole number; NaN is its own floor too.
    if x.is_nan() || x.abs() >= 4_503_599_627_370_496.0 {
        return x;
    }
    let truncated = x as i64 as f64;
    if truncated == x {
        // Whole already: keep the sign of a zero.
        x
    } else if truncated > x {
        truncated - 1.0
    } else {
        truncated
    }
}

/// `libm::floorf(x) as i32` (saturating, NaN becomes 0) without a call:
/// truncate, then step down when the truncation rounded a negative
/// non-integer up. Exactly equal for every `x`, NaN and infinities included
/// (the subtraction saturates).
#[inline]
pub(crate) fn floor_cell(x: f32) -> i32 {
    let truncated = x as i32;
    truncated.saturating_sub(i32::from(truncated as f32 > x))
}

/// `v` as a `usize`, or `usize::MAX` when it does not fit (for the `const`
/// size functions).
pub(crate) const fn saturating_usize(v: u128) -> usize {
    if v > usize::MAX as u128 {
        usize::MAX
    } else {
        v as usize
    }
}

/// `[f(0), f(1), f(2)]`, always inlined: per-axis arrays in hot loops,
/// where `[0, 1, 2].map(f)` can be left as a call that copies its array.
#[cfg(feature = "packets")]
#[inline(always)]
pub(crate) fn per_axis<T>(mut f: impl FnMut(usize) -> T) -> [T; 3] {
    [f(0), f(1), f(2)]
}

#[cfg(test)]
mod tests {
    use super::floor64;

    /// The inlined floor equals libm's on the values around every whole
    /// number and power of two a coordinate can take, and on the odd ones.
    #[test]
    fn floor64_equals_libm_floor() {
        let check = |v: f64| {
            let (ours, theirs) = (floor64(v), libm::floor(v));
            assert!(
                ours.to_bits() == theirs.to_bits() || (ours.is_nan() && theirs.is_nan()),
                "{v:e}: {ours:e} against {theirs:e}"
            );
        };
        for v in [
            0.0,
            f64::NAN,
            f64::INFINITY,
            f64::MIN_POSITIVE,
            f64::MAX,
            f64::EPSILON,
        ] {
            check(v);
            check(-v);
        }
        for k in 0..64 {
            let p = 2f64.powi(k);
            for v in [
                p,
                p - 0.5,
                p + 0.5,
                p * (1.0 - f64::EPSILON),
                p * (1.0 + f64::EPSILON),
            ] {
                for v in [v, v.next_up(), v.next_down()] {
                    check(v);
                    check(-v);
                }
            }
        }
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        for _ in 0..100_000 {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1);
            check(f64::from_bits(state));
            // Coordinates times the terrain's scale: small, both signs.
            check((state >> 11) as f64 * 1e-6 - 4e6);
        }
    }
}
