//! Gives libdnsr.so a versioned soname on Linux, so that programs linked against it record
//! `libdnsr.so.<ABI>` and keep working (or fail cleanly) across installed versions.
//!
//! ABI suffix: for 0.x releases it is `0.<MINOR>` (soname `libdnsr.so.0.1` for 0.1.z), because under
//! Cargo's semver rules a 0.x minor bump is a breaking change; from 1.0 on it is `<MAJOR>`. `make install`
//! derives the same suffix for its symlinks, and dnsrConfigVersion.cmake uses the matching compatibility
//! (same minor for 0.x, same major afterwards).
use std::env;

fn main() {
    println!("cargo:rerun-if-changed=src/build.rs");
    if env::var("CARGO_CFG_TARGET_OS").as_deref() == Ok("linux") {
        let major = env::var("CARGO_PKG_VERSION_MAJOR").unwrap();
        let minor = env::var("CARGO_PKG_VERSION_MINOR").unwrap();
        let abi = if major == "0" { format!("0.{minor}") } else { major };
        println!("cargo:rustc-cdylib-link-arg=-Wl,-soname,libdnsr.so.{abi}");
    }
}
