//! The render settings of a `.vox` file: its rOBJ chunks (sun, sky,
//! bounces), which dot_vox skips, read by a small reader of the chunk
//! stream of its own.
//!
//! Keys read: `_inf` (the sun): `_i` intensity, `_k` color, `_angle`
//! (two angles in degrees: elevation above the ground plane, then azimuth
//! from +x toward +y in MagicaVoxel's z-up axes), `_area` (the disk's
//! angular radius as a fraction of a right angle); `_uni` (a uniform sky):
//! `_i`, `_k`; `_bounce`: `_diffuse`, `_specular`. Everything else
//! (`_env`, `_ibl`, `_atm`, `_fog_uni`, `_lens`, `_film`, `_bloom`,
//! `_ground`, `_bg`, `_edge`, `_grid`, `_setting`, `_scatter`, `_energy`,
//! `_disk`, and the rLIT/rAIR/POST chunks of older files) is ignored.

use std::collections::HashMap;
use std::string::String;

use glam::Vec3;

use crate::source::vox::chunks::{chunks, dict, numbers};
use crate::source::vox::rcam::y_up;

/// The light and bounce settings a file holds.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct VoxSettings {
    /// The sun: direction toward it (voxtrace's y-up axes), radiance
    /// scale (color times intensity) and angular radius in radians.
    pub sun: Option<VoxSun>,
    /// A uniform sky's radiance (color times intensity).
    pub sky: Option<Vec3>,
    /// Diffuse and specular bounce counts.
    pub bounces: Option<(u8, u8)>,
}

/// A file's sun (`_inf`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VoxSun {
    /// Unit direction toward the sun, y up.
    pub direction: Vec3,
    /// Intensity times the color's brightest channel.
    pub intensity: f32,
    /// Angular radius in radians.
    pub radius: f32,
}

/// Intensity `_i` times color `_k` (0-255 per channel).
fn radiance(d: &HashMap<String, String>) -> Option<Vec3> {
    let [i] = numbers::<1>(d.get("_i"))?;
    let k = numbers::<3>(d.get("_k")).unwrap_or([255.0; 3]);
    let r = Vec3::from(k) * (i.max(0.0) / 255.0);
    r.is_finite().then_some(r)
}

/// The settings of the file in `bytes`.
pub(crate) fn settings(bytes: &[u8]) -> VoxSettings {
    let mut s = VoxSettings::default();
    // Malformed chunks are skipped: dot_vox has read the file already.
    for d in chunks(bytes, b"rOBJ").into_iter().filter_map(dict) {
        match d.get("_type").map(String::as_str) {
            Some("_inf") => {
                let Some(light) = radiance(&d) else { continue };
                let [elevation, azimuth] = numbers::<2>(d.get("_angle")).unwrap_or([50.0, 50.0]);
                let (e, a) = (elevation.to_radians(), azimuth.to_radians());
                let (cos, sin) = (libm::cosf, libm::sinf);
                let direction = y_up(Vec3::new(cos(e) * cos(a), cos(e) * sin(a), sin(e)));
                let [area] = numbers::<1>(d.get("_area")).unwrap_or([0.0]);
                s.sun = Some(VoxSun {
                    direction,
                    intensity: light.max_element(),
                    radius: (area.clamp(0.0, 1.0) * core::f32::consts::FRAC_PI_2).min(1.5),
                });
            }
            Some("_uni") => s.sky = radiance(&d),
            Some("_bounce") => {
                let count =
                    |key: &str| numbers::<1>(d.get(key)).map(|[v]| v.clamp(0.0, 255.0) as u8);
                if let (Some(diffuse), Some(specular)) = (count("_diffuse"), count("_specular")) {
                    s.bounces = Some((diffuse, specular));
                }
            }
            _ => {}
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::source::vox::chunks::write;
    use std::vec::Vec;

    /// A file of MAIN with one rOBJ chunk holding `pairs`.
    fn file(pairs: &[(&str, &str)]) -> Vec<u8> {
        write::file(&write::chunk(b"rOBJ", &write::dict(pairs)))
    }

    #[test]
    fn reads_the_sun_sky_and_bounces() {
        let sun = settings(&file(&[
            ("_type", "_inf"),
            ("_i", "0.6"),
            ("_k", "255 255 255"),
            ("_angle", "90 0"),
            ("_area", "0.1"),
        ]));
        let s = sun.sun.unwrap();
        // Straight up in MagicaVoxel's z is straight up in voxtrace's y.
        assert!((s.direction - Vec3::Y).length() < 1e-6, "{:?}", s.direction);
        assert!((s.intensity - 0.6).abs() < 1e-6);
        assert!((s.radius - 0.1 * core::f32::consts::FRAC_PI_2).abs() < 1e-6);
        let sky = settings(&file(&[
            ("_type", "_uni"),
            ("_i", "0.5"),
            ("_k", "255 0 255"),
        ]));
        assert_eq!(sky.sky, Some(Vec3::new(0.5, 0.0, 0.5)));
        let b = settings(&file(&[
            ("_type", "_bounce"),
            ("_diffuse", "2"),
            ("_specular", "5"),
        ]));
        assert_eq!(b.bounces, Some((2, 5)));
    }

    #[test]
    fn garbage_gives_no_settings_and_no_panic() {
        assert_eq!(settings(b"VOX "), VoxSettings::default());
        let mut f = file(&[("_type", "_uni"), ("_i", "x")]);
        assert_eq!(settings(&f), VoxSettings::default());
        f.truncate(f.len() - 3);
        assert_eq!(settings(&f), VoxSettings::default());
        let mut huge = file(&[]);
        let n = huge.len();
        huge[n - 4..].copy_from_slice(&u32::MAX.to_le_bytes());
        assert_eq!(settings(&huge), VoxSettings::default());
    }
}
