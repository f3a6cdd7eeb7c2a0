//! The CPU reference from C: the engine hands one frame of its own data through read callbacks and receives
//! every result through write callbacks, to diff against dnsr's GPU output on the same data.

use super::boundary::{check_no_next, check_type, guard, out, required, CallError};
use super::convert::settings_from_c;
use super::types::{DnsrResult, DnsrSettings, DnsrStructureType, DNSR_STRUCTURE_TYPE_REFERENCE_FRAME_INFO};
use crate::reference::memory::{filled, Frame};
use crate::reference::{decode_normal, run_frame};
use glam::{DMat4, DVec2, DVec3, DVec4};
use std::ffi::c_void;

/// Reference frame flags.
pub type DnsrReferenceFlags = u32;
/// Discard the previous state (the callbacks for previous depth, moments and history are not called).
pub const DNSR_REFERENCE_RESET: DnsrReferenceFlags = 1 << 0;
/// Reverse-Z depth.
pub const DNSR_REFERENCE_DEPTH_INVERTED: DnsrReferenceFlags = 1 << 1;
/// The hit mask holds lit bits (the reference's prepare, which models the word classification forms, is skipped).
pub const DNSR_REFERENCE_HIT_MASK_LIT_BITS: DnsrReferenceFlags = 1 << 2;
/// Penumbra guidance, as DNSR_DISPATCH_USE_HIT_DISTANCE: `readHitDistance` and `lightAngularSize` are used.
pub const DNSR_REFERENCE_USE_HIT_DISTANCE: DnsrReferenceFlags = 1 << 3;
/// A visibility input, as DNSR_SHADOW_INPUT_VISIBILITY: `readVisibility` is called instead of `readHitMask`.
pub const DNSR_REFERENCE_VISIBILITY_INPUT: DnsrReferenceFlags = 1 << 4;
/// A checkerboard input, as DNSR_SHADOW_INPUT_CHECKERBOARD: the hit mask holds the rays of the pixels with
/// (x + y) % 2 == phase (0, or 1 with DNSR_REFERENCE_CHECKERBOARD_PHASE_1).
pub const DNSR_REFERENCE_CHECKERBOARD_INPUT: DnsrReferenceFlags = 1 << 5;
/// With DNSR_REFERENCE_CHECKERBOARD_INPUT: this frame traced the pixels with (x + y) % 2 == 1.
pub const DNSR_REFERENCE_CHECKERBOARD_PHASE_1: DnsrReferenceFlags = 1 << 6;
/// The light has no size (DNSR_DISPATCH_HARD_LIGHT): every receiver's output is its own sample. With
/// DNSR_REFERENCE_USE_HIT_DISTANCE, `lightAngularSize` must be 0.
pub const DNSR_REFERENCE_HARD_LIGHT: DnsrReferenceFlags = 1 << 7;
/// `lightPosition` and `lightAngularSize` are used, as DNSR_DISPATCH_USE_LIGHT_POSITION: receivers turned away from
/// the light keep their shadowed samples.
pub const DNSR_REFERENCE_USE_LIGHT_POSITION: DnsrReferenceFlags = 1 << 8;
/// Forces 32 bits.
pub const DNSR_REFERENCE_MAX_ENUM: DnsrReferenceFlags = 0x7FFF_FFFF;
/// Every DNSR_REFERENCE_* bit.
const KNOWN_FLAGS: DnsrReferenceFlags = DNSR_REFERENCE_RESET
    | DNSR_REFERENCE_DEPTH_INVERTED
    | DNSR_REFERENCE_HIT_MASK_LIT_BITS
    | DNSR_REFERENCE_USE_HIT_DISTANCE
    | DNSR_REFERENCE_VISIBILITY_INPUT
    | DNSR_REFERENCE_CHECKERBOARD_INPUT
    | DNSR_REFERENCE_CHECKERBOARD_PHASE_1
    | DNSR_REFERENCE_HARD_LIGHT
    | DNSR_REFERENCE_USE_LIGHT_POSITION;

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
    /// Optional (NULL = dnsr_settings_init_default's: the Quality preset).
    pub p_settings: *const DnsrSettings,
    /// Motion vector multiplier.
    pub motion_vector_scale: [f32; 2],
    /// Normal decode multiplier.
    pub normals_unpack_mul: f32,
    /// Normal decode offset.
    pub normals_unpack_add: f32,
    /// Eye in world space.
    pub eye: [f32; 3],
    /// Depth edge-stop sigma, > 0 (0, NaN or infinite: refused, as by a dispatch).
    pub depth_similarity_sigma: f32,
    /// Current clip -> view (column-major).
    pub projection_inverse: [f32; 16],
    /// Current clip -> previous clip (column-major).
    pub reprojection_matrix: [f32; 16],
    /// Current clip -> world (column-major).
    pub view_projection_inverse: [f32; 16],
    /// With DNSR_REFERENCE_USE_HIT_DISTANCE or DNSR_REFERENCE_USE_LIGHT_POSITION: the light's angular diameter in
    /// radians, in [0, pi).
    pub light_angular_size: f32,
    /// With DNSR_REFERENCE_USE_LIGHT_POSITION: where the light is, as DnsrShadowsDispatch::lightPosition.
    pub light_position: [f32; 4],
}

/// Read and write callbacks over the engine's own data. Reads are required unless marked optional; writes are
/// optional (NULL = not wanted). Every callback receives `userData`. Pixel coordinates are 0..width-1 and
/// 0..height-1; tile coordinates index 8x4 tiles.
#[repr(C)]
#[derive(Clone, Copy)]
pub struct DnsrReferenceCallbacks {
    /// Optional. Passed to every callback.
    pub user_data: *mut c_void,
    /// Required (optional with DNSR_REFERENCE_VISIBILITY_INPUT: not called). Hit mask word of a tile.
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
    /// deviations, sample count, run of identical samples: +n lit, -n shadowed), rounded as dnsr stores them (with
    /// a hit-mask input the sum is not stored: count * mean * (1 - mean) replaces it).
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
    /// Optional (required with DNSR_REFERENCE_VISIBILITY_INPUT). A pixel's visibility as stored (see
    /// DnsrShadowsDispatch::visibility).
    pub read_visibility: Option<unsafe extern "C" fn(user: *mut c_void, x: i32, y: i32) -> f32>,
    /// Optional (required without DNSR_REFERENCE_RESET). Previous frame's raw normal texel (rgb), decoded as
    /// `readNormal`'s: classification leaves history texels whose surface turned out of the blend.
    pub read_previous_normal: Option<unsafe extern "C" fn(user: *mut c_void, x: i32, y: i32, rgb: *mut f32)>,
    /// Optional. Previous frame's count of quiet frames of a tile (see DnsrSettings::hardTileFrames; the previous
    /// frame's `writeTileQuiet`). NULL: 0 for every tile (no tile is hard by time this frame).
    pub read_previous_tile_quiet: Option<unsafe extern "C" fn(user: *mut c_void, tile_x: i32, tile_y: i32) -> u32>,
    /// Optional. Receives this frame's count of quiet frames of a tile (written with the run features on:
    /// stableHistorySamples or convergedSamples > 0).
    pub write_tile_quiet: Option<unsafe extern "C" fn(user: *mut c_void, tile_x: i32, tile_y: i32, frames: u32)>,
}

fn mat(m: &[f32; 16]) -> DMat4 {
    DMat4::from_cols_array(&m.map(|v| v as f64))
}

/// The checks every reference entry point makes on its frame info: structure, extent, flags, and the constants as a
/// GPU dispatch's are checked.
fn checked<'a>(
    p_info: *const DnsrReferenceFrameInfo,
    p_callbacks: *const DnsrReferenceCallbacks,
) -> Result<(&'a DnsrReferenceFrameInfo, &'a DnsrReferenceCallbacks), CallError> {
    let info = required(p_info, "pInfo")?;
    let cb = required(p_callbacks, "pCallbacks")?;
    check_type(info.s_type, DNSR_STRUCTURE_TYPE_REFERENCE_FRAME_INFO, "DNSR_STRUCTURE_TYPE_REFERENCE_FRAME_INFO", "pInfo")?;
    check_no_next(info.p_next, "pInfo")?;
    crate::validate::extent("pInfo->width/height", info.width, info.height, 16384)?;
    let unknown = info.flags & !KNOWN_FLAGS;
    if unknown != 0 {
        return Err(CallError::InvalidArgument(format!("pInfo->flags has unknown bits {unknown:#x}")));
    }
    // The same checks as a GPU dispatch's constants.
    let m = |a: &[f32; 16]| glam::Mat4::from_cols_array(a);
    crate::validate::camera(&crate::validate::Camera {
        projection_inverse: &m(&info.projection_inverse),
        reprojection_matrix: &m(&info.reprojection_matrix),
        view_projection_inverse: &m(&info.view_projection_inverse),
        eye: glam::Vec3::from_array(info.eye),
        motion_vector_scale: glam::Vec2::from_array(info.motion_vector_scale),
        normals_unpack: [info.normals_unpack_mul, info.normals_unpack_add],
        depth_similarity_sigma: info.depth_similarity_sigma,
    })?;
    if info.flags & (DNSR_REFERENCE_USE_HIT_DISTANCE | DNSR_REFERENCE_USE_LIGHT_POSITION) != 0 {
        crate::validate::light_angular_size(info.light_angular_size)?;
        if info.flags & DNSR_REFERENCE_HARD_LIGHT != 0 {
            crate::validate::hard_light_size(info.light_angular_size)?;
        }
    }
    if info.flags & DNSR_REFERENCE_USE_LIGHT_POSITION != 0 {
        crate::validate::light_position(glam::Vec4::from_array(info.light_position))?;
    }
    Ok((info, cb))
}

/// The error of a failed allocation for `info`'s frame.
fn out_of_memory(info: &DnsrReferenceFrameInfo) -> impl Fn(std::collections::TryReserveError) -> CallError + '_ {
    move |e| CallError::OutOfHostMemory(format!("the CPU reference's buffers for a {}x{} frame: {e}", info.width, info.height))
}

/// Depth, normal texels and motion vectors of every pixel, as the engine's read callbacks return them.
struct RawInputs {
    depth: Vec<f32>,
    normals: Vec<[f32; 4]>,
    velocity: Vec<[f32; 2]>,
}

impl RawInputs {
    fn read(info: &DnsrReferenceFrameInfo, cb: &DnsrReferenceCallbacks) -> Result<RawInputs, CallError> {
        let missing = |name: &str| CallError::InvalidArgument(format!("pCallbacks->{name} is NULL"));
        let read_depth = cb.read_depth.ok_or_else(|| missing("readDepth"))?;
        let read_normal = cb.read_normal.ok_or_else(|| missing("readNormal"))?;
        let read_velocity = cb.read_velocity.ok_or_else(|| missing("readVelocity"))?;
        let (w, h) = (info.width as i32, info.height as i32);
        let n = (info.width * info.height) as usize;
        let oom = out_of_memory(info);
        let mut raw = RawInputs {
            depth: filled(n, 0.0).map_err(&oom)?,
            normals: filled(n, [0.0; 4]).map_err(&oom)?,
            velocity: filled(n, [0.0; 2]).map_err(&oom)?,
        };
        for y in 0..h {
            for x in 0..w {
                let i = (y * w + x) as usize;
                // SAFETY: the engine's callbacks, called as the header documents (rgb: 3 floats, xy: 2).
                unsafe {
                    raw.depth[i] = read_depth(cb.user_data, x, y);
                    read_normal(cb.user_data, x, y, raw.normals[i].as_mut_ptr());
                    read_velocity(cb.user_data, x, y, raw.velocity[i].as_mut_ptr());
                }
            }
        }
        Ok(raw)
    }
}

/// Runs one frame of the CPU reference (f64) over the engine's data: read callbacks in, write callbacks out.
/// Returns DNSR_ERROR_NON_FINITE for non-finite constants, DNSR_ERROR_OUT_OF_HOST_MEMORY where its buffers cannot
/// be allocated (nothing written), DNSR_ERROR_INVALID_ARGUMENT for a missing required
/// callback. Single-threaded; meant for diffing a captured frame, not for real time.
#[unsafe(no_mangle)]
pub extern "C" fn dnsr_reference_run_frame(
    p_info: *const DnsrReferenceFrameInfo,
    p_callbacks: *const DnsrReferenceCallbacks,
) -> DnsrResult {
    guard(|_| {
        let (info, cb) = checked(p_info, p_callbacks)?;
        let settings = match unsafe { info.p_settings.as_ref() } {
            Some(s) => settings_from_c(s, "pInfo->pSettings")?,
            None => crate::Settings::default(),
        };
        settings.validate()?;
        let missing = |name: &str| CallError::InvalidArgument(format!("pCallbacks->{name} is NULL"));
        let guided = info.flags & DNSR_REFERENCE_USE_HIT_DISTANCE != 0;
        let read_hit_distance = if guided {
            crate::validate::light_angular_size(info.light_angular_size)?;
            Some(cb.read_hit_distance.ok_or_else(|| missing("readHitDistance"))?)
        } else {
            None
        };
        let visibility_input = info.flags & DNSR_REFERENCE_VISIBILITY_INPUT != 0;
        let checkerboard = info.flags & DNSR_REFERENCE_CHECKERBOARD_INPUT != 0;
        if checkerboard && visibility_input {
            return Err(CallError::InvalidArgument("pInfo->flags: a checkerboard input reads the hit mask, not visibility".into()));
        }
        if !checkerboard && info.flags & DNSR_REFERENCE_CHECKERBOARD_PHASE_1 != 0 {
            return Err(CallError::InvalidArgument("pInfo->flags: CHECKERBOARD_PHASE_1 needs CHECKERBOARD_INPUT".into()));
        }
        let read_visibility = if visibility_input { Some(cb.read_visibility.ok_or_else(|| missing("readVisibility"))?) } else { None };
        let read_hit_mask = if visibility_input { None } else { Some(cb.read_hit_mask.ok_or_else(|| missing("readHitMask"))?) };
        let raw = RawInputs::read(info, cb)?;
        let reset = info.flags & DNSR_REFERENCE_RESET != 0;
        let previous = if reset {
            None
        } else {
            Some((
                cb.read_previous_depth.ok_or_else(|| missing("readPreviousDepth"))?,
                cb.read_previous_moments.ok_or_else(|| missing("readPreviousMoments"))?,
                cb.read_history.ok_or_else(|| missing("readHistory"))?,
                cb.read_previous_normal.ok_or_else(|| missing("readPreviousNormal"))?,
            ))
        };

        let (w, h) = (info.width as i32, info.height as i32);
        let mut f = Frame::try_new(w, h, settings).map_err(out_of_memory(info))?;
        f.reset = reset;
        f.depth_inverted = info.flags & DNSR_REFERENCE_DEPTH_INVERTED != 0;
        f.projection_inverse = mat(&info.projection_inverse);
        f.reprojection = mat(&info.reprojection_matrix);
        f.view_projection_inverse = mat(&info.view_projection_inverse);
        f.eye = DVec3::from_array(info.eye.map(|v| v as f64));
        f.depth_similarity_sigma = info.depth_similarity_sigma as f64;
        f.hard_light = info.flags & DNSR_REFERENCE_HARD_LIGHT != 0;
        let light = info.light_position.map(|v| v as f64);
        f.light_position = (info.flags & DNSR_REFERENCE_USE_LIGHT_POSITION != 0).then(|| glam::DVec4::from_array(light));
        f.light_angular_size = if f.light_position.is_some() { info.light_angular_size as f64 } else { 0.0 };
        if guided {
            f.penumbra = Some(crate::reference::Penumbra::new(info.light_angular_size as f64, f.projection_inverse, h));
        }
        let user = cb.user_data;
        let fractions = read_visibility.is_some() || checkerboard;
        let (tw, th) = ((w + 7) / 8, (h + 3) / 4);
        if let Some(read) = read_hit_mask {
            for ty in 0..th {
                for tx in 0..tw {
                    f.hit_mask[(ty * tw + tx) as usize] = unsafe { read(user, tx, ty) };
                }
            }
        }
        if let Some(read) = read_visibility {
            let mut v = filled((w * h) as usize, 0.0).map_err(out_of_memory(info))?;
            for (i, value) in v.iter_mut().enumerate() {
                // SAFETY: the engine's callback, called as the header documents.
                *value = unsafe { read(user, i as i32 % w, i as i32 / w) } as f64;
            }
            f.visibility = Some(v);
        }
        let scale = DVec2::new(info.motion_vector_scale[0] as f64, info.motion_vector_scale[1] as f64);
        let (mul, add) = (info.normals_unpack_mul as f64, info.normals_unpack_add as f64);
        for y in 0..h {
            for x in 0..w {
                let i = (y * w + x) as usize;
                let (rgb, xy) = (raw.normals[i], raw.velocity[i]);
                f.depth[i] = raw.depth[i] as f64;
                f.normals[i] = decode_normal(DVec3::new(rgb[0] as f64, rgb[1] as f64, rgb[2] as f64), mul, add);
                f.velocity[i] = DVec2::new(xy[0] as f64, xy[1] as f64) * scale;
                if let Some(read) = read_hit_distance {
                    f.hit_distance[i] = unsafe { read(user, x, y) } as f64;
                }
                if let Some((prev_depth, prev_moments, history, prev_normal)) = previous {
                    let (mut m, mut rgb) = ([0f32; 4], [0f32; 4]);
                    unsafe {
                        prev_normal(user, x, y, rgb.as_mut_ptr());
                        let normal = decode_normal(DVec3::new(rgb[0] as f64, rgb[1] as f64, rgb[2] as f64), mul, add);
                        f.previous_depth[i] = crate::reference::depth_copy(&f, [x, y], prev_depth(user, x, y) as f64, normal);
                        prev_moments(user, x, y, m.as_mut_ptr());
                        f.history[i] = history(user, x, y) as f64;
                    }
                    // As the GPU reads them back: rounded to their format, the sum formed from the mean and the
                    // count with 0/1 samples.
                    f.previous_moments[i] = crate::reference::storage::stored_moments(DVec4::from_array(m.map(|v| v as f64)), fractions);
                }
            }
        }

        if let (Some(read), false) = (cb.read_previous_tile_quiet, reset) {
            for ty in 0..th {
                for tx in 0..tw {
                    f.previous_tile_quiet[(ty * tw + tx) as usize] = unsafe { read(user, tx, ty) };
                }
            }
        }
        let lit_bits = info.flags & DNSR_REFERENCE_HIT_MASK_LIT_BITS != 0;
        if checkerboard {
            // Prepare always reconstructs a checkerboard input, from the FidelityFX convention.
            f.checkerboard_phase = Some((info.flags & DNSR_REFERENCE_CHECKERBOARD_PHASE_1 != 0) as u32);
            if lit_bits {
                f.hit_mask.iter_mut().for_each(|w| *w = !*w);
            }
        } else if lit_bits {
            f.tile_mask = f.hit_mask.clone();
        }
        run_frame(&mut f, !lit_bits || checkerboard);

        if let Some(write) = cb.write_tile_meta {
            for ty in 0..th {
                for tx in 0..tw {
                    unsafe { write(user, tx, ty, f.tile_meta[(ty * tw + tx) as usize]) };
                }
            }
        }
        if let (Some(write), true) = (cb.write_tile_quiet, f.settings.uses_runs()) {
            for ty in 0..th {
                for tx in 0..tw {
                    unsafe { write(user, tx, ty, f.tile_quiet[(ty * tw + tx) as usize]) };
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

/// What a diagnosis found.
pub type DnsrDiagnosisKind = u32;
/// Motion vectors point the wrong way (`value`: the factor on motionVectorScale that fits the camera motion).
pub const DNSR_DIAGNOSIS_VELOCITY_SIGN: DnsrDiagnosisKind = 0;
/// Motion vectors are scaled wrongly (`value`: the factor on motionVectorScale that fits the camera motion).
pub const DNSR_DIAGNOSIS_VELOCITY_SCALE: DnsrDiagnosisKind = 1;
/// Normals are not unit length after normalsUnpackMul/Add (`value`: their mean length).
pub const DNSR_DIAGNOSIS_NORMALS_NOT_UNIT: DnsrDiagnosisKind = 2;
/// The depth-inverted flag contradicts projectionInverse or the depth buffer (`value`: 0).
pub const DNSR_DIAGNOSIS_DEPTH_CONVENTION: DnsrDiagnosisKind = 3;
/// projectionInverse and viewProjectionInverse/eye describe different cameras (`value`: the largest relative
/// difference of view distances).
pub const DNSR_DIAGNOSIS_MATRICES_INCONSISTENT: DnsrDiagnosisKind = 4;
/// Forces 32 bits.
pub const DNSR_DIAGNOSIS_MAX_ENUM: DnsrDiagnosisKind = 0x7FFF_FFFF;

/// Capacity of DnsrDiagnosis::message, NUL included.
pub const DNSR_DIAGNOSIS_MESSAGE_SIZE: u32 = 512;
/// Most diagnoses one call can report (one per kind, with room to grow): an array this long receives all.
pub const DNSR_MAX_DIAGNOSES: u32 = 8;

/// One likely integration mistake.
#[repr(C)]
#[derive(Clone, Copy)]
pub struct DnsrDiagnosis {
    /// DNSR_DIAGNOSIS_*.
    pub kind: DnsrDiagnosisKind,
    /// The measured number the kind names (see each DNSR_DIAGNOSIS_* value).
    pub value: f64,
    /// What is wrong and what to change, in words, with C field names; NUL-terminated (truncated to fit).
    pub message: [std::ffi::c_char; 512],
}

/// Looks at one frame of the engine's inputs (depth, normals and motion vectors through `pCallbacks`' readDepth,
/// readNormal and readVelocity; the others are not called) with its dispatch constants (`pInfo`: the motion
/// vector scale, the normal unpack, the matrices, the eye and DNSR_REFERENCE_DEPTH_INVERTED; pSettings and the
/// other flags are not read) for the mistakes integrations make: motion vectors of the wrong sign or scale (needs
/// a frame whose camera moved), normals that do not unpack to unit length, a depth-inverted flag that contradicts
/// the projection or the depth buffer, matrices of different cameras.
/// `*pDiagnosisCount` is the capacity of `pDiagnoses` on entry and the number written on return (with
/// `pDiagnoses` NULL: the number found). DNSR_MAX_DIAGNOSES entries always suffice. No finding: count 0.
#[unsafe(no_mangle)]
pub extern "C" fn dnsr_reference_diagnose(
    p_info: *const DnsrReferenceFrameInfo,
    p_callbacks: *const DnsrReferenceCallbacks,
    p_diagnosis_count: *mut u32,
    p_diagnoses: *mut DnsrDiagnosis,
) -> DnsrResult {
    use crate::reference::diagnostics::{diagnose, Diagnosis, HostFrame};
    guard(|_| {
        // SAFETY: a non-null count points at a u32 the caller owns.
        let count = out(p_diagnosis_count, "pDiagnosisCount")?;
        let (info, cb) = checked(p_info, p_callbacks)?;
        let raw = RawInputs::read(info, cb)?;
        let frame = HostFrame {
            width: info.width,
            height: info.height,
            depth: &raw.depth,
            normals: &raw.normals,
            velocity: &raw.velocity,
            motion_vector_scale: info.motion_vector_scale,
            normals_unpack: [info.normals_unpack_mul, info.normals_unpack_add],
            projection_inverse: mat(&info.projection_inverse),
            reprojection: mat(&info.reprojection_matrix),
            view_projection_inverse: mat(&info.view_projection_inverse),
            eye: DVec3::from_array(info.eye.map(|v| v as f64)),
            depth_inverted: info.flags & DNSR_REFERENCE_DEPTH_INVERTED != 0,
        };
        let found = diagnose(&frame);
        if p_diagnoses.is_null() {
            *count = found.len() as u32;
            return Ok(DnsrResult::DNSR_SUCCESS);
        }
        let written = found.len().min(*count as usize);
        for (k, d) in found.iter().take(written).enumerate() {
            let (kind, value) = match d {
                Diagnosis::VelocitySign { factor, .. } => (DNSR_DIAGNOSIS_VELOCITY_SIGN, *factor),
                Diagnosis::VelocityScale { factor, .. } => (DNSR_DIAGNOSIS_VELOCITY_SCALE, *factor),
                Diagnosis::NormalsNotUnit { mean_length, .. } => (DNSR_DIAGNOSIS_NORMALS_NOT_UNIT, *mean_length),
                Diagnosis::DepthConvention { .. } => (DNSR_DIAGNOSIS_DEPTH_CONVENTION, 0.0),
                Diagnosis::MatricesInconsistent { relative_error } => (DNSR_DIAGNOSIS_MATRICES_INCONSISTENT, *relative_error),
            };
            let mut out = DnsrDiagnosis { kind, value, message: [0; 512] };
            let text = super::boundary::c_names(&d.to_string());
            for (dst, &b) in out.message.iter_mut().zip(text.as_bytes().iter().take(511)) {
                *dst = b as std::ffi::c_char;
            }
            // SAFETY: the caller's array holds at least *count entries.
            unsafe { p_diagnoses.add(k).write(out) };
        }
        *count = written as u32;
        Ok(DnsrResult::DNSR_SUCCESS)
    })
}
