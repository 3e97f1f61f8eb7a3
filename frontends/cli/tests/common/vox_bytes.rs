//! `.vox` files written byte by byte, so that tests can make files no
//! well-behaved writer would: scene-graph bombs, loops, absurd sizes and
//! counts, broken dictionaries. Layout per the MagicaVoxel format notes
//! (ephtracy/voxel-model, `MagicaVoxel-file-format-vox.txt` and
//! `-extension.txt`): `VOX `, version, one `MAIN` chunk holding the rest.

/// One chunk: id, content and children.
pub fn chunk(id: &[u8; 4], content: &[u8], children: &[u8]) -> Vec<u8> {
    let mut out = id.to_vec();
    out.extend((content.len() as u32).to_le_bytes());
    out.extend((children.len() as u32).to_le_bytes());
    out.extend(content);
    out.extend(children);
    out
}

/// A whole file around `chunks` (already serialized children of MAIN).
pub fn file(chunks: &[Vec<u8>]) -> Vec<u8> {
    let mut out = b"VOX ".to_vec();
    out.extend(150u32.to_le_bytes());
    out.extend(chunk(b"MAIN", &[], &chunks.concat()));
    out
}

fn int(out: &mut Vec<u8>, v: i32) {
    out.extend(v.to_le_bytes());
}

fn string(out: &mut Vec<u8>, s: &str) {
    int(out, s.len() as i32);
    out.extend(s.as_bytes());
}

/// A DICT: a count, then key and value strings.
pub fn dict(out: &mut Vec<u8>, pairs: &[(&str, &str)]) {
    int(out, pairs.len() as i32);
    for (k, v) in pairs {
        string(out, k);
        string(out, v);
    }
}

/// SIZE and XYZI of one model with the given voxels (palette index 1..).
pub fn model(size: [u32; 3], voxels: &[[u8; 4]]) -> Vec<Vec<u8>> {
    let mut sz = Vec::new();
    size.iter().for_each(|&s| sz.extend(s.to_le_bytes()));
    let mut xyzi = (voxels.len() as u32).to_le_bytes().to_vec();
    voxels.iter().for_each(|v| xyzi.extend(v));
    vec![chunk(b"SIZE", &sz, &[]), chunk(b"XYZI", &xyzi, &[])]
}

/// A transform node `id` over `child`, translated by `t` ("x y z").
pub fn transform(id: i32, child: i32, t: Option<&str>) -> Vec<u8> {
    let mut c = Vec::new();
    int(&mut c, id);
    dict(&mut c, &[]);
    int(&mut c, child);
    int(&mut c, -1); // reserved
    int(&mut c, 0); // layer
    int(&mut c, 1); // one frame
    match t {
        Some(t) => dict(&mut c, &[("_t", t)]),
        None => dict(&mut c, &[]),
    }
    chunk(b"nTRN", &c, &[])
}

/// A group node `id` listing `children` (repeats allowed: that is the bomb).
pub fn group(id: i32, children: &[i32]) -> Vec<u8> {
    let mut c = Vec::new();
    int(&mut c, id);
    dict(&mut c, &[]);
    int(&mut c, children.len() as i32);
    children.iter().for_each(|&k| int(&mut c, k));
    chunk(b"nGRP", &c, &[])
}

/// A shape node `id` placing `model`.
pub fn shape(id: i32, model: i32) -> Vec<u8> {
    let mut c = Vec::new();
    int(&mut c, id);
    dict(&mut c, &[]);
    int(&mut c, 1);
    int(&mut c, model);
    dict(&mut c, &[]);
    chunk(b"nSHP", &c, &[])
}

/// A palette chunk of 256 colors.
pub fn palette() -> Vec<u8> {
    let colors: Vec<u8> = (0..=255u8).flat_map(|i| [i, 255 - i, 128, 255]).collect();
    chunk(b"RGBA", &colors, &[])
}

/// A scene graph of `levels` levels, each a transform over a group that
/// lists the next level `fan` times; the last level places model 0 (one
/// voxel, or none). `fan^levels` placements from a file of about
/// `levels * (60 + 4 * fan)` bytes.
pub fn bomb(levels: i32, fan: usize, voxels: bool) -> Vec<u8> {
    let mut chunks = if voxels {
        model([1, 1, 1], &[[0, 0, 0, 1]])
    } else {
        model([1, 1, 1], &[])
    };
    for level in 0..levels {
        let (trn, grp) = (2 * level, 2 * level + 1);
        chunks.push(transform(trn, grp, None));
        chunks.push(group(grp, &vec![grp + 1; fan]));
    }
    let last = 2 * levels;
    chunks.push(transform(last, last + 1, None));
    chunks.push(shape(last + 1, 0));
    file(&chunks) // no palette: MagicaVoxel's default, and a smaller bomb
}

/// Like [`bomb`], but the last level is an empty group: nothing is ever
/// placed, so only the count of visited nodes stops the walk.
pub fn hollow_bomb(levels: i32, fan: usize) -> Vec<u8> {
    let mut chunks = model([1, 1, 1], &[[0, 0, 0, 1]]);
    for level in 0..levels {
        let (trn, grp) = (2 * level, 2 * level + 1);
        chunks.push(transform(trn, grp, None));
        chunks.push(group(grp, &vec![grp + 1; fan]));
    }
    chunks.push(transform(2 * levels, 2 * levels + 1, None));
    chunks.push(group(2 * levels + 1, &[]));
    file(&chunks)
}

/// A small valid scene: a 4x3x2 model placed twice.
pub fn small_scene() -> Vec<u8> {
    let voxels: Vec<[u8; 4]> = (0..4u8)
        .flat_map(|x| (0..2u8).map(move |z| [x, x % 3, z, 1 + x + z]))
        .collect();
    let mut chunks = model([4, 3, 2], &voxels);
    chunks.push(transform(0, 1, None));
    chunks.push(group(1, &[2, 4]));
    chunks.push(transform(2, 3, Some("0 0 0")));
    chunks.push(shape(3, 0));
    chunks.push(transform(4, 5, Some("6 -2 1")));
    chunks.push(shape(5, 0));
    chunks.push(palette());
    file(&chunks)
}

/// Named hostile `.vox` files, each a different way to be wrong or huge.
pub fn hostile_files() -> Vec<(String, Vec<u8>)> {
    let one = || model([2, 2, 2], &[[0, 0, 0, 1], [1, 1, 1, 2]]);
    let with = |extra: Vec<Vec<u8>>| {
        let mut chunks = one();
        chunks.extend(extra);
        chunks.push(palette());
        file(&chunks)
    };
    let mut cases: Vec<(String, Vec<u8>)> = vec![
        ("bomb-10-levels-of-10.vox".into(), bomb(10, 10, true)),
        ("bomb-30-levels-of-2.vox".into(), bomb(30, 2, true)),
        ("bomb-empty-models.vox".into(), bomb(10, 10, false)),
        ("bomb-hollow.vox".into(), hollow_bomb(10, 10)),
        ("deep-200-levels.vox".into(), bomb(200, 1, true)),
        // Wide: one group with many distinct-looking children, each the
        // same transform; fits the limits, so it renders.
        (
            "wide-20000-children.vox".into(),
            with(vec![
                transform(0, 1, None),
                group(1, &[2; 20000]),
                transform(2, 3, None),
                shape(3, 0),
            ]),
        ),
        (
            "loop.vox".into(),
            with(vec![transform(0, 1, None), group(1, &[0])]),
        ),
        (
            "self-group.vox".into(),
            with(vec![transform(0, 1, None), group(1, &[1])]),
        ),
        ("missing-node.vox".into(), with(vec![transform(0, 7, None)])),
        (
            "missing-model.vox".into(),
            with(vec![transform(0, 1, None), shape(1, 9)]),
        ),
        (
            "translation-far.vox".into(),
            with(vec![transform(0, 1, Some("2147483647 0 0")), shape(1, 0)]),
        ),
        // i32::MIN has no i32 absolute value (the scene_graph fuzz target's
        // first finding).
        (
            "translation-i32-min.vox".into(),
            with(vec![transform(0, 1, Some("-2147483648 0 0")), shape(1, 0)]),
        ),
        (
            "translation-garbage.vox".into(),
            with(vec![transform(0, 1, Some("1 two 3")), shape(1, 0)]),
        ),
        // Translations that add up past the coordinate range over levels.
        ("translation-sum.vox".into(), {
            let mut extra = Vec::new();
            for level in 0..30 {
                extra.push(transform(
                    2 * level,
                    2 * level + 1,
                    Some("4000000 4000000 4000000"),
                ));
                extra.push(group(2 * level + 1, &[2 * level + 2]));
            }
            extra.push(transform(60, 61, None));
            extra.push(shape(61, 0));
            with(extra)
        }),
    ];
    // Models: absurd sizes, voxels outside them, counts beyond the chunk.
    let sized = |size: [u32; 3], voxels: &[[u8; 4]]| {
        let mut chunks = model(size, voxels);
        chunks.push(palette());
        file(&chunks)
    };
    cases.push(("size-zero.vox".into(), sized([0, 1, 1], &[])));
    cases.push((
        "size-4-billion.vox".into(),
        sized([u32::MAX; 3], &[[0, 0, 0, 1]]),
    ));
    cases.push((
        "size-2048-corners.vox".into(),
        sized([2048; 3], &[[0, 0, 0, 1], [255, 255, 255, 2]]),
    ));
    cases.push((
        "voxel-outside-size.vox".into(),
        sized([2, 2, 2], &[[5, 0, 0, 1]]),
    ));
    let mut lying_count = model([2, 2, 2], &[[0, 0, 0, 1]]);
    lying_count[1] = chunk(b"XYZI", &u32::MAX.to_le_bytes(), &[]);
    cases.push(("xyzi-count-lies.vox".into(), file(&lying_count)));
    // Palettes: too long, too short, absent.
    let mut chunks = one();
    chunks.push(chunk(b"RGBA", &vec![7; 1 << 20], &[]));
    cases.push(("palette-1mb.vox".into(), file(&chunks)));
    let mut chunks = one();
    chunks.push(chunk(b"RGBA", &[1, 2, 3], &[]));
    cases.push(("palette-3-bytes.vox".into(), file(&chunks)));
    cases.push(("palette-absent.vox".into(), file(&one())));
    // MATL and rOBJ dictionaries: counts that lie, values that are not
    // numbers, keys without values.
    let dict_chunk = |id: &[u8; 4], body: Vec<u8>| with(vec![chunk(id, &body, &[])]);
    let mut matl = Vec::new();
    int(&mut matl, 1);
    dict(
        &mut matl,
        &[
            ("_type", "_glass"),
            ("_rough", "not a number"),
            ("_ior", "-1e999"),
        ],
    );
    cases.push(("matl-garbage-values.vox".into(), dict_chunk(b"MATL", matl)));
    let mut matl = Vec::new();
    int(&mut matl, 300);
    int(&mut matl, i32::MAX); // a dictionary count far beyond the chunk
    cases.push(("matl-count-lies.vox".into(), dict_chunk(b"MATL", matl)));
    let mut robj = Vec::new();
    int(&mut robj, 1);
    int(&mut robj, 1_000_000); // a key length far beyond the chunk
    cases.push(("robj-string-lies.vox".into(), dict_chunk(b"rOBJ", robj)));
    let mut robj = Vec::new();
    dict(
        &mut robj,
        &[("_type", "_bounce"), ("_diffuse", "\u{0}\u{ff}")],
    );
    cases.push(("robj-odd-values.vox".into(), dict_chunk(b"rOBJ", robj)));
    // rCAM: an id with a dictionary count that lies, and values that are
    // not numbers or out of range.
    let mut rcam = Vec::new();
    int(&mut rcam, 0);
    int(&mut rcam, i32::MAX);
    cases.push(("rcam-count-lies.vox".into(), dict_chunk(b"rCAM", rcam)));
    let mut rcam = Vec::new();
    int(&mut rcam, -1);
    dict(
        &mut rcam,
        &[
            ("_mode", "orth"),
            ("_focus", "1e39 nan \u{0}"),
            ("_radius", "-1e999"),
            ("_fov", "180"),
        ],
    );
    cases.push(("rcam-odd-values.vox".into(), dict_chunk(b"rCAM", rcam)));
    // 100,000 cameras in 2 MB (MagicaVoxel writes 10): read in linear time,
    // their warnings counted rather than listed.
    let many: Vec<Vec<u8>> = (0..100_000)
        .map(|id: i32| {
            let mut c = Vec::new();
            int(&mut c, id);
            dict(&mut c, &[("_fov", "0")]);
            chunk(b"rCAM", &c, &[])
        })
        .collect();
    cases.push(("rcam-many.vox".into(), with(many)));
    // Chunk headers whose sizes lie.
    let mut lying = small_scene();
    lying[16..20].copy_from_slice(&u32::MAX.to_le_bytes()); // MAIN's children size
    cases.push(("main-size-lies.vox".into(), lying));
    cases.push(("empty.vox".into(), Vec::new()));
    cases.push(("magic-only.vox".into(), b"VOX ".to_vec()));
    cases
}

/// An instance storm: `fan^levels` instances of one model, through
/// `levels` nested groups of `fan` transforms, child `i` of level `l`
/// translated by `i * spacing` along axis `l % 3`, so that instances stand
/// on a grid `spacing` apart and, `spacing` past the model, fill distinct
/// chunks. The model holds `voxels` voxels 8 apart (each in a chunk of its
/// own; 4,096 at most). A file of about `levels * fan * 60` bytes.
pub fn storm(levels: i32, fan: i32, spacing: i32, voxels: usize) -> Vec<u8> {
    let side = |n: usize| 8 * n.div_ceil(32 * 32).max(1) as u32;
    let spread: Vec<[u8; 4]> = (0..voxels)
        .map(|j| {
            [
                8 * (j % 32) as u8,
                8 * (j / 32 % 32) as u8,
                8 * (j / 1024) as u8,
                1,
            ]
        })
        .collect();
    let size = if voxels <= 1 {
        [1, 1, 1]
    } else {
        [256, 256, side(voxels)]
    };
    let mut chunks = model(size, &spread);
    // Node 0: the root transform; then per level a group and its fan of
    // transforms; last, the shape.
    let group_of = |level: i32| 1 + level * (fan + 1);
    let shape_id = group_of(levels);
    chunks.push(transform(0, group_of(0), None));
    for level in 0..levels {
        let g = group_of(level);
        let kids: Vec<i32> = (1..=fan).map(|i| g + i).collect();
        chunks.push(group(g, &kids));
        let next = if level + 1 == levels {
            shape_id
        } else {
            group_of(level + 1)
        };
        for (i, &kid) in kids.iter().enumerate() {
            let mut t = [0; 3];
            t[(level % 3) as usize] = i as i32 * spacing;
            let t = format!("{} {} {}", t[0], t[1], t[2]);
            chunks.push(transform(kid, next, Some(&t)));
        }
    }
    chunks.push(shape(shape_id, 0));
    chunks.push(palette());
    file(&chunks)
}
