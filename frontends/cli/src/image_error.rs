//! How far a frame is from a reference frame: the root mean square
//! difference of their color channels and the PSNR it gives, for the
//! accuracy report's sections and the tests that measure error.

use voxtrace::unpack;

/// Root mean square difference over every color channel, in 0..=255 units.
pub fn rmse(pixels: &[u32], reference: &[u32]) -> f64 {
    let mut sum = 0.0;
    for (&p, &r) in pixels.iter().zip(reference) {
        let (p, r) = (unpack(p), unpack(r));
        for c in 0..3 {
            let d = f64::from(p[c]) - f64::from(r[c]);
            sum += d * d;
        }
    }
    (sum / (3 * pixels.len().max(1)) as f64).sqrt()
}

/// Peak signal to noise ratio for 8-bit channels; infinite for no error.
pub fn psnr(rmse: f64) -> f64 {
    20.0 * (255.0 / rmse).log10()
}

#[cfg(test)]
mod tests {
    use voxtrace::glam::U8Vec3;
    use voxtrace::pack;

    use super::{psnr, rmse};

    #[test]
    fn a_frame_equal_to_its_reference_has_no_error() {
        let frame: Vec<u32> = (0..64u8)
            .map(|i| pack(U8Vec3::new(i, 255 - i, i / 2)))
            .collect();
        assert_eq!(rmse(&frame, &frame), 0.0);
        assert_eq!(psnr(0.0), f64::INFINITY);
    }

    #[test]
    fn the_error_is_the_root_mean_square_of_the_channel_differences() {
        // Every channel of every pixel off by `d`: the error is `d`, whatever
        // the colors; alpha is not a color channel.
        for d in [1u8, 3, 10, 100] {
            let reference: Vec<u32> = (0..50u8)
                .map(|i| pack(U8Vec3::new(i, i + 1, i + 2)))
                .collect();
            let frame: Vec<u32> = (0..50u8)
                .map(|i| pack(U8Vec3::new(i + d, i + 1 + d, i + 2 + d)) & 0x00ff_ffff)
                .collect();
            assert!((rmse(&frame, &reference) - f64::from(d)).abs() < 1e-9);
        }
        // One channel of one pixel in four off by 12: sqrt(144 / 12) per
        // channel mean.
        let reference = vec![pack(U8Vec3::splat(100)); 4];
        let mut frame = reference.clone();
        frame[2] = pack(U8Vec3::new(112, 100, 100));
        let e = rmse(&frame, &reference);
        assert!((e - 12f64.sqrt()).abs() < 1e-12, "{e}");
        assert!((psnr(e) - 20.0 * (255.0 / e).log10()).abs() < 1e-12);
    }
}
