//! The flags as the plain values the resolvers take: the shared crate's
//! camera flags and effects, and which flags were given that may change
//! nothing. The resolvers never see [`Args`] or clap's matches, so each
//! takes exactly what it uses.

use clap::parser::ValueSource;
use clap::ArgMatches;
use voxtrace::{Background, Occlusion};
use voxtrace_flags::{Aim, CameraFlags, Effects, Sampling};

use super::{Args, BackgroundArg, OrbitArg, ProjectionArg, QualityArg};

/// Which of the flags that can change nothing the command line gave, for
/// the notes that say so. "On the command line" is clap's word, not a
/// comparison with the default: `--size 100` is given.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GivenFlags {
    /// `--vox`: the scene is a file, not the terrain.
    pub vox: bool,
    /// `--seed`.
    pub seed: bool,
    /// `--size` on the command line.
    pub size: bool,
    /// `--ao`.
    pub ao: bool,
    /// `--ao-distance` on the command line.
    pub ao_distance: bool,
    /// `--ortho-height` on the command line.
    pub ortho_height: bool,
    /// `--fov` on the command line.
    pub fov: bool,
    /// `--projection perspective` on the command line (the last one).
    pub perspective: bool,
    /// `--background transparent`.
    pub transparent: bool,
    /// `--noise-threshold`.
    pub noise_threshold: bool,
    /// `--max-spp`.
    pub max_spp: bool,
    /// `--time-limit`.
    pub time_limit: bool,
}

impl Args {
    /// The camera flags as every frontend resolves them
    /// ([`voxtrace_flags::resolve`]); `--view` wins over `--orbit` over
    /// `--position` (clap refuses them together anyway).
    #[must_use]
    pub fn camera_flags(&self) -> CameraFlags {
        let aim = match (self.view, self.orbit, self.position) {
            (Some(view), _, _) => Aim::Preset(view.preset()),
            (None, Some(OrbitArg(orbit)), _) => Aim::Orbit(orbit),
            (None, None, Some(position)) => Aim::Position(position),
            (None, None, None) => Aim::Default,
        };
        CameraFlags {
            width: self.width,
            height: self.height,
            fov: self.fov,
            up: self.up,
            orthographic: self.projection == ProjectionArg::Orthographic,
            ortho_height: self.ortho_height,
            aim,
            lookat: self.lookat,
        }
    }

    /// Whether any camera flag is on the command line (`--position`,
    /// `--lookat`, `--fov`, `--up`, `--projection`, `--ortho-height`,
    /// `--view`, `--orbit`, `--camera`): then the flags say where the
    /// camera stands, and no default view is measured.
    #[must_use]
    pub fn camera_given(matches: &ArgMatches) -> bool {
        const CAMERA: [&str; 9] = [
            "position",
            "lookat",
            "fov",
            "up",
            "projection",
            "ortho_height",
            "view",
            "orbit",
            "camera",
        ];
        CAMERA
            .iter()
            .any(|id| matches.value_source(id) == Some(ValueSource::CommandLine))
    }

    /// The effect flags as every frontend reads them
    /// ([`voxtrace_flags::render_options`]).
    #[must_use]
    pub fn effects(&self) -> Effects {
        let BackgroundArg(background) = self.background;
        Effects {
            flat: self.flat,
            debug: self.debug,
            sun: self.sun.map(|sun| sun.0),
            shadows: self.shadows,
            occlusion: self.ao.map(|rays| Occlusion {
                rays,
                distance: self.ao_distance,
            }),
            ao_distance: self.ao_distance,
            sampling: Sampling {
                spp: self.spp,
                noise_threshold: self.noise_threshold,
                max_spp: self.max_spp,
                quality: self.quality.map(QualityArg::quality),
            },
            fog: self.fog,
            background,
            bounces: self.bounces,
        }
    }

    /// Which flags that can change nothing were given; `matches` are the
    /// ones these arguments were parsed from.
    #[must_use]
    pub fn given(&self, matches: &ArgMatches) -> GivenFlags {
        let given = |id: &str| matches.value_source(id) == Some(ValueSource::CommandLine);
        GivenFlags {
            vox: self.vox.is_some(),
            seed: self.seed.is_some(),
            size: given("size"),
            ao: self.ao.is_some(),
            ao_distance: given("ao_distance"),
            ortho_height: given("ortho_height"),
            fov: given("fov"),
            perspective: self.projection == ProjectionArg::Perspective && given("projection"),
            transparent: self.background.0 == Background::Transparent,
            noise_threshold: self.noise_threshold.is_some(),
            max_spp: self.max_spp.is_some(),
            time_limit: self.time_limit.is_some(),
        }
    }
}
