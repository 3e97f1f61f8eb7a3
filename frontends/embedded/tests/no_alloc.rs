//! Building into caller buffers and rendering allocate nothing: a counting
//! global allocator sees zero allocations on this thread during the work.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

use voxtrace::Node;
use voxtrace_embedded::{render_demo, Backend, Buffers, DENSE_LEN, OCTREE_LEN, PIXELS};

/// The system allocator, counting this thread's allocations.
struct Counting;

thread_local! {
    // `const` initialization: reading it never allocates.
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

// SAFETY: forwards every call to `System` unchanged; only counts.
#[allow(unsafe_code)]
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let _ = ALLOCATIONS.try_with(|n| n.set(n.get() + 1));
        // SAFETY: the caller's contract is passed through.
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: the caller's contract is passed through.
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let _ = ALLOCATIONS.try_with(|n| n.set(n.get() + 1));
        // SAFETY: the caller's contract is passed through.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn allocations() -> usize {
    ALLOCATIONS.with(Cell::get)
}

#[test]
fn building_into_caller_buffers_and_rendering_allocate_nothing() {
    let mut dense = vec![0u8; DENSE_LEN];
    let mut nodes = vec![Node::EMPTY; OCTREE_LEN.nodes];
    let mut materials = vec![0u8; OCTREE_LEN.materials];
    let mut frame = vec![0u32; PIXELS];
    // The counter sees allocations at all (so a zero below means something).
    let before = allocations();
    drop(std::hint::black_box(vec![1u8; 10]));
    assert_eq!(allocations(), before + 1);

    for backend in [Backend::Dense, Backend::Octree] {
        let before = allocations();
        let buffers = Buffers {
            dense: &mut dense,
            nodes: &mut nodes,
            materials: &mut materials,
        };
        let stats = render_demo(backend, buffers, &mut frame).unwrap();
        assert_eq!(allocations(), before, "{backend:?} allocated");
        assert_eq!(stats.primary_rays, PIXELS as u64);
    }
}
