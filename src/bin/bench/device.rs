//! What the report says about the device, the driver and the build.

use super::json::Json;
use dnsr::ash::vk;
use dnsr::testing::gpu::Gpu;

pub struct DeviceInfo {
    pub name: String,
    pub vendor_id: u32,
    pub device_id: u32,
    pub device_type: String,
    /// The device's Vulkan version, major.minor.patch.
    pub api_version: String,
    /// The version the bench created its instance and device with.
    pub used_api_version: String,
    pub driver_version_raw: u32,
    /// driverVersion decoded (NVIDIA's own packing for vendor 0x10DE, VK_VERSION otherwise).
    pub driver_version: String,
    /// VkPhysicalDeviceDriverProperties, when the device has Vulkan 1.2 or VK_KHR_driver_properties.
    pub driver_name: Option<String>,
    pub driver_info: Option<String>,
    pub timestamp_period_ns: f64,
    pub push_descriptor: bool,
    pub float16: bool,
}

fn version(v: u32) -> String {
    format!("{}.{}.{}", vk::api_version_major(v), vk::api_version_minor(v), vk::api_version_patch(v))
}

pub fn decode_driver_version(vendor_id: u32, v: u32) -> String {
    if vendor_id == 0x10DE {
        format!("{}.{}.{:02}", (v >> 22) & 0x3ff, (v >> 14) & 0xff, (v >> 6) & 0xff)
    } else {
        version(v)
    }
}

impl DeviceInfo {
    pub fn query(gpu: &Gpu) -> DeviceInfo {
        let inst = &gpu.instance;
        let props = unsafe { inst.get_physical_device_properties(gpu.physical_device) };
        let exts = unsafe { inst.enumerate_device_extension_properties(gpu.physical_device) }.unwrap_or_default();
        let has_driver_props = props.api_version >= vk::API_VERSION_1_2
            || exts.iter().any(|e| e.extension_name_as_c_str().ok() == Some(ash_driver_properties_name()));
        let (mut driver_name, mut driver_info) = (None, None);
        if has_driver_props {
            let mut driver = vk::PhysicalDeviceDriverProperties::default();
            let mut p2 = vk::PhysicalDeviceProperties2::default().push_next(&mut driver);
            unsafe { inst.get_physical_device_properties2(gpu.physical_device, &mut p2) };
            let text = |c: Result<&std::ffi::CStr, _>| c.ok().map(|c| c.to_string_lossy().into_owned());
            driver_name = text(driver.driver_name_as_c_str());
            driver_info = text(driver.driver_info_as_c_str());
        }
        DeviceInfo {
            name: gpu.device_name.clone(),
            vendor_id: props.vendor_id,
            device_id: props.device_id,
            device_type: format!("{:?}", props.device_type),
            api_version: version(props.api_version),
            used_api_version: version(gpu.api_version),
            driver_version_raw: props.driver_version,
            driver_version: decode_driver_version(props.vendor_id, props.driver_version),
            driver_name,
            driver_info,
            timestamp_period_ns: props.limits.timestamp_period as f64,
            push_descriptor: gpu.features.push_descriptor,
            float16: gpu.features.float16,
        }
    }

    /// The driver as people quote it: the driver's own info string when it has one, else the decoded version.
    pub fn driver(&self) -> String {
        match (&self.driver_name, &self.driver_info) {
            (Some(n), Some(i)) if !i.is_empty() => format!("{n} {i}"),
            (Some(n), _) => format!("{n} {}", self.driver_version),
            _ => self.driver_version.clone(),
        }
    }

    pub fn to_json(&self) -> Json {
        Json::obj([
            ("name", self.name.clone().into()),
            ("vendor_id", format!("0x{:04x}", self.vendor_id).into()),
            ("device_id", format!("0x{:04x}", self.device_id).into()),
            ("device_type", self.device_type.clone().into()),
            ("vulkan_api_version", self.api_version.clone().into()),
            ("bench_api_version", self.used_api_version.clone().into()),
            ("driver_name", self.driver_name.clone().into()),
            ("driver_info", self.driver_info.clone().into()),
            ("driver_version", self.driver_version.clone().into()),
            ("driver_version_raw", self.driver_version_raw.into()),
            ("timestamp_period_ns", self.timestamp_period_ns.into()),
            ("push_descriptor", self.push_descriptor.into()),
            ("float16", self.float16.into()),
        ])
    }
}

fn ash_driver_properties_name() -> &'static std::ffi::CStr {
    dnsr::ash::khr::driver_properties::NAME
}

/// The commit measured: $DNSR_COMMIT if set, else `git rev-parse HEAD` in the working directory (with whether
/// tracked files differ from it), else "unknown".
pub fn commit() -> (String, &'static str, Option<bool>) {
    if let Ok(c) = std::env::var("DNSR_COMMIT") {
        if !c.trim().is_empty() {
            return (c.trim().to_string(), "DNSR_COMMIT", None);
        }
    }
    let git = |args: &[&str]| {
        std::process::Command::new("git")
            .args(args)
            .stderr(std::process::Stdio::null())
            .output()
            .ok()
            .filter(|o| o.status.success())
            .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
    };
    match git(&["rev-parse", "HEAD"]) {
        Some(sha) if !sha.is_empty() => {
            let dirty = git(&["status", "--porcelain", "--untracked-files=no"]).map(|s| !s.is_empty());
            (sha, "git rev-parse HEAD", dirty)
        }
        _ => ("unknown".into(), "none (no DNSR_COMMIT, no git)", None),
    }
}

/// The command line, each argument quoted where a shell would need it.
pub fn command_line() -> String {
    std::env::args()
        .map(|a| {
            if !a.is_empty() && a.chars().all(|c| c.is_ascii_alphanumeric() || "-_./=,:+%".contains(c)) {
                a
            } else {
                format!("'{}'", a.replace('\'', "'\\''"))
            }
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// UTC date and time of `unix` seconds, ISO 8601.
pub fn utc(unix: u64) -> String {
    let (days, secs) = ((unix / 86400) as i64, unix % 86400);
    // Civil from days (Howard Hinnant's algorithm).
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + if m <= 2 { 1 } else { 0 };
    format!("{y:04}-{m:02}-{d:02}T{:02}:{:02}:{:02}Z", secs / 3600, secs / 60 % 60, secs % 60)
}
