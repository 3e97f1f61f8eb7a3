//! Where two parts' settings texts differ, named by the flag that sets it
//! (`--shadows: true against false`), for `voxtrace stitch`'s refusal.
//!
//! A settings text (see [`crate::part::settings_text`]) is `key=value`
//! words whose values are `[...]` groups of `key=value` words or Rust
//! `Debug` forms (`Name { field: value, ... }`): a tree of named fields.
//! The setting named is the first of `FLAGS` whose values differ, shown
//! down to the field inside it that differs.

/// The flag, or what else decides it, of each field path of a settings
/// text, in the order a difference is named when several differ: a
/// field before what derives from it (the camera's position before its
/// direction), and each field before its parent, which names what its
/// unlisted fields differ in.
const FLAGS: &[(&str, &str)] = &[
    ("voxtrace", "the voxtrace version"),
    ("subject.seed", "--seed"),
    ("subject.size", "--size"),
    ("subject.fnv1a64", "the --vox file's contents"),
    ("subject.frame", "--frame"),
    (
        "subject",
        "the scene (--vox, or the terrain's --seed and --size)",
    ),
    ("backend", "--backend"),
    // The resolved camera: its position and projection, then what the
    // view direction, the field of view and the up direction derive.
    ("camera.width", "--width"),
    ("camera.height", "--height"),
    (
        "camera.center",
        "the camera position (--position, --view, --orbit or --camera)",
    ),
    ("camera.orthographic", "--projection"),
    (
        "camera.forward",
        "the view direction (--lookat, --view, --orbit or --camera)",
    ),
    (
        "camera.spread",
        "the field of view (--fov or --ortho-height)",
    ),
    (
        "camera.delta_u",
        "the image's up direction or scale (--up, --fov or --ortho-height)",
    ),
    (
        "camera.delta_v",
        "the image's up direction or scale (--up, --fov or --ortho-height)",
    ),
    ("camera", "the camera"),
    ("options.flat", "--flat"),
    ("options.debug", "--debug"),
    ("options.sun", "--sun"),
    ("options.shadows", "--shadows"),
    ("options.occlusion.distance", "--ao-distance"),
    ("options.occlusion", "--ao"),
    ("options.samples", "--spp"),
    (
        "options.adaptive",
        "--noise-threshold, --max-spp, --quality or --spp",
    ),
    ("options.fog", "--fog"),
    ("options.background", "--background"),
    ("options.lighting.bounces", "--bounces"),
    ("options.lighting.path_trace", "--bounces"),
    ("options.lighting", "the --vox file's light"),
    ("options", "the render options"),
];

/// The longest value shown: a settings text comes from a file, and a
/// message stays one readable line.
const SHOWN: usize = 60;

/// How deep a difference is followed: a settings text nests four levels;
/// a forged one may nest far more.
const DEPTH: usize = 8;

/// The difference between settings texts `a` and `b` (see the module
/// doc), as `--shadows: true against false`; `None` when they are equal.
/// A difference in no listed setting is named by its field's path.
#[must_use]
pub fn settings_difference(a: &str, b: &str) -> Option<String> {
    if a == b {
        return None;
    }
    let listed = FLAGS.iter().find_map(|&(path, name)| {
        let (x, y) = (value_at(a, path)?, value_at(b, path)?);
        (x != y)
            .then(|| narrow(x, y))
            .map(|(_, x, y)| (name.to_string(), x, y))
    });
    let (name, x, y) = listed.unwrap_or_else(|| match narrow(a, b) {
        (path, x, y) if path.is_empty() => ("the settings".to_string(), x, y),
        found => found,
    });
    Some(format!("{name}: {} against {}", shorten(x), shorten(y)))
}

/// The value of the field at `path` (`camera.center`) of `text`, if any.
fn value_at<'t>(text: &'t str, path: &str) -> Option<&'t str> {
    path.split('.').try_fold(text, |value, name| {
        let fields = fields(value)?;
        fields.into_iter().find(|f| f.0 == name).map(|f| f.1)
    })
}

/// Where unequal values `a` and `b` differ: the path of the first field
/// that differs, followed while both sides have the same field names (at
/// most [`DEPTH`] deep), and its two values.
fn narrow<'t>(mut a: &'t str, mut b: &'t str) -> (String, &'t str, &'t str) {
    let mut path = String::new();
    for _ in 0..DEPTH {
        let (Some(fa), Some(fb)) = (fields(a), fields(b)) else {
            break;
        };
        let same_names = fa.len() == fb.len() && fa.iter().zip(&fb).all(|(x, y)| x.0 == y.0);
        let first = fa.into_iter().zip(fb).find(|(x, y)| x.1 != y.1);
        let (true, Some(((name, x), (_, y)))) = (same_names, first) else {
            break;
        };
        if !path.is_empty() {
            path.push('.');
        }
        path.push_str(name);
        (a, b) = (x, y);
    }
    (path, a, b)
}

/// The named fields of `text`: `key=value` words (a value in `[...]` may
/// hold spaces; a bare word is a field named by itself), or the fields of
/// a `Debug` struct `Name { field: value, ... }`, also inside `Some(...)`.
/// `None` for anything else (a number, a tuple, `None`): a leaf.
fn fields(text: &str) -> Option<Vec<(&str, &str)>> {
    let text = text
        .strip_prefix('[')
        .and_then(|t| t.strip_suffix(']'))
        .unwrap_or(text);
    // An option's value is its contents' (`Some(Fog { distance: 90.0 })`).
    if let Some(inner) = text.strip_prefix("Some(").and_then(|t| t.strip_suffix(')')) {
        return fields(inner);
    }
    let structure = text
        .split_once(" { ")
        .filter(|(name, _)| is_identifier(name));
    if let Some((_, body)) = structure {
        let body = body.strip_suffix(" }")?;
        return split_top(body, ", ")
            .into_iter()
            .map(|field| field.split_once(": "))
            .collect();
    }
    let words = split_top(text, " ");
    if words.len() < 2 && !text.contains('=') {
        return None;
    }
    Some(
        words
            .into_iter()
            .map(|word| word.split_once('=').unwrap_or((word, word)))
            .collect(),
    )
}

fn is_identifier(text: &str) -> bool {
    !text.is_empty() && text.chars().all(|c| c.is_alphanumeric() || c == '_')
}

/// `text` split at each `separator` outside brackets.
fn split_top<'t>(text: &'t str, separator: &str) -> Vec<&'t str> {
    let mut parts = Vec::new();
    let (mut depth, mut start) = (0i32, 0);
    let bytes = text.as_bytes();
    let mut i = 0;
    while i < bytes.len() {
        match bytes[i] {
            b'(' | b'[' | b'{' => depth += 1,
            b')' | b']' | b'}' => depth -= 1,
            _ if depth == 0 && bytes[i..].starts_with(separator.as_bytes()) => {
                parts.push(&text[start..i]);
                i += separator.len();
                start = i;
                continue;
            }
            _ => {}
        }
        i += 1;
    }
    parts.push(&text[start..]);
    parts
}

/// `text`, cut to [`SHOWN`] characters with `...` when longer.
fn shorten(text: &str) -> String {
    match text.char_indices().nth(SHOWN) {
        Some((at, _)) => format!("{}...", &text[..at]),
        None => text.to_string(),
    }
}
