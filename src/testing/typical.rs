//! A scene-like sequence for benchmarks: a city of boxes on a ground plane under a large area light, seen by a
//! perspective camera that pans sideways every frame. About 10% of the pixels are sky (above the horizon or
//! beyond the far plane), about 30% lie in penumbrae, the rest is lit or shadowed ground, roofs and walls; the
//! pan opens disocclusion strips at the image edge and behind every box edge (parallax).
//!
//! The sequence is a cycle of `TYPICAL_CYCLE` frames (the camera moves right, then back left, one step per
//! frame), so frame `k` follows frame `k - 1 mod TYPICAL_CYCLE` with a consistent motion and a host can replay
//! the cycle for as long as it likes. Visibility is an analytic soft-shadow approximation (not a truth to judge
//! accuracy against); the hit mask is Bernoulli(visibility) per pixel, like `scene::render`.

use super::scene::{hash01, FrameInputs};
use glam::{DMat4, DVec2, DVec3, DVec4};

/// Frames in one cycle of the sequence.
pub const TYPICAL_CYCLE: usize = 16;

/// Width of one city cell in world units; each cell holds at most one box.
const CELL: f64 = 6.0;
/// Camera height; every box is lower, so no box rises above the horizon.
const EYE_HEIGHT: f64 = 12.0;
/// Camera pitch below the horizontal (radians): the horizon sits near the top tenth of the image.
const PITCH: f64 = 0.39;
const FOV_Y: f64 = 0.9;
const NEAR: f64 = 0.1;
const FAR: f64 = 400.0;
/// Sideways camera step per frame in world units (about 1% of the image width at the image centre).
const PAN_STEP: f64 = 0.45;
/// Tangent of the light's angular radius: penumbra width per unit of distance to the occluder.
const LIGHT_SPREAD: f64 = 0.45;
/// Shadow-ray samples per candidate box.
const SHADOW_SAMPLES: usize = 24;
/// Tallest box (see `city_box`).
const MAX_BOX_HEIGHT: f64 = 5.0;
const BOX_SEED: u64 = 0x0C17_B0C5;

/// Unit vector towards the light.
fn light_dir() -> DVec3 {
    DVec3::new(0.7, 0.4, 0.3).normalize()
}

/// The box of a cell, if any: footprint [x0, x1] x [z0, z1] and height.
#[derive(Clone, Copy)]
struct CityBox {
    min: DVec2,
    max: DVec2,
    height: f64,
}

fn city_box(cx: i64, cz: i64) -> Option<CityBox> {
    let h = |k: u64| hash01(BOX_SEED ^ k.wrapping_mul(0x9E37_79B9), cx as u32, cz as u32);
    if h(0) < 0.45 {
        return None;
    }
    let origin = DVec2::new(cx as f64 * CELL, cz as f64 * CELL);
    let min = origin + DVec2::new(0.8 + 1.4 * h(1), 0.8 + 1.4 * h(2));
    let max = origin + DVec2::new(CELL - 0.8 - 1.4 * h(3), CELL - 0.8 - 1.4 * h(4));
    Some(CityBox { min, max, height: 0.8 + 4.2 * h(5) })
}

fn cell_of(v: f64) -> i64 {
    (v / CELL).floor() as i64
}

/// Ray / box intersection (slab test): entry distance and the normal of the entry face.
fn hit_box(b: &CityBox, o: DVec3, d: DVec3) -> Option<(f64, DVec3)> {
    let lo = DVec3::new(b.min.x, 0.0, b.min.y);
    let hi = DVec3::new(b.max.x, b.height, b.max.y);
    let (mut t0, mut t1, mut normal) = (0.0f64, f64::INFINITY, DVec3::ZERO);
    for axis in 0..3 {
        let (o, d, lo, hi) = (o[axis], d[axis], lo[axis], hi[axis]);
        if d.abs() < 1e-12 {
            if o < lo || o > hi {
                return None;
            }
            continue;
        }
        let (mut a, mut b) = ((lo - o) / d, (hi - o) / d);
        let mut n = DVec3::ZERO;
        n[axis] = -d.signum();
        if a > b {
            std::mem::swap(&mut a, &mut b);
        }
        if a > t0 {
            t0 = a;
            normal = n;
        }
        t1 = t1.min(b);
        if t0 > t1 {
            return None;
        }
    }
    (t0 > 0.0).then_some((t0, normal))
}

/// Nearest surface along a camera ray: distance, normal and the cell of the box hit (None: ground).
fn trace(o: DVec3, d: DVec3, t_max: f64) -> Option<(f64, DVec3, Option<(i64, i64)>)> {
    let t_ground = if d.y < 0.0 { -o.y / d.y } else { f64::INFINITY };
    let t_end = t_ground.min(t_max);
    // 2D DDA over the cells the ray crosses; boxes lie inside their cells, so the first hit is the nearest.
    let (mut cx, mut cz) = (cell_of(o.x), cell_of(o.z));
    let step = |dv: f64| if dv > 0.0 { 1 } else { -1 };
    let next = |c: i64, ov: f64, dv: f64| {
        if dv.abs() < 1e-12 {
            f64::INFINITY
        } else {
            let edge = if dv > 0.0 { (c + 1) as f64 * CELL } else { c as f64 * CELL };
            (edge - ov) / dv
        }
    };
    let (mut tx, mut tz) = (next(cx, o.x, d.x), next(cz, o.z, d.z));
    let (dtx, dtz) = (CELL / d.x.abs().max(1e-12), CELL / d.z.abs().max(1e-12));
    let mut t = 0.0;
    while t <= t_end {
        if let Some(b) = city_box(cx, cz) {
            if let Some((tb, n)) = hit_box(&b, o, d) {
                if tb <= t_end {
                    return Some((tb, n, Some((cx, cz))));
                }
            }
        }
        if tx < tz {
            t = tx;
            tx += dtx;
            cx += step(d.x);
        } else {
            t = tz;
            tz += dtz;
            cz += step(d.z);
        }
    }
    (t_ground <= t_max).then_some((t_ground, DVec3::Y, None))
}

/// Signed distance from a point to a rectangle in the xz plane (negative inside).
fn rect_distance(p: DVec2, b: &CityBox) -> f64 {
    let c = (b.min + b.max) * 0.5;
    let e = (b.max - b.min) * 0.5;
    let q = (p - c).abs() - e;
    q.max(DVec2::ZERO).length() + q.x.max(q.y).min(0.0)
}

/// Soft visibility of the light from `p` (normal `n`, on the box of cell `own` if any).
fn visibility(p: DVec3, n: DVec3, own: Option<(i64, i64)>) -> f64 {
    let l = light_dir();
    if n.dot(l) <= 0.0 {
        return 0.0;
    }
    let lxz = DVec2::new(l.x, l.z);
    let reach = (MAX_BOX_HEIGHT - p.y).max(0.0) / l.y;
    let (a, b) = (DVec2::new(p.x, p.z), DVec2::new(p.x, p.z) + lxz * reach);
    let pad = LIGHT_SPREAD * reach;
    let (lo, hi) = (a.min(b) - pad, a.max(b) + pad);
    let mut v = 1.0;
    for cz in cell_of(lo.y)..=cell_of(hi.y) {
        for cx in cell_of(lo.x)..=cell_of(hi.x) {
            if own == Some((cx, cz)) {
                continue;
            }
            let Some(bx) = city_box(cx, cz) else { continue };
            let t_top = (bx.height - p.y) / l.y;
            if t_top <= 0.0 {
                continue;
            }
            let end = a + lxz * t_top;
            let spread = LIGHT_SPREAD * t_top;
            if a.max(end).x + spread < bx.min.x
                || a.min(end).x - spread > bx.max.x
                || a.max(end).y + spread < bx.min.y
                || a.min(end).y - spread > bx.max.y
            {
                continue;
            }
            let mut m = f64::INFINITY;
            for i in 0..SHADOW_SAMPLES {
                let t = t_top * (i as f64 + 1.0) / SHADOW_SAMPLES as f64;
                m = m.min(rect_distance(a + lxz * t, &bx) / (LIGHT_SPREAD * t));
            }
            v *= super::fields::smoothstep(-1.0, 1.0, m);
            if v == 0.0 {
                return 0.0;
            }
        }
    }
    v
}

/// Camera position of frame `k` of the cycle: right for half the cycle, then back.
fn eye_of(k: usize) -> DVec3 {
    let k = k % TYPICAL_CYCLE;
    let half = TYPICAL_CYCLE / 2;
    let along = if k <= half { k } else { TYPICAL_CYCLE - k };
    DVec3::new(3.1 + along as f64 * PAN_STEP, EYE_HEIGHT, 2.3)
}

/// Projection (Vulkan clip space: y down, depth [0, 1]) and projection times view of a camera at `eye_relative`
/// (relative to the matrices' origin), looking towards -z pitched down by `PITCH`.
fn view_projection(aspect: f64, eye_relative: DVec3) -> (DMat4, DMat4) {
    // Right-handed view space (camera looks down -z), clip depth in [0, 1], clip y flipped so world up is the
    // top of the image (Vulkan NDC y points down).
    let f = 1.0 / (FOV_Y * 0.5).tan();
    let proj = DMat4::from_cols(
        DVec4::new(f / aspect, 0.0, 0.0, 0.0),
        DVec4::new(0.0, -f, 0.0, 0.0),
        DVec4::new(0.0, 0.0, FAR / (NEAR - FAR), -1.0),
        DVec4::new(0.0, 0.0, FAR * NEAR / (NEAR - FAR), 0.0),
    );
    let fwd = DVec3::new(0.0, -PITCH.sin(), -PITCH.cos());
    let s = fwd.cross(DVec3::Y).normalize();
    let u = s.cross(fwd);
    let e = eye_relative;
    let view = DMat4::from_cols(
        DVec4::new(s.x, u.x, -fwd.x, 0.0),
        DVec4::new(s.y, u.y, -fwd.y, 0.0),
        DVec4::new(s.z, u.z, -fwd.z, 0.0),
        DVec4::new(-s.dot(e), -u.dot(e), fwd.dot(e), 1.0),
    );
    (proj, proj * view)
}

/// Frame `k` (taken modulo `TYPICAL_CYCLE`) at `width` x `height`; `seed` draws the hit mask. The previous
/// camera is frame `k - 1`'s, so the reprojection and motion vectors chain around the cycle. Rows are rendered
/// on all available cores.
pub fn typical_frame(width: u32, height: u32, k: usize, seed: u64) -> FrameInputs {
    let k = k % TYPICAL_CYCLE;
    let (eye, prev_eye) = (eye_of(k), eye_of(k + TYPICAL_CYCLE - 1));
    let aspect = width as f64 / height as f64;
    // Camera-relative matrices, like scene::render.
    let origin = eye;
    let (proj, vp) = view_projection(aspect, DVec3::ZERO);
    let (_, vp_prev) = view_projection(aspect, prev_eye - origin);
    let vp_inv = vp.inverse();
    let (tw, th) = (width.div_ceil(8), height.div_ceil(4));
    let mut f = FrameInputs::blank(width, height, 1.0, proj, vp, vp_prev, glam::Vec3::ZERO);

    // One band of whole tile rows per job.
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get()).min(64) as u32;
    let band_tiles = th.div_ceil(threads * 4).max(1);
    let w = width as usize;
    let px_band = (band_tiles * 4) as usize * w;
    std::thread::scope(|s| {
        let bands = f
            .depth
            .chunks_mut(px_band)
            .zip(f.normals.chunks_mut(px_band))
            .zip(f.velocity.chunks_mut(px_band))
            .zip(f.truth.chunks_mut(px_band))
            .zip(f.receiver.chunks_mut(px_band))
            .zip(f.mask.chunks_mut((band_tiles * tw) as usize))
            .enumerate();
        for (band, (((((depth, normals), velocity), truth), receiver), mask)) in bands {
            s.spawn(move || {
                let y0 = band as u32 * band_tiles * 4;
                for i in 0..depth.len() {
                    let (x, y) = ((i % w) as u32, y0 + (i / w) as u32);
                    let uv = DVec2::new((x as f64 + 0.5) / width as f64, (y as f64 + 0.5) / height as f64);
                    let ndc = uv * 2.0 - 1.0;
                    let unproject = |z: f64| {
                        let p = vp_inv * DVec4::new(ndc.x, ndc.y, z, 1.0);
                        p.truncate() / p.w
                    };
                    let near = unproject(0.0);
                    let dir = (unproject(0.5) - near).normalize();
                    let Some((t, normal, own)) = trace(eye + near, dir, FAR) else { continue };
                    let hit = near + dir * t; // relative to the eye
                    let clip = vp * hit.extend(1.0);
                    let z = clip.z / clip.w;
                    if !(z > 0.0 && z < 1.0) {
                        continue;
                    }
                    let prev = vp_prev * hit.extend(1.0);
                    let prev_uv = DVec2::new(prev.x / prev.w, prev.y / prev.w) * 0.5 + 0.5;
                    let v = visibility(hit + eye + normal * 1e-6, normal, own);
                    depth[i] = z as f32;
                    normals[i] = [normal.x as f32, normal.y as f32, normal.z as f32, 0.0];
                    velocity[i] = (prev_uv - uv).as_vec2().to_array();
                    truth[i] = v as f32;
                    receiver[i] = true;
                    if hash01(seed, x, y) >= v {
                        let tile = ((y / 4 - band as u32 * band_tiles) * tw + x / 8) as usize;
                        mask[tile] |= 1 << ((y % 4) * 8 + (x % 8));
                    }
                }
            });
        }
    });
    f
}

/// Fractions of the pixels of a frame: (sky, lit, shadowed, penumbra); visibility within 0.02 of 0 or 1
/// counts as shadowed or lit.
pub fn coverage(f: &FrameInputs) -> [f64; 4] {
    let mut c = [0usize; 4];
    for (v, r) in f.truth.iter().zip(&f.receiver) {
        let class = match (*r, *v) {
            (false, _) => 0,
            (true, v) if v >= 0.98 => 1,
            (true, v) if v <= 0.02 => 2,
            _ => 3,
        };
        c[class] += 1;
    }
    c.map(|n| n as f64 / f.truth.len().max(1) as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn typical_scene_has_the_advertised_mix() {
        let (w, h) = (320, 180);
        let mut sum = [0.0; 4];
        for k in 0..TYPICAL_CYCLE {
            let c = coverage(&typical_frame(w, h, k, 7));
            sum.iter_mut().zip(c).for_each(|(s, c)| *s += c / TYPICAL_CYCLE as f64);
        }
        let [sky, lit, shadowed, penumbra] = sum;
        assert!((0.07..0.13).contains(&sky), "sky {sky}");
        assert!((0.25..0.35).contains(&penumbra), "penumbra {penumbra}");
        assert!(lit > 0.3 && shadowed > 0.05, "lit {lit} shadowed {shadowed}");
    }

    #[test]
    fn typical_motion_vectors_point_to_the_previous_frame() {
        // A receiver's motion vector lands on a receiver of the previous frame (the same surface, or the
        // occluder that hid it), and the camera pans every frame.
        let (w, h) = (160, 90);
        let (cur, prev) = (typical_frame(w, h, 3, 1), typical_frame(w, h, 2, 1));
        let (mut moved, mut onto_sky, mut receivers) = (0, 0, 0);
        for y in 0..h {
            for x in 0..w {
                let i = (y * w + x) as usize;
                if !cur.receiver[i] {
                    continue;
                }
                receivers += 1;
                let [vx, vy] = cur.velocity[i];
                let (px, py) = ((x as f32 + 0.5) + vx * w as f32, (y as f32 + 0.5) + vy * h as f32);
                if vx.abs() * w as f32 > 0.1 {
                    moved += 1;
                }
                if px >= 0.0 && py >= 0.0 && px < w as f32 && py < h as f32 && !prev.receiver[(py as u32 * w + px as u32) as usize] {
                    onto_sky += 1;
                }
            }
        }
        assert!(onto_sky * 100 < receivers, "{onto_sky} of {receivers} receivers move onto sky");
        assert!(moved * 2 > receivers, "the camera pans every frame ({moved} of {receivers} pixels move)");
    }
}
