//! Where two parts' settings texts differ, named by the flag that sets it
//! (`--shadows: true against false`), for `voxtrace stitch`'s refusal.
//!
//! A settings text (see [`crate::part::settings_text`]) is `key=value`
//! words whose values are `[...]` groups of `key=value` words or Rust
//! `Debug` forms (`Name { field: value, ... }`). Both texts are read as the
//! same tree of named fields and walked in order; the first field whose
//! values differ, as deep as both sides have the same fields, is the
//! difference. Its path (`options.shadows`) names the flag through
//! [`FLAGS`]; a path missing there is shown as it is.

/// The flag, or what else decides it, of each field path of a settings
/// text; a path not listed takes its nearest listed parent's name.
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
    ("camera", "the camera"),
    ("camera.width", "--width"),
    ("camera.height", "--height"),
    ("camera.vertical_fov", "--fov"),
    (
        "camera.lookfrom",
        "the camera position (--position, --view, --orbit or --camera)",
    ),
    ("camera.lookat", "--lookat"),
    ("camera.cam_up", "--up"),
    ("camera.up_fallback", "--up"),
    ("camera.projection", "--projection"),
    ("camera.projection.height", "--ortho-height"),
    ("options", "the render options"),
    ("options.flat", "--flat"),
    ("options.debug", "--debug"),
    ("options.sun", "--sun"),
    ("options.shadows", "--shadows"),
    ("options.occlusion", "--ao"),
    ("options.occlusion.distance", "--ao-distance"),
    ("options.samples", "--spp"),
    ("options.fog", "--fog"),
    ("options.background", "--background"),
    ("options.lighting", "the --vox file's light"),
    ("options.lighting.bounces", "--bounces"),
    ("options.lighting.path_trace", "--bounces"),
];

/// The longest value shown: a settings text comes from a file, and a
/// message stays one readable line.
const SHOWN: usize = 60;

/// The first difference between settings texts `a` and `b`, as
/// `--shadows: true against false`; `None` when they are equal.
#[must_use]
pub fn settings_difference(a: &str, b: &str) -> Option<String> {
    let (path, x, y) = first_difference(String::new(), a, b)?;
    let name = setting_name(&path);
    Some(format!("{name}: {} against {}", shorten(x), shorten(y)))
}

/// The flag (or description) of field `path`.
fn setting_name(path: &str) -> String {
    let mut at = path;
    loop {
        if let Some((_, name)) = FLAGS.iter().find(|(p, _)| *p == at) {
            return (*name).to_string();
        }
        match at.rsplit_once('.') {
            Some((parent, _)) => at = parent,
            None if path.is_empty() => return "the settings".to_string(),
            None => return path.to_string(),
        }
    }
}

/// How deep fields are followed: a settings text nests four levels; a
/// forged one may nest far more, and must not exhaust the stack.
const DEPTH: usize = 8;

/// The path and values of the first field where `a` and `b` differ.
fn first_difference<'t>(
    path: String,
    a: &'t str,
    b: &'t str,
) -> Option<(String, &'t str, &'t str)> {
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
            for ((name, x), (_, y)) in fa.into_iter().zip(fb) {
                let inner = if path.is_empty() {
                    name.to_string()
                } else {
                    format!("{path}.{name}")
                };
                if let Some(found) = first_difference(inner, x, y) {
                    return Some(found);
                }
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
