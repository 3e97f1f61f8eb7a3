//! Command-line arguments (the CLI contract in DESIGN.md).

use std::path::PathBuf;

use clap::Parser;
use voxtrace::glam::Vec3;
use voxtrace::Rect;
use voxtrace_cli::Backend;

/// Render the seeded Perlin terrain of the voxtrace paper to a PNG.
#[derive(Debug, Parser)]
#[command(name = "voxtrace", version, about, args_override_self = true)]
pub struct Args {
    /// Storage backend.
    #[arg(long, value_enum, default_value_t = Backend::Octree)]
    pub backend: Backend,

    /// Scene extent N: the volume is [-N, N)^3.
    #[arg(long, default_value_t = 100, value_parser = clap::value_parser!(i32).range(1..=voxtrace::MAX_COORD as i64))]
    pub size: i32,

    /// Camera position X,Y,Z [default: N-10,N-10,N-10].
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    pub position: Option<Vec3>,

    /// Point the camera looks at, X,Y,Z.
    #[arg(long, value_parser = parse_vec3, default_value = "0,0,0", allow_hyphen_values = true)]
    pub lookat: Vec3,

    /// Vertical field of view in degrees, in (0, 180).
    #[arg(long, default_value_t = voxtrace::DEFAULT_FOV)]
    pub fov: f32,

    /// Terrain seed [default: random, printed to stderr].
    #[arg(long)]
    pub seed: Option<u64>,

    /// Image width in pixels.
    #[arg(long, default_value_t = 1920, value_parser = clap::value_parser!(u32).range(1..=65535))]
    pub width: u32,

    /// Image height in pixels.
    #[arg(long, default_value_t = 1080, value_parser = clap::value_parser!(u32).range(1..=65535))]
    pub height: u32,

    /// Output PNG path.
    #[arg(long, default_value = "render.png")]
    pub out: PathBuf,

    /// Render only the crop X,Y,W,H of the frame (the PNG is W x H).
    #[arg(long, value_parser = parse_rect)]
    pub region: Option<Rect>,

    /// Unshaded: each pixel is the hit voxel's color, the sky one constant.
    #[arg(long)]
    pub flat: bool,

    /// Worker threads for the build and the render; 1 runs the scalar
    /// single-threaded path [default: all cores].
    #[arg(long, value_parser = clap::value_parser!(u16).range(1..))]
    pub threads: Option<u16>,

    /// Print `key: value` statistics to stderr.
    #[arg(long)]
    pub stats: bool,
}

fn parse_numbers<const N: usize, T: std::str::FromStr>(
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

fn parse_vec3(s: &str) -> Result<Vec3, String> {
    let [x, y, z] = parse_numbers::<3, f32>(s, "three numbers X,Y,Z")?;
    let v = Vec3::new(x, y, z);
    if v.is_finite() {
        Ok(v)
    } else {
        Err(format!("'{s}' must be finite"))
    }
}

fn parse_rect(s: &str) -> Result<Rect, String> {
    let [x, y, width, height] = parse_numbers::<4, u32>(s, "four whole numbers X,Y,W,H")?;
    Ok(Rect {
        x,
        y,
        width,
        height,
    })
}
