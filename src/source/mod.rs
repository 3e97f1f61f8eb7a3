//! Where voxels come from: the first stage of the pipeline.
//!
//! Each source implements [`crate::voxel::VoxelSource`]: the seeded Perlin
//! terrain of the seed paper ([`terrain`], over the hand-written generator in
//! [`noise`]) and, with the `vox` feature, MagicaVoxel scenes ([`vox`]).
//! Sources are pure functions of position: asking twice gives the same
//! answer, which lets both storages build from them in any order, on any
//! number of threads, with the same bytes. Everything here but `vox` is
//! `no_std` and allocation-free.

pub(crate) mod noise;
pub(crate) mod terrain;
#[cfg(feature = "vox")]
pub(crate) mod vox;
