//! `VoxModel`: a loaded `.vox` scene as a [`VoxelSource`] (feature `vox`).
//! The placed voxels are kept in 8^3 chunks, only where voxels are, so
//! memory follows the voxel count however far apart the instances stand;
//! a box that meets no chunk is known empty without looking inside.

use std::boxed::Box;
use std::collections::HashMap;
use std::format;
use std::string::String;
use std::vec::Vec;

use glam::{IVec3, U8Vec3};

use crate::geom::{IAabb, MAX_COORD};
use crate::material::{MaterialKind, Materials};
use crate::source::vox::rcam::VoxCamera;
use crate::source::vox::robj::VoxSettings;
use crate::source::vox::scene_graph::{placements, Placement, VoxError, MAX_PLACED};

pub(crate) mod chunks;
pub(crate) mod matl;
pub(crate) mod rcam;
pub(crate) mod robj;
pub(crate) mod scene_graph;
use crate::voxel::{fill_by_position, holds, Palette, Region, VoxelSource};

/// Chunk side, as a shift: 8 voxels.
const CHUNK_LOG: i32 = 3;
const CHUNK: i32 = 1 << CHUNK_LOG;
const CHUNK_VOXELS: usize = (CHUNK * CHUNK * CHUNK) as usize;

/// The most chunks a scene may fill: 512 MiB of voxels. Scattered voxels
/// can each open a chunk of their own, so the voxel limit alone would
/// allow far more.
const MAX_CHUNKS: usize = 1 << 20;

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
    /// Chunk coordinates (position >> 3) to an index into `chunks`.
    index: HashMap<IVec3, u32>,
    chunks: Vec<[u8; CHUNK_VOXELS]>,
    voxels: usize,
    /// Materials of the palette entries voxels use (the rest diffuse).
    materials: Box<Materials>,
    /// Emissive voxels, sorted, so the light list is the same every load.
    emitters: Vec<IVec3>,
    settings: VoxSettings,
    /// The rCAM cameras, by id.
    cameras: Vec<VoxCamera>,
    warnings: Vec<String>,
}

/// Offset of `pos` inside its chunk.
fn in_chunk(pos: IVec3) -> usize {
    let l = pos & (CHUNK - 1);
    (l.x | l.y << CHUNK_LOG | l.z << (2 * CHUNK_LOG)) as usize
}

impl VoxModel {
    /// Reads and places the `.vox` file at `path`.
    pub fn load(path: &std::path::Path) -> Result<VoxModel, VoxError> {
        let bytes = std::fs::read(path).map_err(|e| VoxError::Io(format!("{e}")))?;
        VoxModel::from_bytes(&bytes)
    }

    /// Places the `.vox` file in `bytes`. Counts are checked before anything
    /// is allocated for them: a bad file is an error, never a huge
    /// allocation or a panic.
    pub fn from_bytes(bytes: &[u8]) -> Result<VoxModel, VoxError> {
        let data = dot_vox::load_bytes(bytes).map_err(VoxError::Parse)?;
        let placed = placements(&data)?;
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
        let mut model = VoxModel {
            bounds: IAabb {
                min: IVec3::MAX,
                max: IVec3::MIN,
            },
            palette: Palette::new(&colors),
            index: HashMap::new(),
            chunks: Vec::new(),
            voxels: 0,
            materials: Box::new(Materials::all_diffuse()),
            emitters: Vec::new(),
            settings: robj::settings(bytes),
            cameras: Vec::new(),
            warnings: Vec::new(),
        };
        model.cameras = rcam::cameras(bytes, &mut model.warnings);
        for p in &placed {
            for v in &data.models[p.model].voxels {
                model.place(world(p, v), v.i + 1)?;
            }
        }
        if model.voxels == 0 {
            model.bounds = IAabb {
                min: IVec3::ZERO,
                max: IVec3::ONE,
            };
        }
        model.read_materials(&data.materials);
        Ok(model)
    }

    /// Materials for the palette entries the placed voxels use (after
    /// overlapping instances merged), and the list of emissive voxels.
    fn read_materials(&mut self, matl: &[dot_vox::Material]) {
        let mut used = [false; 256];
        for chunk in &self.chunks {
            for &m in chunk {
                used[usize::from(m)] = true;
            }
        }
        used[0] = false;
        *self.materials = matl::materials(matl, &used, &mut self.warnings);
        let glows = |m: u8| self.materials.get(m).kind() == MaterialKind::Emissive;
        let mut emitters = Vec::new();
        for (&key, &slot) in &self.index {
            for (i, &m) in self.chunks[slot as usize].iter().enumerate() {
                if m != 0 && glows(m) {
                    let i = i as i32;
                    let local = IVec3::new(
                        i & (CHUNK - 1),
                        (i >> CHUNK_LOG) & (CHUNK - 1),
                        i >> (2 * CHUNK_LOG),
                    );
                    emitters.push((key << CHUNK_LOG) + local);
                }
            }
        }
        // The chunk index is a hash map: sort, so every load lists the
        // emitters in one order (the order light samples pick them in).
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
        &self.cameras
    }

    /// One line per MATL or rCAM value that was not a number, out of range or
    /// missing (naming the material id and key), and per kind of material
    /// not simulated.
    #[must_use]
    pub fn warnings(&self) -> &[String] {
        &self.warnings
    }

    /// Sets the voxel at `pos` to `material`, growing the bounds.
    fn place(&mut self, pos: IVec3, material: u8) -> Result<(), VoxError> {
        if pos.abs().max_element() >= MAX_COORD {
            return Err(VoxError::TooLarge(format!(
                "a voxel lands at {pos}, beyond +-{MAX_COORD}"
            )));
        }
        let key = pos >> CHUNK_LOG;
        let slot = match self.index.get(&key) {
            Some(&i) => i as usize,
            None => {
                if self.chunks.len() >= MAX_CHUNKS {
                    return Err(VoxError::TooLarge(format!(
                        "its voxels fill more than {MAX_CHUNKS} chunks of 8^3 ({} bytes)",
                        MAX_CHUNKS * CHUNK_VOXELS
                    )));
                }
                let no_memory = |_| VoxError::TooLarge("its chunks cannot be allocated".into());
                self.chunks.try_reserve(1).map_err(no_memory)?;
                self.index.try_reserve(1).map_err(no_memory)?;
                self.chunks.push([0; CHUNK_VOXELS]);
                let i = self.chunks.len() - 1;
                self.index.insert(key, i as u32);
                i
            }
        };
        let cell = &mut self.chunks[slot][in_chunk(pos)];
        self.voxels += usize::from(*cell == 0);
        *cell = material;
        self.bounds.min = self.bounds.min.min(pos);
        self.bounds.max = self.bounds.max.max(pos + 1);
        Ok(())
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

    /// The position of every solid voxel, chunk by chunk (in no particular
    /// order): for framing a camera on the voxels themselves.
    pub fn positions(&self) -> impl Iterator<Item = IVec3> + '_ {
        self.index.iter().flat_map(move |(&key, &slot)| {
            let chunk = &self.chunks[slot as usize];
            (0..CHUNK_VOXELS).filter(|&i| chunk[i] != 0).map(move |i| {
                let i = i as i32;
                let local = IVec3::new(
                    i & (CHUNK - 1),
                    (i >> CHUNK_LOG) & (CHUNK - 1),
                    i >> (2 * CHUNK_LOG),
                );
                (key << CHUNK_LOG) + local
            })
        })
    }

    /// The chunk holding `pos`, if any voxel is in it.
    fn chunk(&self, pos: IVec3) -> Option<&[u8; CHUNK_VOXELS]> {
        let i = *self.index.get(&(pos >> CHUNK_LOG))?;
        self.chunks.get(i as usize)
    }
}

impl VoxelSource for VoxModel {
    fn palette(&self) -> &Palette {
        &self.palette
    }

    fn material(&self, pos: IVec3) -> u8 {
        self.chunk(pos).map_or(0, |c| c[in_chunk(pos)])
    }

    /// Zero, then the voxels of every chunk that meets the region.
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
        if self.classify(region) == Region::Empty {
            return;
        }
        for (zi, z) in (region.min.z..region.max.z).enumerate() {
            for (yi, y) in (region.min.y..region.max.y).enumerate() {
                let row = sx * (yi + sy * zi);
                // One chunk lookup per run of up to 8 voxels of the row.
                let mut x = region.min.x;
                while x < region.max.x {
                    let run_end = ((x >> CHUNK_LOG) + 1) << CHUNK_LOG;
                    let end = run_end.min(region.max.x);
                    if let Some(chunk) = self.chunk(IVec3::new(x, y, z)) {
                        for xx in x..end {
                            let i = row + (xx - region.min.x) as usize;
                            if let Some(slot) = out.get_mut(i) {
                                *slot = chunk[in_chunk(IVec3::new(xx, y, z))];
                            }
                        }
                    }
                    x = end;
                }
            }
        }
    }

    /// Empty when no chunk with voxels meets the region: by looking up the
    /// region's chunks or by scanning the chunks, whichever is fewer.
    fn classify(&self, region: IAabb) -> Region {
        let inside = region.intersect(&self.bounds);
        if inside.is_empty() {
            return Region::Empty;
        }
        let lo = inside.min >> CHUNK_LOG;
        let hi = (inside.max - 1) >> CHUNK_LOG;
        let span = (hi - lo + 1).as_uvec3();
        let region_chunks = u64::from(span.x) * u64::from(span.y) * u64::from(span.z);
        let occupied = if region_chunks <= self.index.len() as u64 {
            IAabb {
                min: lo,
                max: hi + 1,
            }
            .iter()
            .any(|key| self.index.contains_key(&key))
        } else {
            self.index
                .keys()
                .any(|k| k.cmpge(lo).all() && k.cmple(hi).all())
        };
        if occupied {
            Region::Mixed
        } else {
            Region::Empty
        }
    }
}
