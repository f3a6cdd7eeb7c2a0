//! Instance-level Vulkan functions for the FFX layer. The FFX interface hands over a device, a physical device and
//! vkGetDeviceProcAddr, never the instance; dnsr's context queries the physical device through instance functions.
//! The Vulkan loader exports those as trampolines that dispatch on the physical device handle alone (the SDK's own
//! backend links the loader for the same reason), so they are looked up in the loader the process already has.

use ash::vk;
use std::ffi::{c_char, c_void};
use std::sync::OnceLock;

fn loader() -> Option<usize> {
    static LOADER: OnceLock<usize> = OnceLock::new();
    let handle = *LOADER.get_or_init(|| {
        // The engine has the loader loaded already; RTLD_NOLOAD finds it without loading a second copy.
        let names = [c"libvulkan.so.1", c"libvulkan.so"];
        for flags in [libc::RTLD_NOW | libc::RTLD_NOLOAD, libc::RTLD_NOW] {
            for name in names {
                let h = unsafe { libc::dlopen(name.as_ptr(), flags) };
                if !h.is_null() {
                    return h as usize;
                }
            }
        }
        0
    });
    (handle != 0).then_some(handle)
}

/// The loader's exported `name`, or NULL.
pub(super) fn symbol(name: *const c_char) -> *mut c_void {
    match loader() {
        Some(h) => unsafe { libc::dlsym(h as *mut c_void, name) },
        None => std::ptr::null_mut(),
    }
}

/// Handed to dnsr as vkGetInstanceProcAddr: every function from the loader's exports, whatever the instance.
pub(super) unsafe extern "system" fn get_instance_proc_addr(_instance: vk::Instance, name: *const c_char) -> vk::PFN_vkVoidFunction {
    let f = symbol(name);
    // SAFETY: a non-null loader export is a function of the named Vulkan type.
    if f.is_null() { None } else { Some(unsafe { std::mem::transmute::<*mut c_void, unsafe extern "system" fn()>(f) }) }
}
