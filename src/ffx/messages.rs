//! ffx_message.h and ffx_assert.h: where an integration routes the SDK's messages and assert reports. The FFX
//! layer sends every error it returns to the message callback too, so an integration's FFX log shows dnsr's words.

use super::types::FFX_MESSAGE_TYPE_ERROR;
use std::ffi::{c_char, CStr};
use std::sync::Mutex;

type MessageCallback = unsafe extern "C" fn(kind: u32, message: *const libc::wchar_t);
type AssertCallback = unsafe extern "C" fn(message: *const c_char);

static MESSAGE: Mutex<Option<MessageCallback>> = Mutex::new(None);
static ASSERT: Mutex<Option<AssertCallback>> = Mutex::new(None);

fn get<T: Copy>(m: &Mutex<Option<T>>) -> Option<T> {
    *m.lock().unwrap_or_else(|e| e.into_inner())
}

fn set<T>(m: &Mutex<Option<T>>, value: Option<T>) {
    *m.lock().unwrap_or_else(|e| e.into_inner()) = value;
}

/// Sends `text` to the message callback as an error, if one is set.
pub(super) fn error(text: &str) {
    if get(&MESSAGE).is_some() {
        let wide: Vec<libc::wchar_t> = text.chars().map(|c| c as libc::wchar_t).chain(std::iter::once(0)).collect();
        ffxPrintMessage(FFX_MESSAGE_TYPE_ERROR, wide.as_ptr());
    }
}

/// ffx_message.h: routes messages to `callback` (NULL: none); the debug level is not used.
#[unsafe(no_mangle)]
pub extern "C" fn ffxSetPrintMessageCallback(callback: Option<MessageCallback>, _debug_level: u32) {
    set(&MESSAGE, callback);
}

/// ffx_message.h: sends a message to the callback, if one is set.
#[unsafe(no_mangle)]
pub extern "C" fn ffxPrintMessage(kind: u32, message: *const libc::wchar_t) {
    if let (Some(callback), false) = (get(&MESSAGE), message.is_null()) {
        // SAFETY: the integration's callback, given a NUL-terminated wide string that lives for the call.
        unsafe { callback(kind, message) };
    }
}

/// ffx_assert.h: routes assert reports to `callback` (NULL: stderr).
#[unsafe(no_mangle)]
pub extern "C" fn ffxAssertSetPrintingCallback(callback: Option<AssertCallback>) {
    set(&ASSERT, callback);
}

/// ffx_assert.h: reports a failed assert; returns true (as the SDK's).
#[unsafe(no_mangle)]
pub extern "C" fn ffxAssertReport(file: *const c_char, line: i32, condition: *const c_char, msg: *const c_char) -> bool {
    // SAFETY: each non-null argument is a NUL-terminated string of the caller's (the FFX_ASSERT macros' literals).
    let text = |p: *const c_char| if p.is_null() { String::new() } else { unsafe { CStr::from_ptr(p) }.to_string_lossy().into_owned() };
    let report = format!("{}({line}): ASSERT: {} {}", text(file), text(condition), text(msg));
    let report = std::ffi::CString::new(report.replace('\0', " ")).unwrap_or_default();
    match get(&ASSERT) {
        // SAFETY: the integration's callback, given a NUL-terminated string that lives for the call.
        Some(callback) => unsafe { callback(report.as_ptr()) },
        None => eprintln!("{}", report.to_string_lossy()),
    }
    true
}
