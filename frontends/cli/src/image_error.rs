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
