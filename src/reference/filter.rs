//! filter (shaders/filter.glsl): one pass of the edge-avoiding a-trous filter, 3x3 taps at +-step.

use super::{inside, SKY_SIGNAL, is_receiver, linear_depth, pixel_uv, uv_to_ndc, world_position, Coord, Read, Write, PENUMBRA_SIGMA_SCALE, TILE};
use crate::passes::{TILE_CLEARED, TILE_LIT};
use glam::{DVec2, DVec3};

/// Linear depth of a receiver, or None for sky and pixels outside the rectangle.
fn receiver_depth<Io: Read + ?Sized>(io: &Io, p: Coord) -> Option<f64> {
    if !inside(io, p) {
        return None;
    }
    let d = io.read_depth(p);
    is_receiver(d).then(|| linear_depth(io, uv_to_ndc(pixel_uv(io, p)), d))
}

/// From world position w of pixel q to that of the nearer of its receiver neighbours along `axis`, signed as +axis;
/// zero where neither is a receiver (`dnsr_surface_tangent`; the first of two as near, -axis).
fn surface_tangent<Io: Read + ?Sized>(io: &Io, q: Coord, w: DVec3, axis: Coord) -> DVec3 {
    let mut best: Option<DVec3> = None;
    for s in [-1, 1] {
        let r = [q[0] + axis[0] * s, q[1] + axis[1] * s];
        if !inside(io, r) || !is_receiver(io.read_depth(r)) {
            continue;
        }
        let t = (world_position(io, r, io.read_depth(r)) - w) * s as f64;
        if best.is_none_or(|b| t.length_squared() < b.length_squared()) {
            best = Some(t);
        }
    }
    best.unwrap_or(DVec3::ZERO)
}

/// The normal the first pass weighs receiver q's taps by (`dnsr_geometric_normal`): the plane through its nearer
/// neighbour along each axis, on the side of the G-buffer's normal `shading`, where it lies within
/// acos(`Settings::geometric_normal_min_cos`) of it; `shading` elsewhere, where an axis has no receiver, and with
/// `Settings::geometric_normal_degrees` 0.
pub fn geometric_normal<Io: Read + ?Sized>(io: &Io, q: Coord, depth: f64, shading: DVec3) -> DVec3 {
    let min_cos = io.settings().geometric_normal_min_cos() as f64;
    if min_cos > 1.0 {
        return shading;
    }
    let w = world_position(io, q, depth);
    let n = surface_tangent(io, q, w, [1, 0]).cross(surface_tangent(io, q, w, [0, 1]));
    let l = n.length_squared();
    if !(l > 0.0) || l.is_infinite() {
        return shading;
    }
    let n = n / l.sqrt();
    let c = n.dot(shading);
    if c.abs() >= min_cos {
        if c < 0.0 { -n } else { n }
    } else {
        shading
    }
}

/// A receiver's (linear depth, normal) as the pass of step `step` reads them, or None for sky and pixels outside the
/// rectangle: the first pass from the G-buffer (`geometric_normal`), the later ones from this frame's depth copy as
/// stored (their guide).
fn guide<Io: Read + ?Sized>(io: &Io, p: Coord, step: i32) -> Option<(f64, DVec3)> {
    let z = receiver_depth(io, p)?;
    let n = io.read_normal(p);
    if step == 1 {
        return Some((z, geometric_normal(io, p, io.read_depth(p), n)));
    }
    Some(super::storage::unpack_depth_copy(super::depth_copy(io, p, io.read_depth(p), n)))
}

/// With converged pixels on, a converged pixel's signal: variance exactly 0 (shaders/dnsr_common.glsl).
pub fn converged_signal(c: DVec2) -> bool {
    c.y == 0.0
}

/// At least half of the other receivers of the 3x3 around p (step 1) converged (shaders/filter.glsl says why).
fn converged_neighbourhood<Io: Read + ?Sized>(io: &Io, p: Coord) -> bool {
    let (mut receivers, mut converged) = (0, 0);
    for j in -1..=1i32 {
        for i in -1..=1i32 {
            let q = [p[0] + i, p[1] + j];
            if (i == 0 && j == 0) || receiver_depth(io, q).is_none() || super::final_signal(io.read_filter_input(q)) {
                continue;
            }
            receivers += 1;
            converged += converged_signal(io.read_filter_input(q)) as i32;
        }
    }
    2 * converged >= receivers
}

/// With converged pixels on, the variance a receiver that is not converged stores: at least
/// 1 / UNCONVERGED_VARIANCE_INV (UNCONVERGED_VARIANCE_INV_FP16 with float16 intermediates), so that 0 marks the
/// converged ones alone.
pub fn unconverged_variance<Io: Read + ?Sized>(io: &Io, variance: f64) -> f64 {
    if io.settings().converged_samples > 0.0 {
        let inv = if io.half_intermediates() { crate::passes::UNCONVERGED_VARIANCE_INV_FP16 } else { crate::passes::UNCONVERGED_VARIANCE_INV };
        variance.max(1.0 / inv as f64)
    } else {
        variance
    }
}

/// 3x3 Gaussian of the variance (center 1/4, cross 1/8, corner 1/16) over receivers.
fn blurred_variance<Io: Read + ?Sized>(io: &Io, p: Coord) -> f64 {
    let (mut sum, mut weight) = (0.0, 0.0);
    for j in -1..=1i32 {
        for i in -1..=1i32 {
            let q = [p[0] + i, p[1] + j];
            if receiver_depth(io, q).is_none() {
                continue;
            }
            let v = io.read_filter_input(q);
            if super::final_signal(v) {
                continue;
            }
            let v = v.y;
            let w = 1.0 / (4 << (i.abs() + j.abs())) as f64;
            sum += w * v;
            weight += w;
        }
    }
    sum / weight
}

/// Penumbra guidance: 1 / (2 sigma^2) of the Gaussian over tap distance (pixels) that keeps the kernel within
/// the penumbra the tile's blockers cast on a receiver at linear depth `zc`; 0 (no narrowing) without guidance
/// or where no blocker is known.
pub fn penumbra_falloff<Io: Read + ?Sized>(io: &Io, p: Coord, zc: f64) -> f64 {
    let Some(penumbra) = io.penumbra() else { return 0.0 };
    let blocker = io.read_tile_blocker([p[0] / TILE[0], p[1] / TILE[1]]);
    if blocker < 0.0 {
        return 0.0;
    }
    let sigma = penumbra.radius_px(blocker, zc) * PENUMBRA_SIGMA_SCALE;
    0.5 / (sigma * sigma).max(1e-20)
}

/// Whether one ray resolves a receiver of tile `tile` at linear depth `zc`: the light has no size
/// (`ShadowsDispatch::hard_light`), or (penumbra guidance, `Settings::hard_penumbra_pixels`) the tile's blockers
/// cast a penumbra narrow enough.
pub fn hard_penumbra<Io: Read + ?Sized>(io: &Io, tile: Coord, zc: f64) -> bool {
    io.hard_light()
        || io.penumbra().is_some_and(|pen| pen.is_hard(io.read_tile_blocker(tile), zc, io.settings().hard_penumbra_pixels as f64))
}

/// The filtered (mean, variance) of one receiver pixel of a mixed tile, whose guide (`guide`) is (zc, nc).
pub fn filter_pixel<Io: Read + ?Sized>(io: &Io, p: Coord, zc: f64, nc: DVec3) -> DVec2 {
    let s = io.settings();
    let kernel = [1.0, s.kernel_cross_weight as f64];
    let step = io.filter_step();
    let c = io.read_filter_input(p);
    // A final pixel is its own result and no neighbour's tap (shaders/filter.glsl says why). Under a hard penumbra
    // the sample (flagged converged by the temporal part) passes through (dnsr_pass_hard).
    if super::final_signal(c) || (converged_signal(c) && hard_penumbra(io, [p[0] / TILE[0], p[1] / TILE[1]], zc)) {
        return c;
    }
    // A converged pixel (Settings::converged_samples) among converged receivers passes through
    // (shaders/filter.glsl, dnsr_passes_through).
    if s.converged_samples > 0.0 && converged_signal(c) && converged_neighbourhood(io, p) {
        return DVec2::new(if c.x >= 0.5 { 1.0 } else { 0.0 }, 0.0);
    }
    let inv_sigma = 1.0 / blurred_variance(io, p).max(0.0).sqrt().max(s.min_shadow_sigma as f64);
    let inv_depth_sigma = 1.0 / io.depth_similarity_sigma();
    let falloff = penumbra_falloff(io, p, zc);
    let (mut weight_sum, mut mean_sum, mut var_sum) = (1.0, c.x, c.y);
    for j in -1..=1i32 {
        for i in -1..=1i32 {
            if i == 0 && j == 0 {
                continue;
            }
            let q = [p[0] + i * step, p[1] + j * step];
            let Some((zq, nq)) = guide(io, q, step) else { continue };
            let n = io.read_filter_input(q);
            if super::final_signal(n) {
                continue;
            }
            let w = kernel[i.unsigned_abs() as usize]
                * kernel[j.unsigned_abs() as usize]
                * (-(c.x - n.x).abs() * inv_sigma).exp()
                * (-(zc - zq).abs() * inv_depth_sigma).exp()
                * (-((i * i + j * j) * step * step) as f64 * falloff).exp()
                * nc.dot(nq).max(0.0).powf(s.normal_power as f64);
            weight_sum += w;
            mean_sum += w * n.x;
            var_sum += w * w * n.y;
        }
    }
    DVec2::new((mean_sum / weight_sum).clamp(0.0, 1.0), unconverged_variance(io, (var_sum / (weight_sum * weight_sum)).max(0.0)))
}

/// Runs the current filter pass (routing set by `Write::begin_filter_pass`) over the render rectangle.
pub fn run<Io: Read + Write>(io: &mut Io) {
    let e = io.extent();
    let contrast = io.settings().output_contrast as f64;
    for y in 0..e[1] {
        for x in 0..e[0] {
            let p = [x, y];
            // The first pass writes this frame's depth copy (classification has read last frame's).
            if io.filter_step() == 1 {
                let depth = io.read_depth(p);
                let normal = io.read_normal(p);
                io.write_depth_copy(p, super::depth_copy(io, p, depth, normal));
            }
            let meta = io.read_tile_meta([x / TILE[0], y / TILE[1]]);
            let result = match guide(io, p, io.filter_step()) {
                None => SKY_SIGNAL,
                Some(_) if meta & TILE_CLEARED != 0 => DVec2::new(if meta & TILE_LIT != 0 { 1.0 } else { 0.0 }, 0.0),
                Some((zc, nc)) => filter_pixel(io, p, zc, nc),
            };
            if io.write_internal() {
                io.write_filter_output(p, result);
            }
            if io.is_final_pass() {
                io.write_output(p, result.x.powf((contrast - result.y).max(1.0)));
            }
        }
    }
}
