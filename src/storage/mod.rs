//! What voxels are kept in and walked through: the second stage.
//!
//! Both storages implement [`crate::scene::Scene`] over the one cell walk in
//! [`walk`] (Amanatides & Woo's traversal with one tie rule, x before y
//! before z): the flat array of [`dense`] steps it cell by cell, the sparse
//! octree of [`octree`] jumps over empty nodes with it. A jump lands exactly
//! where single steps would, so the two return the same hit, face and `t`
//! for every ray, bit for bit. Tracing allocates nothing and panics on no
//! input; building allocates only through the `build` constructors (feature
//! `alloc`), which fail with an error instead of aborting; [`estimate`]
//! says how many bytes they will need before they are asked to.

pub(crate) mod dense;
pub(crate) mod estimate;
pub(crate) mod octree;
pub(crate) mod walk;
