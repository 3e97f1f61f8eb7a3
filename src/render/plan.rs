//! The effect plan: what a frame will simulate, decided once per frame from
//! the scene's materials (the palette entries its voxels use), its light
//! list and the render options. It picks the kernel, and `--stats` prints
//! it as one line.

use core::fmt;

use crate::material::{MaterialKinds, SceneMaterials};
use crate::render::options::{Bounces, RenderOptions};
use crate::scene::Scene;

/// How a frame's pixels are computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Look {
    /// Unshaded voxel colors.
    Flat,
    /// The seed paper's debug view.
    Debug,
    /// Face shading under the sun, with the options' shadows, occlusion,
    /// samples and fog: what every all-diffuse scene gets.
    Shaded,
    /// Path tracing through the bounces the scene's materials call for.
    /// Only with the feature `path`: without it the frames that would be
    /// path-traced are [`Look::Shaded`], and the plan's description ends
    /// with `no path tracer (feature path): shaded as diffuse`.
    Path,
}

/// What a frame simulates. [`fmt::Display`] lists it, for example
/// `sun, sky, metal(5 bounces), glass(5 bounces), emission(770 lights)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EffectPlan {
    /// The kernel.
    pub look: Look,
    /// The effective options (what cannot run turned off; adaptive
    /// sampling only in [`Look::Path`]).
    pub options: RenderOptions,
    /// The non-diffuse material kinds the scene's used entries hold.
    pub kinds: MaterialKinds,
    /// Emissive voxels in the scene's light list.
    pub lights: usize,
}

impl EffectPlan {
    /// The plan for a scene with `materials` (`None`: all diffuse) under
    /// `options`. Settings [`RenderOptions::validate`] rejects are turned
    /// off.
    #[must_use]
    pub fn new(options: &RenderOptions, materials: Option<SceneMaterials<'_>>) -> EffectPlan {
        let mut options = options.sanitized();
        let kinds = materials.map(|m| m.table.kinds()).unwrap_or_default();
        let look = if options.flat {
            Look::Flat
        } else if options.debug {
            Look::Debug
        } else if wants_path(kinds, &options) && cfg!(feature = "path") {
            Look::Path
        } else {
            Look::Shaded
        };
        // Only the path tracer samples adaptively.
        if look != Look::Path {
            options.adaptive = None;
        }
        let lights = match (look, materials) {
            (Look::Path, Some(m)) if kinds.emissive => m.emitters.len(),
            _ => 0,
        };
        EffectPlan {
            look,
            options,
            kinds,
            lights,
        }
    }

    /// The plan of rendering `scene` with `options`.
    #[must_use]
    pub fn of<S: Scene + ?Sized>(scene: &S, options: &RenderOptions) -> EffectPlan {
        EffectPlan::new(options, scene.materials())
    }
}

impl fmt::Display for EffectPlan {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let o = &self.options;
        let mut first = true;
        let mut item = |f: &mut fmt::Formatter<'_>, args: fmt::Arguments<'_>| {
            let sep = if first { "" } else { ", " };
            first = false;
            write!(f, "{sep}{args}")
        };
        match self.look {
            Look::Flat => return f.write_str("flat"),
            Look::Debug => return f.write_str("debug"),
            Look::Shaded => {
                match o.sun {
                    Some(_) => item(f, format_args!("sun"))?,
                    None => item(f, format_args!("unlit"))?,
                }
                if o.shadows {
                    item(f, format_args!("shadows"))?;
                }
                if let Some(ao) = o.occlusion {
                    item(f, format_args!("ao({} rays)", ao.rays))?;
                }
            }
            Look::Path => {
                let light = &o.lighting;
                if o.sun.is_some() && light.sun_intensity > 0.0 {
                    item(f, format_args!("sun"))?;
                }
                match light.sky {
                    Some(_) => item(f, format_args!("sky(uniform)"))?,
                    None => item(f, format_args!("sky(gradient)"))?,
                }
                let Bounces { diffuse, specular } = light.bounces;
                item(f, format_args!("diffuse({diffuse} bounces)"))?;
                if self.kinds.metal {
                    item(f, format_args!("metal({specular} bounces)"))?;
                }
                if self.kinds.glass {
                    item(f, format_args!("glass({specular} bounces)"))?;
                }
                if self.kinds.emissive {
                    item(f, format_args!("emission({} lights)", self.lights))?;
                }
            }
        }
        match o.adaptive {
            Some(a) => item(
                f,
                format_args!(
                    "adaptive({}-{} spp, threshold {})",
                    a.min_samples, a.max_samples, a.threshold
                ),
            )?,
            None if o.samples > 1 => item(f, format_args!("spp({})", o.samples))?,
            None => {}
        }
        if o.fog.is_some() {
            item(f, format_args!("fog"))?;
        }
        // Only a build without the path tracer shades these.
        if self.look == Look::Shaded && wants_path(self.kinds, o) {
            item(
                f,
                format_args!("no path tracer (feature path): shaded as diffuse"),
            )?;
        }
        Ok(())
    }
}

/// Whether a frame of a scene holding `kinds` under `options` (sanitized)
/// is one to path-trace.
fn wants_path(kinds: MaterialKinds, options: &RenderOptions) -> bool {
    kinds.any() || options.lighting.path_trace
}
