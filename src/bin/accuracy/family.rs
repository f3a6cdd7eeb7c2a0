//! Seeded families of truth-known sequences, reported as distributions rather than one sequence each: hard edges
//! and 1-3 px lines of random orientation on penumbrae of random width (half of them with sky beside the plane,
//! half under a camera panning 0.3-2.7 px per frame, so that the history falls between pixel centres as a real
//! camera's does), and occluders moving 0.5-8 px per frame without motion vectors, each measured against its own
//! static twin (the same field held still).

use dnsr::testing::fields::{band, smoothstep, soft_box};
use dnsr::testing::images::{mask_to_image, rmse};
use dnsr::testing::scene::{render, Camera, FrameInputs};

use super::{FRAMES, H, PX, W, WARMUP};

/// One member of a family: its field over time, its camera, where the plane ends (sky beyond).
pub struct Member {
    pub name: String,
    field: Box<dyn Fn(u32, f64, f64) -> f64>,
    /// Camera pan in pixels per frame (0: still).
    pan_px: f64,
    plane_half_width: f64,
    /// Moving members: the field held at frame 0 (the static twin the motion target compares with).
    pub moving: bool,
}

/// A small deterministic generator (splitmix64), so that the family does not depend on a crate's algorithm.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
}

/// Hard edges and thin lines on a penumbra.
fn lines_member(seed: u64) -> Member {
    let mut r = Rng(seed);
    let (bx, bz, width) = (r.range(-4.0, 2.0), r.range(-3.0, 1.0), r.range(0.2, 3.0));
    let soft = move |x: f64, z: f64| soft_box(x, z, [bx, bx + 3.0], [bz, bz + 2.5], width);
    // Lines 1-3 px wide at random angles through random points, 4-8 units long.
    let lines: Vec<(f64, f64, f64, f64, f64)> = (0..r.range(2.0, 5.0) as usize)
        .map(|_| (r.range(-5.0, 5.0), r.range(-3.0, 3.0), r.range(0.0, std::f64::consts::PI), (1.0 + r.range(0.0, 2.99)).floor() * PX, r.range(2.0, 4.0)))
        .collect();
    let line = move |x: f64, z: f64| {
        lines.iter().fold(0.0f64, |a, &(cx, cz, angle, w, half)| {
            let (dx, dz) = (x - cx, z - cz);
            let (along, across) = (dx * angle.cos() + dz * angle.sin(), -dx * angle.sin() + dz * angle.cos());
            a.max(band(across, [-w / 2.0, w / 2.0], 0.0) * band(along, [-half, half], 0.0))
        })
    };
    // A hard edge: a half-plane at a random angle, as a contact shadow.
    let (ex, ez, ea) = (r.range(-3.0, 3.0), r.range(-2.0, 2.0), r.range(0.0, 2.0 * std::f64::consts::PI));
    let edge = move |x: f64, z: f64| if (x - ex) * ea.cos() + (z - ez) * ea.sin() > 2.0 { 1.0 } else { 0.0 };
    let panning = r.next() < 0.5;
    let plane_half_width = if r.next() < 0.5 { 5.0 } else { 1e9 };
    // Whole-pixel pans keep the history on texel centres, where a moving camera's footprint never splits.
    let pan_px = if panning { r.range(0.3, 2.7) } else { 0.0 };
    Member {
        name: format!("lines {seed}"),
        field: Box::new(move |_, x, z| 1.0 - soft(x, z).max(line(x, z)).max(edge(x, z))),
        pan_px,
        plane_half_width,
        moving: false,
    }
}

/// Discs moving 0.5-8 px per frame (back and forth, so that they stay in view) without motion vectors.
fn moving_member(seed: u64) -> Member {
    let mut r = Rng(seed ^ 0x4D4F_5645);
    let discs: Vec<(f64, f64, f64, f64, f64, f64)> = (0..r.range(1.0, 3.99) as usize)
        .map(|_| {
            // Speed log-uniform in 0.5..8 px per frame, in a random direction.
            let speed = 0.5 * 16f64.powf(r.next()) * PX;
            let dir = r.range(0.0, 2.0 * std::f64::consts::PI);
            (r.range(-3.0, 3.0), r.range(-1.5, 1.5), r.range(0.6, 1.5), r.range(0.1, 1.5), speed, dir)
        })
        .collect();
    Member {
        name: format!("moving {seed}"),
        field: Box::new(move |t, x, z| {
            discs.iter().fold(1.0f64, |v, &(cx, cz, radius, width, speed, dir)| {
                // A triangle wave of 30 px amplitude: constant speed but for the turns.
                let travel = speed * t as f64;
                let span = 30.0 * PX;
                let phase = travel.rem_euclid(2.0 * span);
                let s = if phase < span { phase } else { 2.0 * span - phase } - span / 2.0;
                let (px, pz) = (cx + s * dir.cos(), cz + s * dir.sin());
                let d = ((x - px).powi(2) + (z - pz).powi(2)).sqrt();
                v.min(smoothstep(radius - width / 2.0, radius + width / 2.0, d))
            })
        }),
        pan_px: 0.0,
        plane_half_width: 1e9,
        moving: true,
    }
}

/// `count` members of each kind from `first_seed` on.
pub fn members(first_seed: u64, count: u64) -> Vec<Member> {
    (first_seed..first_seed + count).flat_map(|s| [lines_member(s), moving_member(s)]).collect()
}

impl Member {
    /// Frame t; `still` holds the field at frame 0 (the static twin).
    pub fn frame(&self, t: u32, still: bool) -> FrameInputs {
        let camera = |t: u32| Camera::above(t as f64 * self.pan_px * PX, 0.0, 10.0);
        let ft = if still { 0 } else { t };
        let seed = 0xFA11_0000 + t as u64 * 7919;
        render(W, H, &camera(t), &camera(t.saturating_sub(1)), self.plane_half_width, &|x, z| (self.field)(ft, x, z), seed)
    }

    /// The 1-spp input's RMSE over the frames the harness measures.
    pub fn input_rmse(&self, still: bool) -> f64 {
        let sq: f64 = (WARMUP..FRAMES)
            .map(|t| {
                let f = self.frame(t, still);
                rmse(&mask_to_image(&f), &f.truth, &f.receiver).powi(2)
            })
            .sum();
        (sq / (FRAMES - WARMUP) as f64).sqrt()
    }
}

/// Median, 90th percentile and worst of a list (NaN for none).
pub fn quantiles(mut v: Vec<f64>) -> (f64, f64, f64) {
    if v.is_empty() {
        return (f64::NAN, f64::NAN, f64::NAN);
    }
    v.sort_by(|a, b| a.total_cmp(b));
    let at = |q: f64| v[((q * v.len() as f64) as usize).min(v.len() - 1)];
    (at(0.5), at(0.9), v[v.len() - 1])
}
