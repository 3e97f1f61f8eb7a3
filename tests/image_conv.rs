//! Frames to and from the image crate's `RgbaImage` (feature `image`).
#![cfg(feature = "image")]

use voxtrace::glam::U8Vec3;
use voxtrace::image::RgbaImage;
use voxtrace::{from_rgba_image, pack, to_rgba_image, Framebuffer};

#[test]
fn frames_round_trip_through_rgba_images_channel_for_channel() {
    let (w, h) = (7, 3);
    let frame = Framebuffer::new(w, h).unwrap();
    for y in 0..h {
        for x in 0..w {
            frame.set(x, y, pack(U8Vec3::new(x as u8 * 30, y as u8 * 80, 7)));
        }
    }
    let image = RgbaImage::from(&frame);
    assert_eq!(image.dimensions(), (w, h));
    assert_eq!(image.get_pixel(4, 2).0, [120, 160, 7, 255]);
    let back = Framebuffer::try_from(&image).unwrap();
    assert_eq!(back.to_vec(), frame.to_vec());
    assert_eq!(from_rgba_image(&image), frame.to_vec());
    assert_eq!(to_rgba_image(w, h, &frame.to_vec()), Some(image));
    assert_eq!(to_rgba_image(w, h, &frame.to_vec()[..5]), None);
    assert!(Framebuffer::try_from(&RgbaImage::new(0, 4)).is_err());
}
