//! The hybrid-shadows classifier (shaders/classify.glsl) in f64: per pixel a verdict (lit, shadowed, or to trace
//! with a ray interval) from the cascaded shadow maps, per tile the hit-mask word and the list record.
//!
//! Its decisions are comparisons, so f32 on the GPU and f64 here can only differ where a compared value sits
//! within rounding of its threshold: such pixels are marked fragile (cascade edge, a tap on a texel boundary, a
//! shadow-map depth at the blocker limit, a normal at the terminator), and the parity test compares the tiles
//! without a fragile pixel exactly.

use crate::passes::classify::{blocker_disc, constants, ClassifyConstants, ClassifyDispatch, MAX_SLOPE};
use crate::dispatch::HitMaskConvention;
use crate::error::Result;
use glam::{DMat4, DVec2, DVec3, DVec4};

/// One cascade's shadow map, row-major depths as stored.
pub struct ShadowMap<'a> {
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// Depths, `width * height`.
    pub depth: &'a [f32],
}

/// The inputs of one classify dispatch over the whole render size (no render rectangle).
pub struct ClassifyInputs<'a> {
    /// Render width.
    pub width: u32,
    /// Render height.
    pub height: u32,
    /// Depth per pixel, row-major.
    pub depth: &'a [f32],
    /// Stored normals per pixel (decoded with the dispatch's unpack multiplier and offset).
    pub normals: &'a [[f32; 4]],
    /// The cascades' shadow maps, `dispatch.cascade_count` of them.
    pub cascades: &'a [ShadowMap<'a>],
    /// Everything else (matrices, light, flags); its images are not read.
    pub dispatch: &'a ClassifyDispatch,
}

/// A pixel's verdict.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Verdict {
    /// Decided lit (sky included).
    Lit,
    /// Decided shadowed.
    Shadowed,
    /// Needs a ray: whether most taps saw no blocker, and where the ray may end (it starts at the receiver).
    Trace {
        /// Most taps saw no blocker (the pixel's bit if its tile is not listed).
        guess_lit: bool,
        /// World units from the receiver along the light.
        max_t: f64,
    },
}

/// What the classifier writes.
pub struct ClassifyOutput {
    /// Hit-mask word per tile, in the dispatch's convention.
    pub hit_mask: Vec<u32>,
    /// Listed tiles (x | y << 16, mask to trace, min t, max t), in tile order (the GPU's order is arbitrary).
    pub tiles: Vec<(u32, u32, f64, f64)>,
    /// Per pixel: a compared value lies within rounding of its threshold (f32 may decide otherwise).
    pub fragile: Vec<bool>,
    /// Per pixel verdicts.
    pub verdicts: Vec<Verdict>,
}

/// How close (in the compared quantity's units) a value may come to its threshold before the pixel is fragile.
const EPS: f64 = 1e-5;
/// How close a tap may come to a texel boundary (texels).
const EPS_TEXEL: f64 = 1e-4;

/// The verdict of pixel (x, y) and whether it is fragile.
fn classify_pixel(inp: &ClassifyInputs, c: &ClassifyConstants, x: u32, y: u32) -> (Verdict, bool) {
    let d = inp.dispatch;
    let i = (y * inp.width + x) as usize;
    let depth = inp.depth[i] as f64;
    if !(depth > 0.0 && depth < 1.0) {
        return (Verdict::Lit, false);
    }
    let to_light = DVec3::new(c.light[0] as f64, c.light[1] as f64, c.light[2] as f64);
    let stored = inp.normals[i];
    let n = DVec3::new(stored[0] as f64, stored[1] as f64, stored[2] as f64) * d.normals_unpack_mul as f64 + d.normals_unpack_add as f64;
    let len2 = n.length_squared();
    let n = if len2 > 1e-12 && len2 < 1e30 { n / len2.sqrt() } else { DVec3::ZERO };
    let mut fragile = false;
    if n != DVec3::ZERO {
        let facing = n.dot(to_light);
        fragile |= facing.abs() < EPS;
        if facing <= 0.0 {
            return (Verdict::Shadowed, fragile);
        }
    }
    let unbounded = Verdict::Trace { guess_lit: true, max_t: f64::INFINITY };
    let uv = DVec2::new((x as f64 + 0.5) / inp.width as f64, (y as f64 + 0.5) / inp.height as f64);
    let h = d.view_projection_inverse.as_dmat4() * DVec4::new(uv.x * 2.0 - 1.0, uv.y * 2.0 - 1.0, depth, 1.0);
    let world = h.truncate() / h.w;
    let mut chosen = None;
    for (k, cascade) in d.cascades.iter().take(d.cascade_count as usize).enumerate() {
        let s = (cascade.world_to_shadow.as_dmat4() * world.extend(1.0)).truncate();
        fragile |= [s.x, s.y, 1.0 - s.x, 1.0 - s.y].iter().any(|e| e.abs() < EPS);
        if s.x > 0.0 && s.y > 0.0 && s.x < 1.0 && s.y < 1.0 {
            chosen = Some((k, s));
            break;
        }
    }
    let Some((k, s)) = chosen else { return (unbounded, fragile) };
    let units = c.cascade_units[k].map(|u| u as f64);
    let inverted = d.cascades_depth_inverted;
    let z = if inverted { 1.0 - s.z } else { s.z };
    let radius = c.light[3] as f64 * z.max(0.0) / units[0];
    let map = &inp.cascades[k];
    let size = DVec2::new(map.width as f64, map.height as f64);
    let reach = radius * DVec2::new(units[1], units[2]) * size + 1.0;
    let centre = DVec2::new(s.x, s.y) * size;
    // Taps compare with the receiver's tangent plane under them (how much deeper per texel along u and v), its slope
    // flattened to MAX_SLOPE.
    let axis = |m: &[[f32; 4]; 4]| DVec3::new(m[k][0] as f64, m[k][1] as f64, m[k][2] as f64);
    let plane = if n == DVec3::ZERO {
        DVec2::ZERO
    } else {
        let facing = n.dot(to_light);
        let across = (n - facing * to_light).length();
        let rise = DVec2::new(n.dot(axis(&c.cascade_axes_u)), n.dot(axis(&c.cascade_axes_v)));
        rise / facing.max(across / MAX_SLOPE as f64) * units[0] / size
    };
    let limit = z - units[3];
    let (mut valid, mut blocking) = (0u32, 0u32);
    let mut nearest_light = f64::INFINITY;
    for tap in blocker_disc().iter().take(d.tap_count as usize) {
        let q = centre + DVec2::new(tap[0] as f64, tap[1] as f64) * reach;
        fragile |= [q.x, q.y].iter().any(|v| (v - v.round()).abs() < EPS_TEXEL);
        let t = q.floor();
        if t.x < 0.0 || t.y < 0.0 || t.x >= size.x || t.y >= size.y {
            continue;
        }
        let stored = map.depth[(t.y as u32 * map.width + t.x as u32) as usize] as f64;
        let depth = if inverted { 1.0 - stored } else { stored };
        valid += 1;
        let limit = limit + plane.dot(t + 0.5 - centre);
        fragile |= (depth - limit).abs() < EPS;
        if depth < limit {
            blocking += 1;
            nearest_light = nearest_light.min(depth);
        }
    }
    if valid > 0 && blocking == valid {
        return (Verdict::Shadowed, fragile);
    }
    if valid > 0 && blocking == 0 && d.reject_lit_pixels {
        return (Verdict::Lit, fragile);
    }
    let guess_lit = 2 * blocking < valid;
    if blocking > 0 && d.cascades_bound_ray_interval {
        // The ray starts at the receiver: blockers nearer than the offset or between taps are invisible here.
        let along = (z - nearest_light + units[3]) / units[0];
        let max_t = (along * along + radius * radius).sqrt();
        return (Verdict::Trace { guess_lit, max_t }, fragile);
    }
    (Verdict::Trace { guess_lit, max_t: f64::INFINITY }, fragile)
}

/// Runs the classifier over every tile.
pub fn classify(inp: &ClassifyInputs) -> Result<ClassifyOutput> {
    let d = inp.dispatch;
    let c = constants(d)?;
    let (tw, th) = (inp.width.div_ceil(8), inp.height.div_ceil(4));
    let mut out = ClassifyOutput {
        hit_mask: vec![0; (tw * th) as usize],
        tiles: Vec::new(),
        fragile: vec![false; (inp.width * inp.height) as usize],
        verdicts: vec![Verdict::Lit; (inp.width * inp.height) as usize],
    };
    for ty in 0..th {
        for tx in 0..tw {
            let (mut inside, mut lit, mut trace, mut guess) = (0u32, 0u32, 0u32, 0u32);
            let mut max_t = 0.0f64;
            for y in ty * 4..(ty * 4 + 4).min(inp.height) {
                for x in tx * 8..(tx * 8 + 8).min(inp.width) {
                    let bit = 1u32 << ((y % 4) * 8 + x % 8);
                    let (v, fragile) = classify_pixel(inp, &c, x, y);
                    let i = (y * inp.width + x) as usize;
                    out.fragile[i] = fragile;
                    out.verdicts[i] = v;
                    inside |= bit;
                    match v {
                        Verdict::Lit => lit |= bit,
                        Verdict::Shadowed => {}
                        Verdict::Trace { guess_lit, max_t: b } => {
                            trace |= bit;
                            if guess_lit {
                                guess |= bit;
                            }
                            max_t = max_t.max(b);
                        }
                    }
                }
            }
            let listed = trace.count_ones() > d.tile_cutoff;
            let lit = lit | if listed { 0 } else { guess };
            let traced = if listed { trace } else { 0 };
            out.hit_mask[(ty * tw + tx) as usize] = match d.hit_mask_convention {
                HitMaskConvention::LitBits => lit,
                HitMaskConvention::OccludedBits => inside & !lit & !traced,
            };
            if listed {
                out.tiles.push((tx | (ty << 16), trace, 0.0, max_t));
            }
        }
    }
    Ok(out)
}

/// An orthographic cascade looking along `-to_light` (for tests and examples): centred on `centre`, `extent`
/// world units across, depth 0 at `near_distance` toward the light from the centre and 1 at `depth_range` beyond.
pub fn orthographic_cascade(to_light: DVec3, centre: DVec3, extent: f64, near_distance: f64, depth_range: f64) -> DMat4 {
    let forward = -to_light.normalize();
    let helper = if forward.y.abs() > 0.9 { DVec3::X } else { DVec3::Y };
    let right = forward.cross(helper).normalize();
    let up = right.cross(forward);
    let origin = centre - forward * near_distance;
    // Rows: u, v, depth, (0, 0, 0, 1); uv (0, 0) at the top-left corner of the map.
    let row = |axis: DVec3, scale: f64, offset: f64| DVec4::new(axis.x * scale, axis.y * scale, axis.z * scale, offset - axis.dot(origin) * scale);
    DMat4::from_cols(
        row(right, 1.0 / extent, 0.5),
        row(-up, 1.0 / extent, 0.5),
        row(forward, 1.0 / depth_range, 0.0),
        DVec4::W,
    )
    .transpose()
}
