//! The CPU reference from C: the engine hands one frame of its own data through read callbacks and receives
//! every result through write callbacks, to diff against dnsr's GPU output on the same data.

use super::boundary::{check_no_next, check_type, guard, required, CallError};
use super::convert::settings_from_c;
use super::types::{DnsrResult, DnsrSettings, DnsrStructureType};
use crate::reference::{decode_normal, memory::Frame, run_frame};
use glam::{DMat4, DVec2, DVec3, DVec4};
use std::ffi::c_void;

/// `DnsrReferenceFrameInfo`.
pub const DNSR_STRUCTURE_TYPE_REFERENCE_FRAME_INFO: DnsrStructureType = 6;

/// Reference frame flags.
pub type DnsrReferenceFlags = u32;
/// Discard the previous state (the callbacks for previous depth, moments and history are not called).
pub const DNSR_REFERENCE_RESET: DnsrReferenceFlags = 1 << 0;
/// Reverse-Z depth.
pub const DNSR_REFERENCE_DEPTH_INVERTED: DnsrReferenceFlags = 1 << 1;
/// The hit mask holds lit bits (prepare skipped).
pub const DNSR_REFERENCE_HIT_MASK_LIT_BITS: DnsrReferenceFlags = 1 << 2;
/// Penumbra guidance, as DNSR_DISPATCH_USE_HIT_DISTANCE: `readHitDistance` and `lightAngularSize` are used.
pub const DNSR_REFERENCE_USE_HIT_DISTANCE: DnsrReferenceFlags = 1 << 3;
/// Forces 32 bits.
pub const DNSR_REFERENCE_MAX_ENUM: DnsrReferenceFlags = 0x7FFF_FFFF;

/// The constants of one reference frame (the same values as a DnsrShadowsDispatch; the render rectangle is
/// the whole `width` x `height`).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct DnsrReferenceFrameInfo {
    /// Must be DNSR_STRUCTURE_TYPE_REFERENCE_FRAME_INFO.
    pub s_type: DnsrStructureType,
    /// Must be NULL.
    pub p_next: *const c_void,
    /// Width in pixels, 1..16384.
    pub width: u32,
    /// Height in pixels, 1..16384.
    pub height: u32,
    /// DNSR_REFERENCE_* bits.
    pub flags: DnsrReferenceFlags,
    /// Optional (NULL = FidelityFX defaults).
    pub p_settings: *const DnsrSettings,
    /// Motion vector multiplier.
    pub motion_vector_scale: [f32; 2],
    /// Normal decode multiplier.
    pub normals_unpack_mul: f32,
    /// Normal decode offset.
    pub normals_unpack_add: f32,
    /// Eye in world space.
    pub eye: [f32; 3],
    /// Depth edge-stop sigma, > 0.
    pub depth_similarity_sigma: f32,
    /// Current clip -> view (column-major).
    pub projection_inverse: [f32; 16],
    /// Current clip -> previous clip (column-major).
    pub reprojection_matrix: [f32; 16],
    /// Current clip -> world (column-major).
    pub view_projection_inverse: [f32; 16],
    /// With DNSR_REFERENCE_USE_HIT_DISTANCE: the light's angular diameter in radians, in [0, pi).
    pub light_angular_size: f32,
}

/// Read and write callbacks over the engine's own data. Reads are required unless marked optional; writes are
/// optional (NULL = not wanted). Every callback receives `userData`. Pixel coordinates are 0..width-1 and
/// 0..height-1; tile coordinates index 8x4 tiles.
#[repr(C)]
#[derive(Clone, Copy)]
pub struct DnsrReferenceCallbacks {
    /// Optional. Passed to every callback.
    pub user_data: *mut c_void,
    /// Required. Hit mask word of a tile.
    pub read_hit_mask: Option<unsafe extern "C" fn(user: *mut c_void, tile_x: i32, tile_y: i32) -> u32>,
    /// Required. Raw depth.
    pub read_depth: Option<unsafe extern "C" fn(user: *mut c_void, x: i32, y: i32) -> f32>,
    /// Required. Raw normal texel (rgb); dnsr decodes it with normalsUnpackMul/Add.
    pub read_normal: Option<unsafe extern "C" fn(user: *mut c_void, x: i32, y: i32, rgb: *mut f32)>,
    /// Required. Raw motion vector (xy); dnsr multiplies it by motionVectorScale.
    pub read_velocity: Option<unsafe extern "C" fn(user: *mut c_void, x: i32, y: i32, xy: *mut f32)>,
    /// Optional (required without DNSR_REFERENCE_RESET). Previous frame's raw depth.
    pub read_previous_depth: Option<unsafe extern "C" fn(user: *mut c_void, x: i32, y: i32) -> f32>,
    /// Optional (required without DNSR_REFERENCE_RESET). Previous frame's moments: 4 floats (mean, sum of squared
    /// deviations, sample count, run of identical samples: +n lit, -n shadowed).
    pub read_previous_moments: Option<unsafe extern "C" fn(user: *mut c_void, x: i32, y: i32, moments: *mut f32)>,
    /// Optional (required without DNSR_REFERENCE_RESET). Previous frame's history texel (filter pass 0 mean).
    pub read_history: Option<unsafe extern "C" fn(user: *mut c_void, x: i32, y: i32) -> f32>,
    /// Optional. Receives the denoised shadow.
    pub write_output: Option<unsafe extern "C" fn(user: *mut c_void, x: i32, y: i32, value: f32)>,
    /// Optional. Receives tile metadata (bit 0 cleared, bit 1 lit).
    pub write_tile_meta: Option<unsafe extern "C" fn(user: *mut c_void, tile_x: i32, tile_y: i32, meta: u32)>,
    /// Optional. Receives the temporal result (mean, variance).
    pub write_reprojection: Option<unsafe extern "C" fn(user: *mut c_void, x: i32, y: i32, mean: f32, variance: f32)>,
    /// Optional. Receives this frame's moments, 4 floats (the next frame's previous moments).
    pub write_moments: Option<unsafe extern "C" fn(user: *mut c_void, x: i32, y: i32, moments: *const f32)>,
    /// Optional. Receives this frame's history (the next frame's `read_history`).
    pub write_history: Option<unsafe extern "C" fn(user: *mut c_void, x: i32, y: i32, value: f32)>,
    /// Optional (required with DNSR_REFERENCE_USE_HIT_DISTANCE). Hit distance of a pixel (see
    /// DnsrShadowsDispatch::hitDistance; called for every pixel, used where the mask says the ray hit).
    pub read_hit_distance: Option<unsafe extern "C" fn(user: *mut c_void, x: i32, y: i32) -> f32>,
}

fn mat(m: &[f32; 16]) -> DMat4 {
    DMat4::from_cols_array(&m.map(|v| v as f64))
}

/// Runs one frame of the CPU reference (f64) over the engine's data: read callbacks in, write callbacks out.
/// Returns DNSR_ERROR_NON_FINITE for non-finite matrices, DNSR_ERROR_INVALID_ARGUMENT for a missing required
/// callback. Single-threaded; meant for diffing a captured frame, not for real time.
#[unsafe(no_mangle)]
pub extern "C" fn dnsr_reference_run_frame(
    p_info: *const DnsrReferenceFrameInfo,
    p_callbacks: *const DnsrReferenceCallbacks,
) -> DnsrResult {
    guard(|_| {
        let info = required(p_info, "pInfo")?;
        let cb = required(p_callbacks, "pCallbacks")?;
        check_type(info.s_type, DNSR_STRUCTURE_TYPE_REFERENCE_FRAME_INFO, "DNSR_STRUCTURE_TYPE_REFERENCE_FRAME_INFO", "pInfo")?;
        check_no_next(info.p_next, "pInfo")?;
        crate::validate::extent("pInfo->width/height", info.width, info.height, 16384)?;
        let settings = match unsafe { info.p_settings.as_ref() } {
            Some(s) => settings_from_c(s, "pInfo->pSettings")?,
            None => crate::Settings::default(),
        };
        settings.validate()?;
        for (name, m) in [
            ("projectionInverse", &info.projection_inverse),
            ("reprojectionMatrix", &info.reprojection_matrix),
            ("viewProjectionInverse", &info.view_projection_inverse),
        ] {
            if m.iter().any(|v| !v.is_finite()) {
                return Err(CallError::Core(crate::Error::NonFinite(name)));
            }
        }
        let missing = |name: &str| CallError::InvalidArgument(format!("pCallbacks->{name} is NULL"));
        let guided = info.flags & DNSR_REFERENCE_USE_HIT_DISTANCE != 0;
        let read_hit_distance = if guided {
            crate::validate::light_angular_size(info.light_angular_size)?;
            Some(cb.read_hit_distance.ok_or_else(|| missing("readHitDistance"))?)
        } else {
            None
        };
        let read_hit_mask = cb.read_hit_mask.ok_or_else(|| missing("readHitMask"))?;
        let read_depth = cb.read_depth.ok_or_else(|| missing("readDepth"))?;
        let read_normal = cb.read_normal.ok_or_else(|| missing("readNormal"))?;
        let read_velocity = cb.read_velocity.ok_or_else(|| missing("readVelocity"))?;
        let reset = info.flags & DNSR_REFERENCE_RESET != 0;
        let previous = if reset {
            None
        } else {
            Some((
                cb.read_previous_depth.ok_or_else(|| missing("readPreviousDepth"))?,
                cb.read_previous_moments.ok_or_else(|| missing("readPreviousMoments"))?,
                cb.read_history.ok_or_else(|| missing("readHistory"))?,
            ))
        };

        let (w, h) = (info.width as i32, info.height as i32);
        let mut f = Frame::new(w, h, settings);
        f.reset = reset;
        f.depth_inverted = info.flags & DNSR_REFERENCE_DEPTH_INVERTED != 0;
        f.projection_inverse = mat(&info.projection_inverse);
        f.reprojection = mat(&info.reprojection_matrix);
        f.view_projection_inverse = mat(&info.view_projection_inverse);
        f.eye = DVec3::from_array(info.eye.map(|v| v as f64));
        f.depth_similarity_sigma = info.depth_similarity_sigma as f64;
        if guided {
            f.penumbra = Some(crate::reference::Penumbra::new(info.light_angular_size as f64, f.projection_inverse, h));
        }
        let user = cb.user_data;
        let (tw, th) = ((w + 7) / 8, (h + 3) / 4);
        for ty in 0..th {
            for tx in 0..tw {
                f.hit_mask[(ty * tw + tx) as usize] = unsafe { read_hit_mask(user, tx, ty) };
            }
        }
        let scale = DVec2::new(info.motion_vector_scale[0] as f64, info.motion_vector_scale[1] as f64);
        let (mul, add) = (info.normals_unpack_mul as f64, info.normals_unpack_add as f64);
        for y in 0..h {
            for x in 0..w {
                let i = (y * w + x) as usize;
                let (mut rgb, mut xy) = ([0f32; 3], [0f32; 2]);
                unsafe {
                    f.depth[i] = read_depth(user, x, y) as f64;
                    read_normal(user, x, y, rgb.as_mut_ptr());
                    read_velocity(user, x, y, xy.as_mut_ptr());
                }
                f.normals[i] = decode_normal(DVec3::from_array(rgb.map(|v| v as f64)), mul, add);
                f.velocity[i] = DVec2::new(xy[0] as f64, xy[1] as f64) * scale;
                if let Some(read) = read_hit_distance {
                    f.hit_distance[i] = unsafe { read(user, x, y) } as f64;
                }
                if let Some((prev_depth, prev_moments, history)) = previous {
                    let mut m = [0f32; 4];
                    unsafe {
                        f.previous_depth[i] = prev_depth(user, x, y) as f64;
                        prev_moments(user, x, y, m.as_mut_ptr());
                        f.history[i] = history(user, x, y) as f64;
                    }
                    f.previous_moments[i] = DVec4::from_array(m.map(|v| v as f64));
                }
            }
        }

        if info.flags & DNSR_REFERENCE_HIT_MASK_LIT_BITS != 0 {
            f.tile_mask = f.hit_mask.clone();
        }
        run_frame(&mut f, info.flags & DNSR_REFERENCE_HIT_MASK_LIT_BITS == 0);

        if let Some(write) = cb.write_tile_meta {
            for ty in 0..th {
                for tx in 0..tw {
                    unsafe { write(user, tx, ty, f.tile_meta[(ty * tw + tx) as usize]) };
                }
            }
        }
        for y in 0..h {
            for x in 0..w {
                let i = (y * w + x) as usize;
                unsafe {
                    if let Some(write) = cb.write_output {
                        write(user, x, y, f.output[i] as f32);
                    }
                    if let Some(write) = cb.write_reprojection {
                        write(user, x, y, f.reprojection_out[i].x as f32, f.reprojection_out[i].y as f32);
                    }
                    if let Some(write) = cb.write_moments {
                        let m = f.moments[i].to_array().map(|v| v as f32);
                        write(user, x, y, m.as_ptr());
                    }
                    if let Some(write) = cb.write_history {
                        write(user, x, y, f.filter_out[0][i].x as f32);
                    }
                }
            }
        }
        Ok(DnsrResult::DNSR_SUCCESS)
    })
}
