//! Refusing a scene before it is built: the bytes the storage and the frame
//! will need (estimated by the core, which stays `no_std`) against the
//! memory this process can have (read from the OS here), or `--max-memory`.

use voxtrace::IAabb;
use voxtrace_cli::{human_bytes, Backend};

/// Bytes per pixel of the frame: the framebuffer, which becomes the
/// finished pixels in place and which the encoders read (or convert to RGB)
/// in place. What an encoder allocates besides comes on top (see
/// [`output::encoder_bytes`](crate::output::encoder_bytes)).
const FRAME_BYTES_PER_PIXEL: u128 = 4;

/// What the run will need and what it may use, for one refusal message.
pub struct Budget {
    /// Bytes the storage needs (exact for dense, an estimate for the
    /// octree), and a `.vox` model's own, loaded beside it.
    pub storage: u128,
    /// Bytes of the frame at its peak: its pixels and the encoder's own.
    pub frame: u128,
    /// Bytes available, and where the figure comes from.
    pub available: (u128, &'static str),
    /// Whether the scene is a `.vox` model, whose size no flag changes.
    pub model: bool,
}

/// The budget of a render of `pixels` pixels with `backend` over `bounds`,
/// whose encoder allocates `encoder` bytes besides; `model` is a loaded
/// `.vox` model's solid voxel count and heap bytes (`None` for the
/// terrain).
pub fn budget(
    backend: Backend,
    bounds: IAabb,
    model: Option<(u64, u128)>,
    (pixels, encoder): (u64, u128),
    max_memory: Option<u64>,
) -> Budget {
    let solid_voxels = model.map(|(voxels, _)| voxels);
    let storage = match backend {
        Backend::Dense => voxtrace::dense_bytes(bounds),
        Backend::Octree => voxtrace::octree_bytes(bounds, solid_voxels),
    } + model.map_or(0, |(_, bytes)| bytes);
    let available = match max_memory {
        Some(bytes) => (u128::from(bytes), "--max-memory"),
        None => available_memory(),
    };
    Budget {
        storage,
        frame: u128::from(pixels) * FRAME_BYTES_PER_PIXEL + encoder,
        available,
        model: model.is_some(),
    }
}

impl Budget {
    /// `Ok` when storage and frame together fit; otherwise the one-line
    /// refusal, naming the estimate and the limit, and the remedies that
    /// apply to this scene.
    pub fn check(&self, backend: Backend) -> Result<(), String> {
        let (available, from) = self.available;
        if self.storage.saturating_add(self.frame) <= available {
            return Ok(());
        }
        let what = match (backend, self.model) {
            (Backend::Dense, false) => "the dense array for this scene needs",
            (Backend::Octree, false) => "the octree for this scene needs about",
            (Backend::Dense, true) => "the dense array for this model and the model need",
            (Backend::Octree, true) => "the octree for this model and the model need about",
        };
        Err(format!(
            "{what} {}, estimated before building, and the frame {}: more than \
             the {} available ({from}); try {}",
            human_bytes(self.storage),
            human_bytes(self.frame),
            human_bytes(available),
            self.remedies(backend)
        ))
    }

    /// What would make the run fit: for the larger of the two shares, the
    /// flags that shrink it (a `.vox` model's size is its own, `--size`
    /// only sizes the terrain), then `--max-memory`.
    fn remedies(&self, backend: Backend) -> String {
        let mut remedies = Vec::new();
        if self.frame > self.storage {
            remedies.push("a smaller frame (--width and --height, or --tiles)");
        } else {
            if backend == Backend::Dense {
                remedies.push("--backend octree");
            }
            if !self.model {
                remedies.push("a smaller --size");
            }
        }
        let last = "--max-memory to override";
        match remedies.as_slice() {
            [] => last.to_string(),
            _ => format!("{}, or {last}", remedies.join(", ")),
        }
    }
}

/// The memory this process may still use: the least of the machine's
/// available memory, its cgroup's remaining limit and its address-space
/// limit (as `prlimit --as` sets it), each when the OS says. Unknown
/// (not Linux): no limit, and the build's own allocation checks remain.
pub(crate) fn available_memory() -> (u128, &'static str) {
    let read = |path: &str| std::fs::read_to_string(path).ok();
    let mut best = (u128::MAX, "no limit known");
    let mut take = |bytes: Option<u128>, from: &'static str| {
        if let Some(bytes) = bytes.filter(|&b| b < best.0) {
            best = (bytes, from);
        }
    };
    take(
        read("/proc/meminfo").and_then(|t| field_kib(&t, "MemAvailable:")),
        "MemAvailable in /proc/meminfo",
    );
    let cgroup = |name: &str| {
        read(&format!("/sys/fs/cgroup/{name}")).and_then(|t| t.trim().parse::<u128>().ok())
    };
    take(
        cgroup("memory.max").map(|max| max.saturating_sub(cgroup("memory.current").unwrap_or(0))),
        "the cgroup's memory.max",
    );
    let address_space = read("/proc/self/limits").and_then(|t| {
        let line = t.lines().find(|l| l.starts_with("Max address space"))?;
        line.split_whitespace().nth(3)?.parse::<u128>().ok()
    });
    let mapped = read("/proc/self/status").and_then(|t| field_kib(&t, "VmSize:"));
    take(
        address_space.map(|limit| limit.saturating_sub(mapped.unwrap_or(0))),
        "the address-space limit",
    );
    best
}

/// The value of a `Name:   123 kB` line, in bytes.
fn field_kib(text: &str, name: &str) -> Option<u128> {
    let line = text.lines().find(|l| l.starts_with(name))?;
    let kib: u128 = line[name.len()..].split_whitespace().next()?.parse().ok()?;
    Some(kib * 1024)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_os_gives_a_figure_on_linux() {
        let (bytes, from) = available_memory();
        if cfg!(target_os = "linux") {
            assert!(bytes > 0 && bytes < u128::MAX, "{bytes} from {from}");
        }
    }

    #[test]
    fn a_refusal_names_the_estimate_and_the_limit() {
        // 20^3 voxels, 100 pixels of 4 bytes and 800 bytes of the
        // encoder's: 9200 bytes in all.
        let frame = (100, 800);
        let b = budget(Backend::Dense, IAabb::centered(10), None, frame, Some(9200));
        assert_eq!((b.storage, b.frame), (8000, 1200));
        assert_eq!(b.check(Backend::Dense), Ok(()));
        let b = budget(Backend::Dense, IAabb::centered(10), None, frame, Some(9199));
        let refusal = b.check(Backend::Dense).unwrap_err();
        assert!(
            refusal.contains("7.8 KiB (8000 bytes)")
                && refusal.contains("1.2 KiB (1200 bytes)")
                && refusal.contains("9.0 KiB (9199 bytes) available")
                && refusal.contains("--max-memory"),
            "{refusal}"
        );
        // Large figures read short, the exact count after them.
        let b = budget(
            Backend::Dense,
            IAabb::centered(4096),
            None,
            (16, 0),
            Some(1 << 30),
        );
        let refusal = b.check(Backend::Dense).unwrap_err();
        assert!(
            refusal.contains("512 GiB (549755813888 bytes)")
                && refusal.contains("1.0 GiB (1073741824 bytes) available"),
            "{refusal}"
        );
    }

    #[test]
    fn a_refusal_suggests_only_what_applies_to_the_scene() {
        let refuse = |backend, model: Option<(u64, u128)>, frame| {
            let b = budget(backend, IAabb::centered(100), model, frame, Some(1000));
            b.check(backend).unwrap_err()
        };
        let small = (1, 0);
        let terrain = refuse(Backend::Dense, None, small);
        assert!(
            terrain
                .ends_with("try --backend octree, a smaller --size, or --max-memory to override"),
            "{terrain}"
        );
        let terrain = refuse(Backend::Octree, None, small);
        assert!(
            terrain.ends_with("try a smaller --size, or --max-memory to override"),
            "{terrain}"
        );
        // A .vox model's size is its own: --size does nothing to it.
        let model = refuse(Backend::Dense, Some((1 << 20, 1 << 16)), small);
        assert!(
            model.ends_with("try --backend octree, or --max-memory to override"),
            "{model}"
        );
        let model = refuse(Backend::Octree, Some((1 << 20, 1 << 16)), small);
        assert!(model.ends_with("try --max-memory to override"), "{model}");
        // The loaded model's own bytes count with the storage.
        let alone = budget(
            Backend::Octree,
            IAabb::centered(100),
            Some((1 << 20, 0)),
            small,
            None,
        );
        let loaded = budget(
            Backend::Octree,
            IAabb::centered(100),
            Some((1 << 20, 1 << 16)),
            small,
            None,
        );
        assert_eq!(loaded.storage - alone.storage, 1 << 16);
        assert!(
            model.contains("the octree for this model and the model need about"),
            "{model}"
        );
        // A frame larger than the storage: a smaller frame, for either.
        for voxels in [None, Some((1, 512))] {
            let big_frame = refuse(Backend::Octree, voxels, (1 << 30, 0));
            assert!(
                big_frame.ends_with("try a smaller frame (--width and --height, or --tiles), or --max-memory to override")
                    && !big_frame.contains("--size"),
                "{big_frame}"
            );
        }
    }
}
