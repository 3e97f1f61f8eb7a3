//! Where two parts' settings texts differ, named by the flag that sets it
//! (`--shadows: true against false`), for `voxtrace stitch`'s refusal.
//!
//! A settings text (see [`crate::part::settings_text`]) is `key=value`
//! words whose values are `[...]` groups of `key=value` words or Rust
//! `Debug` forms (`Name { field: value, ... }`). Both texts are read as the
//! same tree of named fields, as deep as both sides have the same fields.
//! Of the fields that differ, the one listed first in [`FLAGS`] is named
//! (the resolved camera's position before the vectors derived from it),
//! by its flag; a path missing there is shown as it is.

/// The flag, or what else decides it, of each field path of a settings
/// text, in the order a difference is named when several fields differ; a
/// path not listed takes its nearest listed parent's name and place.
const FLAGS: &[(&str, &str)] = &[
    ("voxtrace", "the voxtrace version"),
    (
        "subject",
        "the scene (--vox, or the terrain's --seed and --size)",
    ),
    ("subject.seed", "--seed"),
    ("subject.size", "--size"),
    ("subject.fnv1a64", "the --vox file's contents"),
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

/// How deep fields are followed: a settings text nests four levels; a
/// forged one may nest far more, and must not exhaust the stack.
const DEPTH: usize = 8;

/// The difference between settings texts `a` and `b` (see the module
/// doc), as `--shadows: true against false`; `None` when they are equal.
#[must_use]
pub fn settings_difference(a: &str, b: &str) -> Option<String> {
    let (path, x, y) = difference(String::new(), a, b)?;
    let name = match listed(&path) {
        Some((_, name)) => name.to_string(),
        None if path.is_empty() => "the settings".to_string(),
        None => path,
    };
    Some(format!("{name}: {} against {}", shorten(x), shorten(y)))
}

/// The place in [`FLAGS`] and the name of field `path`, or of its nearest
/// listed parent.
fn listed(path: &str) -> Option<(usize, &'static str)> {
    let mut at = path;
    loop {
        if let Some(found) = FLAGS.iter().position(|(p, _)| *p == at) {
            return Some((found, FLAGS[found].1));
        }
        at = at.rsplit_once('.')?.0;
    }
}

/// The path and values of the field to name where `a` and `b` differ.
fn difference<'t>(path: String, a: &'t str, b: &'t str) -> Option<(String, &'t str, &'t str)> {
    if a == b {
        return None;
    }
    let depth = path.split('.').count();
    let (fa, fb) = if depth < DEPTH {
        (fields(a), fields(b))
    } else {
        (None, None)
    };
    if let (Some(fa), Some(fb)) = (fa, fb) {
        let same_names = fa.len() == fb.len() && fa.iter().zip(&fb).all(|(x, y)| x.0 == y.0);
        if same_names {
            let differing = fa.into_iter().zip(fb).filter_map(|((name, x), (_, y))| {
                let inner = if path.is_empty() {
                    name.to_string()
                } else {
                    format!("{path}.{name}")
                };
                difference(inner, x, y)
            });
            // The first listed; unlisted ones after them, in their order.
            let rank = |found: &(String, &str, &str)| listed(&found.0).map_or(usize::MAX, |l| l.0);
            if let Some(found) = differing.min_by_key(rank) {
                return Some(found);
            }
        }
    }
    Some((path, a, b))
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

#[cfg(test)]
mod tests {
    use super::settings_difference;
    use crate::part::settings_text;

    #[derive(Debug)]
    #[allow(dead_code)] // read through Debug
    struct Options {
        flat: bool,
        shadows: bool,
        occlusion: Option<Occlusion>,
    }

    #[derive(Debug)]
    #[allow(dead_code)] // read through Debug
    struct Occlusion {
        rays: u16,
        distance: f32,
    }

    fn text(subject: &str, backend: &str, shadows: bool, ao: Option<(u16, f32)>) -> String {
        let options = Options {
            flat: false,
            shadows,
            occlusion: ao.map(|(rays, distance)| Occlusion { rays, distance }),
        };
        settings_text(subject, backend, &(1.5f32, "camera"), &options)
    }

    #[test]
    fn a_difference_names_the_flag_and_both_values() {
        let base = text("terrain seed=3 size=30", "octree", true, None);
        let diff = |other: &str| settings_difference(&base, other);
        assert_eq!(diff(&base), None);
        assert_eq!(
            diff(&text("terrain seed=3 size=30", "octree", false, None)).unwrap(),
            "--shadows: true against false"
        );
        assert_eq!(
            diff(&text("terrain seed=9 size=30", "octree", true, None)).unwrap(),
            "--seed: 3 against 9"
        );
        assert_eq!(
            diff(&text("terrain seed=3 size=30", "dense", true, None)).unwrap(),
            "--backend: octree against dense"
        );
        assert_eq!(
            diff(&text(
                "terrain seed=3 size=30",
                "octree",
                true,
                Some((4, 8.0))
            ))
            .unwrap(),
            "--ao: None against Some(Occlusion { rays: 4, distance: 8.0 })"
        );
        let a = text("terrain seed=3 size=30", "octree", true, Some((4, 8.0)));
        let b = text("terrain seed=3 size=30", "octree", true, Some((4, 2.5)));
        assert_eq!(
            settings_difference(&a, &b).unwrap(),
            "--ao-distance: 8.0 against 2.5"
        );
        let vox = text("vox fnv1a64=00000000000000ff", "octree", true, None);
        assert!(
            diff(&vox).unwrap().starts_with("the scene"),
            "{:?}",
            diff(&vox)
        );
    }

    #[derive(Debug)]
    #[allow(dead_code)] // read through Debug
    struct Camera {
        pixel00: (f32, f32),
        center: (f32, f32),
    }

    #[test]
    fn of_several_differences_the_one_listed_first_is_named() {
        // The position is named before what it derives, though later in
        // the text.
        let camera = |x: f32| Camera {
            pixel00: (x - 1.0, 0.5),
            center: (x, 0.0),
        };
        let text = |x| settings_text("terrain seed=1 size=9", "octree", &camera(x), &());
        let diff = settings_difference(&text(1.0), &text(2.0)).unwrap();
        assert!(
            diff.starts_with("the camera position (--position")
                && diff.ends_with(": (1.0, 0.0) against (2.0, 0.0)"),
            "{diff}"
        );
    }

    #[test]
    fn texts_that_are_not_settings_still_give_one_short_line() {
        let long = "x".repeat(10_000);
        let diff = settings_difference("a=1 b=[2", &long).unwrap();
        assert!(diff.len() < 200 && diff.ends_with("..."), "{diff}");
        assert_eq!(settings_difference("é=1", "é=2").unwrap(), "é: 1 against 2");
        // Nesting deeper than any settings text stops early, not on the stack.
        let nested = |leaf: &str| "A { a: ".repeat(100_000) + leaf + &" }".repeat(100_000);
        let deep = settings_difference(&nested("1"), &nested("2")).unwrap();
        assert!(deep.lines().count() == 1 && deep.len() < 200, "{deep}");
    }
}
