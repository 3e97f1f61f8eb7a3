//! What a frame simulates: the render settings, each effect opt-in.

use glam::{U8Vec3, Vec3};

use crate::error::Error;
use crate::render::adaptive::Adaptive;

/// The default sun: high, from +x and slightly from -z, so that tops are
/// brightest and the two lit sides read apart (the seed paper's Fig. 1 look).
pub const DEFAULT_SUN: Vec3 = Vec3::new(0.45, 1.0, -0.3);

/// Ambient occlusion: `rays` rays over the hemisphere of each hit face; a
/// ray that meets a voxel within `distance` is occluded.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Occlusion {
    /// Rays per hit, at least 1.
    pub rays: u16,
    /// How far an occluder counts, in voxels; positive and finite.
    pub distance: f32,
}

impl Occlusion {
    /// The default reach: 8 voxels, a little more than a hill's shoulder.
    pub const DEFAULT_DISTANCE: f32 = 8.0;
}

/// Distance fog: a hit at distance `t` blends toward the sky's horizon color
/// by `min(t / distance, 1)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fog {
    /// Distance at which a hit is all fog, in voxels; positive and finite.
    pub distance: f32,
}

/// What a pixel whose primary ray hits nothing shows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Background {
    /// The sky: the gradient of the lit look, [`crate::FLAT_SKY`] under
    /// `flat` (the default).
    #[default]
    Sky,
    /// Nothing: alpha 0 (and color 0). With several samples per pixel the
    /// alpha is the share of samples that hit, the color their mean.
    Transparent,
    /// One opaque color.
    Color(U8Vec3),
}

/// How many bounces a light path may take, by kind (MagicaVoxel's
/// `_bounce` settings).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Bounces {
    /// Diffuse bounces after the first hit (0: direct light only).
    pub diffuse: u8,
    /// Specular events: mirror and glossy reflections, refractions.
    pub specular: u8,
}

impl Bounces {
    /// The counts MagicaVoxel files carry by default: 2 diffuse, 5
    /// specular.
    pub const DEFAULT: Bounces = Bounces {
        diffuse: 2,
        specular: 5,
    };
}

/// The light of a path-traced frame: what a frame whose scene has metal,
/// glass or emitters (or that asks for `path_trace`) is lit by. The
/// face-shaded look of the other frames does not read it.
///
/// Radiances are in units where 1 is a color's full value (255): a diffuse
/// voxel of color `c` under a uniform sky of radiance `L` with nothing
/// above it is `c * L`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lighting {
    /// A uniform sky of this radiance (MagicaVoxel's `_uni`); `None`: the
    /// sky gradient ([`crate::sky`]) as radiance.
    pub sky: Option<Vec3>,
    /// The sun's strength: a diffuse face of color `c` facing the sun
    /// receives `c * sun_intensity` from it (and less by the cosine).
    /// Its direction is [`RenderOptions::sun`].
    pub sun_intensity: f32,
    /// The sun's angular radius in radians (0: a point, hard shadows).
    pub sun_radius: f32,
    /// Bounce limits.
    pub bounces: Bounces,
    /// Path-trace even a scene whose materials are all diffuse (global
    /// illumination from the sky and the sun).
    pub path_trace: bool,
}

impl Lighting {
    /// The default light: the sky gradient, a sun of strength 0.6 and
    /// angular radius 0.02 (about a degree), [`Bounces::DEFAULT`], and
    /// path tracing only where materials call for it.
    pub const DEFAULT: Lighting = Lighting {
        sky: None,
        sun_intensity: 0.6,
        sun_radius: 0.02,
        bounces: Bounces::DEFAULT,
        path_trace: false,
    };
}

impl Default for Lighting {
    fn default() -> Self {
        Lighting::DEFAULT
    }
}

/// The look of a frame: which effects it simulates. Every effect is off
/// unless asked for, and an effect that is off traces no ray (the kernel
/// tests each effect once per sample).
///
/// The default is the terrain's look: face shading under
/// [`DEFAULT_SUN`], the sky gradient, one primary ray per pixel and nothing
/// more.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderOptions {
    /// Unshaded: every pixel is exactly the color of the voxel its ray hits
    /// first, the sky is [`crate::FLAT_SKY`]; every other effect is ignored.
    /// What palette checks and reference renderers compare against.
    pub flat: bool,
    /// The seed paper's debug view: voxels black, the edges of the boxes the
    /// storage walks through (octree nodes, or cells for the dense array)
    /// drawn in a color hashed from each box's position; other effects are
    /// ignored.
    pub debug: bool,
    /// Direction toward the scene's one light, the sun (need not be unit
    /// length). `None`: the scene has no light; faces get fixed per-face
    /// brightnesses and no shadow rays are traced.
    pub sun: Option<Vec3>,
    /// Hard shadows: one ray toward the sun from each hit whose face the sun
    /// lights.
    pub shadows: bool,
    /// Ambient occlusion, off when `None`.
    pub occlusion: Option<Occlusion>,
    /// Samples per pixel (anti-aliasing), at least 1; 1 samples the pixel's
    /// center. Every pixel of a face-shaded frame takes exactly this many,
    /// and so does a path-traced frame's without `adaptive`.
    pub samples: u16,
    /// Adaptive sampling of path-traced frames: each pixel takes samples
    /// until another would take less than a threshold off its estimated
    /// error (`samples` is then unused). Face-shaded, flat and debug frames ignore it and keep their
    /// pixels. Off when `None`.
    pub adaptive: Option<Adaptive>,
    /// Distance fog, off when `None`.
    pub fog: Option<Fog>,
    /// What misses show.
    pub background: Background,
    /// The light of path-traced frames (scenes with metal, glass or
    /// emitters).
    pub lighting: Lighting,
}

impl Default for RenderOptions {
    fn default() -> Self {
        Self::terrain()
    }
}

impl RenderOptions {
    /// The terrain's look (the default): face shading under [`DEFAULT_SUN`],
    /// one sample per pixel, no secondary rays.
    #[must_use]
    pub const fn terrain() -> Self {
        Self {
            flat: false,
            debug: false,
            sun: Some(DEFAULT_SUN),
            shadows: false,
            occlusion: None,
            samples: 1,
            adaptive: None,
            fog: None,
            background: Background::Sky,
            lighting: Lighting::DEFAULT,
        }
    }

    /// The unshaded look (`flat` on, everything else off).
    #[must_use]
    pub const fn flat() -> Self {
        Self {
            flat: true,
            ..Self::terrain()
        }
    }

    /// Checks every setting is usable: a finite non-zero sun, at least one
    /// sample, usable adaptive settings ([`Adaptive::is_usable`]), at least
    /// one occlusion ray, positive finite distances.
    pub fn validate(&self) -> Result<(), Error> {
        let invalid = |reason| Err(Error::InvalidOptions { reason });
        if self.sun.is_some_and(|sun| !usable_sun(sun)) {
            return invalid("the sun direction must be finite and non-zero");
        }
        if self.samples == 0 {
            return invalid("samples per pixel must be at least 1");
        }
        if self.adaptive.is_some_and(|a| !a.is_usable()) {
            return invalid(
                "adaptive sampling needs 1 <= min samples <= max samples and a positive finite threshold",
            );
        }
        if let Some(ao) = self.occlusion {
            if ao.rays == 0 {
                return invalid("ambient occlusion needs at least one ray");
            }
            if !usable_distance(ao.distance) {
                return invalid("the occlusion distance must be positive and finite");
            }
        }
        if self.fog.is_some_and(|fog| !usable_distance(fog.distance)) {
            return invalid("the fog distance must be positive and finite");
        }
        let light = &self.lighting;
        if light.sky.is_some_and(|sky| !usable_radiance(sky)) {
            return invalid("the sky radiance must be finite and non-negative");
        }
        if !(light.sun_intensity >= 0.0 && light.sun_intensity.is_finite()) {
            return invalid("the sun intensity must be finite and non-negative");
        }
        if !(0.0..=1.5).contains(&light.sun_radius) {
            return invalid("the sun's angular radius must be in [0, 1.5] radians");
        }
        Ok(())
    }

    /// [`RenderOptions::effective`] with every setting
    /// [`RenderOptions::validate`] would reject turned off (at least one
    /// sample): what renderers that cannot return an error run.
    #[must_use]
    pub(crate) fn sanitized(&self) -> RenderOptions {
        let mut options = self.effective();
        options.sun = options.sun.filter(|&sun| usable_sun(sun));
        options.shadows &= options.sun.is_some();
        options.samples = options.samples.max(1);
        // (Only the path tracer reads it.)
        #[cfg(feature = "path")]
        {
            options.adaptive = options.adaptive.filter(Adaptive::is_usable);
        }
        options.occlusion = options
            .occlusion
            .filter(|ao| ao.rays > 0 && usable_distance(ao.distance));
        options.fog = options.fog.filter(|fog| usable_distance(fog.distance));
        let light = &mut options.lighting;
        light.sky = light.sky.filter(|&sky| usable_radiance(sky));
        if !(light.sun_intensity >= 0.0 && light.sun_intensity.is_finite()) {
            light.sun_intensity = 0.0;
        }
        if !(0.0..=1.5).contains(&light.sun_radius) {
            light.sun_radius = 0.0;
        }
        options
    }

    /// The effects that will actually run: the settings with what cannot
    /// apply turned off. Shadows need a sun; `flat` and `debug` draw no
    /// shading at all. Compare with `self` to tell a user what was ignored.
    #[must_use]
    pub fn effective(&self) -> RenderOptions {
        if self.flat || self.debug {
            return RenderOptions {
                flat: self.flat,
                debug: self.debug && !self.flat,
                sun: None,
                shadows: false,
                occlusion: None,
                samples: 1,
                adaptive: None,
                fog: None,
                background: self.background,
                lighting: self.lighting,
            };
        }
        RenderOptions {
            shadows: self.shadows && self.sun.is_some(),
            ..*self
        }
    }
}

/// A sun direction the shading can normalize.
fn usable_sun(sun: Vec3) -> bool {
    sun.is_finite() && sun != Vec3::ZERO
}

/// A radiance the path tracer can use: finite, no negative channel.
fn usable_radiance(radiance: Vec3) -> bool {
    radiance.is_finite() && radiance.min_element() >= 0.0
}

/// A positive, finite distance.
fn usable_distance(distance: f32) -> bool {
    distance > 0.0 && distance.is_finite()
}
