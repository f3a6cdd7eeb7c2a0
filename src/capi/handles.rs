//! Live contexts by handle. A handle is an id, never a pointer dnsr dereferences, so a destroyed or made-up
//! handle is reported (DNSR_ERROR_INVALID_HANDLE) instead of being followed.

use super::boundary::{CallError, LogSink};
use super::types::{DnsrContext, DnsrContext_T};
use crate::context::Context;
use std::collections::BTreeMap;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};

pub(crate) struct Entry {
    pub context: Mutex<Context>,
    pub log: Option<LogSink>,
}

static LIVE: Mutex<BTreeMap<u64, Arc<Entry>>> = Mutex::new(BTreeMap::new());
static NEXT_ID: AtomicU64 = AtomicU64::new(1);

fn live() -> MutexGuard<'static, BTreeMap<u64, Arc<Entry>>> {
    // The map is only inserted into and removed from; a panic elsewhere cannot leave it inconsistent.
    LIVE.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

pub(crate) fn insert(context: Context, log: Option<LogSink>) -> DnsrContext {
    let id = NEXT_ID.fetch_add(1, Ordering::Relaxed);
    live().insert(id, Arc::new(Entry { context: Mutex::new(context), log }));
    id as usize as *mut DnsrContext_T
}

pub(crate) fn get(handle: DnsrContext) -> Result<Arc<Entry>, CallError> {
    live().get(&(handle as usize as u64)).cloned().ok_or(CallError::InvalidHandle("context"))
}

/// The live context of `handle` for a call that reports its errors to the context's log sink too: the sink is
/// named in `sink` (the panic boundary's) before anything else can fail.
pub(crate) fn get_logged(handle: DnsrContext, sink: &mut Option<LogSink>) -> Result<Arc<Entry>, CallError> {
    let entry = get(handle)?;
    *sink = entry.log;
    Ok(entry)
}

/// Removes a handle; the context is dropped once no call still uses it.
pub(crate) fn remove(handle: DnsrContext) -> Result<Arc<Entry>, CallError> {
    live().remove(&(handle as usize as u64)).ok_or(CallError::InvalidHandle("context"))
}

impl Entry {
    pub(crate) fn lock(&self) -> Result<MutexGuard<'_, Context>, CallError> {
        self.context.lock().map_err(|_| {
            CallError::Internal("the context is unusable after an earlier internal error; destroy it".into())
        })
    }
}
