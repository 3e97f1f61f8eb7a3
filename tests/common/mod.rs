//! Shared test helpers: an independent brute-force reference for the first
//! hit, ray generators concentrated on hard places, and small voxel sources.
#![allow(dead_code)]

pub mod frames;
pub mod rays;
pub mod reference;
pub mod sources;
