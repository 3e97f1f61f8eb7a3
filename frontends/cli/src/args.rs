//! Command-line arguments (the CLI contract in ARCHITECTURE.md and the README).

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

    /// Render this MagicaVoxel .vox scene instead of the terrain (--size and
    /// --seed are then unused).
    #[arg(long, value_name = "FILE")]
    pub vox: Option<PathBuf>,

    /// Scene extent N: the volume is [-N, N)^3.
    #[arg(long, default_value_t = 100, value_parser = clap::value_parser!(i32).range(1..=voxtrace::MAX_COORD as i64))]
    pub size: i32,

    /// Camera position X,Y,Z [default: N-10,N-10,N-10; with --vox, a
    /// three-quarter view that frames the model].
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    pub position: Option<Vec3>,

    /// Point the camera looks at, X,Y,Z [default: 0,0,0; with --vox, the
    /// model's center].
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    pub lookat: Option<Vec3>,

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

    /// The seed paper's debug view: the edges of the boxes the storage walks
    /// through (octree nodes; cells for dense), colored by a Pearson hash of
    /// their position, voxels black.
    #[arg(long)]
    pub debug: bool,

    /// Direction toward the sun X,Y,Z, or `none` for a scene without light
    /// [default: 0.45,1,-0.3].
    #[arg(long, value_parser = parse_sun, allow_hyphen_values = true)]
    pub sun: Option<Sun>,

    /// Hard shadows: one ray toward the sun per hit on a sunlit face.
    #[arg(long)]
    pub shadows: bool,

    /// Ambient occlusion with N rays per hit.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..=4096))]
    pub ao: Option<u16>,

    /// How far ambient occlusion looks for occluders, in voxels.
    #[arg(long, value_name = "VOXELS", default_value_t = voxtrace::Occlusion::DEFAULT_DISTANCE, value_parser = parse_distance)]
    pub ao_distance: f32,

    /// Samples per pixel (anti-aliasing).
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = clap::value_parser!(u16).range(1..=4096))]
    pub spp: u16,

    /// Distance fog, all fog at 3 x --size voxels from the camera (1.5 x the
    /// model's largest side with --vox).
    #[arg(long)]
    pub fog: bool,

    /// Bounces per light path, diffuse and specular alike (overrides a .vox
    /// file's `_bounce`); path-traces even an all-diffuse scene.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u8))]
    pub bounces: Option<u8>,

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

/// The `--sun` setting: a direction, or no light at all.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sun(pub Option<Vec3>);

fn parse_sun(s: &str) -> Result<Sun, String> {
    if s.trim().eq_ignore_ascii_case("none") {
        return Ok(Sun(None));
    }
    let v = parse_vec3(s)?;
    if v == Vec3::ZERO {
        return Err(format!("'{s}' is not a direction (all zero)"));
    }
    Ok(Sun(Some(v)))
}

fn parse_distance(s: &str) -> Result<f32, String> {
    match s.trim().parse::<f32>() {
        Ok(d) if d > 0.0 && d.is_finite() => Ok(d),
        _ => Err(format!("'{s}' is not a positive finite distance")),
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
