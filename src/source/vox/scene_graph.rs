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

/// Every model instance of `data`, placed. Files without a scene graph put
/// each model at the origin.
pub(crate) fn placements(data: &DotVoxData) -> Result<Vec<Placement>, VoxError> {
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
    let mut out = Vec::new();
    if data.scenes.is_empty() {
        for model in 0..data.models.len() {
            out.push(Placement {
                model,
                rotation: Z_UP_TO_Y_UP,
                translation: IVec3::ZERO,
            });
        }
        return Ok(out);
    }
    let mut visiting = HashSet::new();
    walk(
        data,
        0,
        IMat3::IDENTITY,
        IVec3::ZERO,
        0,
        &mut visiting,
        &mut out,
    )?;
    for p in &mut out {
        p.rotation = Z_UP_TO_Y_UP * p.rotation;
        p.translation = Z_UP_TO_Y_UP * p.translation;
    }
    Ok(out)
}

/// Visits node `index` under the accumulated transform (z-up).
fn walk(
    data: &DotVoxData,
    index: u32,
    rotation: IMat3,
    translation: IVec3,
    depth: usize,
    visiting: &mut HashSet<u32>,
    out: &mut Vec<Placement>,
) -> Result<(), VoxError> {
    if depth > MAX_DEPTH || !visiting.insert(index) {
        return Err(VoxError::Invalid(format!(
            "the scene graph loops or nests deeper than {MAX_DEPTH} at node {index}"
        )));
    }
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
            if hidden(attributes) || hidden_layer {
                visiting.remove(&index);
                return Ok(());
            }
            let (r, t) = match frames.first() {
                Some(frame) => (
                    rotation_of(frame.attributes.get("_r"))?,
                    translation_of(frame.attributes.get("_t"))?,
                ),
                None => (IMat3::IDENTITY, IVec3::ZERO),
            };
            let t = rotation * t + translation;
            walk(data, *child, rotation * r, t, depth + 1, visiting, out)?;
        }
        SceneNode::Group {
            attributes,
            children,
        } => {
            if !hidden(attributes) {
                for &child in children {
                    walk(data, child, rotation, translation, depth + 1, visiting, out)?;
                }
            }
        }
        SceneNode::Shape { models, .. } => {
            for shape in models {
                let model = shape.model_id as usize;
                if model >= data.models.len() {
                    return Err(VoxError::Invalid(format!(
                        "a shape uses model {model}, but the file has {}",
                        data.models.len()
                    )));
                }
                out.push(Placement {
                    model,
                    rotation,
                    translation,
                });
            }
        }
    }
    visiting.remove(&index);
    Ok(())
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
        [x, y, z] if [x, y, z].iter().all(|c| c.abs() <= MAX_COORD) => Ok(IVec3::new(x, y, z)),
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
        for bad in ["1 2", "1 2 3 4", "a b c", "1 2 99999999"] {
            assert!(t(bad).is_err(), "{bad}");
        }
    }
}
