//! Optional GPU timestamps around each pass, kept for the last few recorded frames.

use crate::error::{vk_check, Error, Result};
use crate::gpu::loader::Vk;
use crate::settings::MAX_FILTER_PASSES;
use ash::vk;

/// Passes of a frame whose time is reported: prepare, tile classification, each filter pass.
const PASSES: u32 = 2 + MAX_FILTER_PASSES;
/// Most rounds of a frame: a record whose lights share their transient images runs each light's passes in a
/// round of its own; otherwise one round holds every light's dispatches of each pass.
const MAX_ROUNDS: u32 = crate::dispatch::MAX_LIGHTS_PER_RECORD as u32;
/// The start, then the end of each pass of each round (a round's start is the end of the round before).
pub(crate) const QUERIES_PER_FRAME: u32 = 1 + MAX_ROUNDS * PASSES;
/// Frames whose timestamps are kept; timings stay readable while fewer frames than this are in flight.
pub(crate) const FRAME_SLOTS: u32 = 4;
/// Before and after one classifier dispatch (`Context::record_classify`), in FRAME_SLOTS slots after the frames'.
const CLASSIFY_QUERIES: u32 = 2;
const CLASSIFY_BASE: u32 = QUERIES_PER_FRAME * FRAME_SLOTS;

/// GPU time of each pass of one recorded frame, in milliseconds. Where a record's lights run in turn (they share
/// their transient images), each pass's time is the sum of its lights'.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PassTimings {
    /// Which recorded frame these are from (counts `record_shadows` calls from 1).
    pub frame: u64,
    /// prepare pass: visibility and checkerboard inputs only (otherwise the empty interval between its two
    /// timestamps).
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

/// GPU time of one hybrid-shadows classifier dispatch, in milliseconds.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ClassifierTimings {
    /// Which classifier dispatch these are from (counts `record_classify` calls from 1).
    pub dispatch: u64,
    /// From before the classifier's first command (its counters' reset) to after its dispatch.
    pub classify_ms: f64,
}

pub(crate) struct Timestamps {
    pub pool: vk::QueryPool,
    period_ns: f64,
    valid_mask: u64,
    /// Frame number, filter pass count and rounds recorded into each slot (frame 0: never used).
    slots: [(u64, u32, u32); FRAME_SLOTS as usize],
    /// Classifier dispatch recorded into each classifier slot (0: never used).
    classify_slots: [u64; FRAME_SLOTS as usize],
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
            .query_count(CLASSIFY_BASE + CLASSIFY_QUERIES * FRAME_SLOTS);
        let pool = vk_check("vkCreateQueryPool", unsafe { vk.device.create_query_pool(&info, vk.alloc()) })?;
        Ok(Timestamps {
            pool,
            period_ns: props.limits.timestamp_period as f64,
            valid_mask: if bits >= 64 { u64::MAX } else { (1u64 << bits) - 1 },
            slots: [(0, 0, 0); FRAME_SLOTS as usize],
            classify_slots: [0; FRAME_SLOTS as usize],
        })
    }

    /// Claims the classifier slot for `dispatch` and records the reset of its queries. Returns its first query.
    pub(crate) fn begin_classify(&mut self, d: &ash::Device, cmd: vk::CommandBuffer, dispatch: u64) -> u32 {
        let slot = (dispatch % FRAME_SLOTS as u64) as usize;
        self.classify_slots[slot] = dispatch;
        let first = CLASSIFY_BASE + slot as u32 * CLASSIFY_QUERIES;
        unsafe { d.cmd_reset_query_pool(cmd, self.pool, first, CLASSIFY_QUERIES) };
        first
    }

    /// Timings of the most recent classifier dispatch whose queries are available.
    pub(crate) fn latest_classify(&self, d: &ash::Device) -> Result<Option<ClassifierTimings>> {
        for slot in newest_first(&self.classify_slots) {
            let mut data = [[0u64; 2]; CLASSIFY_QUERIES as usize];
            if self.read(d, CLASSIFY_BASE + slot as u32 * CLASSIFY_QUERIES, &mut data)? {
                return Ok(Some(ClassifierTimings { dispatch: self.classify_slots[slot], classify_ms: self.ms(&data, 0, 1) }));
            }
        }
        Ok(None)
    }

    /// Writes query `query` once everything recorded before it has completed.
    pub(crate) fn stamp(&self, d: &ash::Device, cmd: vk::CommandBuffer, query: u32) {
        unsafe { d.cmd_write_timestamp(cmd, vk::PipelineStageFlags::BOTTOM_OF_PIPE, self.pool, query) };
    }

    /// Reads `data.len()` queries from `first` with their availability; true when all of them are available.
    fn read(&self, d: &ash::Device, first: u32, data: &mut [[u64; 2]]) -> Result<bool> {
        let r = unsafe { d.get_query_pool_results(self.pool, first, data, vk::QueryResultFlags::TYPE_64 | vk::QueryResultFlags::WITH_AVAILABILITY) };
        match r {
            Ok(()) | Err(vk::Result::NOT_READY) => Ok(data.iter().all(|q| q[1] != 0)),
            Err(result) => Err(Error::Vulkan { call: "vkGetQueryPoolResults", result }),
        }
    }

    /// Milliseconds from query `a` to query `b` of `data`.
    fn ms(&self, data: &[[u64; 2]], a: usize, b: usize) -> f64 {
        (data[b][0] & self.valid_mask).wrapping_sub(data[a][0] & self.valid_mask) as f64 * self.period_ns * 1e-6
    }

    /// Claims the slot for `frame`, whose `rounds` (1..=MAX_ROUNDS) each run `2 + filter_passes` passes, and
    /// records the reset of its queries. Returns the slot's first query; `query` numbers the others.
    pub(crate) fn begin(&mut self, d: &ash::Device, cmd: vk::CommandBuffer, frame: u64, filter_passes: u32, rounds: u32) -> u32 {
        debug_assert!((1..=MAX_ROUNDS).contains(&rounds));
        let slot = (frame % FRAME_SLOTS as u64) as usize;
        self.slots[slot] = (frame, filter_passes, rounds);
        let first = slot as u32 * QUERIES_PER_FRAME;
        unsafe { d.cmd_reset_query_pool(cmd, self.pool, first, QUERIES_PER_FRAME) };
        first
    }

    /// The query after pass `pass` (0 prepare, 1 classification, 2.. the filter passes) of round `round` of a frame
    /// of `filter_passes`, counted from its first (the start).
    pub(crate) fn query(filter_passes: u32, round: u32, pass: u32) -> u32 {
        1 + round * (2 + filter_passes) + pass
    }

    /// Timings of the most recent frame whose queries are all available.
    pub(crate) fn latest(&self, d: &ash::Device) -> Result<Option<PassTimings>> {
        for slot in newest_first(&self.slots.map(|s| s.0)) {
            let (frame, passes, rounds) = self.slots[slot];
            let mut data = [[0u64; 2]; QUERIES_PER_FRAME as usize];
            let used = Self::query(passes, rounds - 1, passes + 1) as usize + 1;
            if !self.read(d, slot as u32 * QUERIES_PER_FRAME, &mut data[..used])? {
                continue;
            }
            // Each pass's time summed over the rounds.
            let pass_ms = |pass: u32| -> f64 {
                let end = |round| Self::query(passes, round, pass) as usize;
                (0..rounds).map(|round| self.ms(&data, end(round) - 1, end(round))).sum()
            };
            let mut t = PassTimings {
                frame,
                prepare_ms: pass_ms(0),
                tile_classification_ms: pass_ms(1),
                filter_passes: passes,
                total_ms: self.ms(&data, 0, used - 1),
                ..Default::default()
            };
            for p in 0..passes {
                t.filter_ms[p as usize] = pass_ms(2 + p);
            }
            return Ok(Some(t));
        }
        Ok(None)
    }
}

/// The used slots (recorded number not 0), the most recent first.
fn newest_first(recorded: &[u64; FRAME_SLOTS as usize]) -> impl Iterator<Item = usize> {
    let mut order: Vec<usize> = (0..FRAME_SLOTS as usize).filter(|&s| recorded[s] != 0).collect();
    order.sort_by_key(|&s| std::cmp::Reverse(recorded[s]));
    order.into_iter()
}
