//! `VoxModel`: a loaded `.vox` scene as a [`VoxelSource`] (feature `vox`).
//! The placed voxels are kept in 8^3 chunks, only where voxels are, so
//! memory follows the voxel count however far apart the instances stand;
//! a box that meets no chunk is known empty without looking inside.

use std::boxed::Box;
use std::format;
use std::string::String;
use std::vec::Vec;

use glam::{IVec3, U8Vec3};

use crate::geom::IAabb;
use crate::material::{MaterialKind, Materials};
use crate::source::vox::index::{ChunkIndex, CHUNK, CHUNK_LOG, CHUNK_VOXELS};
use crate::source::vox::rcam::Cameras;
use crate::source::vox::rcam::VoxCamera;
use crate::source::vox::robj::VoxSettings;
use crate::source::vox::scene_graph::{frame_count, placements, Placement, VoxError, MAX_PLACED};

pub(crate) mod chunks;
pub(crate) mod index;
pub(crate) mod matl;
pub(crate) mod matl_bytes;
pub(crate) mod rcam;
pub(crate) mod robj;
mod rows;
pub(crate) mod scene_graph;
pub(crate) mod warnings;
use crate::voxel::{fill_by_position, holds, Palette, Region, VoxelSource};

/// A MagicaVoxel scene: every model of the file where MagicaVoxel shows it,
/// in voxtrace's axes (y up; MagicaVoxel's z becomes y).
///
/// # Guarantees
/// `bounds()` is the tight box of the solid voxels (one empty voxel for a
/// file without any). Material `m` is MagicaVoxel's palette index `m`, with
/// the file's color. A later instance overwrites an earlier one where they
/// overlap. Memory is proportional to the voxels placed, never to the
/// volume of the bounds.
#[derive(Clone, Debug)]
pub struct VoxModel {
    bounds: IAabb,
    palette: Palette,
    /// Which chunk coordinates (position >> 3) hold voxels: chunk `i` of
    /// `chunks` is the index's `i`-th.
    index: ChunkIndex,
    chunks: Vec<[u8; CHUNK_VOXELS]>,
    voxels: usize,
    /// Materials of the palette entries voxels use (the rest diffuse).
    materials: Box<Materials>,
    /// Emissive voxels, sorted, so the light list is the same every load.
    emitters: Vec<IVec3>,
    settings: VoxSettings,
    /// The rCAM cameras, by id, and the malformed rCAM chunks.
    cameras: Cameras,
    /// The file's animation frames (1 for a still).
    frames: u32,
    warnings: Vec<String>,
}

/// Offset of `pos` inside its chunk.
fn in_chunk(pos: IVec3) -> usize {
    let l = pos & (CHUNK - 1);
    (l.x | l.y << CHUNK_LOG | l.z << (2 * CHUNK_LOG)) as usize
}

impl VoxModel {
    /// Reads and places the `.vox` file at `path` (its first animation
    /// frame: [`VoxModel::load_frame`]).
    pub fn load(path: &std::path::Path) -> Result<VoxModel, VoxError> {
        VoxModel::load_frame(path, 0)
    }

    /// Reads and places animation frame `frame` (from 0) of the `.vox`
    /// file at `path` ([`VoxModel::from_bytes_frame`]).
    pub fn load_frame(path: &std::path::Path, frame: u32) -> Result<VoxModel, VoxError> {
        let bytes = std::fs::read(path).map_err(|e| VoxError::Io(format!("{e}")))?;
        VoxModel::from_bytes_frame(&bytes, frame)
    }

    /// Places the `.vox` file in `bytes` (its first animation frame:
    /// [`VoxModel::from_bytes_frame`]).
    pub fn from_bytes(bytes: &[u8]) -> Result<VoxModel, VoxError> {
        VoxModel::from_bytes_frame(bytes, 0)
    }

    /// Places animation frame `frame` (from 0) of the `.vox` file in
    /// `bytes`: of a file of several models and no scene graph
    /// (MagicaVoxel's animations), model `frame`; of a scene graph, each
    /// transform's and shape's keyframe (`_f`) that holds at `frame`. A
    /// still file has one frame ([`VoxModel::frames`]); a frame past the
    /// last is an error. Counts are checked before anything is allocated
    /// for them: a bad file is an error, never a huge allocation or a
    /// panic.
    pub fn from_bytes_frame(bytes: &[u8], frame: u32) -> Result<VoxModel, VoxError> {
        let data = dot_vox::load_bytes(bytes).map_err(VoxError::Parse)?;
        let frames = frame_count(&data);
        if frame >= frames {
            return Err(VoxError::Invalid(format!(
                "it has {frames} animation frame{} (0 to {}), no frame {frame}",
                if frames == 1 { "" } else { "s" },
                frames - 1
            )));
        }
        let placed = placements(&data, frame)?;
        let colors: Vec<U8Vec3> = data
            .palette
            .iter()
            .map(|c| U8Vec3::new(c.r, c.g, c.b))
            .collect();
        // Voxel index i (already one less than the file's 1-based index)
        // is material i + 1, which needs palette entry i.
        for (m, model) in data.models.iter().enumerate() {
            if let Some(v) = model
                .voxels
                .iter()
                .find(|v| usize::from(v.i) >= colors.len())
            {
                return Err(VoxError::Invalid(format!(
                    "model {m} uses palette index {} but the palette has {} colors",
                    u16::from(v.i) + 1,
                    colors.len()
                )));
            }
        }
        let total: u64 = placed
            .iter()
            .map(|p| data.models[p.model].voxels.len() as u64)
            .sum();
        if total > MAX_PLACED {
            return Err(VoxError::TooLarge(format!(
                "its instances place {total} voxels, more than {MAX_PLACED}"
            )));
        }
        let world = |p: &Placement, v: &dot_vox::Voxel| {
            let s = data.models[p.model].size;
            let pivot = IVec3::new((s.x / 2) as i32, (s.y / 2) as i32, (s.z / 2) as i32);
            let local = IVec3::new(i32::from(v.x), i32::from(v.y), i32::from(v.z));
            // The voxel's center, doubled to stay integral, rotated about
            // the pivot; `>> 1` floors back to the voxel holding it.
            ((p.rotation * (2 * (local - pivot) + 1)) >> 1) + p.translation
        };
        let (models, world) = (&data.models, &world);
        let voxels = || {
            placed
                .iter()
                .flat_map(move |p| models[p.model].voxels.iter().map(move |v| (p, v)))
                .map(move |(p, v)| (world(p, v), v.i + 1))
        };
        // Count the chunks first (8 bytes each), then allocate them once.
        let index = ChunkIndex::count(voxels().map(|(pos, _)| pos), total)?;
        let mut chunks = Vec::new();
        chunks
            .try_reserve_exact(index.len())
            .map_err(|_| VoxError::TooLarge("its chunks cannot be allocated".into()))?;
        chunks.resize(index.len(), [0; CHUNK_VOXELS]);
        let mut model = VoxModel {
            bounds: IAabb {
                min: IVec3::MAX,
                max: IVec3::MIN,
            },
            palette: Palette::new(&colors),
            index,
            chunks,
            voxels: 0,
            materials: Box::new(Materials::all_diffuse()),
            emitters: Vec::new(),
            settings: robj::settings(bytes),
            cameras: Cameras::default(),
            frames,
            warnings: Vec::new(),
        };
        model.cameras = rcam::cameras(bytes, &mut model.warnings);
        let mut last: Option<(IVec3, usize)> = None;
        for (pos, material) in voxels() {
            let key = pos >> CHUNK_LOG;
            let slot = match last {
                Some((k, slot)) if k == key => slot,
                _ => {
                    // Every key was indexed by `ChunkIndex::count`.
                    let Some(slot) = model.index.slot(key) else {
                        continue;
                    };
                    last = Some((key, slot));
                    slot
                }
            };
            let cell = &mut model.chunks[slot][in_chunk(pos)];
            model.voxels += usize::from(*cell == 0);
            *cell = material;
            model.bounds.min = model.bounds.min.min(pos);
            model.bounds.max = model.bounds.max.max(pos + 1);
        }
        if model.voxels == 0 {
            model.bounds = IAabb {
                min: IVec3::ZERO,
                max: IVec3::ONE,
            };
        }
        model.read_materials(&matl_bytes::matl_chunks(&data.materials, bytes));
        Ok(model)
    }

    /// Materials for the palette entries the placed voxels use (after
    /// overlapping instances merged), and the list of emissive voxels.
    fn read_materials(&mut self, matl: &[matl_bytes::Matl<'_>]) {
        let mut used = [false; 256];
        for chunk in &self.chunks {
            for &m in chunk {
                used[usize::from(m)] = true;
            }
        }
        used[0] = false;
        *self.materials = matl::materials(matl, &used, &mut self.warnings);
        let mut emitters: Vec<IVec3> = self
            .solid()
            .filter(|&(_, m)| self.materials.get(m).kind() == MaterialKind::Emissive)
            .map(|(pos, _)| pos)
            .collect();
        // The chunks are in Morton order: sort, so the light list is in
        // position order (the order light samples pick them in).
        emitters.sort_unstable_by_key(|p| (p.x, p.y, p.z));
        self.emitters = emitters;
    }

    /// The materials of the palette entries the scene's voxels use, from
    /// the file's MATL chunks; entries no voxel uses are diffuse.
    #[must_use]
    pub fn materials(&self) -> &Materials {
        &self.materials
    }

    /// The emissive voxels, sorted by position: the light list.
    #[must_use]
    pub fn emitters(&self) -> &[IVec3] {
        &self.emitters
    }

    /// The file's sun, sky and bounce settings (its rOBJ chunks).
    #[must_use]
    pub fn settings(&self) -> &VoxSettings {
        &self.settings
    }

    /// The file's cameras (its rCAM chunks), sorted by id.
    #[must_use]
    pub fn cameras(&self) -> &[VoxCamera] {
        &self.cameras.cameras
    }

    /// How many of the file's rCAM chunks are malformed (hold no camera),
    /// and the first of them, named, with what is wrong with it.
    #[must_use]
    pub fn malformed_cameras(&self) -> (usize, Option<&str>) {
        (
            self.cameras.malformed,
            self.cameras.first_malformed.as_deref(),
        )
    }

    /// The file's animation frames: several for a file of several models
    /// and no scene graph, or a scene graph with keyframes; 1 for a still.
    #[must_use]
    pub fn frames(&self) -> u32 {
        self.frames
    }

    /// One line per MATL or rCAM value that was not a number (or not UTF-8
    /// text), out of range or missing (naming the material id and key), per
    /// MATL key that was not UTF-8 text, per malformed rCAM chunk
    /// and per kind of material not simulated: the first 16 of MATL and of
    /// rCAM, then a line counting the rest ("... and 749 more MATL
    /// warnings").
    #[must_use]
    pub fn warnings(&self) -> &[String] {
        &self.warnings
    }

    /// The tight box around the scene's voxels.
    #[must_use]
    pub fn bounds(&self) -> IAabb {
        self.bounds
    }

    /// Solid voxels in the scene (after overlapping instances merge).
    #[must_use]
    pub fn voxel_count(&self) -> usize {
        self.voxels
    }

    /// Bytes the loaded scene holds on the heap: its chunks (512 bytes
    /// each), their index, the light list, cameras and warnings. A memory
    /// budget adds these to what it builds from the scene.
    #[must_use]
    pub fn heap_bytes(&self) -> usize {
        let strings: usize = self.warnings.iter().map(String::capacity).sum();
        self.chunks.capacity() * CHUNK_VOXELS
            + self.index.heap_bytes()
            + self.emitters.capacity() * core::mem::size_of::<IVec3>()
            + self.cameras.cameras.capacity() * core::mem::size_of::<VoxCamera>()
            + self.warnings.capacity() * core::mem::size_of::<String>()
            + strings
            + core::mem::size_of::<Materials>()
    }

    /// The position of every solid voxel, chunk by chunk (in no particular
    /// order): for framing a camera on the voxels themselves.
    pub fn positions(&self) -> impl Iterator<Item = IVec3> + '_ {
        self.solid().map(|(pos, _)| pos)
    }

    /// Every solid voxel's position and material, chunk by chunk.
    fn solid(&self) -> impl Iterator<Item = (IVec3, u8)> + '_ {
        self.index.keys().flat_map(move |(key, slot)| {
            let corner = key << CHUNK_LOG;
            (0..CHUNK_VOXELS as i32)
                .zip(self.chunks[slot].iter().copied())
                .filter(|&(_, m)| m != 0)
                .map(move |(i, m)| {
                    let l = IVec3::new(i, i >> CHUNK_LOG, i >> (2 * CHUNK_LOG));
                    (corner + (l & (CHUNK - 1)), m)
                })
        })
    }

    /// The chunk holding `pos`, if any voxel is in it.
    fn chunk(&self, pos: IVec3) -> Option<&[u8; CHUNK_VOXELS]> {
        self.chunks.get(self.index.slot(pos >> CHUNK_LOG)?)
    }
}

/// A loaded 2x1x1 model of palette entries 1 and 2, then `matls`: the
/// MATL tests' scene.
#[cfg(test)]
pub(crate) fn two_voxels_with(matls: &[Vec<u8>]) -> VoxModel {
    let mut children = chunks::write::two_voxels();
    matls.iter().for_each(|m| children.extend_from_slice(m));
    VoxModel::from_bytes(&chunks::write::file(&children)).unwrap()
}

impl VoxelSource for VoxModel {
    fn palette(&self) -> &Palette {
        &self.palette
    }

    fn material(&self, pos: IVec3) -> u8 {
        self.chunk(pos).map_or(0, |c| c[in_chunk(pos)])
    }

    /// Zero, then the voxels of every chunk that meets the region: one
    /// lookup per chunk, one copy per row of a chunk.
    fn fill_box(&self, region: IAabb, out: &mut [u8]) {
        if region.is_empty() {
            return;
        }
        if !holds(region, out) {
            return fill_by_position(self, region, out);
        }
        let size = region.size();
        let (sx, sy) = (size.x as usize, size.y as usize);
        let len = sx * sy * size.z as usize; // holds: at most out.len()
        out[..len].fill(0);
        let inside = region.intersect(&self.bounds);
        if inside.is_empty() {
            return;
        }
        let (lo, hi) = (inside.min >> CHUNK_LOG, (inside.max - 1) >> CHUNK_LOG);
        if !self.index.any_in(lo, hi) {
            return;
        }
        for key in (IAabb {
            min: lo,
            max: hi + 1,
        })
        .iter()
        {
            let Some(slot) = self.index.slot(key) else {
                continue;
            };
            let chunk = &self.chunks[slot];
            let corner = key << CHUNK_LOG;
            let part = inside.intersect(&IAabb::new(corner, corner + CHUNK));
            let width = (part.max.x - part.min.x) as usize;
            for z in part.min.z..part.max.z {
                for y in part.min.y..part.max.y {
                    let from = IVec3::new(part.min.x, y, z);
                    let at = from - region.min;
                    let row = at.x as usize + sx * (at.y as usize + sy * at.z as usize);
                    let start = in_chunk(from);
                    out[row..row + width].copy_from_slice(&chunk[start..start + width]);
                }
            }
        }
    }

    /// Empty when no chunk with voxels meets the region, found in the
    /// index's pyramid of occupied cells.
    fn classify(&self, region: IAabb) -> Region {
        let inside = region.intersect(&self.bounds);
        if !inside.is_empty()
            && self
                .index
                .any_in(inside.min >> CHUNK_LOG, (inside.max - 1) >> CHUNK_LOG)
        {
            Region::Mixed
        } else {
            Region::Empty
        }
    }
}
