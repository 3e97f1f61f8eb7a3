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

#[inline]
pub(crate) fn floor64(x: f64) -> f64 {
    libm::floor(x)
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
