//! `Memories`: what the walks of neighbouring pixels share, one
//! [`WalkMemory`] per kind of ray, for every kernel (the face-shaded ones
//! and the path tracer).

use crate::scene::WalkMemory;

/// What the walks of neighbouring pixels share, one memory per kind of ray
/// (each kind's rays are coherent with each other, not with the others).
/// A memory moves where a walk begins, never what it hits.
#[derive(Default)]
pub(crate) struct Memories<'s> {
    /// Rays from the camera.
    pub(crate) primary: WalkMemory<'s>,
    /// Rays toward the sun, and the path tracer's rays toward its lights.
    pub(crate) shadow: WalkMemory<'s>,
    /// Ambient occlusion rays, and the path tracer's bounces.
    pub(crate) occlusion: WalkMemory<'s>,
}
