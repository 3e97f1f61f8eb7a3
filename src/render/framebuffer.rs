//! `Framebuffer`: one `AtomicU32` per pixel, so any number of threads can
//! write disjoint pixels through a shared reference (feature `std`).
//!
//! Pixels are packed RGBA8 (see [`crate::pack`]), row-major, the same layout
//! as the scalar render's `&mut [u32]`.

use core::sync::atomic::{AtomicU32, Ordering};
use std::vec::Vec;

use crate::error::Error;

/// A `width x height` image of atomic RGBA8 pixels.
///
/// # Guarantees
/// `width` and `height` are non-zero and the pixel slice holds exactly
/// `width * height` pixels, row-major. Stores and loads are `Relaxed`: a
/// render publishes its pixels by returning (the threads are joined), not
/// through the atomics.
#[derive(Debug)]
pub struct Framebuffer {
    width: u32,
    height: u32,
    pixels: Vec<AtomicU32>,
}

impl Framebuffer {
    /// A framebuffer of transparent black pixels. Allocates its pixels with
    /// `try_reserve`: an image too large for memory is
    /// [`Error::OutOfMemory`], never an abort.
    pub fn new(width: u32, height: u32) -> Result<Self, Error> {
        let (len, mut pixels) = Self::reserve(width, height)?;
        pixels.resize_with(len, || AtomicU32::new(0));
        Ok(Framebuffer {
            width,
            height,
            pixels,
        })
    }

    /// [`Framebuffer::new`], its pixels zeroed by the tasks of the current
    /// rayon pool: the one a caller's `install` runs in, else rayon's
    /// global pool, which this then starts (feature `rayon`). The same
    /// framebuffer, the same errors. Zeroing is the first write to every
    /// page of a fresh allocation, and on one thread it took 5.2 to 5.9 ms
    /// of a 1920x1080 frame (2 threads: 2.9 to 3.4 ms, 2-core Xeon VM):
    /// worth it where frames are large or cheap to render.
    #[cfg(feature = "rayon")]
    pub fn new_parallel(width: u32, height: u32) -> Result<Self, Error> {
        use rayon::iter::{IntoParallelIterator, ParallelExtend, ParallelIterator};
        let (len, mut pixels) = Self::reserve(width, height)?;
        // Indexed, into reserved room: written in place, no reallocation.
        pixels.par_extend((0..len).into_par_iter().map(|_| AtomicU32::new(0)));
        Ok(Framebuffer {
            width,
            height,
            pixels,
        })
    }

    /// The pixel count of a `width x height` image and an empty vector
    /// with room for exactly that many, or the constructors' errors.
    fn reserve(width: u32, height: u32) -> Result<(usize, Vec<AtomicU32>), Error> {
        if width == 0 || height == 0 {
            return Err(Error::ZeroSize);
        }
        let len = (width as usize)
            .checked_mul(height as usize)
            .ok_or(Error::SizeOverflow)?;
        Ok((len, crate::fallible::try_vec::<AtomicU32>(len)?))
    }

    /// Columns.
    #[must_use]
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Rows.
    #[must_use]
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Every pixel, row-major.
    #[must_use]
    pub fn pixels(&self) -> &[AtomicU32] {
        &self.pixels
    }

    /// The pixel at `(x, y)`, or `None` outside the image.
    #[must_use]
    pub fn get(&self, x: u32, y: u32) -> Option<u32> {
        (x < self.width && y < self.height)
            .then(|| self.pixels[self.index(x, y)].load(Ordering::Relaxed))
    }

    /// Sets the pixel at `(x, y)`; returns `false` (and writes nothing)
    /// outside the image.
    pub fn set(&self, x: u32, y: u32, rgba: u32) -> bool {
        let inside = x < self.width && y < self.height;
        if inside {
            self.pixels[self.index(x, y)].store(rgba, Ordering::Relaxed);
        }
        inside
    }

    fn index(&self, x: u32, y: u32) -> usize {
        y as usize * self.width as usize + x as usize
    }

    /// Copies the pixels into `out` in the scalar render's layout; fails
    /// with [`Error::BufferTooSmall`] if `out` is shorter than the image
    /// (the rest of a longer `out` is left alone). Allocates nothing.
    pub fn copy_to(&self, out: &mut [u32]) -> Result<(), Error> {
        let actual = out.len();
        let out = out
            .get_mut(..self.pixels.len())
            .ok_or(Error::BufferTooSmall {
                required: self.pixels.len(),
                actual,
            })?;
        for (dst, src) in out.iter_mut().zip(&self.pixels) {
            *dst = src.load(Ordering::Relaxed);
        }
        Ok(())
    }

    /// A copy of the pixels in the scalar layout (row-major, packed),
    /// leaving the framebuffer as it is. Allocates the copy.
    #[must_use]
    pub fn to_vec(&self) -> Vec<u32> {
        self.pixels
            .iter()
            .map(|p| p.load(Ordering::Relaxed))
            .collect()
    }

    /// The pixels as plain `u32`s in the scalar render's layout, reusing
    /// the framebuffer's allocation.
    #[must_use]
    pub fn into_pixels(self) -> Vec<u32> {
        // Same size and alignment: the standard library collects in place.
        self.pixels.into_iter().map(AtomicU32::into_inner).collect()
    }
}
