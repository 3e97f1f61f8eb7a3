//! What the `voxtrace` CLI's camera and effect flags mean, written once for
//! every frontend that offers them, so that the web page's picture for the
//! same flags is the CLI's byte for byte:
//!
//! - [`framing`](mod@framing): cameras that fit what they show ([`fit`], [`FILL`],
//!   [`MODEL_VIEW`]);
//! - [`camera`]: the one camera that `--view`, `--orbit`, `--position`,
//!   `--lookat`, `--projection` and friends describe together
//!   ([`resolve`]), and the flags that reproduce a camera ([`describe`]);
//! - [`effects`]: the render options the effect flags ask for, a `.vox`
//!   file's light folded in ([`render_options`]);
//! - [`quality`]: `--spp`, `--noise-threshold` and `--quality` as the
//!   frame's samples, uniform or adaptive ([`Quality`], [`Sampling`]);
//! - [`open_side`](mod@open_side): the default view chosen by measurement,
//!   the orbit that sees the most of the scene ([`open_side()`],
//!   [`MODEL_FOV`]);
//! - [`subject`]: the terrain or a model, what its camera frames, and the
//!   storage built from it ([`Subject`], [`Built`], [`Backend`]).
//!
//! Every function takes plain values, not a frontend's parsed arguments.

pub mod camera;
pub mod effects;
pub mod framing;
pub mod open_side;
pub mod quality;
pub mod subject;

pub use camera::{describe, resolve, Aim, CameraFlags, Stage};
pub use effects::{render_options, shoulder_sun, Effects};
pub use framing::{fit, framing, Boxes, FILL, MODEL_VIEW};
pub use open_side::{
    default_lens, in_front_half, measured_view, open_side, seen, Seen, MODEL_FOV, OPEN_SIDE_ORBITS,
};
pub use quality::{Quality, Sampling};
pub use subject::{materials_of, Backend, Built, Subject, Tracer};
