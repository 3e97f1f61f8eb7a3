//! Command-line arguments (the CLI contract in ARCHITECTURE.md and the
//! README): every clap type and value parser of the binary lives here and
//! in its children, with the plain values the resolvers take (`plain`),
//! and this module imports no sibling.

use std::path::PathBuf;

use clap::Parser;
use voxtrace::glam::Vec3;
use voxtrace::Rect;
use voxtrace_cli::{parse_frame, parse_frame_range, Backend, FrameArg, FrameRange};

mod farm;
mod plain;
mod values;

pub use farm::{StitchArgs, TileArgs};
pub use plain::GivenFlags;
pub use values::{
    parse_background, parse_bytes, parse_distance, parse_orbit, parse_rect, parse_seconds,
    parse_sun, parse_threshold, parse_vec3, BackgroundArg, FormatArg, OrbitArg, ProjectionArg,
    QualityArg, Sun, ViewArg,
};

/// Render the seeded Perlin terrain of the voxtrace paper, or a MagicaVoxel
/// .vox scene, to an image (PNG, BMP, TGA or PPM).
#[derive(Debug, Parser)]
#[command(
    name = "voxtrace",
    version,
    about,
    args_override_self = true,
    // `voxtrace stitch ...` or a render's flags, not both; `voxtrace help`
    // is `--help`, as a new user types it.
    args_conflicts_with_subcommands = true,
)]
pub struct Args {
    /// Storage backend.
    #[arg(long, value_enum, default_value_t = Backend::Octree)]
    pub backend: Backend,

    /// Render this MagicaVoxel .vox scene instead of the terrain (--size and
    /// --seed are then unused).
    #[arg(long, value_name = "FILE")]
    pub vox: Option<PathBuf>,

    /// Render animation frame N (from 0) of the --vox file: its model N
    /// when it holds several and no scene graph (MagicaVoxel's animations),
    /// else the scene graph's keyframes at N [default: 0, the first].
    /// `all` renders every frame, each to --out with its run of # made
    /// the frame's number (walk_####.png -> walk_0000.png, ...).
    #[arg(long, value_name = "N|all", requires = "vox", value_parser = parse_frame)]
    pub frame: Option<FrameArg>,

    /// Scene extent N: the volume is [-N, N)^3.
    #[arg(long, default_value_t = 100, value_parser = clap::value_parser!(i32).range(1..=voxtrace::MAX_COORD as i64))]
    pub size: i32,

    /// Camera position X,Y,Z [default: N-10,N-10,N-10, or where that is
    /// inside the ground the view that sees the most of the terrain; with
    /// --vox and no camera flag, of eight views around the model from 30
    /// degrees above, the one of its front half (--orbit yaw 315 to 45)
    /// that sees the most of it, unless another side sees clearly more (a
    /// room's open side), framed, at --fov 30; with other camera flags,
    /// the model's front from a little above].
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true, conflicts_with_all = ["view", "orbit"])]
    pub position: Option<Vec3>,

    /// Point the camera looks at, X,Y,Z [default: 0,0,0; with --vox, the
    /// model's center].
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    pub lookat: Option<Vec3>,

    /// Vertical field of view in degrees, in (0, 180) (a .vox model's
    /// default view, without camera flags, is at 30).
    #[arg(long, default_value_t = voxtrace::DEFAULT_FOV)]
    pub fov: f32,

    /// The scene's up direction X,Y,Z: the image's top leans toward it. An
    /// --up parallel to the view is refused; without --up a view straight
    /// down has the image's top toward -z (a map), straight up its mirror
    /// [default: 0,1,0].
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    pub up: Option<Vec3>,

    /// How rays leave the camera.
    #[arg(long, value_enum, default_value_t = ProjectionArg::Perspective)]
    pub projection: ProjectionArg,

    /// Height of an orthographic image in voxels [default: fits the scene].
    #[arg(long, value_name = "VOXELS", value_parser = parse_distance)]
    pub ortho_height: Option<f32>,

    /// A named view of the whole scene, framed to fit: front is +z (a .vox
    /// model's front), right +x, top +y (a map, -z at the top); iso is the
    /// isometric view from front, right and above, orthographic.
    #[arg(long, value_enum, conflicts_with = "orbit")]
    pub view: Option<ViewArg>,

    /// Orbit the target: YAW degrees around the vertical from the front
    /// (+z, positive toward +x), PITCH degrees above the horizon, at
    /// DISTANCE [default distance: framed to fit].
    #[arg(long, value_name = "YAW,PITCH[,DISTANCE]", value_parser = parse_orbit, allow_hyphen_values = true)]
    pub orbit: Option<OrbitArg>,

    /// Render from the --vox file's own camera N (its rCAM camera id, as
    /// MagicaVoxel numbers them): position, target, up and projection come
    /// from the file.
    #[arg(long, value_name = "N", conflicts_with_all = ["position", "lookat", "view", "orbit", "up", "fov", "projection", "ortho_height"])]
    pub camera: Option<u32>,

    /// Render N frames of a turntable: the camera turns 360 degrees about
    /// the vertical through its target; --out needs a run of # for the
    /// frame number (spin_####.png), frames count from 1.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=100_000))]
    pub frames: Option<u32>,

    /// Render only frames A to B of --frames (A-B, or one frame A): the same
    /// bytes as those frames of the full run.
    #[arg(long, value_name = "A-B", value_parser = parse_frame_range, requires = "frames")]
    pub frame_range: Option<FrameRange>,

    /// What pixels whose ray misses every voxel show: transparent (alpha
    /// 0, in formats with alpha: png, tga, bmp), sky, or a color R,G,B.
    #[arg(long, value_name = "transparent|sky|R,G,B", value_parser = parse_background, default_value = "sky")]
    pub background: BackgroundArg,

    /// Terrain seed [default: random, printed to stderr].
    #[arg(long)]
    pub seed: Option<u64>,

    /// Image width in pixels.
    #[arg(long, default_value_t = 1920, value_parser = clap::value_parser!(u32).range(1..=65535))]
    pub width: u32,

    /// Image height in pixels.
    #[arg(long, default_value_t = 1080, value_parser = clap::value_parser!(u32).range(1..=65535))]
    pub height: u32,

    /// Output image path; the extension picks the format (png, bmp, tga,
    /// ppm; no extension: png), `-` writes to standard output.
    #[arg(long, default_value = "render.png")]
    pub out: PathBuf,

    /// Output format, whatever the --out extension says (for --out -).
    #[arg(long, value_enum)]
    pub format: Option<FormatArg>,

    /// Write the terrain of --size and --seed as a MagicaVoxel .vox file
    /// (its surface voxels; --size at most 128) and render nothing.
    #[arg(long, value_name = "FILE", conflicts_with = "vox")]
    pub export_vox: Option<PathBuf>,

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
    /// [default: the terrain 0.45,1,-0.3; a --vox file its own sun, else
    /// over the camera's right shoulder: 30 degrees to the side of the way
    /// back from what the camera looks at, 45 above the horizon].
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

    /// Samples per pixel, exactly N for every pixel (anti-aliasing; in a
    /// path-traced scene, uniform sampling instead of adaptive) [default:
    /// 1; a path-traced scene samples adaptively, see --noise-threshold].
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..=4096))]
    pub spp: Option<u16>,

    /// Adaptive sampling of a path-traced scene (metal, glass, emitters or
    /// --bounces): each pixel takes 16 to 64 samples in rounds of 16 (32 to
    /// 256 in rounds of 32 with --quality final), stopping once another
    /// sample would take less than X off its error: once the spread of its
    /// samples (clamped to white, in units of white, the channels'
    /// variances averaged) over their count is below X [default: 0.005,
    /// final 0.0015; the default without --spp].
    #[arg(long, value_name = "X", value_parser = parse_threshold, allow_hyphen_values = true, conflicts_with = "spp")]
    pub noise_threshold: Option<f32>,

    /// The most samples a pixel of an adaptively sampled path-traced scene
    /// takes, 1 to 4096 (its first round no larger) [default: 64, final
    /// 256].
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..=4096), conflicts_with = "spp")]
    pub max_spp: Option<u16>,

    /// A time budget in seconds for the render of each path-traced frame
    /// (not the build): its samples are taken in rounds over the whole
    /// frame (16 per pixel, or the adaptive minimum), and a round begins
    /// only if the time spent plus the last round's time is within the
    /// budget; the first round always runs. The frame written is exactly
    /// the one the flag `--stats` prints as `reproduce` (--spp N or
    /// --max-spp N) renders without a limit. Not with --tiles.
    #[arg(long, value_name = "SECONDS", value_parser = parse_seconds, allow_hyphen_values = true)]
    pub time_limit: Option<std::time::Duration>,

    /// Effects and samples in one word. draft (alias preview): one sample,
    /// no effects, the terrain's default; standard: --shadows --ao 8
    /// --spp 4, a --vox model's default; final: --shadows --ao 16 --spp
    /// 16. A path-traced scene keeps its adaptive sampling, to a lower
    /// noise threshold under final. Flags given explicitly win.
    #[arg(long, value_enum)]
    pub quality: Option<QualityArg>,

    /// Distance fog, all fog at 3 x --size voxels from the camera (with
    /// --vox, at twice the distance to the model's far side).
    #[arg(long)]
    pub fog: bool,

    /// Bounces per light path, diffuse and specular alike (overrides a .vox
    /// file's `_bounce`); path-traces even an all-diffuse scene.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u8))]
    pub bounces: Option<u8>,

    /// Denoise the finished frame with Intel Open Image Denoise, guided by
    /// the first hit's albedo and normal (for path-traced frames at few
    /// samples). Needs a build with `--features denoise` (docs/denoise.md);
    /// not with --tiles, whose parts would show seams.
    #[arg(long)]
    pub denoise: bool,

    /// Worker threads for the build and the render, 1 to 256; 1 runs the
    /// scalar single-threaded path [default: all cores]. (More threads than
    /// that only reserve stacks: 65535 of them do not fit in a small
    /// address space.)
    #[arg(long, value_parser = clap::value_parser!(u16).range(1..=256))]
    pub threads: Option<u16>,

    /// Print `key: value` statistics to stderr.
    #[arg(long)]
    pub stats: bool,

    /// Render-farm tiles (`--tiles`, `--tile-index`).
    #[command(flatten)]
    pub farm: TileArgs,

    /// Memory the scene and frame may use, in bytes with an optional K, M, G
    /// or T suffix (512M, 4G); a scene estimated to need more is refused
    /// before it is built [default: what the OS says is available].
    #[arg(long, value_name = "BYTES", value_parser = parse_bytes)]
    pub max_memory: Option<u64>,

    /// `voxtrace stitch`, instead of a render.
    #[command(subcommand)]
    pub command: Option<Command>,
}

/// The subcommands: without one, `voxtrace` renders.
#[derive(Debug, clap::Subcommand)]
pub enum Command {
    /// Assemble the tiles of one frame (rendered with --tiles) into the full
    /// PNG, the same file a single render writes; refuses parts that do not
    /// fit together.
    Stitch(StitchArgs),
}
