//! Resource behaviour over many frames: no pool exhaustion, no host allocation on the recording path after the
//! first frame, timestamps, memory accounting.

use super::static_frame;
use crate::testing::gpu::{Gpu, GpuOptions};
use crate::testing::Runner;
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

struct CountingAllocator;

thread_local! {
    static ALLOCATIONS: Cell<u64> = const { Cell::new(0) };
}

fn count() {
    let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
}

unsafe impl GlobalAlloc for CountingAllocator {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count();
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count();
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static ALLOCATOR: CountingAllocator = CountingAllocator;

fn allocations() -> u64 {
    ALLOCATIONS.with(|c| c.get())
}

/// Records 10,000 frames (1,000 per command buffer), submits them, and checks no pool ran out and the recording
/// path allocated nothing on the host after the first frame.
fn ten_thousand_frames(push_descriptor: bool) {
    let g = Gpu::new(GpuOptions { push_descriptor, ..Default::default() });
    assert_eq!(g.features.push_descriptor, push_descriptor, "device lacks VK_KHR_push_descriptor");
    let (w, h) = (16, 8);
    let mut info = g.create_info(w, h);
    info.enable_timestamps = true;
    let mut r = Runner::new(&g, &info).unwrap();
    let f = static_frame(w, h, &|_, _| 1.0, 1);
    r.frame(&f, false);
    let d = r.dispatch(&f);
    let cmd = g.command_buffer();
    for batch in 0..10 {
        g.submit_with(cmd, |cmd| {
            for i in 0..1000 {
                let before = allocations();
                r.ctx.record_shadows(cmd, &d).unwrap_or_else(|e| panic!("frame {}: {e}", batch * 1000 + i));
                let allocated = allocations() - before;
                assert_eq!(allocated, 0, "record_shadows allocated on the host at frame {}", batch * 1000 + i);
            }
        });
    }
    g.free_command_buffer(cmd);
    let out = r.frame(&f, false);
    assert!(out.iter().all(|&o| o == 1.0));
    drop(r);
    g.assert_clean();
}

#[test]
fn ten_thousand_frames_with_push_descriptors() {
    ten_thousand_frames(true);
}

#[test]
fn ten_thousand_frames_with_descriptor_set_cache() {
    ten_thousand_frames(false);
}

#[test]
fn timestamps_and_memory_are_reported() {
    let g = super::gpu();
    let (w, h) = (40, 24);
    let mut info = g.create_info(w, h);
    info.enable_timestamps = true;
    let mut r = Runner::new(&g, &info).unwrap();
    assert_eq!(r.ctx.timings().unwrap(), None, "no frame recorded yet");
    for frame in 0..3 {
        r.frame(&static_frame(w, h, &super::correctness::smooth, frame), false);
    }
    let t = r.ctx.timings().unwrap().expect("timings of a completed frame");
    assert_eq!(t.frame, 3);
    assert_eq!(t.filter_passes, 3);
    let parts = [t.prepare_ms, t.tile_classification_ms, t.filter_ms[0], t.filter_ms[1], t.filter_ms[2]];
    assert!(parts.iter().all(|p| p.is_finite() && *p >= 0.0), "{t:?}");
    assert!(t.total_ms > 0.0 && t.total_ms >= t.tile_classification_ms, "{t:?}");
    assert_eq!(t.filter_ms[3], 0.0);

    // Per pixel: reprojection + history (RG32F, 8 B each), two depth copies (R32F), two moments (RGBA32F);
    // per tile: mask + metadata (R32_UINT). Drivers may pad, never shrink.
    let px = (w * h) as u64;
    let minimum = px * (8 + 8 + 4 + 4 + 16 + 16) + 2 * 4 * (w.div_ceil(8) * h.div_ceil(4)) as u64;
    let bytes = r.ctx.memory_bytes();
    assert!(bytes >= minimum && bytes < minimum * 2 + 65536, "memory_bytes {bytes}, expected about {minimum}");
    drop(r);
    g.assert_clean();
}
