//! Materials: what a palette entry is made of (diffuse, metal, glass or
//! emissive), one per palette index, and the table a scene carries them in.
//!
//! Every scene is all-diffuse unless it supplies a [`Materials`] table
//! (through [`crate::WithMaterials`]); a table should describe only the
//! entries some voxel uses (the `.vox` loader leaves the others diffuse), so
//! that the frame's effect plan asks only for what is on screen.

use glam::IVec3;

use crate::error::Error;

/// What a palette entry is made of.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum MaterialKind {
    /// Lambertian: the voxel's color is its albedo.
    #[default]
    Diffuse,
    /// Metal: a share (`metalness`) of the light is reflected by a
    /// microfacet (GGX) lobe tinted by the color, the rest diffusely.
    Metal,
    /// Glass: a share (`transparency`) of the light meets a dielectric
    /// interface of index `ior` (Fresnel reflection and refraction, tinted
    /// by the color on the way through), the rest is diffuse.
    Glass,
    /// Emissive: the voxel glows with radiance `color * emission` and
    /// reflects nothing.
    Emissive,
}

/// One palette entry's material. Build it with the constructors, which
/// check every parameter.
///
/// # Guarantees
/// Every value is finite; `metalness`, `transparency` and `roughness` are in
/// `[0, 1]`, `ior >= 1`, `emission >= 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material {
    kind: MaterialKind,
    metalness: f32,
    transparency: f32,
    roughness: f32,
    ior: f32,
    emission: f32,
}

impl Default for Material {
    fn default() -> Self {
        Material::DIFFUSE
    }
}

/// A parameter in `[0, 1]`.
fn unit(value: f32, reason: &'static str) -> Result<f32, Error> {
    if (0.0..=1.0).contains(&value) {
        Ok(value)
    } else {
        Err(Error::InvalidMaterial { reason })
    }
}

impl Material {
    /// The diffuse material every entry has unless told otherwise.
    pub const DIFFUSE: Material = Material {
        kind: MaterialKind::Diffuse,
        metalness: 0.0,
        transparency: 0.0,
        roughness: 1.0,
        ior: 1.5,
        emission: 0.0,
    };

    /// A metal: `metalness` of the light (in `[0, 1]`) reflected by a GGX
    /// lobe of `roughness` (in `[0, 1]`, 0 a mirror), tinted by the color.
    pub fn metal(metalness: f32, roughness: f32) -> Result<Material, Error> {
        Ok(Material {
            kind: MaterialKind::Metal,
            metalness: unit(metalness, "metalness must be in [0, 1]")?,
            roughness: unit(roughness, "roughness must be in [0, 1]")?,
            ..Material::DIFFUSE
        })
    }

    /// Glass: `transparency` of the light (in `[0, 1]`) meets a dielectric
    /// of index `ior` (at least 1, finite) with `roughness` in `[0, 1]`.
    pub fn glass(transparency: f32, ior: f32, roughness: f32) -> Result<Material, Error> {
        if !(ior >= 1.0 && ior.is_finite()) {
            return Err(Error::InvalidMaterial {
                reason: "the index of refraction must be at least 1 and finite",
            });
        }
        Ok(Material {
            kind: MaterialKind::Glass,
            transparency: unit(transparency, "transparency must be in [0, 1]")?,
            roughness: unit(roughness, "roughness must be in [0, 1]")?,
            ior,
            ..Material::DIFFUSE
        })
    }

    /// An emitter of radiance `color * emission` (in units where 1 is the
    /// color's full value): `emission` non-negative and finite.
    pub fn emissive(emission: f32) -> Result<Material, Error> {
        if !(emission >= 0.0 && emission.is_finite()) {
            return Err(Error::InvalidMaterial {
                reason: "emission must be non-negative and finite",
            });
        }
        Ok(Material {
            kind: MaterialKind::Emissive,
            emission,
            ..Material::DIFFUSE
        })
    }

    /// What the entry is made of.
    #[must_use]
    pub fn kind(&self) -> MaterialKind {
        self.kind
    }

    /// Share of specular (metal) reflection, in `[0, 1]`.
    #[must_use]
    pub fn metalness(&self) -> f32 {
        self.metalness
    }

    /// Share of light meeting the glass interface, in `[0, 1]`.
    #[must_use]
    pub fn transparency(&self) -> f32 {
        self.transparency
    }

    /// Microfacet roughness, in `[0, 1]` (0: a perfect mirror or pane).
    #[must_use]
    pub fn roughness(&self) -> f32 {
        self.roughness
    }

    /// Index of refraction, at least 1.
    #[must_use]
    pub fn ior(&self) -> f32 {
        self.ior
    }

    /// Emission strength: radiance is the color times this.
    #[must_use]
    pub fn emission(&self) -> f32 {
        self.emission
    }
}

/// One material per palette index (index 0, empty, is never looked up).
#[derive(Clone, Debug, PartialEq)]
pub struct Materials {
    table: [Material; 256],
}

impl Default for Materials {
    fn default() -> Self {
        Materials::all_diffuse()
    }
}

impl Materials {
    /// Every entry diffuse.
    #[must_use]
    pub const fn all_diffuse() -> Materials {
        Materials {
            table: [Material::DIFFUSE; 256],
        }
    }

    /// Sets the material of palette index `index`.
    pub fn set(&mut self, index: u8, material: Material) {
        self.table[usize::from(index)] = material;
    }

    /// The material of palette index `index`.
    #[inline]
    #[must_use]
    pub fn get(&self, index: u8) -> Material {
        self.table[usize::from(index)]
    }

    /// Which kinds the entries 1..=255 hold.
    #[must_use]
    pub fn kinds(&self) -> MaterialKinds {
        let mut kinds = MaterialKinds::default();
        for m in &self.table[1..] {
            match m.kind {
                MaterialKind::Diffuse => {}
                MaterialKind::Metal => kinds.metal |= m.metalness > 0.0,
                MaterialKind::Glass => kinds.glass |= m.transparency > 0.0,
                MaterialKind::Emissive => kinds.emissive |= m.emission > 0.0,
            }
        }
        kinds
    }
}

/// Which non-diffuse kinds a table holds (a metal without metalness, glass
/// without transparency or an emitter without emission acts as diffuse and
/// counts as nothing new).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct MaterialKinds {
    /// Some entry reflects specularly.
    pub metal: bool,
    /// Some entry refracts.
    pub glass: bool,
    /// Some entry glows.
    pub emissive: bool,
}

impl MaterialKinds {
    /// Whether any entry is more than diffuse.
    #[must_use]
    pub fn any(&self) -> bool {
        self.metal || self.glass || self.emissive
    }
}

/// What a scene tells the renderer about its materials: the table, and the
/// positions of its emissive voxels (the light list next-event estimation
/// samples; empty when the scene has none or does not list them, and then
/// emitters are only found by rays that happen to hit them).
#[derive(Clone, Copy, Debug)]
pub struct SceneMaterials<'a> {
    /// One material per palette index.
    pub table: &'a Materials,
    /// Emissive voxels.
    pub emitters: &'a [IVec3],
}
