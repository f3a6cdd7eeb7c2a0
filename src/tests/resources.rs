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

/// Records 10,000 frames, submitted in batches (1,000 per command buffer with push descriptors; without them
/// a batch is max_frames_in_flight frames, the most one light may have in flight), and checks that nothing ran
/// out and the recording path allocated nothing on the host after the first frame.
fn ten_thousand_frames(push_descriptor: bool) {
    let g = Gpu::new(GpuOptions { push_descriptor, ..Default::default() });
    assert_eq!(g.features.push_descriptor, push_descriptor, "device lacks VK_KHR_push_descriptor");
    let (w, h) = (16, 8);
    let mut info = g.create_info(w, h);
    info.enable_timestamps = true;
    info.max_frames_in_flight = crate::MAX_FRAMES_IN_FLIGHT;
    let per_batch = if push_descriptor { 1000 } else { info.max_frames_in_flight };
    let mut r = Runner::new(&g, &info).unwrap();
    let f = static_frame(w, h, &|_, _| 1.0, 1);
    r.frame(&f, false);
    let d = r.dispatch(&f);
    let cmd = g.command_buffer();
    for batch in 0..10_000 / per_batch {
        g.submit_with(cmd, |cmd| {
            for i in 0..per_batch {
                let frame = batch * per_batch + i;
                let before = allocations();
                r.ctx.record_shadows(cmd, &d).unwrap_or_else(|e| panic!("frame {frame}: {e}"));
                let allocated = allocations() - before;
                assert_eq!(allocated, 0, "record_shadows allocated on the host at frame {frame}");
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
fn ten_thousand_frames_with_descriptor_set_ring() {
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
    assert_eq!(t.filter_passes, crate::Settings::default().filter_passes);
    assert_eq!(t.filter_passes, 2);
    let parts = [t.prepare_ms, t.tile_classification_ms, t.filter_ms[0], t.filter_ms[1]];
    assert!(parts.iter().all(|p| p.is_finite() && *p >= 0.0), "{t:?}");
    assert!(t.total_ms > 0.0 && t.total_ms >= t.tile_classification_ms, "{t:?}");
    assert_eq!(t.filter_ms[2..], [0.0, 0.0], "passes beyond filter_passes report 0");

    // Per pixel: the reprojection (RG16 unorm, 4 B), the history (its mean, R16 unorm, 2 B), the depth copy
    // (R32_UINT, also the later filter passes' guide), the kept and this frame's moments (packed, 4 B each with a
    // hit mask, whose frame moments' memory also holds the filter's signal between passes); per tile: metadata and
    // blocker and the two quiet counts (4 B each; a hit mask has no tile mask of dnsr's). Drivers may pad, never
    // shrink.
    let px = (w * h) as u64;
    let tiles = (w.div_ceil(8) * h.div_ceil(4)) as u64;
    let minimum = px * (4 + 2 + 4 + 4 + 4) + 4 * 4 * tiles;
    let bytes = r.ctx.memory_bytes();
    assert!(bytes >= minimum && bytes < minimum * 2 + 65536, "memory_bytes {bytes}, expected about {minimum}");
    let estimate = crate::memory_requirements(w, h, crate::Precision::Fp32, 3, 1).unwrap();
    assert!(estimate >= minimum && estimate <= bytes, "memory_requirements {estimate}, allocated {bytes}");
    // What persists between records: the history (2 B), the depth copy (4 B), the kept moments (4 B; this frame's
    // are transient); per tile the two quiet counts (4 B each).
    let persistent = r.ctx.persistent_memory_bytes();
    let persistent_estimate = crate::persistent_memory_requirements(w, h, crate::Precision::Fp32, 1).unwrap();
    assert_eq!(persistent_estimate, px * (2 + 4 + 4) + 2 * 4 * tiles);
    assert!(persistent >= persistent_estimate && persistent < bytes, "persistent {persistent} of {bytes}");
    assert_eq!(crate::persistent_memory_requirements(w, h, crate::Precision::Fp32, 3).unwrap(), 3 * persistent_estimate);
    drop(r);

    // Every filter pass count needs the same images (the later passes' guide is the depth copy, and the fourth
    // pass's input is the signal again, free once the second pass read it), and every configuration denoises
    // cleanly.
    info.settings.filter_passes = 1;
    let mut r = Runner::new(&g, &info).unwrap();
    let mut sizes = vec![r.ctx.memory_bytes()];
    assert_eq!(crate::memory_requirements(w, h, crate::Precision::Fp32, 1, 1).unwrap(), estimate);
    assert_eq!(crate::memory_requirements(w, h, crate::Precision::Fp32, 4, 1).unwrap(), estimate);
    for passes in [1, 2, 4, 1] {
        r.ctx.set_settings(crate::Settings { filter_passes: passes, ..r.ctx.settings() }).unwrap();
        sizes.push(r.ctx.memory_bytes());
        let out = r.frame(&static_frame(w, h, &super::correctness::smooth, passes as u64), false);
        assert!(out.iter().all(|o| o.is_finite() && (0.0..=1.0).contains(o)), "{passes} passes");
    }
    assert!(sizes.iter().all(|&s| s == sizes[0]), "{sizes:?}");
    drop(r);
    g.assert_clean();
}

mod hooks {
    use super::super::{gpu, static_frame};
    use crate::testing::Runner;
    use crate::{GpuAllocation, GpuMemoryAllocator, ResourceKind};
    use ash::vk;
    use std::ffi::c_void;
    use std::sync::atomic::{AtomicI64, AtomicU64, Ordering};
    use std::sync::{Arc, Mutex};

    /// Live CPU allocations made through the callbacks, and the total count.
    #[derive(Default)]
    struct CpuCounts {
        live: AtomicI64,
        total: AtomicU64,
    }

    unsafe extern "system" fn alloc(user: *mut c_void, size: usize, align: usize, _: vk::SystemAllocationScope) -> *mut c_void {
        let c = unsafe { &*(user as *const CpuCounts) };
        c.live.fetch_add(1, Ordering::SeqCst);
        c.total.fetch_add(1, Ordering::SeqCst);
        let mut p = std::ptr::null_mut();
        unsafe { libc::posix_memalign(&mut p, align.max(8), size.max(1)) };
        p
    }
    unsafe extern "system" fn realloc(
        user: *mut c_void,
        old: *mut c_void,
        size: usize,
        align: usize,
        scope: vk::SystemAllocationScope,
    ) -> *mut c_void {
        if old.is_null() {
            return unsafe { alloc(user, size, align, scope) };
        }
        // Aligned realloc: a fresh block (the old size is unknown here, so copy conservatively via libc).
        let p = unsafe { libc::realloc(old, size) };
        if (p as usize) % align.max(8) == 0 {
            return p;
        }
        let q = unsafe { alloc(user, size, align, scope) };
        unsafe { std::ptr::copy_nonoverlapping(p as *const u8, q as *mut u8, size) };
        unsafe { free(user, p) };
        q
    }
    unsafe extern "system" fn free(user: *mut c_void, p: *mut c_void) {
        if p.is_null() {
            return;
        }
        let c = unsafe { &*(user as *const CpuCounts) };
        c.live.fetch_sub(1, Ordering::SeqCst);
        unsafe { libc::free(p) };
    }

    /// A GPU allocator that carves every request out of its own vkAllocateMemory and records what it saw.
    struct HostGpuAllocator {
        device: ash::Device,
        memory_type: u32,
        log: Mutex<Vec<(ResourceKind, bool)>>,
        live: AtomicI64,
    }

    impl GpuMemoryAllocator for HostGpuAllocator {
        fn allocate(&self, req: &vk::MemoryRequirements, kind: ResourceKind) -> Result<GpuAllocation, vk::Result> {
            assert!(req.memory_type_bits & (1 << self.memory_type) != 0);
            // Place the resource at a non-zero aligned offset to check dnsr binds at the offset it is given.
            let offset = req.alignment.max(1) * 4;
            let info = vk::MemoryAllocateInfo::default().allocation_size(req.size + offset).memory_type_index(self.memory_type);
            let memory = unsafe { self.device.allocate_memory(&info, None) }?;
            self.log.lock().unwrap().push((kind, true));
            self.live.fetch_add(1, Ordering::SeqCst);
            Ok(GpuAllocation { memory, offset, user_handle: 7 })
        }
        fn free(&self, a: &GpuAllocation) {
            assert_eq!(a.user_handle, 7);
            unsafe { self.device.free_memory(a.memory, None) };
            self.live.fetch_sub(1, Ordering::SeqCst);
        }
    }

    #[test]
    fn host_allocators_and_debug_names_are_used_for_everything() {
        let g = gpu();
        let cpu = Box::new(CpuCounts::default());
        let callbacks = vk::AllocationCallbacks::default()
            .user_data(&*cpu as *const CpuCounts as *mut c_void)
            .pfn_allocation(Some(alloc))
            .pfn_reallocation(Some(realloc))
            .pfn_free(Some(free));
        let props = unsafe { g.instance.get_physical_device_memory_properties(g.physical_device) };
        let memory_type = (0..props.memory_type_count)
            .find(|&i| props.memory_types[i as usize].property_flags.contains(vk::MemoryPropertyFlags::DEVICE_LOCAL))
            .unwrap();
        let gpu_alloc =
            Arc::new(HostGpuAllocator { device: g.device.clone(), memory_type, log: Mutex::new(Vec::new()), live: AtomicI64::new(0) });
        let names: Arc<Mutex<Vec<(vk::ObjectType, String)>>> = Arc::default();
        let sink = names.clone();

        let (w, h) = (24, 16);
        let mut info = g.create_info(w, h);
        info.output_format = vk::Format::R32_SFLOAT;
        info.hooks.allocation_callbacks = Some(callbacks);
        info.hooks.gpu_memory = Some(gpu_alloc.clone());
        info.hooks.debug_names =
            Some(Arc::new(move |t, _, n| sink.lock().unwrap().push((t, n.to_string_lossy().into_owned()))));
        {
            let mut r = Runner::new(&g, &info).unwrap();
            for frame in 0..3 {
                let out = r.frame(&static_frame(w, h, &|_, _| 1.0, frame), false);
                assert!(out.iter().all(|&o| o == 1.0));
            }
            r.resize(16, 8).unwrap();
            r.frame(&static_frame(16, 8, &|_, _| 0.0, 9), false);
        }
        assert!(cpu.total.load(Ordering::SeqCst) > 0, "VkAllocationCallbacks never called");
        assert_eq!(cpu.live.load(Ordering::SeqCst), 0, "CPU allocations leaked through the callbacks");
        let log = gpu_alloc.log.lock().unwrap();
        assert!(log.iter().filter(|(k, _)| *k == ResourceKind::Image).count() >= 16, "images: {log:?}");
        assert!(log.iter().any(|(k, _)| *k == ResourceKind::Buffer));
        assert_eq!(gpu_alloc.live.load(Ordering::SeqCst), 0, "GPU allocations leaked");
        let names = names.lock().unwrap();
        for expect in ["dnsr.light0.history", "dnsr.light0.moments", "dnsr.lights.frame_moments", "dnsr.tile_classification_r32f", "dnsr.constants"] {
            assert!(names.iter().any(|(_, n)| n == expect), "no object named {expect}: {names:?}");
        }
        assert!(names.iter().any(|(t, _)| *t == vk::ObjectType::PIPELINE));
        g.assert_clean();
    }
}

/// The state table (src/state/table.rs) is what the images are created with: every row's images exist exactly where
/// its `Needed` says (a row that shares another's memory as a view of it), per light or per context, with its format
/// for the precision, its size (per pixel or per tile) and its lifetime; also after the settings add passes to a
/// context, which allocates nothing. The lights' transient images are one set that they share, or one set each
/// with `transient_memory_per_light`; their persistent images are always their own, but the depth copy of lights
/// recorded together (`lights_recorded_together`: the first light's, and a frame depth in each transient set).
#[test]
fn state_table_is_what_the_images_are_created_with() {
    use crate::state::table::{Image, Needed, Scope, RESOURCES};
    use crate::{Precision, Settings, ShadowInput};
    let g = super::gpu();
    let (w, h) = (44u32, 26u32);
    let check = |ctx: &crate::Context, what: &str, lights: usize, precision: Precision, input: ShadowInput, together: bool| {
        let mut seen: Vec<(ash::vk::Image, bool)> = Vec::new();
        for r in RESOURCES {
            let owners: Vec<Option<usize>> = if r.scope == Scope::Light { (0..lights).map(Some).collect() } else { vec![None] };
            for owner in owners {
                for copy in 0..=r.copies {
                    let made = ctx.state_image(owner, r.image, copy);
                    let shared = r.shared_with(precision, input);
                    let needed = r.needed.holds(input) || (together && r.needed == Needed::LightsTogether);
                    let own = !(together && r.image == Image::DepthCopy && owner != Some(0));
                    let wanted = copy < r.copies && needed && own && shared.is_none();
                    assert_eq!(made.is_some(), wanted, "{what}: {:?} {owner:?} copy {copy}", r.image);
                    let Some(img) = made else { continue };
                    if !seen.contains(&(img.image, img.persistent)) {
                        seen.push((img.image, img.persistent));
                    }
                    assert_eq!(img.format, r.format_for(precision, input), "{what}: {:?}", r.image);
                    assert_eq!(img.extent, crate::state::image_extent(r.per, [w, h]), "{what}: {:?}", r.image);
                    assert_eq!(img.persistent, r.lifetime == crate::state::Lifetime::Persistent, "{what}: {:?}", r.image);
                    // A row another shares: its second view exactly then.
                    let sharer = RESOURCES.iter().any(|s| s.needed.holds(input) && s.shared_with(precision, input) == Some(r.image));
                    assert_eq!(img.shared_view != ash::vk::ImageView::null(), sharer, "{what}: {:?}", r.image);
                }
            }
        }
        // The table lists every image the context has (its transient and persistent images, counted apart), each
        // light's persistent ones its own and the transient ones in the context's sets.
        let (transient, persistent) = ctx.transient_images();
        assert_eq!(transient.len() + persistent, seen.len(), "{what}");
        let rows = |persistent: bool| seen.iter().filter(|s| s.1 == persistent).count();
        assert_eq!((rows(true) + if together { lights - 1 } else { 0 }) % lights, 0, "{what}: every light has its own persistent images");
        assert_eq!(rows(false), transient.len(), "{what}");
        assert_eq!(rows(false) % ctx.transient_set_count(), 0, "{what}");
    };
    let mut precisions = vec![Precision::Fp32];
    if g.features.float16 {
        precisions.push(Precision::Fp16);
    }
    for precision in precisions {
        for (input, passes) in [(ShadowInput::HitMask, 1), (ShadowInput::HitMask, 3), (ShadowInput::Checkerboard, 4), (ShadowInput::Visibility, 2)] {
            let mut info = g.create_info(w, h);
            info.precision = precision;
            info.shadow_input = input;
            info.light_count = 2;
            info.settings.filter_passes = passes;
            let mut ctx = crate::Context::new(&info).unwrap();
            let what = format!("{precision:?}, {input:?}, {passes} passes");
            check(&ctx, &what, 2, precision, input, false);
            assert_eq!(ctx.transient_set_count(), 1, "{what}: the lights share their transient images");
            // context_memory_requirements: what the context holds, less driver padding (a few KB at this size).
            let estimated = |ctx: &crate::Context, info: &crate::ContextCreateInfo, what: &str| {
                let (bytes, persistent) = crate::context_memory_requirements(info).unwrap();
                let (held, kept) = (ctx.memory_bytes(), ctx.persistent_memory_bytes());
                assert!(bytes <= held && held - bytes < 65536, "{what}: estimated {bytes}, holds {held}");
                assert!(persistent <= kept && kept - persistent < 32768, "{what}: estimated {persistent} kept, keeps {kept}");
                (bytes, persistent)
            };
            let default_estimate = estimated(&ctx, &info, &what);
            let shared = ctx.memory_bytes();
            // Each light its own transient set: 2 sets, the same persistent images.
            info.transient_memory_per_light = true;
            let own = crate::Context::new(&info).unwrap();
            check(&own, &format!("{what}, a set per light"), 2, precision, input, false);
            let own_estimate = estimated(&own, &info, &format!("{what}, a set per light"));
            assert!(own_estimate.0 > default_estimate.0 && own_estimate.1 == default_estimate.1, "{what}");
            assert_eq!(own.transient_set_count(), 2, "{what}");
            assert_eq!(own.persistent_memory_bytes(), ctx.persistent_memory_bytes(), "{what}");
            // The second set is what the shared context holds beyond its persistent images, less its constants.
            let (added, one_set) = (own.memory_bytes() - shared, shared - ctx.persistent_memory_bytes());
            assert!(added > 0 && added <= one_set && one_set - added <= 8192, "{what}: {added} more, a set and the constants {one_set}");
            drop(own);
            // Recorded together, with a shared set and with a set each (a hit mask, three passes).
            info.lights_recorded_together = true;
            for per_light in [true, false].into_iter().filter(|_| input == ShadowInput::HitMask && passes == 3) {
                info.transient_memory_per_light = per_light;
                let together = crate::Context::new(&info).unwrap();
                check(&together, &format!("{what}, together, a set per light {per_light}"), 2, precision, input, true);
                let together_estimate = estimated(&together, &info, &format!("{what}, together"));
                assert!(together_estimate.1 < default_estimate.1, "{what}: one depth copy for both lights");
                drop(together);
            }
            (info.lights_recorded_together, info.transient_memory_per_light) = (false, false);
            if passes == 1 {
                // More passes need no image more.
                let bytes = ctx.memory_bytes();
                ctx.set_settings(Settings { filter_passes: 4, ..ctx.settings() }).unwrap();
                check(&ctx, &format!("{what}, then 4"), 2, precision, input, false);
                assert_eq!(ctx.memory_bytes(), bytes, "{what}");
            }
        }
    }
    g.assert_clean();
}

/// The driver's pipeline statistics: an error, not a panic, where the host did not enable
/// VK_KHR_pipeline_executable_properties (lavapipe has none); where it did, every pipeline the preset's frames
/// bind, each with a statistic.
#[test]
fn pipeline_statistics_need_their_extension() {
    for pipeline_statistics in [false, true] {
        let g = Gpu::new(GpuOptions { pipeline_statistics, ..Default::default() });
        let ctx = crate::Context::new(&g.create_info(40, 24)).unwrap();
        match ctx.pipeline_statistics(false, &[]) {
            Ok(pipelines) => {
                assert!(g.pipeline_statistics, "statistics without the extension enabled");
                assert_eq!(pipelines.len(), 6, "{pipelines:?}");
                assert!(pipelines.iter().all(|(_, stats)| !stats.is_empty()), "{pipelines:?}");
            }
            Err(e) => {
                assert!(!g.pipeline_statistics, "extension enabled, yet: {e}");
                assert!(matches!(e, crate::Error::MissingFeature(_)), "{e}");
            }
        }
        drop(ctx);
        assert!(g.take_messages().is_empty());
    }
}
