//! `vt_render`: a scene through the CLI's camera and effect flags into a
//! caller's RGBA buffer, on this thread or a pool.

use voxtrace::glam::Vec3;
use voxtrace::rayon::ThreadPoolBuilder;
use voxtrace::{render, unpack, Camera, Framebuffer, Occlusion, Orbit, Rect, Target, ViewPreset};
use voxtrace_flags::{
    default_lens, measured_view, render_options, resolve, Aim, CameraFlags, Effects, Quality,
    Sampling, Subject, Tracer,
};

use crate::{
    guarded, invalid, refused, VtEffects, VtScene, VtStatus, VtView, VT_AIM_ORBIT, VT_AIM_POSITION,
    VT_AIM_VIEW, VT_MAX_THREADS, VT_QUALITY_DEFAULT, VT_QUALITY_DRAFT, VT_QUALITY_FINAL,
    VT_QUALITY_STANDARD,
};

/// The effect flags `effects` names (null: none), as the CLI reads its own.
fn effects_of(effects: Option<&VtEffects>) -> Result<Effects, (VtStatus, String)> {
    let mut out = Effects::default();
    let Some(e) = effects else {
        return Ok(out);
    };
    let quality = match e.quality {
        VT_QUALITY_DEFAULT => None,
        VT_QUALITY_DRAFT => Some(Quality::Draft),
        VT_QUALITY_STANDARD => Some(Quality::Standard),
        VT_QUALITY_FINAL => Some(Quality::Final),
        n => {
            return Err(invalid(format!(
                "quality {n} is not 0 (default), 1, 2 or 3"
            )))
        }
    };
    if !(e.ao_distance == 0.0 || e.ao_distance > 0.0 && e.ao_distance.is_finite()) {
        return Err(invalid(format!(
            "ao_distance {} is not a positive distance",
            e.ao_distance
        )));
    }
    if e.ao_distance > 0.0 {
        out.ao_distance = e.ao_distance;
    }
    out.shadows = e.shadows != 0;
    out.occlusion = (e.ao_rays > 0).then_some(Occlusion {
        rays: e.ao_rays,
        distance: out.ao_distance,
    });
    out.sampling = Sampling {
        spp: (e.spp > 0).then_some(e.spp),
        quality,
        ..Sampling::default()
    };
    out.fog = e.fog != 0;
    out.flat = e.flat != 0;
    Ok(out)
}

/// A render into packed pixels, on this thread or a pool of `threads`.
struct Job<'a> {
    camera: &'a Camera,
    options: &'a voxtrace::RenderOptions,
    threads: u32,
}

impl Tracer for Job<'_> {
    type Output = Result<Vec<u32>, (VtStatus, String)>;

    fn trace<S: voxtrace::Scene + Sync>(self, scene: &S) -> Self::Output {
        let region = Rect::full(self.camera);
        if self.threads == 1 {
            let mut pixels = Vec::new();
            let area = region.area().map_err(refused)?;
            pixels
                .try_reserve_exact(area)
                .map_err(|_| (VtStatus::OutOfMemory, "no memory for the frame".into()))?;
            pixels.resize(area, 0);
            render(
                scene,
                self.camera,
                self.options,
                region,
                Target::Buffer(&mut pixels),
                None,
            )
            .map_err(refused)?;
            return Ok(pixels);
        }
        let threaded = || {
            let frame = Framebuffer::new_parallel(region.width, region.height).map_err(refused)?;
            render(
                scene,
                self.camera,
                self.options,
                region,
                Target::Framebuffer(&frame),
                None,
            )
            .map_err(refused)?;
            Ok(frame.to_vec())
        };
        if self.threads == 0 {
            // rayon's global pool: one thread per core, started once.
            return threaded();
        }
        ThreadPoolBuilder::new()
            .num_threads(self.threads as usize)
            .build()
            .map_err(|e| {
                (
                    VtStatus::RenderFailed,
                    format!("cannot start worker threads: {e}"),
                )
            })?
            .install(threaded)
    }
}

/// Renders `scene` through `view` with `effects` (null: the CLI's
/// defaults) into `rgba`, `view.width * view.height` pixels of 4 bytes
/// (R, G, B, A), rows from the top: the bytes the CLI writes for the same
/// flags. `threads` 1 renders on this thread; 0 on rayon's global pool,
/// one thread per core; any other count up to [`VT_MAX_THREADS`] on a
/// pool of that many started for the call (the bytes are the same).
///
/// # Safety
/// `scene` is a live scene or null, `view` readable or null, `effects`
/// readable or null, `rgba` null or `len` writable bytes.
#[no_mangle]
pub unsafe extern "C" fn vt_render(
    scene: *const VtScene,
    view: *const VtView,
    effects: *const VtEffects,
    threads: u32,
    rgba: *mut u8,
    len: usize,
) -> VtStatus {
    guarded(|| {
        // SAFETY: null or live and readable, as the caller promises.
        let (Some(scene), Some(view)) = (unsafe { scene.as_ref() }, unsafe { view.as_ref() })
        else {
            return Err(invalid("scene or view is null"));
        };
        if rgba.is_null() {
            return Err(invalid("rgba is null"));
        }
        if threads > VT_MAX_THREADS {
            return Err(invalid(format!(
                "{threads} threads: at most {VT_MAX_THREADS}"
            )));
        }
        let needed = (view.width as usize)
            .checked_mul(view.height as usize)
            .and_then(|n| n.checked_mul(4))
            .ok_or_else(|| invalid("the frame does not fit in memory"))?;
        if len < needed {
            return Err(invalid(format!(
                "rgba holds {len} bytes; a {}x{} frame needs {needed}",
                view.width, view.height
            )));
        }
        let fov = if view.fov == 0.0 {
            voxtrace::DEFAULT_FOV
        } else {
            view.fov
        };
        let aim = match view.aim {
            VT_AIM_POSITION => Aim::Position(Vec3::from_array(view.position)),
            VT_AIM_ORBIT => {
                let [yaw, pitch, distance] = view.orbit;
                let distance = (distance != 0.0).then_some(distance);
                Aim::Orbit(Orbit {
                    yaw,
                    pitch,
                    distance,
                })
            }
            VT_AIM_VIEW => match ViewPreset::ALL.get(view.view as usize) {
                Some(&preset) => Aim::Preset(preset),
                None => return Err(invalid(format!("view {} is not 0 to 6", view.view))),
            },
            n => {
                return Err(invalid(format!(
                    "aim {n} is not 0 (position), 1 (orbit) or 2 (view)"
                )))
            }
        };
        let lookat = Vec3::from_array(view.lookat);
        let flags = CameraFlags {
            fov,
            lookat: (!lookat.is_nan()).then_some(lookat),
            ..CameraFlags::new(view.width, view.height, aim)
        };
        let settings = resolve(&flags, &scene.stage()).map_err(invalid)?;
        let camera = Camera::new(settings).map_err(refused)?;
        // SAFETY: null or readable, as the caller promises.
        let effects = effects_of(unsafe { effects.as_ref() })?;
        let model = scene.subject.as_ref().and_then(Subject::model);
        let options = render_options(&effects, scene.bounds, model, &settings);
        let materials = scene.subject.as_ref().and_then(Subject::materials);
        let job = Job {
            camera: &camera,
            options: &options,
            threads,
        };
        let pixels = scene.built.trace(materials, job)?;
        // SAFETY: the caller gives `len` >= `needed` writable bytes.
        let out = unsafe { std::slice::from_raw_parts_mut(rgba, needed) };
        for (bytes, &pixel) in out.chunks_exact_mut(4).zip(&pixels) {
            bytes.copy_from_slice(&unpack(pixel));
        }
        Ok(())
    })
}

/// Fills `*out` with the camera the CLI takes for `scene` at `width` x
/// `height` when no camera flag is given (what its `--stats` prints as
/// `camera:`): the terrain's paper camera, or for a model (and a caller's
/// voxels) the measured view from its front half. `vt_render` through it
/// writes the CLI's default frame.
///
/// # Safety
/// `scene` is a live scene or null; `out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn vt_default_view(
    scene: *const VtScene,
    width: u32,
    height: u32,
    out: *mut VtView,
) -> VtStatus {
    guarded(|| {
        // SAFETY: null or live, as the caller promises.
        let Some(scene) = (unsafe { scene.as_ref() }) else {
            return Err(invalid("scene is null"));
        };
        if out.is_null() {
            return Err(invalid("out is null"));
        }
        if width == 0 || height == 0 {
            return Err(invalid(format!(
                "a {width}x{height} frame: both sides at least 1"
            )));
        }
        let stage = scene.stage();
        let flags = CameraFlags::new(width, height, Aim::Default);
        let inside = |position: Vec3| {
            let cell = position.floor().as_ivec3();
            scene
                .subject
                .as_ref()
                .is_some_and(|s| s.bounds().contains(cell) && s.material(cell) != 0)
        };
        let flags = match default_lens(flags, &stage, inside) {
            Some(lens) => measured_view(lens, scene.built.scene(), &stage),
            None => flags,
        };
        let settings = resolve(&flags, &stage).map_err(invalid)?;
        let view = VtView {
            width,
            height,
            position: settings.lookfrom.to_array(),
            lookat: settings.lookat.to_array(),
            fov: settings.vertical_fov,
            aim: VT_AIM_POSITION,
            orbit: [0.0; 3],
            view: 0,
        };
        // SAFETY: checked non-null; the caller gives a writable pointer.
        unsafe { *out = view };
        Ok(())
    })
}
