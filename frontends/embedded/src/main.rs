//! The firmware: renders the demo scene with both storages into static
//! buffers on a Cortex-M4F and checks that the frames agree. No std, no
//! allocator; nothing here reads the result but a debugger (`FRAME_SUM`).

#![no_std]
#![no_main]

use core::sync::atomic::{AtomicU32, Ordering};

use cortex_m_rt::entry;
use voxtrace::Node;
use voxtrace_embedded::{render_demo, Backend, Buffers, DENSE_LEN, OCTREE_LEN, PIXELS};

/// A checksum of the frame for a debugger to read; `u32::MAX` if the two
/// storages disagreed or a build failed.
static FRAME_SUM: AtomicU32 = AtomicU32::new(0);

#[entry]
fn main() -> ! {
    // cortex-m-rt turns these into `&'static mut`, safely: `main` runs once.
    static mut DENSE: [u8; DENSE_LEN] = [0; DENSE_LEN];
    static mut NODES: [Node; OCTREE_LEN.nodes] = [Node::EMPTY; OCTREE_LEN.nodes];
    static mut MATERIALS: [u8; OCTREE_LEN.materials] = [0; OCTREE_LEN.materials];
    static mut FRAME_A: [u32; PIXELS] = [0; PIXELS];
    static mut FRAME_B: [u32; PIXELS] = [0; PIXELS];

    let mut sum = u32::MAX;
    let dense = render_demo(
        Backend::Dense,
        Buffers {
            dense: DENSE,
            nodes: &mut [],
            materials: &mut [],
        },
        FRAME_A,
    );
    let octree = render_demo(
        Backend::Octree,
        Buffers {
            dense: &mut [],
            nodes: NODES,
            materials: MATERIALS,
        },
        FRAME_B,
    );
    if dense.is_ok() && octree.is_ok() && FRAME_A == FRAME_B {
        sum = FRAME_A.iter().fold(0u32, |acc, &p| acc.rotate_left(5) ^ p);
    }
    FRAME_SUM.store(sum, Ordering::Relaxed);
    loop {
        core::hint::spin_loop();
    }
}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    FRAME_SUM.store(u32::MAX, Ordering::Relaxed);
    loop {
        core::hint::spin_loop();
    }
}
