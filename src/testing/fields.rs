//! Building blocks of truth-known visibility fields (world units on the ground plane).

/// Hermite step from 0 at `e0` to 1 at `e1` (a hard step when `e1 <= e0`).
pub fn smoothstep(e0: f64, e1: f64, x: f64) -> f64 {
    if e1 <= e0 {
        return if x < e0 { 0.0 } else { 1.0 };
    }
    let t = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// 1 inside [lo, hi], 0 outside, with smoothstep ramps `width` wide centred on both edges.
pub fn band(t: f64, [lo, hi]: [f64; 2], width: f64) -> f64 {
    let w = 0.5 * width;
    smoothstep(lo - w, lo + w, t) * (1.0 - smoothstep(hi - w, hi + w, t))
}

/// Occlusion of a box occluder with penumbra `width`.
pub fn soft_box(x: f64, z: f64, xs: [f64; 2], zs: [f64; 2], width: f64) -> f64 {
    band(x, xs, width) * band(z, zs, width)
}
