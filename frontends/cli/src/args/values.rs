//! The flags' values: the enums clap lists (`--projection`, `--view`,
//! `--format`) and the parsers of the values clap cannot type itself
//! (vectors, rectangles, orbits, backgrounds, byte counts). Each parser's
//! error is one line naming the bad text.

use clap::ValueEnum;
use voxtrace::glam::{U8Vec3, Vec3};
use voxtrace::{Background, Orbit, Rect, ViewPreset};
use voxtrace_flags::Quality;

/// `--projection`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ProjectionArg {
    /// Rays fan out from the camera over --fov.
    Perspective,
    /// Parallel rays, an image --ortho-height voxels tall.
    Orthographic,
}

/// `--quality`: the shared crate's [`Quality`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum QualityArg {
    /// Fast: one sample, no effects (the terrain's default look).
    #[value(alias = "preview")]
    Draft,
    /// Shadows, 8 occlusion rays and 4 samples (a model's default look).
    Standard,
    /// Converged path tracing, or shadows, 16 occlusion rays and 16
    /// samples.
    Final,
}

impl QualityArg {
    /// The shared crate's value.
    #[must_use]
    pub fn quality(self) -> Quality {
        match self {
            QualityArg::Draft => Quality::Draft,
            QualityArg::Standard => Quality::Standard,
            QualityArg::Final => Quality::Final,
        }
    }
}

/// `--view`: the core's presets.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ViewArg {
    /// From +z.
    Front,
    /// From -z.
    Back,
    /// From -x.
    Left,
    /// From +x.
    Right,
    /// From above, -z at the image's top.
    Top,
    /// From below.
    Bottom,
    /// Isometric, orthographic.
    Iso,
}

impl ViewArg {
    /// The core's preset this flag value names.
    pub fn preset(self) -> ViewPreset {
        match self {
            ViewArg::Front => ViewPreset::Front,
            ViewArg::Back => ViewPreset::Back,
            ViewArg::Left => ViewPreset::Left,
            ViewArg::Right => ViewPreset::Right,
            ViewArg::Top => ViewPreset::Top,
            ViewArg::Bottom => ViewPreset::Bottom,
            ViewArg::Iso => ViewPreset::Iso,
        }
    }
}

/// `--orbit YAW,PITCH[,DISTANCE]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OrbitArg(pub Orbit);

/// `YAW,PITCH[,DISTANCE]` in degrees and voxels.
pub fn parse_orbit(s: &str) -> Result<OrbitArg, String> {
    let orbit = match s.split(',').count() {
        2 => {
            let [yaw, pitch] = parse_numbers::<2, f32>(s, "YAW,PITCH or YAW,PITCH,DISTANCE")?;
            Orbit {
                yaw,
                pitch,
                distance: None,
            }
        }
        _ => {
            let [yaw, pitch, d] = parse_numbers::<3, f32>(s, "YAW,PITCH or YAW,PITCH,DISTANCE")?;
            if !(d > 0.0 && d.is_finite()) {
                return Err(format!("the distance in '{s}' must be positive and finite"));
            }
            Orbit {
                yaw,
                pitch,
                distance: Some(d),
            }
        }
    };
    if !(orbit.yaw.is_finite() && orbit.pitch.is_finite()) {
        return Err(format!("'{s}' must be finite"));
    }
    if orbit.pitch.abs() > 90.0 {
        return Err(format!(
            "the pitch in '{s}' must be within -90 to 90 degrees"
        ));
    }
    Ok(OrbitArg(orbit))
}

/// `--background`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BackgroundArg(pub Background);

/// `transparent`, `sky` or `R,G,B`.
pub fn parse_background(s: &str) -> Result<BackgroundArg, String> {
    let t = s.trim();
    if t.eq_ignore_ascii_case("transparent") {
        return Ok(BackgroundArg(Background::Transparent));
    }
    if t.eq_ignore_ascii_case("sky") {
        return Ok(BackgroundArg(Background::Sky));
    }
    let expected = "transparent, sky, or a color R,G,B of whole numbers 0 to 255";
    let [r, g, b] =
        parse_numbers::<3, u8>(s, expected).map_err(|_| format!("'{s}' is not {expected}"))?;
    Ok(BackgroundArg(Background::Color(U8Vec3::new(r, g, b))))
}

/// `--format`: every format a build can write.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum FormatArg {
    /// PNG, with alpha.
    Png,
    /// Windows bitmap (with the `image` feature), with alpha.
    Bmp,
    /// Targa (with the `image` feature), with alpha.
    Tga,
    /// Binary color pixmap (with the `image` feature), no alpha.
    Ppm,
}

/// `N` comma-separated numbers of type `T`; `what` names them in errors.
pub fn parse_numbers<const N: usize, T: std::str::FromStr>(
    s: &str,
    what: &str,
) -> Result<[T; N], String> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    if parts.len() != N {
        return Err(format!("expected {what}, got '{s}'"));
    }
    let mut out = Vec::with_capacity(N);
    for p in parts {
        out.push(
            p.parse::<T>()
                .map_err(|_| format!("'{p}' is not a valid number in '{s}'"))?,
        );
    }
    out.try_into()
        .map_err(|_| format!("expected {what}, got '{s}'"))
}

/// `X,Y,Z`, finite.
pub fn parse_vec3(s: &str) -> Result<Vec3, String> {
    let [x, y, z] = parse_numbers::<3, f32>(s, "three numbers X,Y,Z")?;
    let v = Vec3::new(x, y, z);
    if v.is_finite() {
        Ok(v)
    } else {
        Err(format!("'{s}' must be finite"))
    }
}

/// The `--sun` setting: a direction, or no light at all.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sun(pub Option<Vec3>);

/// `--sun`: `none`, or a direction that is not all zero.
pub fn parse_sun(s: &str) -> Result<Sun, String> {
    if s.trim().eq_ignore_ascii_case("none") {
        return Ok(Sun(None));
    }
    let v = parse_vec3(s)?;
    if v == Vec3::ZERO {
        return Err(format!("'{s}' is not a direction (all zero)"));
    }
    Ok(Sun(Some(v)))
}

/// A positive finite distance in voxels.
pub fn parse_distance(s: &str) -> Result<f32, String> {
    match s.trim().parse::<f32>() {
        Ok(d) if d > 0.0 && d.is_finite() => Ok(d),
        _ => Err(format!("'{s}' is not a positive finite distance")),
    }
}

/// `--noise-threshold`: positive, finite and at most 1 (above that every
/// pixel would stop at its first round).
pub fn parse_threshold(s: &str) -> Result<f32, String> {
    match s.trim().parse::<f32>() {
        Ok(t) if t > 0.0 && t <= 1.0 => Ok(t),
        _ => Err(format!(
            "'{s}' is not a noise threshold: a number in (0, 1], such as 0.005"
        )),
    }
}

/// `--time-limit`: seconds, positive and finite (a fraction allowed), as
/// a duration of at least a nanosecond (one beyond `Duration`'s range is
/// its largest: no limit).
pub fn parse_seconds(s: &str) -> Result<std::time::Duration, String> {
    use std::time::Duration;
    match s.trim().parse::<f64>() {
        Ok(secs) if secs > 0.0 && secs.is_finite() => Ok(Duration::try_from_secs_f64(secs)
            .unwrap_or(Duration::MAX)
            .max(Duration::from_nanos(1))),
        _ => Err(format!(
            "'{s}' is not a time limit: a positive number of seconds, such as 30"
        )),
    }
}

/// `X,Y,W,H` in whole pixels.
pub fn parse_rect(s: &str) -> Result<Rect, String> {
    let [x, y, width, height] = parse_numbers::<4, u32>(s, "four whole numbers X,Y,W,H")?;
    Ok(Rect {
        x,
        y,
        width,
        height,
    })
}

/// Parses `--max-memory`: a byte count with an optional binary suffix, `K`,
/// `M`, `G` or `T` (powers of 1024, also written `KiB`, `KB`, `k`, ...).
pub fn parse_bytes(s: &str) -> Result<u64, String> {
    let text = s.trim();
    let digits = text
        .find(|c: char| !c.is_ascii_digit())
        .unwrap_or(text.len());
    let (number, suffix) = text.split_at(digits);
    let shift = match suffix.trim().to_ascii_uppercase().as_str() {
        "" | "B" => 0,
        "K" | "KB" | "KIB" => 10,
        "M" | "MB" | "MIB" => 20,
        "G" | "GB" | "GIB" => 30,
        "T" | "TB" | "TIB" => 40,
        _ => return Err(format!("'{s}' is not a byte count like 512M or 4G")),
    };
    number
        .parse::<u64>()
        .ok()
        .and_then(|n| n.checked_mul(1u64 << shift))
        .filter(|&n| n > 0)
        .ok_or_else(|| format!("'{s}' is not a byte count like 512M or 4G"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn byte_counts_take_binary_suffixes() {
        assert_eq!(parse_bytes("1000"), Ok(1000));
        assert_eq!(parse_bytes("512M"), Ok(512 << 20));
        assert_eq!(parse_bytes("4G"), Ok(4 << 30));
        assert_eq!(parse_bytes("4GiB"), Ok(4 << 30));
        assert_eq!(parse_bytes("2k"), Ok(2048));
        for bad in ["", "0", "G", "4X", "-1", "1.5G", "99999999999T"] {
            assert!(parse_bytes(bad).is_err(), "{bad}");
        }
    }
}
