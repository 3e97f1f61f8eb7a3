//! The crate's one error type.

use core::fmt;

/// Everything that can go wrong in voxtrace, as one `Copy` value.
///
/// Input is checked where a value is constructed (a camera, a ray, a
/// storage), so the hot paths (`trace`, `render_row`) cannot fail.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Error {
    /// A box, image or buffer with a zero dimension.
    ZeroSize,
    /// A size whose element or byte count does not fit in `usize`.
    SizeOverflow,
    /// A volume whose coordinates leave the supported range
    /// `[-MAX_COORD, MAX_COORD]` (see [`crate::MAX_COORD`]).
    ExtentTooLarge {
        /// The largest supported absolute coordinate.
        max: i32,
    },
    /// A caller-provided buffer is shorter than the operation needs.
    BufferTooSmall {
        /// Elements needed.
        required: usize,
        /// Elements given.
        actual: usize,
    },
    /// An allocation was refused; nothing was built.
    OutOfMemory {
        /// Bytes that were requested.
        bytes: usize,
    },
    /// The camera parameters cannot produce rays; the reason names the bad one.
    InvalidCamera {
        /// Which parameter is wrong and why.
        reason: &'static str,
    },
    /// A render setting is out of range; the reason names it.
    InvalidOptions {
        /// Which setting is wrong and why.
        reason: &'static str,
    },
    /// A material parameter is out of range; the reason names it.
    InvalidMaterial {
        /// Which parameter is wrong and why.
        reason: &'static str,
    },
    /// A ray with a non-finite origin, or a zero or non-finite direction.
    InvalidRay,
    /// A [`crate::VoxelSource`] contradicted itself while a storage was
    /// built from it: `classify` answered differently for the same region
    /// (the region is `[min, max)`). Sources must answer the same question
    /// the same way; nothing was built.
    InconsistentSource {
        /// The region's lowest corner.
        min: [i32; 3],
        /// The region's upper corner (exclusive).
        max: [i32; 3],
    },
    /// A framebuffer whose size is not the size of the region rendered into it.
    SizeMismatch {
        /// `(width, height)` the operation needs.
        expected: (u32, u32),
        /// `(width, height)` given.
        actual: (u32, u32),
    },
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Error::ZeroSize => f.write_str("size must be non-zero in every dimension"),
            Error::SizeOverflow => f.write_str("size overflows the address space"),
            Error::ExtentTooLarge { max } => {
                write!(f, "volume coordinates must lie within [-{max}, {max}]")
            }
            Error::BufferTooSmall { required, actual } => {
                write!(
                    f,
                    "buffer too small: {required} elements needed, {actual} given"
                )
            }
            Error::OutOfMemory { bytes } => {
                write!(f, "out of memory: could not allocate {bytes} bytes")
            }
            Error::InvalidCamera { reason } => write!(f, "invalid camera: {reason}"),
            Error::InvalidOptions { reason } => write!(f, "invalid render options: {reason}"),
            Error::InvalidMaterial { reason } => write!(f, "invalid material: {reason}"),
            Error::InvalidRay => {
                f.write_str("invalid ray: origin must be finite, direction finite and non-zero")
            }
            Error::InconsistentSource { min, max } => write!(
                f,
                "the voxel source answered differently for the same region \
                 [{}, {}, {}]..[{}, {}, {}]: its classify must be deterministic",
                min[0], min[1], min[2], max[0], max[1], max[2]
            ),
            Error::SizeMismatch { expected, actual } => write!(
                f,
                "size mismatch: {}x{} needed, {}x{} given",
                expected.0, expected.1, actual.0, actual.1
            ),
        }
    }
}

impl core::error::Error for Error {}
