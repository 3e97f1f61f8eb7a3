//! The small reader of a `.vox` file's chunk stream that the rOBJ and rCAM
//! chunks need (dot_vox skips both), and the MATL chunks dot_vox drops
//! (`matl.rs`): the chunks among MAIN's children with a given id,
//! MagicaVoxel's DICT, and numbers separated by spaces. Every
//! read is bounds-checked: malformed bytes give `None` or nothing, never a
//! panic or an allocation larger than the input.

use std::collections::HashMap;
use std::string::String;
use std::vec::Vec;

/// A little-endian `u32` at `at`, if the bytes are there.
pub(crate) fn u32_at(bytes: &[u8], at: usize) -> Option<u32> {
    let b = bytes.get(at..at.checked_add(4)?)?;
    Some(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
}

/// A MagicaVoxel DICT (count, then length-prefixed key and value strings),
/// each string lossily as text (a byte that is not UTF-8 becomes U+FFFD).
pub(crate) fn dict(bytes: &[u8]) -> Option<HashMap<String, String>> {
    let text = |s: &[u8]| String::from_utf8_lossy(s).into_owned();
    Some(
        raw_dict(bytes)?
            .into_iter()
            .map(|(key, value)| (text(key), text(value)))
            .collect(),
    )
}

/// A MagicaVoxel DICT's key and value strings as bytes, in file order
/// (a later pair with the same key is the one a map keeps).
pub(crate) fn raw_dict(bytes: &[u8]) -> Option<Vec<(&[u8], &[u8])>> {
    let count = u32_at(bytes, 0)? as usize;
    let mut at = 4;
    let string = |at: &mut usize| -> Option<&[u8]> {
        let len = u32_at(bytes, *at)? as usize;
        let start = at.checked_add(4)?;
        let s = bytes.get(start..start.checked_add(len)?)?;
        *at = start + len;
        Some(s)
    };
    // Each pair takes at least 8 bytes: a count past that is malformed.
    if count > bytes.len() / 8 {
        return None;
    }
    let mut out = Vec::new();
    for _ in 0..count {
        let key = string(&mut at)?;
        let value = string(&mut at)?;
        out.push((key, value));
    }
    Some(out)
}

/// The contents of every chunk with `id` among MAIN's children, in file
/// order; a chunk whose size runs past the file ends the scan.
pub(crate) fn chunks<'a>(bytes: &'a [u8], id: &[u8; 4]) -> Vec<&'a [u8]> {
    let mut out = Vec::new();
    // "VOX ", version, then MAIN: id, content size, children size.
    if bytes.get(..4) != Some(b"VOX ") || bytes.get(8..12) != Some(b"MAIN") {
        return out;
    }
    let Some(content) = u32_at(bytes, 12) else {
        return out;
    };
    let mut at = 20usize.saturating_add(content as usize);
    while let (Some(chunk_id), Some(size), Some(children)) = (
        at.checked_add(4).and_then(|end| bytes.get(at..end)),
        u32_at(bytes, at.saturating_add(4)),
        u32_at(bytes, at.saturating_add(8)),
    ) {
        let start = at + 12;
        let Some(end) = start.checked_add(size as usize) else {
            break;
        };
        if chunk_id == id {
            match bytes.get(start..end) {
                Some(content) => out.push(content),
                None => break,
            }
        }
        let Some(next) = end.checked_add(children as usize) else {
            break;
        };
        at = next;
    }
    out
}

/// `N` finite numbers separated by spaces, or `None`.
pub(crate) fn numbers<const N: usize>(text: Option<&String>) -> Option<[f32; N]> {
    let mut out = [0.0; N];
    let mut parts = text?.split_whitespace();
    for slot in &mut out {
        *slot = parts
            .next()?
            .parse::<f32>()
            .ok()
            .filter(|v| v.is_finite())?;
    }
    Some(out)
}

/// Writers of the stream the reader above reads, for the tests of the
/// chunks built on it (rOBJ, rCAM, MATL).
#[cfg(test)]
pub(crate) mod write {
    use std::vec::Vec;

    /// MagicaVoxel's DICT of `pairs`: a count, then each key and value as
    /// a length and its bytes.
    pub(crate) fn dict(pairs: &[(&str, &str)]) -> Vec<u8> {
        let pairs: Vec<(&[u8], &[u8])> = pairs
            .iter()
            .map(|(k, v)| (k.as_bytes(), v.as_bytes()))
            .collect();
        raw_dict(&pairs)
    }

    /// [`dict`] of strings of any bytes, UTF-8 or not.
    pub(crate) fn raw_dict(pairs: &[(&[u8], &[u8])]) -> Vec<u8> {
        let mut d = (pairs.len() as u32).to_le_bytes().to_vec();
        for (k, v) in pairs {
            for s in [k, v] {
                d.extend_from_slice(&(s.len() as u32).to_le_bytes());
                d.extend_from_slice(s);
            }
        }
        d
    }

    /// A MATL chunk for material `id` with `pairs` (any bytes).
    pub(crate) fn matl(id: u32, pairs: &[(&[u8], &[u8])]) -> Vec<u8> {
        let mut content = id.to_le_bytes().to_vec();
        content.extend(raw_dict(pairs));
        chunk(b"MATL", &content)
    }

    /// SIZE and XYZI of a 2x1x1 model of palette entries 1 and 2.
    pub(crate) fn two_voxels() -> Vec<u8> {
        let mut out = chunk(b"SIZE", &[2, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0]);
        out.extend(chunk(b"XYZI", &[2, 0, 0, 0, 0, 0, 0, 1, 1, 0, 0, 2]));
        out
    }

    /// A chunk `id` with `content` and no children.
    pub(crate) fn chunk(id: &[u8; 4], content: &[u8]) -> Vec<u8> {
        let mut out = id.to_vec();
        out.extend_from_slice(&(content.len() as u32).to_le_bytes());
        out.extend_from_slice(&0u32.to_le_bytes());
        out.extend_from_slice(content);
        out
    }

    /// A version-150 file whose MAIN chunk has `children`.
    pub(crate) fn file(children: &[u8]) -> Vec<u8> {
        let mut out = b"VOX ".to_vec();
        out.extend_from_slice(&150u32.to_le_bytes());
        out.extend_from_slice(b"MAIN");
        out.extend_from_slice(&0u32.to_le_bytes());
        out.extend_from_slice(&(children.len() as u32).to_le_bytes());
        out.extend_from_slice(children);
        out
    }
}
