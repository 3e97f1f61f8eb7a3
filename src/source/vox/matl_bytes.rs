//! The MATL chunks of a `.vox` file as voxtrace reads them: dot_vox's
//! materials, and the ones dot_vox drops whole for a key or value that is
//! not UTF-8, read again from the file's bytes in their place (see
//! [`matl_chunks`] for why, and why only here).

use core::fmt::Write;
use std::borrow::Cow;
use std::collections::HashMap;
use std::string::String;
use std::vec::Vec;

use dot_vox::Material as VoxMaterial;

use crate::source::vox::chunks::{chunks, raw_dict, u32_at};

/// One MATL chunk as voxtrace reads it: dot_vox's material, or one that
/// dot_vox dropped whole for a key or value that is not UTF-8, rebuilt
/// from its other pairs (see [`matl_chunks`]).
pub(crate) struct Matl<'a> {
    pub(super) material: Cow<'a, VoxMaterial>,
    /// Keys that are not UTF-8, as [`shown`] shows them.
    pub(super) bad_keys: Vec<String>,
    /// Values that are not UTF-8, as [`shown`] shows them, by key.
    pub(super) bad_values: HashMap<String, String>,
}

/// The file's MATL chunks, in file order: dot_vox's materials `read`, with
/// the ones it dropped put back in their place.
///
/// Why: dot_vox 5.2 turns a MATL chunk with one string that is not UTF-8
/// into `Chunk::Invalid` and leaves it out, place and all, so one bad byte
/// would silently lose every key of the material. The scan walks the MATL
/// chunks among MAIN's children: one whose strings are all UTF-8 takes the
/// next material of `read` as it is; one with a string that is not UTF-8
/// is rebuilt from its UTF-8 pairs, the rest kept for the warnings; a
/// malformed one is skipped, as dot_vox skips it. Materials of `read` left
/// over follow in their order. So a file without such a string gives
/// exactly dot_vox's list.
pub(crate) fn matl_chunks<'a>(read: &'a [VoxMaterial], bytes: &[u8]) -> Vec<Matl<'a>> {
    let plain = |material: &'a VoxMaterial| Matl {
        material: Cow::Borrowed(material),
        bad_keys: Vec::new(),
        bad_values: HashMap::new(),
    };
    let mut read = read.iter();
    let mut out = Vec::new();
    for content in chunks(bytes, b"MATL") {
        let (Some(id), Some(pairs)) = (u32_at(content, 0), content.get(4..).and_then(raw_dict))
        else {
            continue;
        };
        let utf8 = |s: &[u8]| core::str::from_utf8(s).is_ok();
        if pairs.iter().all(|(key, value)| utf8(key) && utf8(value)) {
            out.extend(read.next().map(plain));
        } else {
            out.push(rebuilt(id, &pairs));
        }
    }
    out.extend(read.map(plain));
    out
}

/// The material of MATL `id` with `pairs`, some of them not UTF-8: a later
/// pair with the same key replaces an earlier one, as in dot_vox's map.
fn rebuilt(id: u32, pairs: &[(&[u8], &[u8])]) -> Matl<'static> {
    let mut material = VoxMaterial {
        id,
        // (dot_vox's map type: std's, or ahash's where another crate of
        // the build turns that feature on.)
        properties: dot_vox::Dict::default(),
    };
    let (mut bad_keys, mut bad_values) = (Vec::new(), HashMap::new());
    for (key, value) in pairs {
        let Ok(key) = core::str::from_utf8(key) else {
            bad_keys.push(shown(key));
            continue;
        };
        match core::str::from_utf8(value) {
            Ok(value) => {
                bad_values.remove(key);
                material.properties.insert(key.into(), value.into());
            }
            Err(_) => {
                material.properties.remove(key);
                bad_values.insert(key.into(), shown(value));
            }
        }
    }
    Matl {
        material: Cow::Owned(material),
        bad_keys,
        bad_values,
    }
}

/// `bytes` as a warning shows them, on one line and exactly: text as it
/// is, control characters escaped as Rust writes them (`\n`, `\u{1b}`),
/// bytes that are not UTF-8 as `\xff`.
fn shown(bytes: &[u8]) -> String {
    let mut out = String::new();
    for chunk in bytes.utf8_chunks() {
        for c in chunk.valid().chars() {
            if c.is_control() {
                out.extend(c.escape_debug());
            } else {
                out.push(c);
            }
        }
        for byte in chunk.invalid() {
            let _ = write!(out, "\\x{byte:02x}");
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use std::string::ToString;

    use proptest::prelude::*;

    use super::*;
    use crate::material::MaterialKind;
    use crate::source::vox::chunks::write::{file, matl};
    use crate::source::vox::two_voxels_with as scene;

    #[test]
    fn rebuilt_materials_keep_their_place_in_the_file() {
        // A later chunk for the same entry wins, whichever was dropped.
        let bad = matl(1, &[(b"_type", b"_metal"), (b"_rough", b"\xff")]);
        let good = matl(1, &[(b"_type", b"_glass"), (b"_trans", b"1")]);
        let model = scene(&[bad.clone(), good.clone()]);
        assert_eq!(model.materials().get(1).kind(), MaterialKind::Glass);
        let model = scene(&[good, bad]);
        assert_eq!(model.materials().get(1).kind(), MaterialKind::Metal);
        assert!(
            model
                .warnings()
                .iter()
                .any(|w| w.contains(r"material 1: _rough is '\xff'")),
            "{:?}",
            model.warnings()
        );
    }

    /// A string of bytes from a small alphabet: ASCII, UTF-8 and bytes that
    /// are never UTF-8, so that keys repeat and some strings are bad.
    fn string() -> impl Strategy<Value = Vec<u8>> {
        proptest::collection::vec(
            prop_oneof![Just(b'_'), Just(b'a'), Just(0xff), Just(0xc3), Just(0xa9)],
            0..4,
        )
    }

    proptest! {
        /// Against dot_vox on any DICT: a chunk whose strings are all
        /// UTF-8 is dot_vox's material untouched; any other keeps exactly
        /// its UTF-8 pairs (the last of a key), and names the rest.
        #[test]
        fn matl_chunks_are_dot_vox_s_plus_the_ones_it_drops(
            chunks in proptest::collection::vec(
                proptest::collection::vec((string(), string()), 0..6),
                0..4,
            ),
        ) {
            let mut children = Vec::new();
            for (id, pairs) in chunks.iter().enumerate() {
                let pairs: Vec<(&[u8], &[u8])> =
                    pairs.iter().map(|(k, v)| (k.as_slice(), v.as_slice())).collect();
                children.extend(matl(id as u32, &pairs));
            }
            let bytes = file(&children);
            let data = dot_vox::load_bytes(&bytes).unwrap();
            let read = matl_chunks(&data.materials, &bytes);
            prop_assert_eq!(read.len(), chunks.len());
            let text = |s: &[u8]| core::str::from_utf8(s).ok().map(ToString::to_string);
            for (id, (m, pairs)) in read.iter().zip(&chunks).enumerate() {
                prop_assert_eq!(m.material.id, id as u32);
                let clean = pairs.iter().all(|(k, v)| text(k).is_some() && text(v).is_some());
                prop_assert_eq!(matches!(m.material, Cow::Borrowed(_)), clean);
                let mut expected = dot_vox::Dict::default();
                let mut bad = HashMap::new();
                for (k, v) in pairs {
                    let Some(k) = text(k) else { continue };
                    match text(v) {
                        Some(v) => {
                            bad.remove(&k);
                            expected.insert(k, v);
                        }
                        None => {
                            expected.remove(&k);
                            bad.insert(k, shown(v));
                        }
                    }
                }
                prop_assert_eq!(&m.material.properties, &expected);
                prop_assert_eq!(&m.bad_values, &bad);
                let bad_keys = pairs.iter().filter(|(k, _)| text(k).is_none()).count();
                prop_assert_eq!(m.bad_keys.len(), bad_keys);
            }
        }
    }
}
