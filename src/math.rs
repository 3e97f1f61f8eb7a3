//! Float functions, all through libm in one place, so that a no_std build
//! and a desktop build run the same code and give the same bits.

#[inline]
pub(crate) fn floor32(x: f32) -> f32 {
    libm::floorf(x)
}

#[inline]
pub(crate) fn ceil32(x: f32) -> f32 {
    libm::ceilf(x)
}

#[inline]
pub(crate) fn sqrt32(x: f32) -> f32 {
    libm::sqrtf(x)
}

#[inline]
pub(crate) fn tan32(x: f32) -> f32 {
    libm::tanf(x)
}

#[inline]
pub(crate) fn floor64(x: f64) -> f64 {
    libm::floor(x)
}

/// Converts a float cell coordinate to `i32`, saturating (NaN becomes 0).
/// Callers clamp the result into the volume afterwards.
#[inline]
pub(crate) fn to_cell(x: f32) -> i32 {
    x as i32
}
