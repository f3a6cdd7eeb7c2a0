//! The one panic boundary every export goes through, the thread-local last error, and error -> code mapping.

use super::types::{DnsrLogCallback, DnsrResult, DNSR_LOG_LEVEL_ERROR};
use crate::error::Error;
use std::cell::RefCell;
use std::ffi::c_char;
use std::panic::{catch_unwind, AssertUnwindSafe};

/// Why a C call failed: a core error, or a problem with the C arguments themselves.
pub(crate) enum CallError {
    Core(Error),
    InvalidArgument(String),
    InvalidStructure(String),
    InvalidHandle(&'static str),
    Internal(String),
    OutOfHostMemory(String),
}

impl From<Error> for CallError {
    fn from(e: Error) -> Self {
        CallError::Core(e)
    }
}

fn code(e: &Error) -> DnsrResult {
    use DnsrResult::*;
    match e {
        Error::NullHandle(_) => DNSR_ERROR_NULL_HANDLE,
        Error::UnsupportedApiVersion { .. } => DNSR_ERROR_UNSUPPORTED_API_VERSION,
        Error::MissingFeature(_) => DNSR_ERROR_MISSING_FEATURE,
        Error::ZeroExtent { .. } | Error::ExtentTooLarge { .. } => DNSR_ERROR_INVALID_EXTENT,
        Error::ImageExtentMismatch { .. } => DNSR_ERROR_IMAGE_EXTENT_MISMATCH,
        Error::UnsupportedFormat { .. } | Error::OutputFormatMismatch { .. } => DNSR_ERROR_UNSUPPORTED_FORMAT,
        Error::UnsupportedLayout { .. } => DNSR_ERROR_UNSUPPORTED_LAYOUT,
        Error::NonFinite(_) => DNSR_ERROR_NON_FINITE,
        Error::InvalidRenderRect { .. } => DNSR_ERROR_INVALID_RENDER_RECT,
        Error::InvalidSetting { .. } => DNSR_ERROR_INVALID_SETTING,
        Error::InvalidLightIndex { .. } => DNSR_ERROR_INVALID_LIGHT_INDEX,
        Error::InvalidValue { .. } => DNSR_ERROR_INVALID_ARGUMENT,
        Error::OutOfDeviceMemory { .. } => DNSR_ERROR_OUT_OF_DEVICE_MEMORY,
        Error::InvalidHostSync { .. } => DNSR_ERROR_INVALID_HOST_SYNC,
        Error::InvalidQueueFamily { .. } => DNSR_ERROR_INVALID_QUEUE_FAMILY,
        Error::Light { error, .. } => code(error),
        Error::NotResized => DNSR_ERROR_VULKAN,
        Error::TimestampsUnsupported => DNSR_ERROR_TIMESTAMPS_UNSUPPORTED,
        Error::ClassifierNotEnabled => DNSR_ERROR_CLASSIFIER_NOT_ENABLED,
        Error::ShaderInterface(_) => DNSR_ERROR_SHADER_INTERFACE,
        Error::Vulkan { .. } => DNSR_ERROR_VULKAN,
    }
}

thread_local! {
    /// NUL-terminated message of this thread's most recent dnsr call (empty after a success). Kept as a byte
    /// vector so that clearing it on the recording path does not allocate.
    static LAST_ERROR: RefCell<Vec<u8>> = RefCell::new(vec![0]);
}

pub(crate) fn set_last_error(message: &str) {
    LAST_ERROR.with(|m| {
        let mut m = m.borrow_mut();
        m.clear();
        m.extend(message.bytes().filter(|&b| b != 0));
        m.push(0);
    });
}

/// Pointer to this thread's last error message (valid until this thread's next dnsr call).
pub(crate) fn last_error_ptr() -> *const c_char {
    LAST_ERROR.with(|m| m.borrow().as_ptr() as *const c_char)
}

/// A log sink captured from a create info or a live context.
#[derive(Clone, Copy)]
pub(crate) struct LogSink(pub DnsrLogCallback);
// SAFETY: the host promises its callback and user data may be used from the threads it calls dnsr on.
unsafe impl Send for LogSink {}
unsafe impl Sync for LogSink {}

impl LogSink {
    pub(crate) fn log(&self, level: u32, message: &[u8]) {
        if let Some(f) = self.0.log {
            // `message` is NUL-terminated (LAST_ERROR's storage).
            unsafe { f(self.0.user_data, level, message.as_ptr() as *const c_char) };
        }
    }
}

/// Runs `f` behind the panic boundary. `f` may name a log sink (once it knows the context) through its argument;
/// failures are stored as this thread's last error and sent to that sink.
pub(crate) fn guard(f: impl FnOnce(&mut Option<LogSink>) -> Result<DnsrResult, CallError>) -> DnsrResult {
    let mut sink = None;
    let outcome = catch_unwind(AssertUnwindSafe(|| f(&mut sink)));
    let (result, message) = match outcome {
        Ok(Ok(r)) => {
            set_last_error("");
            return r;
        }
        Ok(Err(CallError::Core(e))) => (code(&e), c_names(&e.to_string())),
        Ok(Err(CallError::InvalidArgument(m))) => (DnsrResult::DNSR_ERROR_INVALID_ARGUMENT, m),
        Ok(Err(CallError::InvalidStructure(m))) => (DnsrResult::DNSR_ERROR_INVALID_STRUCTURE, m),
        Ok(Err(CallError::InvalidHandle(what))) => {
            (DnsrResult::DNSR_ERROR_INVALID_HANDLE, format!("{what} is not a live DnsrContext (never created, or destroyed)"))
        }
        Ok(Err(CallError::Internal(m))) => (DnsrResult::DNSR_ERROR_INTERNAL, m),
        Ok(Err(CallError::OutOfHostMemory(m))) => (DnsrResult::DNSR_ERROR_OUT_OF_HOST_MEMORY, m),
        Err(panic) => {
            let text = panic
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| panic.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic".into());
            (DnsrResult::DNSR_ERROR_INTERNAL, format!("internal error (please report): {text}"))
        }
    };
    set_last_error(&message);
    if let Some(sink) = sink {
        // A copy, so that the callback may itself call dnsr (which rewrites the last error).
        let text: Vec<u8> = LAST_ERROR.with(|m| m.borrow().clone());
        sink.log(DNSR_LOG_LEVEL_ERROR, &text);
    }
    result
}

/// Rewrites the Rust API's names in a core error message to the C header's (`hit_mask.view` -> `hitMask.view`,
/// `get_device_proc_addr` -> `vulkanFunctions.vkGetDeviceProcAddr`, `Context::resize` -> `dnsr_context_resize`).
/// Only words that start in lower case and contain an underscore are Rust field names; Vulkan and dnsr names
/// (`VK_KHR_push_descriptor`, `R16_SFLOAT`, `dnsr_...`) pass unchanged.
pub(crate) fn c_names(message: &str) -> String {
    let special = [
        ("get_instance_proc_addr", "vulkanFunctions.vkGetInstanceProcAddr"),
        ("get_device_proc_addr", "vulkanFunctions.vkGetDeviceProcAddr"),
        ("features.float16", "DNSR_FEATURE_FLOAT16"),
        ("features.push_descriptor", "DNSR_FEATURE_PUSH_DESCRIPTOR"),
        ("precision Fp16", "DNSR_PRECISION_FP16"),
        ("Context::resize", "dnsr_context_resize"),
        ("(MAX_LIGHT_COUNT)", "(DNSR_MAX_LIGHT_COUNT)"),
        ("(MAX_LIGHTS_PER_RECORD)", "(DNSR_MAX_LIGHTS_PER_RECORD)"),
        ("record_lights", "dnsr_lights_record"),
        ("each LightDispatch", "each DnsrLightDispatch"),
        ("lights[", "pLights["),
        ("(MAX_FRAMES_IN_FLIGHT)", "(DNSR_MAX_FRAMES_IN_FLIGHT)"),
        ("(shader_variants lists them)", "(dnsr_get_shader_variants lists them)"),
    ];
    let mut text = message.to_string();
    for (rust, c) in special {
        text = text.replace(rust, c);
    }
    let mut out = String::with_capacity(text.len());
    let mut rest = text.as_str();
    while let Some(start) = rest.find(|c: char| c.is_ascii_alphanumeric() || c == '_') {
        out.push_str(&rest[..start]);
        rest = &rest[start..];
        let end = rest.find(|c: char| !(c.is_ascii_alphanumeric() || c == '_')).unwrap_or(rest.len());
        let word = &rest[..end];
        // A quoted word is a name the caller gave (a shader variant, a GLSL binding): it stays as written.
        let quoted = out.ends_with('"') || out.ends_with('\'');
        if word.starts_with(|c: char| c.is_ascii_lowercase()) && word.contains('_') && !word.starts_with("dnsr_") && !quoted {
            out.push_str(&camel(word));
        } else {
            out.push_str(word);
        }
        rest = &rest[end..];
    }
    out.push_str(rest);
    out
}

/// snake_case -> camelCase, as cbindgen renames fields.
fn camel(word: &str) -> String {
    let mut out = String::with_capacity(word.len());
    let mut upper = false;
    for ch in word.chars() {
        if ch == '_' {
            upper = true;
        } else if upper {
            out.push(ch.to_ascii_uppercase());
            upper = false;
        } else {
            out.push(ch);
        }
    }
    out
}

/// Checks a required pointer argument and borrows it.
pub(crate) fn required<'a, T>(p: *const T, name: &str) -> Result<&'a T, CallError> {
    // SAFETY: the C caller guarantees a non-null pointer points at a valid, aligned object for the call.
    unsafe { p.as_ref() }.ok_or_else(|| CallError::InvalidArgument(format!("{name} is NULL")))
}

/// An out-parameter: `name` is NULL is an invalid argument.
pub(crate) fn out<'a, T>(p: *mut T, name: &str) -> Result<&'a mut T, CallError> {
    optional_out(p).ok_or_else(|| CallError::InvalidArgument(format!("{name} is NULL")))
}

/// An optional out-parameter: None where it is NULL.
pub(crate) fn optional_out<'a, T>(p: *mut T) -> Option<&'a mut T> {
    // SAFETY: the C caller guarantees a non-null pointer points at a valid, aligned, writable object for the call.
    unsafe { p.as_mut() }
}

/// Checks a structure's sType.
pub(crate) fn check_type(actual: u32, expected: u32, expected_name: &str, what: &str) -> Result<(), CallError> {
    if actual == expected {
        Ok(())
    } else {
        Err(CallError::InvalidStructure(format!("{what}->sType is {actual}, expected {expected_name} ({expected})")))
    }
}

/// Checks that an extension-chain pointer is NULL (no extension structures exist yet).
pub(crate) fn check_no_next(p_next: *const std::ffi::c_void, what: &str) -> Result<(), CallError> {
    if p_next.is_null() {
        Ok(())
    } else {
        Err(CallError::InvalidStructure(format!("{what}->pNext must be NULL (this dnsr version defines no extension structures)")))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::ffi::CStr;

    #[test]
    fn rust_field_names_become_c_names() {
        assert_eq!(c_names("hit_mask.view is null"), "hitMask.view is null");
        assert_eq!(c_names("get_device_proc_addr is null"), "vulkanFunctions.vkGetDeviceProcAddr is null");
        assert_eq!(c_names("setting filter_passes is 5; it must be in [1, 4]"), "setting filterPasses is 5; it must be in [1, 4]");
        assert_eq!(c_names("normals_unpack_mul/add contains NaN"), "normalsUnpackMul/add contains NaN");
        assert_eq!(c_names("DNSR_ERROR_X and R16_SFLOAT stay"), "DNSR_ERROR_X and R16_SFLOAT stay");
        assert_eq!(c_names("enable VK_KHR_push_descriptor"), "enable VK_KHR_push_descriptor");
        assert_eq!(c_names("call Context::resize again"), "call dnsr_context_resize again");
        assert_eq!(c_names("sync.input_src_access: x"), "sync.inputSrcAccess: x");
        assert_eq!(c_names("light_count is 65; [1, 64] (MAX_LIGHT_COUNT)"), "lightCount is 65; [1, 64] (DNSR_MAX_LIGHT_COUNT)");
        assert_eq!(c_names("override \"filter_final_r8\" binds 'engine_depth'"), "override \"filter_final_r8\" binds 'engine_depth'");
    }

    #[test]
    fn a_panic_becomes_an_internal_error_with_its_message() {
        let r = guard(|_| panic!("planted failure"));
        assert_eq!(r, DnsrResult::DNSR_ERROR_INTERNAL);
        let msg = unsafe { CStr::from_ptr(last_error_ptr()) }.to_string_lossy().into_owned();
        assert!(msg.contains("planted failure"), "{msg}");
        assert_eq!(guard(|_| Ok(DnsrResult::DNSR_SUCCESS)), DnsrResult::DNSR_SUCCESS);
        assert_eq!(unsafe { CStr::from_ptr(last_error_ptr()) }.to_bytes(), b"");
    }
}
