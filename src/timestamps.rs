//! Optional GPU timestamps around each pass, kept for the last few recorded frames.

use crate::error::{vk_check, Error, Result};
use crate::gpu::loader::Vk;
use crate::settings::MAX_FILTER_PASSES;
use ash::vk;

/// Start, after prepare, after tile classification, after each filter pass.
pub(crate) const QUERIES_PER_FRAME: u32 = 3 + MAX_FILTER_PASSES;
/// Frames whose timestamps are kept; timings stay readable while fewer frames than this are in flight.
pub(crate) const FRAME_SLOTS: u32 = 4;

/// GPU time of each pass of one recorded frame, in milliseconds.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PassTimings {
    /// Which recorded frame these are from (counts `record_shadows` calls from 1).
    pub frame: u64,
    /// prepare pass (0 when skipped).
    pub prepare_ms: f64,
    /// tile classification pass.
    pub tile_classification_ms: f64,
    /// Each filter pass; entries at and beyond `filter_passes` are 0.
    pub filter_ms: [f64; MAX_FILTER_PASSES as usize],
    /// Number of filter passes that ran.
    pub filter_passes: u32,
    /// From before the first pass to after the last.
    pub total_ms: f64,
}

pub(crate) struct Timestamps {
    pub pool: vk::QueryPool,
    period_ns: f64,
    valid_mask: u64,
    /// Frame number and filter pass count recorded into each slot (frame 0: never used).
    slots: [(u64, u32); FRAME_SLOTS as usize],
}

impl Timestamps {
    pub(crate) fn new(vk: &Vk, queue_family_index: u32) -> Result<Timestamps> {
        let families = unsafe { vk.instance.get_physical_device_queue_family_properties(vk.physical_device) };
        let bits = families.get(queue_family_index as usize).map(|f| f.timestamp_valid_bits).unwrap_or(0);
        if bits == 0 {
            return Err(Error::TimestampsUnsupported);
        }
        let props = unsafe { vk.instance.get_physical_device_properties(vk.physical_device) };
        let info = vk::QueryPoolCreateInfo::default()
            .query_type(vk::QueryType::TIMESTAMP)
            .query_count(QUERIES_PER_FRAME * FRAME_SLOTS);
        let pool = vk_check("vkCreateQueryPool", unsafe { vk.device.create_query_pool(&info, vk.alloc()) })?;
        Ok(Timestamps {
            pool,
            period_ns: props.limits.timestamp_period as f64,
            valid_mask: if bits >= 64 { u64::MAX } else { (1u64 << bits) - 1 },
            slots: [(0, 0); FRAME_SLOTS as usize],
        })
    }

    /// Claims the slot for `frame` and records the reset of its queries. Returns the slot's first query.
    pub(crate) fn begin(&mut self, d: &ash::Device, cmd: vk::CommandBuffer, frame: u64, filter_passes: u32) -> u32 {
        let slot = (frame % FRAME_SLOTS as u64) as usize;
        self.slots[slot] = (frame, filter_passes);
        let first = slot as u32 * QUERIES_PER_FRAME;
        unsafe { d.cmd_reset_query_pool(cmd, self.pool, first, QUERIES_PER_FRAME) };
        first
    }

    /// Timings of the most recent frame whose queries are all available.
    pub(crate) fn latest(&self, d: &ash::Device) -> Result<Option<PassTimings>> {
        let mut order: Vec<usize> = (0..FRAME_SLOTS as usize).filter(|&s| self.slots[s].0 != 0).collect();
        order.sort_by_key(|&s| std::cmp::Reverse(self.slots[s].0));
        for slot in order {
            let (frame, passes) = self.slots[slot];
            let mut data = [[0u64; 2]; QUERIES_PER_FRAME as usize];
            let r = unsafe {
                d.get_query_pool_results(
                    self.pool,
                    slot as u32 * QUERIES_PER_FRAME,
                    &mut data,
                    vk::QueryResultFlags::TYPE_64 | vk::QueryResultFlags::WITH_AVAILABILITY,
                )
            };
            match r {
                Ok(()) | Err(vk::Result::NOT_READY) => {}
                Err(result) => return Err(Error::Vulkan { call: "vkGetQueryPoolResults", result }),
            }
            let used = 3 + passes as usize;
            if data[..used].iter().any(|q| q[1] == 0) {
                continue;
            }
            let ms = |a: usize, b: usize| {
                (data[b][0] & self.valid_mask).wrapping_sub(data[a][0] & self.valid_mask) as f64 * self.period_ns * 1e-6
            };
            let mut t = PassTimings {
                frame,
                prepare_ms: ms(0, 1),
                tile_classification_ms: ms(1, 2),
                filter_passes: passes,
                total_ms: ms(0, used - 1),
                ..Default::default()
            };
            for p in 0..passes as usize {
                t.filter_ms[p] = ms(2 + p, 3 + p);
            }
            return Ok(Some(t));
        }
        Ok(None)
    }
}
