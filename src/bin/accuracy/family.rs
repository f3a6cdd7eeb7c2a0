//! Seeded families of truth-known sequences, reported as distributions rather than one sequence each: hard edges
//! and 1-3 px lines of random orientation on penumbrae of random width (half of them with sky beside the plane,
//! half under a camera panning 0.3-2.7 px per frame, so that the history falls between pixel centres as a real
//! camera's does); occluders moving 0.5-8 px per frame without motion vectors, each measured against its own
//! static twin (the same field held still); boxes standing on the plane under a camera moving back and forth, which
//! uncovers strips of ground beside them every frame (disocclusion); and thin two-sided shells whose plane the
//! camera crosses, so that the side it sees flips from lit to shadowed or back at the same depth.

use dnsr::testing::fields::{band, smoothstep, soft_box};
use dnsr::testing::images::{mask_to_image, rmse};
use dnsr::testing::scene::{Camera, FrameInputs, Ground, Quad, render_scene};
use glam::DVec3;

use super::{FRAMES, H, PX, W, WARMUP};

/// The families, in the order the report lists them.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Kind {
    Lines,
    Disocclusion,
    Shells,
    Moving,
}

impl Kind {
    pub const ALL: [Kind; 4] = [Kind::Lines, Kind::Disocclusion, Kind::Shells, Kind::Moving];

    pub fn name(self) -> &'static str {
        match self {
            Kind::Lines => "lines",
            Kind::Disocclusion => "disocclusion",
            Kind::Shells => "shells",
            Kind::Moving => "moving",
        }
    }
}

/// The visibility of one side of a quad at (s, t).
type SideField = Box<dyn Fn(f64, f64) -> f64>;

/// A quad standing on or above the plane, its two sides' fields owned.
struct Solid {
    corner: DVec3,
    edges: [DVec3; 2],
    sides: [SideField; 2],
}

/// One member of a family: its ground field over time, the quads above the ground, its camera's path, where the
/// plane ends (sky beyond).
pub struct Member {
    pub name: String,
    pub kind: Kind,
    field: Box<dyn Fn(u32, f64, f64) -> f64>,
    solids: Vec<Solid>,
    /// Camera position (x, z) at frame t, world units.
    camera: Box<dyn Fn(u32) -> (f64, f64)>,
    plane_half_width: f64,
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
        .map(|_| {
            (
                r.range(-5.0, 5.0),
                r.range(-3.0, 3.0),
                r.range(0.0, std::f64::consts::PI),
                (1.0 + r.range(0.0, 2.99)).floor() * PX,
                r.range(2.0, 4.0),
            )
        })
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
    let edge = move |x: f64, z: f64| {
        if (x - ex) * ea.cos() + (z - ez) * ea.sin() > 2.0 { 1.0 } else { 0.0 }
    };
    let panning = r.next() < 0.5;
    let plane_half_width = if r.next() < 0.5 { 5.0 } else { 1e9 };
    // Whole-pixel pans keep the history on texel centres, where a moving camera's footprint never splits.
    let pan_px = if panning { r.range(0.3, 2.7) } else { 0.0 };
    Member {
        name: format!("lines {seed}"),
        kind: Kind::Lines,
        field: Box::new(move |_, x, z| 1.0 - soft(x, z).max(line(x, z)).max(edge(x, z))),
        solids: Vec::new(),
        camera: Box::new(move |t| (t as f64 * pan_px * PX, 0.0)),
        plane_half_width,
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
        kind: Kind::Moving,
        field: Box::new(move |t, x, z| {
            discs.iter().fold(1.0f64, |v, &(cx, cz, radius, width, speed, dir)| {
                let s = back_and_forth(speed, 30.0 * PX, t);
                let (px, pz) = (cx + s * dir.cos(), cz + s * dir.sin());
                let d = ((x - px).powi(2) + (z - pz).powi(2)).sqrt();
                v.min(smoothstep(radius - width / 2.0, radius + width / 2.0, d))
            })
        }),
        solids: Vec::new(),
        camera: Box::new(|_| (0.0, 0.0)),
        plane_half_width: 1e9,
    }
}

/// A triangle wave of `span` amplitude around 0 at `speed` per frame: constant speed but for the turns.
fn back_and_forth(speed: f64, span: f64, t: u32) -> f64 {
    let phase = (speed * t as f64).rem_euclid(2.0 * span);
    (if phase < span { phase } else { 2.0 * span - phase }) - span / 2.0
}

/// 1-3 boxes 1.5-4 units tall standing on the plane, lit from -x: the top and the faces towards -x and along z lit,
/// the face towards +x shadowed, and a soft shadow 0.2-1.5 units wide on the ground towards +x. The camera moves
/// back and forth 0.5-3 px per frame in a random direction, so the boxes' parallax uncovers ground every frame.
fn disocclusion_member(seed: u64) -> Member {
    let mut r = Rng(seed ^ 0x4449_534F);
    let mut solids = Vec::new();
    let mut shadows = Vec::new();
    for _ in 0..r.range(1.0, 3.99) as usize {
        let (x0, z0, w, d, h) =
            (r.range(-5.0, 3.0), r.range(-3.5, 1.5), r.range(1.0, 2.5), r.range(1.0, 2.0), r.range(1.5, 4.0));
        let (reach, width) = (h * r.range(0.3, 1.0), r.range(0.2, 1.5));
        shadows.push((x0, z0, w, d, reach, width));
        let c = |x: f64, y: f64, z: f64| DVec3::new(x0 + x * w, y * h, z0 + z * d);
        let lit: fn(f64, f64) -> f64 = |_, _| 1.0;
        let dark: fn(f64, f64) -> f64 = |_, _| 0.0;
        // Each face's front points out of the box (its inside is never seen).
        let face = |corner: DVec3, a: DVec3, b: DVec3, outside: fn(f64, f64) -> f64| Solid {
            corner,
            edges: [a, b],
            sides: [Box::new(outside), Box::new(dark)],
        };
        let (ex, ey, ez) = (DVec3::X * w, DVec3::Y * h, DVec3::Z * d);
        solids.push(face(c(0.0, 1.0, 0.0), ez, ex, lit));
        solids.push(face(c(0.0, 0.0, 0.0), ez, ey, lit));
        solids.push(face(c(1.0, 0.0, 0.0), ey, ez, dark));
        solids.push(face(c(0.0, 0.0, 0.0), ey, ex, lit));
        solids.push(face(c(0.0, 0.0, 1.0), ex, ey, lit));
    }
    let (speed, dir) = (r.range(0.5, 3.0) * PX, r.range(0.0, 2.0 * std::f64::consts::PI));
    Member {
        name: format!("disocclusion {seed}"),
        kind: Kind::Disocclusion,
        field: Box::new(move |_, x, z| {
            1.0 - shadows.iter().fold(0.0f64, |a, &(x0, z0, w, d, reach, width)| {
                a.max(soft_box(x, z, [x0, x0 + w + reach], [z0, z0 + d], width))
            })
        }),
        solids,
        camera: Box::new(move |t| {
            let s = back_and_forth(speed, 40.0 * PX, t);
            (s * dir.cos(), s * dir.sin())
        }),
        plane_half_width: 1e9,
    }
}

/// 1-2 thin two-sided shells standing on the plane, tilted 8-30 degrees from vertical, one side lit (with a soft
/// band across it) and the other shadowed, and the camera panning 0.5-2.5 px per frame across each shell's plane
/// between frames 20 and 36: the side it sees flips at the same depth. Half of them go dark to lit.
fn shell_member(seed: u64) -> Member {
    let mut r = Rng(seed ^ 0x5348_454C);
    let (speed, cross) = (r.range(0.5, 2.5) * PX * if r.next() < 0.5 { 1.0 } else { -1.0 }, r.range(20.0, 36.0));
    let mut solids = Vec::new();
    let mut shadows = Vec::new();
    let shells = r.range(1.0, 2.99) as usize;
    let (mut first_x, mut crossing_x) = (0.0, 0.0);
    for i in 0..shells {
        let (tilt, height, length) = (r.range(8.0, 30.0).to_radians(), r.range(1.5, 3.0), r.range(2.0, 5.0));
        let (z0, band_at, band_width) = (r.range(-3.5, 0.5), r.range(0.2, 0.8), r.range(0.05, 0.5));
        // The camera (height 10) crosses the plane of the first shell, normal (cos, sin, 0), at frame `cross`;
        // the others stand within 3 units of it.
        let x0 = if i == 0 { r.range(-2.0, 2.0) } else { first_x + r.range(-3.0, 3.0) };
        if i == 0 {
            first_x = x0;
            crossing_x = x0 - tilt.tan() * 10.0;
        }
        let up = DVec3::new(-tilt.sin(), tilt.cos(), 0.0) * height;
        let lit = move |_: f64, t: f64| {
            1.0 - 0.8 * band(t, [band_at - band_width / 2.0, band_at + band_width / 2.0], band_width)
        };
        let dark = |_: f64, _: f64| 0.0;
        let sides: [SideField; 2] =
            if r.next() < 0.5 { [Box::new(lit), Box::new(dark)] } else { [Box::new(dark), Box::new(lit)] };
        solids.push(Solid { corner: DVec3::new(x0, 0.0, z0), edges: [up, DVec3::Z * length], sides });
        shadows.push((x0, z0, length, r.range(0.5, 2.0), r.range(0.2, 1.5)));
    }
    Member {
        name: format!("shells {seed}"),
        kind: Kind::Shells,
        field: Box::new(move |_, x, z| {
            1.0 - shadows.iter().fold(0.0f64, |a, &(x0, z0, length, reach, width)| {
                a.max(soft_box(x, z, [x0, x0 + reach], [z0, z0 + length], width))
            })
        }),
        solids,
        camera: Box::new(move |t| (crossing_x + (t as f64 - cross) * speed, 0.0)),
        plane_half_width: 1e9,
    }
}

/// `count` members of each kind from `first_seed` on.
pub fn members(first_seed: u64, count: u64) -> Vec<Member> {
    (first_seed..first_seed + count)
        .flat_map(|s| [lines_member(s), disocclusion_member(s), shell_member(s), moving_member(s)])
        .collect()
}

impl Member {
    /// Moving members have a static twin: the field held at frame 0, which the motion target compares with.
    pub fn moving(&self) -> bool {
        self.kind == Kind::Moving
    }

    /// Frame t; `still` holds the field at frame 0 (the static twin).
    pub fn frame(&self, t: u32, still: bool) -> FrameInputs {
        let camera = |t: u32| {
            let (x, z) = (self.camera)(t);
            Camera::above(x, z, 10.0)
        };
        let ft = if still { 0 } else { t };
        let seed = 0xFA11_0000 + t as u64 * 7919;
        let field = |x: f64, z: f64| (self.field)(ft, x, z);
        let ground = Ground { half_width: self.plane_half_width, visibility: &field, blocker: &|_, _| 0.0 };
        let quads: Vec<Quad> = self
            .solids
            .iter()
            .map(|s| Quad { corner: s.corner, edges: s.edges, sides: [&*s.sides[0], &*s.sides[1]] })
            .collect();
        render_scene(W, H, &camera(t), &camera(t.saturating_sub(1)), &ground, &quads, seed)
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
