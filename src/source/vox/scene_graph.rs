//! Reading MagicaVoxel `.vox` files (feature `vox`): every model of the file
//! placed where MagicaVoxel shows it, through the scene graph's translations
//! and rotations. Parsing is `dot_vox`'s; this module checks what it returns
//! and places the voxels.

use std::collections::HashSet;
use std::format;
use std::string::String;
use std::vec::Vec;

use dot_vox::{DotVoxData, SceneNode};
use glam::IVec3;

use crate::geom::MAX_COORD;

/// Why a `.vox` file cannot be used. Every message names the problem.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum VoxError {
    /// The file could not be read.
    Io(String),
    /// `dot_vox` rejected the bytes (wrong magic, truncated chunk, ...).
    Parse(&'static str),
    /// Something in the file is inconsistent or out of range; the text says
    /// what.
    Invalid(String),
    /// The placed scene is larger than voxtrace takes.
    TooLarge(String),
}

impl core::fmt::Display for VoxError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            VoxError::Io(e) => write!(f, "cannot read the file: {e}"),
            VoxError::Parse(e) => write!(f, "not a readable .vox file: {e}"),
            VoxError::Invalid(e) => write!(f, "invalid .vox file: {e}"),
            VoxError::TooLarge(e) => write!(f, "the .vox scene is too large: {e}"),
        }
    }
}

impl core::error::Error for VoxError {}

/// The largest model side MagicaVoxel writes (256 in most versions; 2048
/// allows for newer ones).
const MAX_MODEL_SIDE: u32 = 2048;

/// Scene graphs deeper than this are treated as malformed (MagicaVoxel
/// writes a handful of levels).
const MAX_DEPTH: usize = 64;

/// The most model instances a scene may place. A group may list the same
/// child many times, so placements can grow exponentially with the depth
/// of a tiny file; the walk counts them as it goes and stops here, with 15
/// MB of placements at most. Real scenes place hundreds to thousands.
pub(crate) const MAX_PLACEMENTS: usize = 1 << 18;

/// The most voxels the instances may place, counted as the walk goes (each
/// instance counts its model's voxels again): 2^24, so that a small file
/// of many overlapping instances of a big model (under the chunk limit)
/// loads in under a second. Real scenes place a few million at most.
pub(crate) const MAX_PLACED: u64 = 1 << 24;

/// The most scene-graph nodes one walk visits, counting a shared subtree
/// each time it is reached: bounds the time of a graph of empty groups
/// that place nothing.
const MAX_VISITS: u64 = 1 << 22;

/// An integer 3x3 matrix by rows: the signed permutations MagicaVoxel
/// rotates models with (glam has no integer matrix).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct IMat3 {
    rows: [IVec3; 3],
}

impl IMat3 {
    const IDENTITY: IMat3 = IMat3::from_rows(IVec3::X, IVec3::Y, IVec3::Z);

    const fn from_rows(x: IVec3, y: IVec3, z: IVec3) -> IMat3 {
        IMat3 { rows: [x, y, z] }
    }

    #[cfg(test)]
    fn determinant(self) -> i32 {
        let [a, b, c] = self.rows;
        a.dot(b.cross(c))
    }
}

impl core::ops::Mul<IVec3> for IMat3 {
    type Output = IVec3;
    fn mul(self, v: IVec3) -> IVec3 {
        IVec3::new(
            self.rows[0].dot(v),
            self.rows[1].dot(v),
            self.rows[2].dot(v),
        )
    }
}

impl core::ops::Mul for IMat3 {
    type Output = IMat3;
    fn mul(self, other: IMat3) -> IMat3 {
        // Row i of the product: row i of `self` combining the rows of `other`.
        let row = |r: IVec3| other.rows[0] * r.x + other.rows[1] * r.y + other.rows[2] * r.z;
        IMat3::from_rows(row(self.rows[0]), row(self.rows[1]), row(self.rows[2]))
    }
}

/// A placement of a model: world = rotation * local + translation, in
/// voxtrace's axes (y up).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Placement {
    pub(crate) model: usize,
    pub(crate) rotation: IMat3,
    pub(crate) translation: IVec3,
}

/// MagicaVoxel is z-up, voxtrace y-up: (x, y, z) -> (x, z, -y), a rotation
/// (no mirror), so models keep their handedness.
const Z_UP_TO_Y_UP: IMat3 = IMat3::from_rows(IVec3::X, IVec3::Z, IVec3::NEG_Y);

/// The animation frames of `data`: a file without a scene graph holds one
/// per model (MagicaVoxel's animation files before its scene graph);
/// one with a scene graph as many as its highest keyframe (`_f`) plus one.
pub(crate) fn frame_count(data: &DotVoxData) -> u32 {
    if data.scenes.is_empty() {
        return u32::try_from(data.models.len()).unwrap_or(u32::MAX).max(1);
    }
    let keys = data.scenes.iter().flat_map(|node| match node {
        SceneNode::Transform { frames, .. } => frames.iter().map(|f| key(&f.attributes)).collect(),
        SceneNode::Shape { models, .. } => models.iter().map(|m| key(&m.attributes)).collect(),
        SceneNode::Group { .. } => Vec::new(),
    });
    keys.max().unwrap_or(0).saturating_add(1)
}

/// A keyframe's frame (`_f`; 0 when absent or not a number).
fn key(attributes: &dot_vox::Dict) -> u32 {
    attributes
        .get("_f")
        .and_then(|f| f.trim().parse().ok())
        .unwrap_or(0)
}

/// Of keyframes listed in order, the one `frame` shows: the one with the
/// greatest key at most `frame` (a keyframe holds until the next), the
/// first listed of equals, else the first listed.
fn keyframe_at<T>(
    keyframes: &[T],
    attributes: impl Fn(&T) -> &dot_vox::Dict,
    frame: u32,
) -> Option<&T> {
    // Reversed: `max_by_key` keeps the last of equal keys.
    let key_of = |k: &&T| key(attributes(k));
    let shown = keyframes.iter().rev().filter(|k| key_of(k) <= frame);
    shown.max_by_key(key_of).or(keyframes.first())
}

/// Every model instance of animation frame `frame` of `data` (below
/// [`frame_count`]), placed. A file without a scene graph shows its model
/// `frame` at the origin.
pub(crate) fn placements(data: &DotVoxData, frame: u32) -> Result<Vec<Placement>, VoxError> {
    for (i, model) in data.models.iter().enumerate() {
        let s = model.size;
        if [s.x, s.y, s.z]
            .iter()
            .any(|&d| d == 0 || d > MAX_MODEL_SIDE)
        {
            return Err(VoxError::Invalid(format!(
                "model {i} has size {}x{}x{} (each side must be 1 to {MAX_MODEL_SIDE})",
                s.x, s.y, s.z
            )));
        }
        if let Some(v) = model
            .voxels
            .iter()
            .find(|v| u32::from(v.x) >= s.x || u32::from(v.y) >= s.y || u32::from(v.z) >= s.z)
        {
            return Err(VoxError::Invalid(format!(
                "model {i} has a voxel at ({}, {}, {}) outside its size {}x{}x{}",
                v.x, v.y, v.z, s.x, s.y, s.z
            )));
        }
    }
    if data.scenes.is_empty() {
        let at_origin = |model| Placement {
            model,
            rotation: Z_UP_TO_Y_UP,
            translation: IVec3::ZERO,
        };
        return Ok(data
            .models
            .get(frame as usize)
            .map(|_| at_origin(frame as usize))
            .into_iter()
            .collect());
    }
    let mut walker = Walker {
        data,
        frame,
        visiting: HashSet::new(),
        out: Vec::new(),
        visits: 0,
        voxels: 0,
    };
    // The file's z-up world turned y-up first: every transform below it
    // then places in voxtrace's axes (integer math, so exactly as turning
    // each placement after).
    walker.walk(0, Z_UP_TO_Y_UP, IVec3::ZERO, 0)?;
    Ok(walker.out)
}

/// The walk over the scene graph, with what it has counted so far.
struct Walker<'d> {
    data: &'d DotVoxData,
    /// The animation frame whose keyframes the walk takes.
    frame: u32,
    /// Nodes on the current path: a node met again on it is a loop.
    visiting: HashSet<u32>,
    out: Vec<Placement>,
    /// Nodes visited, shared ones each time.
    visits: u64,
    /// Voxels the placements so far place.
    voxels: u64,
}

impl Walker<'_> {
    /// Visits node `index` under the accumulated transform.
    fn walk(
        &mut self,
        index: u32,
        rotation: IMat3,
        translation: IVec3,
        depth: usize,
    ) -> Result<(), VoxError> {
        self.visits += 1;
        if self.visits > MAX_VISITS {
            return Err(VoxError::TooLarge(format!(
                "its scene graph visits more than {MAX_VISITS} nodes (shared subtrees count each time)"
            )));
        }
        if depth > MAX_DEPTH || !self.visiting.insert(index) {
            return Err(VoxError::Invalid(format!(
                "the scene graph loops or nests deeper than {MAX_DEPTH} at node {index}"
            )));
        }
        let data = self.data;
        let node = data.scenes.get(index as usize).ok_or_else(|| {
            VoxError::Invalid(format!("the scene graph refers to missing node {index}"))
        })?;
        match node {
            SceneNode::Transform {
                attributes,
                frames,
                child,
                layer_id,
            } => {
                let hidden_layer = data
                    .layers
                    .get(*layer_id as usize)
                    .is_some_and(|layer| layer.hidden());
                if !(hidden(attributes) || hidden_layer) {
                    let (r, t) = match keyframe_at(frames, |f| &f.attributes, self.frame) {
                        Some(frame) => (
                            rotation_of(frame.attributes.get("_r"))?,
                            translation_of(frame.attributes.get("_t"))?,
                        ),
                        None => (IMat3::IDENTITY, IVec3::ZERO),
                    };
                    // Cannot overflow: each level adds at most MAX_COORD
                    // (2^22) per axis (a signed permutation keeps sizes), over
                    // at most MAX_DEPTH (64) levels: below 2^28.
                    debug_assert!(translation.abs().max_element() <= MAX_COORD * MAX_DEPTH as i32);
                    let t = rotation * t + translation;
                    self.walk(*child, rotation * r, t, depth + 1)?;
                }
            }
            SceneNode::Group {
                attributes,
                children,
            } => {
                if !hidden(attributes) {
                    for &child in children {
                        self.walk(child, rotation, translation, depth + 1)?;
                    }
                }
            }
            SceneNode::Shape { models, .. } => {
                if let Some(shape) = keyframe_at(models, |m| &m.attributes, self.frame) {
                    self.place(shape.model_id as usize, rotation, translation)?;
                }
            }
        }
        self.visiting.remove(&index);
        Ok(())
    }

    /// Records one instance of `model`, counting it and its voxels against
    /// the limits before anything is stored.
    fn place(&mut self, model: usize, rotation: IMat3, translation: IVec3) -> Result<(), VoxError> {
        let Some(m) = self.data.models.get(model) else {
            return Err(VoxError::Invalid(format!(
                "a shape uses model {model}, but the file has {}",
                self.data.models.len()
            )));
        };
        if self.out.len() >= MAX_PLACEMENTS {
            return Err(VoxError::TooLarge(format!(
                "its scene graph places more than {MAX_PLACEMENTS} model instances"
            )));
        }
        self.voxels += m.voxels.len() as u64;
        if self.voxels > MAX_PLACED {
            return Err(VoxError::TooLarge(format!(
                "its instances place more than {MAX_PLACED} voxels"
            )));
        }
        self.out
            .try_reserve(1)
            .map_err(|_| VoxError::TooLarge("its placements cannot be allocated".into()))?;
        self.out.push(Placement {
            model,
            rotation,
            translation,
        });
        Ok(())
    }
}

fn hidden(attributes: &dot_vox::Dict) -> bool {
    attributes.get("_hidden").is_some_and(|v| v == "1")
}

/// The `_t` attribute, "x y z"; absent means no translation.
fn translation_of(value: Option<&String>) -> Result<IVec3, VoxError> {
    let Some(value) = value else {
        return Ok(IVec3::ZERO);
    };
    let parts: Vec<i32> = value
        .split_whitespace()
        .map(str::parse)
        .collect::<Result<_, _>>()
        .map_err(|_| VoxError::Invalid(format!("translation '{value}' is not three integers")))?;
    match parts[..] {
        // unsigned_abs: i32::MIN has no i32 absolute value.
        [x, y, z]
            if [x, y, z]
                .iter()
                .all(|c| c.unsigned_abs() <= MAX_COORD as u32) =>
        {
            Ok(IVec3::new(x, y, z))
        }
        _ => Err(VoxError::Invalid(format!(
            "translation '{value}' is not three integers within +-{MAX_COORD}"
        ))),
    }
}

/// The `_r` attribute: a byte encoding a rotation as a signed permutation.
/// Bits 0-1 give the column of row 0's non-zero entry, bits 2-3 that of row
/// 1 (row 2 takes the remaining one), bits 4, 5, 6 make rows 0, 1, 2
/// negative. Absent means the identity.
fn rotation_of(value: Option<&String>) -> Result<IMat3, VoxError> {
    let Some(value) = value else {
        return Ok(IMat3::IDENTITY);
    };
    let bad = || VoxError::Invalid(format!("rotation '{value}' is not a valid rotation byte"));
    let byte: u8 = value.trim().parse().map_err(|_| bad())?;
    let first = usize::from(byte & 3);
    let second = usize::from((byte >> 2) & 3);
    if first == 3 || second == 3 || first == second {
        return Err(bad());
    }
    let third = 3 - first - second;
    let sign = |bit: u8| if byte >> bit & 1 == 1 { -1 } else { 1 };
    let mut rows = [IVec3::ZERO; 3];
    rows[0][first] = sign(4);
    rows[1][second] = sign(5);
    rows[2][third] = sign(6);
    Ok(IMat3::from_rows(rows[0], rows[1], rows[2]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rotation_bytes_become_signed_permutations() {
        let r = |b: u8| rotation_of(Some(&format!("{b}"))).unwrap();
        // 4 = rows (x, y, z), no signs: the identity.
        assert_eq!(r(4), IMat3::IDENTITY);
        // Row 0 picks y, row 1 picks x, negated: a quarter turn about z.
        let quarter = r(0b0010_0001);
        assert_eq!(quarter * IVec3::X, IVec3::NEG_Y);
        assert_eq!(quarter * IVec3::Y, IVec3::X);
        assert_eq!(quarter * IVec3::Z, IVec3::Z);
        for bad in ["3", "5", "15", "x", "300"] {
            assert!(rotation_of(Some(&String::from(bad))).is_err(), "{bad}");
        }
    }

    #[test]
    fn z_up_becomes_y_up_without_a_mirror() {
        assert_eq!(Z_UP_TO_Y_UP * IVec3::Z, IVec3::Y);
        assert_eq!(Z_UP_TO_Y_UP * IVec3::Y, IVec3::NEG_Z);
        assert_eq!(Z_UP_TO_Y_UP.determinant(), 1);
    }

    #[test]
    fn translations_parse_and_reject_garbage() {
        let t = |s: &str| translation_of(Some(&String::from(s)));
        assert_eq!(t("1 -2 30").unwrap(), IVec3::new(1, -2, 30));
        for bad in ["1 2", "1 2 3 4", "a b c", "1 2 99999999", "-2147483648 0 0"] {
            assert!(t(bad).is_err(), "{bad}");
        }
    }
}
