//! The framebuffer's parallel pixel iterator (feature `rayon`), built on
//! rayon's plumbing: an indexed parallel iterator whose producer splits the
//! pixel slice by range, so every thread gets runs of consecutive pixels of
//! the same rows, which trace through the same part of the scene.

use core::sync::atomic::{AtomicU32, Ordering};

use rayon::iter::plumbing::{bridge, Consumer, Producer, ProducerCallback, UnindexedConsumer};
use rayon::iter::{IndexedParallelIterator, ParallelIterator};

use crate::render::framebuffer::Framebuffer;

/// One pixel of a [`Framebuffer`]: its coordinates and the pixel itself.
#[derive(Clone, Copy, Debug)]
pub struct PixelRef<'a> {
    /// Column.
    pub x: u32,
    /// Row.
    pub y: u32,
    /// The pixel, packed RGBA8.
    pub pixel: &'a AtomicU32,
}

impl PixelRef<'_> {
    /// Stores a packed RGBA8 color.
    #[inline]
    pub fn set(&self, rgba: u32) {
        self.pixel.store(rgba, Ordering::Relaxed);
    }

    /// Loads the packed RGBA8 color.
    #[inline]
    #[must_use]
    pub fn get(&self) -> u32 {
        self.pixel.load(Ordering::Relaxed)
    }
}

impl Framebuffer {
    /// Every pixel in row-major order, on the calling thread.
    #[must_use]
    pub fn pixel_refs(&self) -> Pixels<'_> {
        Pixels::new(self.pixels(), self.width(), 0)
    }

    /// Every pixel, in parallel. Indexed: `len` is `width * height` and
    /// item `i` is pixel `(i % width, i / width)`; each pixel is yielded
    /// exactly once.
    #[must_use]
    pub fn par_pixels(&self) -> ParPixels<'_> {
        ParPixels {
            producer: PixelProducer {
                pixels: self.pixels(),
                width: self.width(),
                first: 0,
            },
        }
    }
}

/// A sequential iterator over a run of pixels (a producer's share).
#[derive(Clone, Debug)]
pub struct Pixels<'a> {
    pixels: core::iter::Enumerate<core::slice::Iter<'a, AtomicU32>>,
    width: u32,
    /// Row-major index of the run's first pixel in the whole image.
    first: usize,
}

impl<'a> Pixels<'a> {
    fn new(pixels: &'a [AtomicU32], width: u32, first: usize) -> Self {
        Pixels {
            pixels: pixels.iter().enumerate(),
            width,
            first,
        }
    }

    #[inline]
    fn item(&self, (offset, pixel): (usize, &'a AtomicU32)) -> PixelRef<'a> {
        let index = self.first + offset;
        let width = self.width as usize;
        // Both fit in u32: the image is at most u32::MAX on each side.
        PixelRef {
            x: (index % width) as u32,
            y: (index / width) as u32,
            pixel,
        }
    }
}

impl<'a> Iterator for Pixels<'a> {
    type Item = PixelRef<'a>;

    #[inline]
    fn next(&mut self) -> Option<PixelRef<'a>> {
        let next = self.pixels.next()?;
        Some(self.item(next))
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        self.pixels.size_hint()
    }
}

impl DoubleEndedIterator for Pixels<'_> {
    fn next_back(&mut self) -> Option<Self::Item> {
        let next = self.pixels.next_back()?;
        Some(self.item(next))
    }
}

impl ExactSizeIterator for Pixels<'_> {}

/// The producer: a contiguous run of pixels that splits at any index.
#[derive(Clone, Copy, Debug)]
struct PixelProducer<'a> {
    pixels: &'a [AtomicU32],
    width: u32,
    first: usize,
}

impl<'a> Producer for PixelProducer<'a> {
    type Item = PixelRef<'a>;
    type IntoIter = Pixels<'a>;

    fn into_iter(self) -> Pixels<'a> {
        Pixels::new(self.pixels, self.width, self.first)
    }

    fn split_at(self, index: usize) -> (Self, Self) {
        let (left, right) = self.pixels.split_at(index);
        (
            PixelProducer {
                pixels: left,
                ..self
            },
            PixelProducer {
                pixels: right,
                first: self.first + index,
                ..self
            },
        )
    }
}

/// The parallel iterator of [`Framebuffer::par_pixels`].
///
/// To keep neighbouring pixels on one thread, combine it with rayon's
/// chunking adapters, for example `fold_chunks(width, ..)` for whole rows.
/// ([`crate::render()`] does not use it: it hands out bands of rows
/// traced in tiles, each band its own job.)
#[derive(Clone, Copy, Debug)]
pub struct ParPixels<'a> {
    producer: PixelProducer<'a>,
}

impl<'a> ParallelIterator for ParPixels<'a> {
    type Item = PixelRef<'a>;

    fn drive_unindexed<C: UnindexedConsumer<Self::Item>>(self, consumer: C) -> C::Result {
        bridge(self, consumer)
    }

    fn opt_len(&self) -> Option<usize> {
        Some(self.producer.pixels.len())
    }
}

impl IndexedParallelIterator for ParPixels<'_> {
    fn len(&self) -> usize {
        self.producer.pixels.len()
    }

    fn drive<C: Consumer<Self::Item>>(self, consumer: C) -> C::Result {
        bridge(self, consumer)
    }

    fn with_producer<CB: ProducerCallback<Self::Item>>(self, callback: CB) -> CB::Output {
        callback.callback(self.producer)
    }
}
