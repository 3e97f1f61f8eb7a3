//! Materials from a `.vox` file's MATL chunks (as dot_vox reads them, and
//! the ones it drops for text that is not UTF-8: see `matl_bytes.rs`), for
//! the palette entries the scene's voxels use.
//!
//! Keys read, by `_type`: `_metal`: `_metal` (or the older `_weight`) as
//! metalness, `_rough`; `_glass`: `_trans` (or `_alpha`, or `_weight`) as
//! transparency, `_ior` (MagicaVoxel stores the index minus 1, so the index
//! is `1 + _ior`), `_rough`; `_emit`: `_emit` (or `_weight`) and `_flux`;
//! `_diffuse`: nothing. `_media`, `_blend` and cloud materials are rendered
//! diffuse (volumes are not simulated); `_sp`, `_spec`, `_g`, `_att`,
//! `_ldr`, `_d`, `_plastic` are ignored.
//!
//! Emission: MagicaVoxel documents no formula for `_emit` and `_flux`, and
//! importers differ (seen: `emit * 10 * flux`, `emit * (1 + flux)`,
//! `5 emit (1 + flux)^2`). voxtrace takes radiance `color * emit * (1 +
//! flux)`: `_emit 1, _flux 0` glows with exactly its color, and each step
//! of flux adds that much again.

use std::format;
use std::string::String;
use std::vec::Vec;

use crate::material::{Material, Materials};
use crate::source::vox::matl_bytes::Matl;
use crate::source::vox::warnings::Capped;

/// One MATL key's value: `Ok(None)` when absent, `Err` text when it is
/// not UTF-8 or not a number.
fn number(m: &Matl<'_>, key: &str) -> Result<Option<f32>, String> {
    let id = m.material.id;
    if let Some(bytes) = m.bad_values.get(key) {
        return Err(format!("material {id}: {key} is '{bytes}', not UTF-8 text"));
    }
    match m.material.properties.get(key) {
        None => Ok(None),
        Some(text) => match text.trim().parse::<f32>() {
            Ok(v) if v.is_finite() => Ok(Some(v)),
            _ => Err(format!("material {id}: {key} is '{text}', not a number")),
        },
    }
}

/// Reads materials for the entries `used` marks, warning (one line each,
/// naming the material id and key: the first 16, then a line counting the
/// rest) about values that are not UTF-8, not numbers, out of range or
/// missing, and keys that are not UTF-8; each such value falls back to the
/// nearest usable one (a `_type` to diffuse), each such key is ignored.
pub(crate) fn materials(
    matl: &[Matl<'_>],
    used: &[bool; 256],
    warnings: &mut Vec<String>,
) -> Materials {
    let mut table = Materials::all_diffuse();
    let mut media = Vec::new();
    let mut lines = Capped::new("MATL");
    for m in matl {
        let Ok(index) = u8::try_from(m.material.id) else {
            continue;
        };
        if index == 0 || !used[usize::from(index)] {
            continue;
        }
        for key in &m.bad_keys {
            lines.push(format!(
                "material {index}: key '{key}' is not UTF-8 text; ignored"
            ));
        }
        let kind = match m.bad_values.get("_type") {
            Some(bytes) => {
                lines.push(format!(
                    "material {index}: _type is '{bytes}', not UTF-8 text; rendering it diffuse"
                ));
                "_diffuse"
            }
            None => m.material.material_type().unwrap_or("_diffuse"),
        };
        // The first of `keys` present, clamped to [0, hi]; `required`: the
        // key that says how much of the type the material has (without it
        // the type's full strength is used, with a warning).
        let mut get = |keys: &[&str], required: bool, default: f32, hi: f32, what: &str| {
            for key in keys {
                match number(m, key) {
                    Ok(None) => continue,
                    Ok(Some(v)) if (0.0..=hi).contains(&v) => return v,
                    Ok(Some(v)) => {
                        let clamped = v.clamp(0.0, hi);
                        lines.push(format!(
                            "material {index}: {key} is {v}, {what}; using {clamped}"
                        ));
                        return clamped;
                    }
                    Err(e) => {
                        lines.push(format!("{e}; using {default}"));
                        return default;
                    }
                }
            }
            if required {
                lines.push(format!(
                    "material {index}: {} is missing; using {default}",
                    keys[0]
                ));
            }
            default
        };
        let (unit, max) = ("outside [0, 1]", f32::MAX);
        let material = match kind {
            "_diffuse" => None,
            "_metal" => {
                let metal = get(&["_metal", "_weight"], true, 1.0, 1.0, unit);
                let rough = get(&["_rough"], false, 0.0, 1.0, unit);
                Material::metal(metal, rough).ok()
            }
            "_glass" => {
                let trans = get(&["_trans", "_alpha", "_weight"], true, 1.0, 1.0, unit);
                let rough = get(&["_rough"], false, 0.0, 1.0, unit);
                let why = "below 0 (an index of refraction below 1)";
                let ior = get(&["_ior"], false, 0.5, max, why);
                Material::glass(trans, 1.0 + ior, rough).ok()
            }
            "_emit" => {
                let emit = get(&["_emit", "_weight"], true, 1.0, max, "negative emission");
                let flux = get(&["_flux"], false, 0.0, max, "negative flux");
                (emit > 0.0)
                    .then(|| Material::emissive(emit * (1.0 + flux)).ok())
                    .flatten()
            }
            "_media" | "_blend" | "_cloud" => {
                media.push(index);
                None
            }
            other => {
                lines.push(format!(
                    "material {index}: _type '{other}' is unknown; rendering it diffuse"
                ));
                None
            }
        };
        if let Some(material) = material {
            table.set(index, material);
        }
    }
    if !media.is_empty() {
        let ids: Vec<String> = media.iter().map(|i| format!("{i}")).collect();
        lines.push(format!(
            "materials {} are media or cloud, not simulated: rendered diffuse",
            ids.join(", ")
        ));
    }
    lines.append_to(warnings);
    table
}

#[cfg(test)]
mod tests {
    use crate::material::MaterialKind;
    use crate::source::vox::chunks::write::matl;
    use crate::source::vox::{two_voxels_with as scene, VoxModel};

    fn has(model: &VoxModel, needles: &[&str]) -> bool {
        model
            .warnings()
            .iter()
            .any(|line| needles.iter().all(|n| line.contains(n)))
    }

    #[test]
    fn a_value_not_utf8_warns_and_keeps_the_rest_of_the_material() {
        let model = scene(&[
            matl(
                1,
                &[
                    (b"_type", b"_metal"),
                    (b"_metal", b"0.\xff\xfe"),
                    (b"_rough", b"0.25"),
                ],
            ),
            matl(2, &[(b"_type", b"_glass"), (b"_trans", b"0.5")]),
        ]);
        let w = model.warnings();
        assert!(
            has(
                &model,
                &["material 1", "_metal", r"'0.\xff\xfe'", "not UTF-8"]
            ),
            "{w:?}"
        );
        assert_eq!(w.len(), 1, "{w:?}");
        // The rest of material 1, the value's fallback, and material 2 after it.
        let m = model.materials();
        assert_eq!(m.get(1).kind(), MaterialKind::Metal);
        assert_eq!((m.get(1).metalness(), m.get(1).roughness()), (1.0, 0.25));
        assert_eq!(m.get(2).kind(), MaterialKind::Glass);
        assert_eq!(m.get(2).transparency(), 0.5);
    }

    #[test]
    fn a_type_or_key_not_utf8_warns_naming_it() {
        let model = scene(&[
            matl(1, &[(b"_type", b"_gl\xe4ss"), (b"_trans", b"1")]),
            matl(
                2,
                &[
                    (b"_type", b"_emit"),
                    (b"_r\xf6ugh\n", b"0.5"),
                    (b"_emit", b"2"),
                ],
            ),
        ]);
        let w = model.warnings();
        assert!(
            has(&model, &["material 1", "_type", r"'_gl\xe4ss'", "diffuse"]),
            "{w:?}"
        );
        assert!(
            has(
                &model,
                &["material 2", r"'_r\xf6ugh\n'", "not UTF-8", "ignored"]
            ),
            "{w:?}"
        );
        assert!(w.iter().all(|line| !line.contains('\n')), "{w:?}");
        let m = model.materials();
        assert_eq!(m.get(1).kind(), MaterialKind::Diffuse);
        assert_eq!(m.get(2).kind(), MaterialKind::Emissive);
        assert_eq!(m.get(2).emission(), 2.0);
    }
}
