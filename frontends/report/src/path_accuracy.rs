//! The accuracy report's material section: what samples per pixel and
//! bounces cost in time and buy in error on path-traced frames. A voxel
//! room the report builds itself (glass pane, metal mirror, emissive lamp;
//! it stands without the shared files) and, when `../shared/scenes/vox` is
//! there, study.vox with its own materials, sun and sky. Each scene: a
//! converged reference (many samples, the most bounces), then every spp x
//! bounces setting, with time, rays and error (RMSE, PSNR).

use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

use plotters::chart::SeriesLabelPosition;
use voxtrace::{
    render, Bounces, Camera, CameraSettings, Framebuffer, IAabb, Lighting, OctreeScene, Orbit,
    RayStats, Rect, RenderOptions, Scene, Target, VoxModel, WithMaterials,
};
use voxtrace_cli::room;
use voxtrace_flags::{fit, Boxes};

use crate::measure::{count_of, format_ms, median_of};
use crate::plot::{Chart, Line, Series};
use voxtrace_cli::image_error::{psnr, rmse};

/// Where study.vox is, from the repository root; skipped when absent.
const STUDY: &str = "../shared/scenes/vox/study.vox";

/// The settings measured and the reference, per mode.
pub struct Grid {
    /// Image size.
    pub size: (u32, u32),
    /// Samples per pixel along one axis.
    pub spp: &'static [u16],
    /// Bounces (diffuse and specular alike, as `--bounces N`) along the other.
    pub bounces: &'static [u8],
    /// The reference's samples per pixel (at the most bounces).
    pub reference_spp: u16,
}

/// The README's grid: 320x180, reference 256 spp at 8 bounces (about two
/// minutes per scene on two cores).
pub const GRID: Grid = Grid {
    size: (320, 180),
    spp: &[1, 4, 16],
    bounces: &[1, 2, 4, 8],
    reference_spp: 256,
};

/// A smoke run: 160x90, reference 32 spp.
pub const QUICK: Grid = Grid {
    size: (160, 90),
    spp: &[1, 4],
    bounces: &[1, 4],
    reference_spp: 32,
};

/// One measured setting of one scene.
pub struct Row {
    spp: u16,
    bounces: u8,
    ms: f64,
    rays: RayStats,
    rmse: f64,
}

/// One scene's measurements.
pub struct Measured {
    name: String,
    about: String,
    reference_ms: f64,
    rows: Vec<Row>,
}

/// Renders `scene` at every setting of `grid` and against its reference.
fn measure<S: Scene + Sync + ?Sized>(
    name: &str,
    about: String,
    scene: &S,
    camera: &Camera,
    base: &RenderOptions,
    grid: &Grid,
    runs: usize,
) -> Result<Measured, String> {
    let (width, height) = grid.size;
    let frame = Framebuffer::new(width, height).map_err(|e| e.to_string())?;
    let with = |spp: u16, bounces: u8| RenderOptions {
        samples: spp,
        lighting: Lighting {
            bounces: Bounces {
                diffuse: bounces,
                specular: bounces,
            },
            path_trace: true,
            ..base.lighting
        },
        ..*base
    };
    let render = |options: &RenderOptions| {
        let started = Instant::now();
        render(
            scene,
            camera,
            options,
            Rect::full(camera),
            Target::Framebuffer(&frame),
            None,
        )
        .map(|rays| (started.elapsed(), rays))
        .map_err(|e| e.to_string())
    };
    let most = grid.bounces.iter().copied().max().unwrap_or(1);
    eprintln!(
        "{name}: reference {} spp x {most} bounces, {width}x{height}",
        grid.reference_spp
    );
    let (elapsed, _) = render(&with(grid.reference_spp, most))?;
    let reference = frame.to_vec();
    let mut rows = Vec::new();
    for &bounces in grid.bounces {
        for &spp in grid.spp {
            let mut rays = RayStats::default();
            let ms = median_of(runs, || {
                let (elapsed, counted) = render(&with(spp, bounces))?;
                rays = counted;
                Ok(elapsed)
            })?;
            let rmse = rmse(&frame.to_vec(), &reference);
            eprintln!(
                "{name} spp {spp} bounces {bounces}: {} rmse {rmse:.3}",
                format_ms(ms)
            );
            rows.push(Row {
                spp,
                bounces,
                ms,
                rays,
                rmse,
            });
        }
    }
    Ok(Measured {
        name: name.to_string(),
        about,
        reference_ms: elapsed.as_secs_f64() * 1e3,
        rows,
    })
}

/// The room and, when present, study.vox, measured on `grid`.
pub fn measure_all(grid: &Grid, runs: usize) -> Result<Vec<Measured>, String> {
    let mut out = Vec::new();
    for_each_scene(grid.size, |scene| {
        out.push(measure(
            scene.name,
            scene.about.clone(),
            scene.scene,
            scene.camera,
            scene.options,
            grid,
            runs,
        )?);
        Ok(())
    })?;
    Ok(out)
}

/// One path-traced scene the report measures, as `for_each_scene` lends it.
pub struct PathScene<'a> {
    /// Its short name: "room" or "study.vox".
    pub name: &'static str,
    /// What it is, for the report's text.
    pub about: String,
    /// The storage with the scene's materials.
    pub scene: &'a (dyn Scene + Sync),
    /// Its camera at the size asked for.
    pub camera: &'a Camera,
    /// Its light (samples and bounces are the measurer's to set).
    pub options: &'a RenderOptions,
}

/// Calls `f` with each path-traced scene at `size`: the material room the
/// CLI library builds ([`voxtrace_cli::room`]), then study.vox with its
/// own materials, sun and sky when `../shared/scenes/vox` is there (a
/// note on standard error when it is not).
pub fn for_each_scene(
    (width, height): (u32, u32),
    mut f: impl FnMut(&PathScene<'_>) -> Result<(), String>,
) -> Result<(), String> {
    let storage = OctreeScene::build(&room::source(), IAabb::centered(room::BOUNDS))
        .map_err(|e| e.to_string())?;
    let (materials, lamps) = (room::materials(), room::lamps());
    let options = room::path_options(1);
    f(&PathScene {
        name: "room",
        about: "a 21x17x21 voxel room the report builds: a glass pane (ior 1.5), a mirror \
                (metal, roughness 0.05), a lamp of 16 emissive voxels (radiance 4), open to \
                a uniform sky of 0.25, no sun; camera outside the open side"
            .to_string(),
        scene: &WithMaterials::new(&storage, &materials, &lamps),
        camera: &room::camera(width, height),
        options: &options,
    })?;

    if !Path::new(STUDY).exists() {
        eprintln!("note: {STUDY} is absent: the material section measures the room only");
        return Ok(());
    }
    let model = VoxModel::load(Path::new(STUDY)).map_err(|e| format!("{STUDY}: {e}"))?;
    let storage =
        OctreeScene::build(&model, model.bounds()).map_err(|e| format!("{STUDY}: {e}"))?;
    let orbit = Orbit {
        yaw: 200.0,
        pitch: 30.0,
        distance: None,
    };
    let base_camera = CameraSettings {
        width,
        height,
        ..CameraSettings::default()
    };
    let camera = Camera::new(fit(base_camera, orbit.direction(), Boxes::Model(&model))?)
        .map_err(|e| e.to_string())?;
    // The file's light, as the CLI reads it.
    let settings = model.settings();
    let mut lighting = Lighting::DEFAULT;
    if let Some(sun) = settings.sun {
        lighting.sun_intensity = sun.intensity;
        lighting.sun_radius = sun.radius;
    }
    lighting.sky = settings.sky.or(lighting.sky);
    let options = RenderOptions {
        sun: Some(settings.sun.map_or(voxtrace::DEFAULT_SUN, |s| s.direction)),
        lighting,
        ..RenderOptions::default()
    };
    f(&PathScene {
        name: "study.vox",
        about: format!(
            "study.vox ({STUDY}) with its materials ({} emissive voxels), sun and sky, from \
             the orbit 200,30 framed to fit (the README's camera)",
            model.emitters().len()
        ),
        scene: &WithMaterials::new(&storage, model.materials(), model.emitters()),
        camera: &camera,
        options: &options,
    })
}

/// The markdown of the section.
pub fn section(measured: &[Measured], grid: &Grid, runs: usize) -> String {
    let (width, height) = grid.size;
    let most = grid.bounces.iter().copied().max().unwrap_or(1);
    let mut md = String::new();
    let _ = writeln!(
        md,
        "\n### Materials: samples per pixel x bounces\n\n\
         Path-traced frames at {width}x{height}, median of {} per setting; \
         bounces N as `--bounces N` (diffuse and specular alike). Error against a \
         reference of {} samples per pixel at {most} bounces, which is itself noisy: \
         its own error floors the figures at about the last rows' size.\n",
        count_of(runs, "run"),
        grid.reference_spp
    );
    if !measured.iter().any(|m| m.name == "study.vox") {
        let _ = writeln!(
            md,
            "(study.vox was absent: `{STUDY}`; only the room is measured.)\n"
        );
    }
    for m in measured {
        let _ = writeln!(
            md,
            "**{}**: {}. Reference: {}.\n\n\
             | spp | bounces | time | primary rays | reflection rays | refraction rays | light rays | RMSE | PSNR |\n\
             |---|---|---|---|---|---|---|---|---|",
            m.name,
            m.about,
            format_ms(m.reference_ms)
        );
        for r in &m.rows {
            let _ = writeln!(
                md,
                "| {} | {} | {} | {} | {} | {} | {} | {:.2} | {:.1} dB |",
                r.spp,
                r.bounces,
                format_ms(r.ms),
                r.rays.primary_rays,
                r.rays.reflection_rays,
                r.rays.refraction_rays,
                r.rays.light_rays,
                r.rmse,
                psnr(r.rmse)
            );
        }
        md.push('\n');
    }
    md
}

/// Error against time: one line per scene and bounce count, along spp.
pub fn chart(measured: &[Measured], grid: &Grid) -> Chart {
    let (width, height) = grid.size;
    let mut series = Vec::new();
    for (scene, m) in measured.iter().enumerate() {
        for (i, &bounces) in grid.bounces.iter().enumerate() {
            let points = m
                .rows
                .iter()
                .filter(|r| r.bounces == bounces && r.rmse > 0.0)
                .map(|r| (r.ms, r.rmse))
                .collect();
            series.push(Series {
                name: format!("{} {bounces} bounces", m.name),
                points,
                // A color per bounce count; the room thick, study.vox thin.
                color: i,
                line: if scene == 0 { Line::Thick } else { Line::Thin },
            });
        }
    }
    Chart {
        title: format!("Path-traced error against time, spp x bounces, {width}x{height}"),
        x_label: "ms per frame (median)".to_string(),
        y_label: "RMSE against the reference (0-255)".to_string(),
        series,
        legend: SeriesLabelPosition::UpperRight,
    }
}
