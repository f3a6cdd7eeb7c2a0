//! tile classification (shaders/tile_classification.glsl): uniform-tile skip, reprojection, disocclusion,
//! temporal moments and the history blend, pixel by pixel in f64.

use super::{inside, SKY_SIGNAL, is_receiver, linear_depth, pixel_uv, tile_bit, uv_to_ndc, world_position, Coord, Read, Write, TILE};
use crate::passes::{RUN_CLAMP_SAMPLES, TILE_CLEARED, TILE_LIT};
use crate::settings::MAX_SAMPLE_RUN;
use glam::{DVec2, DVec3, DVec4, IVec3};

/// Radius of the local-moment window (17x17).
pub const MOMENT_RADIUS: i32 = crate::passes::MOMENT_RADIUS as i32;

fn tile_count<Io: Read + ?Sized>(io: &Io) -> Coord {
    let e = io.extent();
    [(e[0] + TILE[0] - 1) / TILE[0], (e[1] + TILE[1] - 1) / TILE[1]]
}

/// Bits of a tile whose pixels lie inside the render rectangle (0 outside the tile grid).
pub fn tile_valid_bits<Io: Read + ?Sized>(io: &Io, tile: Coord) -> u32 {
    let t = tile_count(io);
    if tile[0] < 0 || tile[1] < 0 || tile[0] >= t[0] || tile[1] >= t[1] {
        return 0;
    }
    let e = io.extent();
    let n = [(e[0] - tile[0] * TILE[0]).min(8), (e[1] - tile[1] * TILE[1]).min(4)];
    let row = if n[0] >= 8 { 0xFF } else { (1u32 << n[0]) - 1 };
    (0..n[1]).fold(0, |bits, r| bits | (row << (8 * r)))
}

/// The pixel's sample this frame: its lit bit, or its visibility in [0, 1] with a visibility input.
fn sample<Io: Read + ?Sized>(io: &Io, p: Coord) -> f64 {
    if io.visibility_input() {
        return super::sanitize_visibility(io.read_visibility(p));
    }
    let word = io.read_tile_mask([p[0].div_euclid(8), p[1].div_euclid(4)]);
    ((word >> tile_bit(p)) & 1) as f64
}

/// The normal of the plane that receiver q (device depth `depth`) lies inside, on the side of its G-buffer normal
/// `shading` (`dnsr_plane_normal`): its neighbours on either side along each axis are receivers on one line through
/// it (`state::PLANE_LINE_COS2_PERCENT`); zero elsewhere (an edge, a crease, a feature of 1-2 px).
fn plane_normal<Io: Read + ?Sized>(io: &Io, q: Coord, depth: f64, shading: DVec3) -> DVec3 {
    let w = world_position(io, q, depth);
    let mut tangent = [DVec3::ZERO; 2];
    for (a, t) in tangent.iter_mut().enumerate() {
        let axis = [1 - a as i32, a as i32];
        let (r0, r1) = ([q[0] - axis[0], q[1] - axis[1]], [q[0] + axis[0], q[1] + axis[1]]);
        if !inside(io, r0) || !inside(io, r1) {
            return DVec3::ZERO;
        }
        let (d0, d1) = (io.read_depth(r0), io.read_depth(r1));
        if !is_receiver(d0) || !is_receiver(d1) {
            return DVec3::ZERO;
        }
        let (back, ahead) = (w - world_position(io, r0, d0), world_position(io, r1, d1) - w);
        let c = back.dot(ahead);
        let min_cos2 = crate::state::PLANE_LINE_COS2_PERCENT as f64 / 100.0;
        if !(c > 0.0) || c * c < min_cos2 * back.length_squared() * ahead.length_squared() {
            return DVec3::ZERO;
        }
        *t = back + ahead;
    }
    let n = tangent[0].cross(tangent[1]);
    let l = n.length_squared();
    if !(l > 0.0) || l.is_infinite() {
        return DVec3::ZERO;
    }
    let n = n / l.sqrt();
    if n.dot(shading) < 0.0 { -n } else { n }
}

/// Receiver p, whose G-buffer normal `shading` faces away from the light at `to_light`, lies inside a plane that
/// faces it (`dnsr_plane_faces_light`): a normal map tilted its normal past the light.
fn plane_faces_light<Io: Read + ?Sized>(io: &Io, p: Coord, depth: f64, shading: DVec3, to_light: DVec3) -> bool {
    plane_normal(io, p, depth, shading).dot(to_light) > 0.0
}

/// The vector from world point `world` to the light at homogeneous position `light`
/// (`ShadowsDispatch::light_position`).
fn to_light(light: DVec4, world: DVec3) -> DVec3 {
    light.truncate() - light.w * world
}

/// Normal `n` faces away from every point of the light's disc seen along `to_light` (`dnsr_faces_away_from_disc`).
fn faces_away_from_disc<Io: Read + ?Sized>(io: &Io, n: DVec3, to_light: DVec3) -> bool {
    n.dot(to_light) < -io.light_sin_radius() * to_light.length()
}

/// What a group of `passes::WIDE_GROUP` pixels' lit samples tell of the host's rays this frame: whether they test
/// the G-buffer's normals. Only with the run features and a light position (`DNSR_SPEC_STABLE_HISTORY`); an untraced
/// pixel of a checkerboard input has no sample.
#[derive(Clone, Copy, Debug, Default)]
pub struct GroupEvidence {
    /// A receiver whose G-buffer normal faces away from the light, inside a plane that faces it, has a lit sample
    /// (`s_lit_against_normal`): a shadowed sample of such a receiver is not exact.
    pub lit_against_normal: bool,
    /// A receiver whose G-buffer normal faces away from the whole light has a lit sample (`s_lit_away_from_disc`):
    /// no shadowed sample of the group is final.
    pub lit_away_from_disc: bool,
}

/// Every group's `GroupEvidence`, row by row (`group_index`).
fn group_evidence<Io: Read + ?Sized>(io: &Io) -> Vec<GroupEvidence> {
    let e = io.extent();
    let mut found = vec![GroupEvidence::default(); group_index(e, [e[0] - 1, e[1] - 1]) + 1];
    let Some(light) = io.light_position().filter(|_| io.settings().uses_runs()) else { return found };
    for y in 0..e[1] {
        for x in 0..e[0] {
            let p = [x, y];
            let depth = io.read_depth(p);
            if !is_receiver(depth) || sample(io, p) != 1.0 || !io.is_traced(p) {
                continue;
            }
            let l = to_light(light, world_position(io, p, depth));
            let shading = io.read_normal(p);
            let group = &mut found[group_index(e, p)];
            group.lit_against_normal |= shading.dot(l) < 0.0 && plane_faces_light(io, p, depth, shading, l);
            group.lit_away_from_disc |= faces_away_from_disc(io, shading, l);
        }
    }
    found
}

/// The index of pixel p's group of `passes::WIDE_GROUP` pixels (row by row) in an image of extent `e`.
fn group_index(e: Coord, p: Coord) -> usize {
    let g = crate::passes::WIDE_GROUP.map(|v| v as i32);
    ((p[1] / g[1]) * ((e[0] + g[0] - 1) / g[0]) + p[0] / g[0]) as usize
}

/// A sample that is exactly lit or exactly shadowed: only those extend runs of identical samples (always so for
/// a hit mask; with visibility, a pixel whose rays disagreed this frame lies in a penumbra).
pub fn is_exact(x: f64) -> bool {
    x == 0.0 || x == 1.0
}

/// The bits of a tile whose sample is exactly 1 (`lit` true) or exactly 0: the tile mask and its complement, or
/// with a visibility input the two words prepare wrote.
fn exact_word<Io: Read + ?Sized>(io: &Io, tile: Coord, lit: bool) -> u32 {
    match (lit, io.visibility_input()) {
        (true, _) => io.read_tile_mask(tile),
        (false, false) => !io.read_tile_mask(tile),
        (false, true) => io.read_tile_dark(tile),
    }
}

fn moment_weight<Io: Read + ?Sized>(io: &Io, i: i32) -> f64 {
    (-(io.settings().spatial_falloff as f64) * (i * i) as f64 / 81.0).exp()
}

/// Spatial mean and variance of the samples in the 17x17 Gaussian window (taps inside the rectangle only). For
/// a binary mask the variance is mean - mean^2; visibilities need the weighted mean of their squares.
pub fn local_moments<Io: Read + ?Sized>(io: &Io, p: Coord) -> DVec2 {
    let mut sum = glam::DVec3::ZERO;
    for j in -MOMENT_RADIUS..=MOMENT_RADIUS {
        let mut row = glam::DVec3::ZERO;
        for i in -MOMENT_RADIUS..=MOMENT_RADIUS {
            let q = [p[0] + i, p[1] + j];
            if inside(io, q) {
                let v = sample(io, q);
                row += moment_weight(io, i) * glam::DVec3::new(v, v * v, 1.0);
            }
        }
        sum += moment_weight(io, j) * row;
    }
    let mean = sum.x / sum.z.max(1e-20);
    let square = if io.visibility_input() { sum.y / sum.z.max(1e-20) } else { mean };
    DVec2::new(mean, (square - mean * mean).max(0.0))
}

/// Normal codes a and b (`window_normal`) of one surface: within acos(`state::TURNED_NORMAL_COS_PERCENT` / 100)
/// of each other, as the GPU's exact integer test (`dnsr_same_surface`).
fn same_surface(a: IVec3, b: IVec3) -> bool {
    a.dot(b) >= crate::passes::SURFACE_DOT_MIN as i32
}

/// A pixel's normal in the surface window, quantized as classification keeps it in shared memory (three integers
/// of scale `passes::SURFACE_NORMAL_SCALE`): zero for sky and outside the rectangle.
fn window_normal<Io: Read + ?Sized>(io: &Io, q: Coord) -> IVec3 {
    if !inside(io, q) || !is_receiver(io.read_depth(q)) {
        return IVec3::ZERO;
    }
    (io.read_normal(q) * crate::passes::SURFACE_NORMAL_SCALE as f64 + 0.5).floor().as_ivec3()
}

/// Adjacent pixels a and b on one surface: both known and their codes `same_surface`.
fn joined<Io: Read + ?Sized>(io: &Io, a: Coord, b: Coord) -> bool {
    same_surface(window_normal(io, a), window_normal(io, b))
}

/// How far a chain of adjacent pixels on one surface reaches from p in direction d, at most `MOMENT_RADIUS`.
fn reach<Io: Read + ?Sized>(io: &Io, p: Coord, d: Coord) -> i32 {
    let at = |k: i32| [p[0] + k * d[0], p[1] + k * d[1]];
    (0..MOMENT_RADIUS).take_while(|&k| joined(io, at(k), at(k + 1))).count() as i32
}

/// Spatial mean and variance of the binary mask over p's own surface (`DNSR_SURFACE_WINDOW`): the taps that a
/// chain of adjacent pixels on one surface joins to p, separably as the GPU computes it: up and down p's column,
/// then along each row from its pixel in p's column (shaders/tile_classification.glsl,
/// `dnsr_window_and_surface_moments`, says why). `window` (the whole window's moments) where p's own normal is
/// unknown.
pub fn surface_moments<Io: Read + ?Sized>(io: &Io, p: Coord, window: DVec2) -> DVec2 {
    if window_normal(io, p) == IVec3::ZERO {
        return window;
    }
    // Each row's sums are kept as 16-bit fixed-point numbers (`passes::SURFACE_SUM_SCALE`).
    let fixed = |v: f64| {
        let scale = crate::passes::SURFACE_SUM_SCALE as f64;
        (v * scale + 0.5).floor() / scale
    };
    let (mut lit, mut weight) = (0.0, 0.0);
    for j in -reach(io, p, [0, -1])..=reach(io, p, [0, 1]) {
        let centre = [p[0], p[1] + j];
        let (mut row_lit, mut row_weight) = (0.0, 0.0);
        for i in -reach(io, centre, [-1, 0])..=reach(io, centre, [1, 0]) {
            row_lit += moment_weight(io, i) * sample(io, [p[0] + i, p[1] + j]);
            row_weight += moment_weight(io, i);
        }
        lit += moment_weight(io, j) * fixed(row_lit);
        weight += moment_weight(io, j) * fixed(row_weight);
    }
    let mean = lit / weight;
    DVec2::new(mean, (mean - mean * mean).max(0.0))
}

/// 0: mixed; 1: every valid pixel within +-8 px of the tile is exactly lit; 2: every one is exactly shadowed.
pub fn uniform_state<Io: Read + ?Sized>(io: &Io, tile: Coord) -> u32 {
    let (mut all_lit, mut all_shadow) = (true, true);
    for dy in -2..=2 {
        for dx in -1..=1 {
            let t = [tile[0] + dx, tile[1] + dy];
            let valid = tile_valid_bits(io, t);
            if valid == 0 {
                continue;
            }
            all_lit &= exact_word(io, t, true) & valid == valid;
            all_shadow &= exact_word(io, t, false) & valid == valid;
        }
    }
    if all_lit { 1 } else if all_shadow { 2 } else { 0 }
}

fn has_receiver<Io: Read + ?Sized>(io: &Io, tile: Coord) -> bool {
    (0..TILE[1]).any(|y| {
        (0..TILE[0]).any(|x| {
            let p = [tile[0] * TILE[0] + x, tile[1] * TILE[1] + y];
            inside(io, p) && is_receiver(io.read_depth(p))
        })
    })
}

/// Velocity of the closest receiver in the pixel's 2x2 quad (ties keep the pixel itself, then scan order).
fn quad_velocity<Io: Read + ?Sized>(io: &Io, p: Coord) -> DVec2 {
    let key = |q: Coord| {
        if !inside(io, q) {
            return 1e30;
        }
        let d = io.read_depth(q);
        if !is_receiver(d) {
            1e30
        } else if io.is_depth_inverted() {
            -d
        } else {
            d
        }
    };
    let q0 = [p[0] & !1, p[1] & !1];
    let mut best = p;
    for j in 0..2 {
        for i in 0..2 {
            let q = [q0[0] + i, q0[1] + j];
            if key(q) < key(best) {
                best = q;
            }
        }
    }
    io.read_velocity(best)
}

fn finite(v: DVec2) -> bool {
    v.x.is_finite() && v.y.is_finite()
}

/// Scales a Welford state (mean kept) to represent `f` times as many samples.
fn scale_moments(m: &mut DVec4, f: f64) {
    m.y *= f;
    m.z *= f;
}

/// The run of identical samples after sample `x`, from the run before it: +n when the last n samples were lit,
/// -n when they were shadowed, at most `MAX_SAMPLE_RUN` long. A run that breaks a stable run (at least
/// `stable_after` samples, when that is positive) of the other value carries a half, n + 0.5.
pub fn sample_run(previous: f64, x: f64, stable_after: f64) -> f64 {
    let lit = x >= 0.5;
    if (lit && previous > 0.0) || (!lit && previous < 0.0) {
        let n = (previous.abs() + 1.0).min(MAX_SAMPLE_RUN as f64);
        return if lit { n } else { -n };
    }
    let start = if stable_after > 0.0 && previous.abs() >= stable_after { 1.5 } else { 1.0 };
    if lit { start } else { -start }
}

/// The run after a sample that is not exact (a pixel whose rays disagreed): no run of identical samples, but a
/// stable run it interrupts is broken (a marker of half a sample of the other value), and a break already under
/// way stays one, so that the first exact sample of the other value after a penumbra passed restarts the history
/// as it does after a single ray.
pub fn fractional_run(previous: f64, stable_after: f64) -> f64 {
    let n = previous.abs();
    if stable_after > 0.0 && n >= stable_after {
        return if previous > 0.0 { -0.5 } else { 0.5 };
    }
    if n.fract() == 0.5 {
        return if previous > 0.0 { 0.5 } else { -0.5 };
    }
    0.0
}

/// A run of at least `converged_after` (> 0) identical samples that sample `x` does not contradict (on the run's
/// side of 0.5; shaders/tile_classification.glsl says why not equal).
pub fn converged(run: f64, x: f64, converged_after: f64) -> bool {
    converged_after > 0.0 && run.abs() >= converged_after && (x - run_value(run)).abs() < 0.5
}

/// The value a run of identical samples holds: 1 (lit) for a positive run, 0 otherwise.
fn run_value(run: f64) -> f64 {
    if run > 0.0 { 1.0 } else { 0.0 }
}

/// How much of its linear depth a footprint texel of this surface may differ by per pixel of distance from the
/// history position, beyond the disocclusion test's threshold: `state::FOOTPRINT_SLOPE_PERCENT` of a plane's change
/// at the surface's angle to the view (its tan, at most `state::FOOTPRINT_MAX_SLOPE`; `dnsr_texel_depth_slope`).
fn texel_depth_slope<Io: Read + ?Sized>(io: &Io, depth: f64, n_dot_v: f64) -> f64 {
    let tan_angle = ((1.0 - n_dot_v * n_dot_v).max(0.0).sqrt() / n_dot_v.max(1e-3)).min(crate::state::FOOTPRINT_MAX_SLOPE as f64);
    let pixel = super::Penumbra::new(0.0, io.projection_inverse(), io.extent()[1]).footprint(depth);
    crate::state::FOOTPRINT_SLOPE_PERCENT as f64 / 100.0 * pixel * tan_angle
}

/// Normals `a` and `b` (last frame's, this frame's) both known and further apart than
/// `state::TURNED_NORMAL_COS_PERCENT` allows (`dnsr_normal_turned`).
fn normal_turned(a: DVec3, b: DVec3) -> bool {
    a.dot(a) > 0.0 && b.dot(b) > 0.0 && a.dot(b) < crate::state::TURNED_NORMAL_COS_PERCENT as f64 / 100.0
}

/// A run whose value is exact sample `x`'s (any length).
fn sign_agreeing(run: f64, x: f64) -> bool {
    is_exact(x) && if x >= 0.5 { run > 0.0 } else { run < 0.0 }
}

/// Moments whose every sample had one value: the run covers the whole count (and is no break marker), and the
/// mean is exactly the run's value or the run is at least twice the count (shaders/tile_classification.glsl says
/// why the run alone does not tell).
fn pure_moments(mq: DVec4) -> bool {
    mq.z > 0.0 && mq.w.abs() >= mq.z && mq.w.abs().fract() == 0.0 && (mq.x == run_value(mq.w) || mq.w.abs() >= 2.0 * mq.z)
}

/// Whether two or more of the 8 pixels around p inside the rectangle hold exactly sample `x` this frame (sky pixels
/// count by their mask bit: the test reads the samples alone).
fn two_neighbours_share<Io: Read + ?Sized>(io: &Io, p: Coord, x: f64) -> bool {
    let shares = |i: i32, j: i32| (i, j) != (0, 0) && inside(io, [p[0] + i, p[1] + j]) && sample(io, [p[0] + i, p[1] + j]) == x;
    (-1..=1).flat_map(|j| (-1..=1).map(move |i| (i, j))).filter(|&(i, j)| shares(i, j)).count() >= 2
}

/// Last frame resolved the 4x4 texels around history position `t` (the footprint and one texel beyond it each way):
/// every receiver texel there pure, and of at least `converged_after` samples where its run holds the other value
/// than `x` (`dnsr_resolved_area`: shaders/tile_classification.glsl says why).
fn resolved_area<Io: Read + ?Sized>(io: &Io, t: DVec2, x: f64, converged_after: f64) -> bool {
    let e = io.extent();
    (0..16).all(|k| {
        let q = [(t.x.floor() as i32 - 1 + (k & 3)).clamp(0, e[0] - 1), (t.y.floor() as i32 - 1 + (k >> 2)).clamp(0, e[1] - 1)];
        let mq = io.read_previous_moments(q);
        !(mq.z > 0.0) || (pure_moments(mq) && (sign_agreeing(mq.w, x) || mq.w.abs() >= converged_after))
    })
}

/// A previous run that is stable (`stable_after` > 0 samples or more) and of the same value as sample `x`, which
/// is exact.
fn stable_agreeing(run: f64, x: f64, stable_after: f64) -> bool {
    is_exact(x) && stable_after > 0.0 && run.abs() >= stable_after && if x >= 0.5 { run > 0.0 } else { run < 0.0 }
}

/// What a pixel's stored moments (their first word, `storage::pack_moments`) add to its window tile's sums in
/// `shadow_moved` (`dnsr_moment_terms`): its mean (the unorm14 code over 16: `passes::MOVING_SAMPLE_UNIT` is one
/// sample) in the low 16 bits,
/// its Bernoulli variance mean * (1 - mean) (code * (max - code) over 2^16) in the high 16; integers, summed alike in
/// any order.
pub fn moment_terms(word: u32) -> u32 {
    let max = crate::packing::MOMENTS_MEAN_MAX;
    let code = word & max;
    ((code + 8) >> 4) | (((code * (max - code)) >> 16) << 16)
}

/// Whether the shadow moved over `tile`'s neighbourhood (one tile either side, two above and below) since last
/// frame (`dnsr_shadow_moved`; shaders/tile_classification.glsl says why): over the pixels whose last frame's
/// moments are not empty (a receiver's), this frame's samples (`passes::MOVING_SAMPLE_UNIT` per sample) differ from
/// the moments' accumulated means by more than `Settings::moving_shadow_sigmas` of their Bernoulli spread, plus
/// `passes::MOVING_MARGIN_SAMPLES`.
pub fn shadow_moved<Io: Read + ?Sized>(io: &Io, tile: Coord) -> bool {
    use crate::passes::{MOVING_MARGIN_SAMPLES, MOVING_SAMPLE_UNIT};
    let unit = MOVING_SAMPLE_UNIT as f64;
    let sigmas = io.settings().moving_shadow_sigmas as f64;
    let (mut samples, mut means, mut variances) = (0u64, 0u64, 0u64);
    for y in (tile[1] - 2) * TILE[1]..(tile[1] + 3) * TILE[1] {
        for x in (tile[0] - 1) * TILE[0]..(tile[0] + 2) * TILE[0] {
            if !inside(io, [x, y]) {
                continue;
            }
            let word = super::storage::pack_moments(io.read_previous_moments([x, y]));
            if word == 0 {
                continue;
            }
            samples += (sample(io, [x, y]) * unit + 0.5).floor() as u64;
            means += (moment_terms(word) & 0xFFFF) as u64;
            variances += (moment_terms(word) >> 16) as u64;
        }
    }
    let change = (samples as f64 - means as f64).abs() / unit;
    let max = crate::packing::MOMENTS_MEAN_MAX as f64;
    sigmas > 0.0 && !io.is_reset() && change > sigmas * (variances as f64 * 65536.0 / (max * max)).sqrt() + MOVING_MARGIN_SAMPLES as f64
}

/// Whether the 3x3 tiles around `tile` were all quiet (no receiver's sample contradicted last frame's) for
/// `Settings::hard_tile_frames` frames or more last frame, on a frame that is no reset (`dnsr_quiet_tiles`).
pub fn quiet_tiles<Io: Read + ?Sized>(io: &Io, tile: Coord) -> bool {
    let (t, frames) = (tile_count(io), io.settings().hard_tile_frames as u32);
    let least = (-1..=1)
        .flat_map(|j| (-1..=1).map(move |i| [(tile[0] + i).clamp(0, t[0] - 1), (tile[1] + j).clamp(0, t[1] - 1)]))
        .map(|q| io.read_previous_tile_quiet(q))
        .min()
        .unwrap_or(0);
    frames > 0 && !io.is_reset() && least >= frames
}

/// A tile's count of quiet frames before its receivers' contradictions clear it: last frame's plus one (at most
/// `settings::MAX_QUIET_FRAMES`), 0 on a reset.
fn quiet_count<Io: Read + ?Sized>(io: &Io, tile: Coord) -> u32 {
    if io.is_reset() { 0 } else { (io.read_previous_tile_quiet(tile) + 1).min(crate::settings::MAX_QUIET_FRAMES) }
}

/// A footprint texel's moments that held both values (`passes::MIXED_TEXEL_SAMPLES`,
/// `passes::MIXED_TEXEL_SPREAD_PERCENT`).
fn mixed_texel(mq: DVec4) -> bool {
    mq.z >= crate::passes::MIXED_TEXEL_SAMPLES as f64 && (mq.x - 0.5).abs() <= crate::passes::MIXED_TEXEL_SPREAD_PERCENT as f64 / 100.0
}

/// Whether sample `x` contradicts last frame's samples around history position `t` (`dnsr_contradicts`: why), given
/// the footprint's `texels` (all receivers on the pixel's surface), how many of them last sampled the other value
/// and how many held both.
fn contradicts<Io: Read + ?Sized>(io: &Io, t: DVec2, x: f64, texels: u32, other: u32, mixed: u32) -> bool {
    if texels == 1 {
        return other == 1;
    }
    if mixed == texels {
        return true;
    }
    if other < texels {
        return false;
    }
    let e = io.extent();
    let centre = [(t.x + 0.5).floor() as i32, (t.y + 0.5).floor() as i32];
    !(0..9).any(|k| {
        let q = [(centre[0] - 1 + k % 3).clamp(0, e[0] - 1), (centre[1] - 1 + k / 3).clamp(0, e[1] - 1)];
        let mq = io.read_previous_moments(q);
        mq.z > 0.0 && (mq.w > 0.0) == (x >= 0.5)
    })
}

/// The temporal part for one receiver pixel of a mixed tile: returns (moments, (shadow, variance), whether its
/// sample contradicts last frame's: `contradicts`). `moved`: the shadow moved over its tile's neighbourhood
/// (`shadow_moved`); `quiet`: its tile is hard by time (`quiet_tiles`).
pub fn temporal<Io: Read + ?Sized>(io: &Io, p: Coord, depth: f64, moved: bool, quiet: bool, group: GroupEvidence) -> (DVec4, DVec2, bool) {
    let s = io.settings();
    let (thr_facing, thr_grazing, angle_exp, clamp_k) = (
        s.disocclusion_threshold_facing as f64,
        s.disocclusion_threshold_grazing as f64,
        s.disocclusion_angle_exponent as f64,
        s.history_clamp_sigmas as f64,
    );
    let (rej_falloff, rej_min, boost) =
        (s.history_rejection_falloff as f64, s.history_rejection_min_sigma as f64, s.variance_boost_samples as f64);
    let (full, min_blend, max_samples) =
        (s.full_history_samples as f64, s.min_current_weight as f64, s.max_history_samples as f64);
    let e = io.extent();

    let mut local = local_moments(io, p);
    // The flip rule keeps the whole window's mean; the rest the surface's, with the run features, a hit mask and no
    // penumbra guidance (`DNSR_SURFACE_WINDOW`).
    let window_mean = local.x;
    if s.uses_runs() && !io.visibility_input() && io.penumbra().is_none() {
        local = surface_moments(io, p, local);
    }
    let mut x = sample(io, p);
    // Checkerboard input: a pixel not traced this frame holds its neighbours' mean, not a sample of its own.
    let untraced = !io.is_traced(p);
    let uv = pixel_uv(io, p);
    let ndc = uv_to_ndc(uv);
    let velocity = quad_velocity(io, p);
    let history_uv = uv + velocity;
    // Where the shadow moved over this still pixel, its history holds where the shadow was: a tighter clamp (a
    // pixel that moves under 1 / `passes::STILL_MOTION_INV_PIXELS` px; shaders/tile_classification.glsl says why).
    let motion = velocity * DVec2::new(e[0] as f64, e[1] as f64) * crate::passes::STILL_MOTION_INV_PIXELS as f64;
    let shadow_moved_here = moved && motion.dot(motion) < 1.0;
    let clamp_k = if shadow_moved_here { s.moving_history_clamp_sigmas as f64 } else { clamp_k };

    let prev_clip = io.reprojection_matrix() * DVec4::new(ndc.x, ndc.y, depth, 1.0);
    let prev_ndc = prev_clip.truncate() / prev_clip.w;
    let prev_uv = prev_ndc.truncate() * 0.5 + 0.5;
    let world = super::world_position(io, p, depth);
    let view_dir = (io.eye() - world).normalize();
    let normal = io.read_normal(p);
    let n_dot_v = normal.dot(view_dir).clamp(0.0, 1.0);
    let threshold = thr_facing + (thr_grazing - thr_facing) * (1.0 - n_dot_v).powf(angle_exp);
    let in01 = |v: DVec2| v.x >= 0.0 && v.y >= 0.0 && v.x < 1.0 && v.y < 1.0;
    let on_screen = finite(prev_uv) && finite(history_uv) && prev_clip.w > 0.0 && in01(prev_uv) && in01(history_uv);
    let clamp_px = |v: DVec2| [((v.x * e[0] as f64) as i32).clamp(0, e[0] - 1), ((v.y * e[1] as f64) as i32).clamp(0, e[1] - 1)];
    let mut disoccluded = io.is_reset() || !on_screen;
    // Last frame's depth of this surface point.
    let expected = linear_depth(io, prev_ndc.truncate(), prev_ndc.z);
    if !disoccluded {
        let previous = io.read_previous_depth(clamp_px(prev_uv));
        disoccluded = !((previous - expected).abs() < threshold * expected);
    }

    let stable_after = s.stable_history_samples as f64;
    let converged_after = s.converged_samples as f64;
    let mut m = DVec4::ZERO;
    // A resolved change (see below): this frame's sample stands alone.
    let mut resolved = false;
    let mut contradiction = false;
    // History blended from the texels that agree (weighted sum, weight), when only some of them do.
    let mut run_history = None;
    if !disoccluded {
        let hp = clamp_px(history_uv);
        m = io.read_previous_moments(hp);
        // Where the nearest texel's normal turned, its moments are another surface's: start again, or (below)
        // continue the heaviest texel of the footprint that kept this surface's normal
        // (shaders/tile_classification.glsl says why). With the run features only: Balanced keeps the FidelityFX
        // behaviour.
        let turned = s.uses_runs() && normal_turned(io.read_previous_normal(hp), normal);
        if turned {
            m = DVec4::ZERO;
        }
        // An untraced stable pixel takes its run's value as this frame's sample (and keeps its run, below), unless
        // its neighbours' mean lies more than 0.5 from that value.
        let contradicted = (x - if m.w > 0.0 { 1.0 } else { 0.0 }).abs() > 0.5;
        if untraced && !contradicted && stable_after > 0.0 && m.w.abs() >= stable_after && m.w.abs() <= MAX_SAMPLE_RUN as f64 {
            x = if m.w > 0.0 { 1.0 } else { 0.0 };
        }
        // A moving camera puts history_uv between texels, and next to a hard edge the bilinear footprint lies
        // across it. The texels whose stable run holds this sample's value are where this surface point was: blend
        // the history from them alone. (A texel weighed at under 1/16 does not count; the bound also keeps float
        // rounding at texel centres out. Taking their moments too left the viewer's orbiting fins worse.)
        if s.uses_runs() {
            let t = DVec2::new(history_uv.x * e[0] as f64 - 0.5, history_uv.y * e[1] as f64 - 0.5);
            let f = t - t.floor();
            // A footprint texel of this surface lies within the disocclusion test's depth range, widened per pixel
            // of its distance from the history position (`texel_depth_slope`).
            let slope = texel_depth_slope(io, expected, n_dot_v);
            let (mut agree, mut all, mut receivers) = (DVec2::ZERO, 0.0, DVec2::ZERO);
            // Texels weighed at 1/16 or more: one where the camera stood still.
            let mut texels = 0;
            // The texel of the longest pure run that agrees with x: its moments and history.
            let (mut pure, mut pure_history) = (DVec4::ZERO, 0.0);
            // Every receiver texel resolved: of the other value (one of them is) pure and converged, of this
            // sample's value pure or converged.
            let (mut all_resolved, mut any_other, mut all_pure) = (true, false, true);
            // The heaviest receiver texel whose normal did not turn: its moments, where the nearest texel turned.
            let (mut kept, mut kept_weight) = (DVec4::ZERO, 0.0);
            // Receiver texels whose last sample was not x, and those that held both values (`contradicts`).
            let (mut other_texels, mut mixed_texels) = (0, 0);
            for k in 0..4 {
                let weight = (if k & 1 != 0 { f.x } else { 1.0 - f.x }) * (if k & 2 != 0 { f.y } else { 1.0 - f.y });
                let q = [
                    (t.x.floor() as i32 + (k & 1)).clamp(0, e[0] - 1),
                    (t.y.floor() as i32 + (k >> 1)).clamp(0, e[1] - 1),
                ];
                if weight < 1.0 / 16.0 {
                    continue;
                }
                let mq = io.read_previous_moments(q);
                all += weight;
                texels += 1;
                // Texels without a receiver (sky: no samples) leave the blend too: their lit sky signal would
                // brighten a shadowed receiver along every silhouette against the background. So do texels whose
                // normal turned, or whose depth is not this surface point's (the disocclusion test's): they hold
                // another surface.
                if !(mq.z > 0.0)
                    || normal_turned(io.read_previous_normal(q), normal)
                    || !((io.read_previous_depth(q) - expected).abs()
                        < threshold * expected + (DVec2::new(q[0] as f64, q[1] as f64) - t).length() * slope)
                {
                    continue;
                }
                if weight > kept_weight {
                    (kept, kept_weight) = (mq, weight);
                }
                let texel = io.read_history_texel(q);
                receivers += DVec2::new(weight * texel, weight);
                other_texels += u32::from((mq.w > 0.0) != (x >= 0.5));
                mixed_texels += u32::from(mixed_texel(mq));
                let agreeing = sign_agreeing(mq.w, x);
                let texel_pure = pure_moments(mq);
                let converged_run = mq.w.abs() >= converged_after;
                all_resolved &= if agreeing { texel_pure || converged_run } else { texel_pure && converged_run };
                any_other |= !agreeing;
                all_pure &= texel_pure;
                if texel_pure && agreeing && mq.w.abs() > pure.w.abs() {
                    pure = mq;
                    pure_history = texel;
                }
                if !stable_agreeing(mq.w, x, stable_after) {
                    continue;
                }
                agree += DVec2::new(weight * texel, weight);
            }
            // A hard edge or a thin feature under a moving camera, where the nearest texel's samples all held the
            // other value and every receiver texel's samples held one value: continue the agreeing texel whose
            // samples all agree, moments and history (shaders/tile_classification.glsl says why the whole footprint).
            if turned {
                m = kept;
            }
            contradiction = texels > 0 && !(receivers.y < all) && contradicts(io, t, x, texels, other_texels, mixed_texels);
            let adopt = pure.z > 0.0 && !sign_agreeing(m.w, x) && pure_moments(m) && all_pure;
            // Elsewhere, where the nearest texel lies across the edge from this surface point, the pixel continues
            // a stable run of stable_after samples, no longer (shaders/tile_classification.glsl says why).
            if agree.y > 0.0 && !stable_agreeing(m.w, x, stable_after) {
                m.w = if x >= 0.5 { stable_after } else { -stable_after };
            }
            if adopt {
                m = pure;
            }
            // A silhouette, edge or thin feature under a moving camera between resolved surfaces: this sample stands
            // alone (shaders/tile_classification.glsl says why, and why the whole area away from the sky).
            resolved = converged_after > 0.0
                && is_exact(x)
                && !untraced
                && any_other
                && all_resolved
                && two_neighbours_share(io, p, x)
                && (receivers.y < all || (texels > 1 && resolved_area(io, t, x, converged_after)));
            // Continue the agreeing texel whose samples all agree, or start from this sample.
            if resolved {
                m = pure;
                run_history = Some(if pure.z > 0.0 { pure_history } else { x });
            // Only where the footprint is split: elsewhere the plain blend stands.
            } else if agree.y > 0.0 && agree.y < all {
                run_history = Some(agree.x / agree.y);
            } else if adopt {
                run_history = Some(pure_history);
            } else if receivers.y > 0.0 && receivers.y < all {
                run_history = Some(receivers.x / receivers.y);
            }
        }
        let sane = m.z >= 0.0
            && m.z <= max_samples
            && m.y >= 0.0
            && m.y < 1e30
            && m.x.is_finite()
            && m.w.abs() <= MAX_SAMPLE_RUN as f64;
        if !sane {
            m = DVec4::ZERO;
            run_history = None;
        }
    }
    if m.z > max_samples - 1.0 {
        let f = (max_samples - 1.0) / m.z;
        scale_moments(&mut m, f);
    }
    // Welford's update without cancellation when the previous count is tiny (shaders/tile_classification.glsl).
    let previous = m.z;
    let delta = x - m.x;
    m.z += 1.0;
    m.x += delta / m.z;
    m.y += delta * delta * (previous / m.z);
    let mut variance = if previous > 0.0 { m.y / previous } else { 1.0 };
    let flip_after = (s.history_flip_samples as f64).floor();
    let exact = is_exact(x);
    if !untraced {
        m.w = if exact { sample_run(m.w, x, stable_after) } else { fractional_run(m.w, stable_after) };
    }
    // Enough identical samples in a row: the input resolves this pixel (a hard edge, say), and the local
    // distribution, which straddles the edge, must not pull its history (nor reject it). Its history is clamped
    // to what the run allows instead: within RUN_CLAMP_SAMPLES / n of the run's value (the rule of three).
    let stable = stable_after > 0.0 && m.w.abs() >= stable_after;
    // flip_after samples of the other value right after a stable run, or the first one where the local
    // distribution already leans to it: the shadow moved over this pixel. Restart from the new samples, the
    // history from the local mean.
    let breaking = flip_after > 0.0 && m.w.abs().fract() == 0.5;
    let flipped = breaking && exact && !untraced && (m.w.abs() == flip_after + 0.5 || (x - window_mean).abs() < 0.5);
    if flipped {
        let n = m.w.abs().floor();
        m = DVec4::new(x, 0.0, n, if x >= 0.5 { n } else { -n });
        variance = if n > 1.0 { 0.0 } else { 1.0 };
    }

    let sigma = local.y.sqrt();
    let mut history = match run_history {
        _ if disoccluded => local.x,
        Some(h) => h,
        None => io.read_history(history_uv),
    };
    if !history.is_finite() {
        history = local.x;
    }
    let (clamped, d) = if flipped {
        (local.x, 0.0)
    } else if stable || resolved {
        let width = RUN_CLAMP_SAMPLES as f64 / m.w.abs();
        (history.clamp(x - width, x + width), 0.0)
    } else {
        (history.clamp(local.x - clamp_k * sigma, local.x + clamp_k * sigma), (history - local.x) / (clamp_k * sigma).max(rej_min))
    };
    scale_moments(&mut m, (-d * d / rej_falloff).exp());

    // A stable pixel's samples already resolve it: boosting its variance towards the local one (which straddles
    // the edge) would let the filter blur the edge it resolves.
    if m.z < boost && !stable {
        variance = variance.max(local.y) * (boost - m.z).max(1.0);
    }
    let history_weight = ((full - m.z).max(0.0) / full).sqrt();
    let alpha = min_blend + (1.0 - min_blend) * history_weight;
    let shadow = clamped + (x - clamped) * alpha;
    // A sample that is not exact contradicts nothing (its tile is no hard one anyway); nor does an untraced one.
    let contradicted = contradiction && is_exact(x) && !untraced;
    // Under a light of no size, a hard penumbra (Settings::hard_penumbra_pixels) or in a tile hard by time
    // (Settings::hard_tile_frames) where the pixel does not contradict (disoccluded or not: the shader says why),
    // this sample is the output; the moments go on. Not on an untraced pixel of a checkerboard input (its value is
    // its neighbours' mean). Hard tiles not under penumbra guidance (shaders/tile_classification.glsl says why); the
    // counts go on.
    let quiet = quiet && io.penumbra().is_none() && !contradicted;
    // A receiver turned away from the light whose ray hit keeps its sample (`ShadowsDispatch::light_position`;
    // shaders/tile_classification.glsl says why), unless a normal map tilted its normal past the light in a group
    // where such a receiver's ray reached it (`GroupEvidence::lit_against_normal`). With the run features only:
    // Balanced keeps the FidelityFX behaviour. Turned away from the whole disc (N.L below -sin of its angular
    // radius), it is final, not in a quiet tile nor in a group whose rays do not test the normals
    // (`GroupEvidence::lit_away_from_disc`): the filter returns it as it is and leaves it out of its neighbours' taps
    // (shaders/tile_classification.glsl says why).
    let (mut turned_away, mut final_here) = (false, false);
    if let Some(l) = io.light_position().filter(|_| s.uses_runs() && x == 0.0) {
        let l = to_light(l, world);
        turned_away = normal.dot(l) < 0.0 && !(group.lit_against_normal && plane_faces_light(io, p, depth, normal, l));
        final_here = turned_away
            && !quiet
            && !untraced
            && !group.lit_away_from_disc
            && faces_away_from_disc(io, normal, l);
    }
    let exact = DVec2::new(x, if final_here { super::FINAL_VARIANCE } else { 0.0 });
    // A resolved pixel is this sample, flagged converged (or final).
    if resolved {
        return (m, exact, contradicted);
    }
    if !untraced && (quiet || turned_away || super::filter::hard_penumbra(io, [p[0] / TILE[0], p[1] / TILE[1]], linear_depth(io, ndc, depth))) {
        return (m, exact, contradicted);
    }
    // Converged (Settings::converged_samples, on a stable pixel): variance 0 tells the filter that the input may
    // resolve this pixel; the value stays the temporal one; not where the shadow moved over this still pixel
    // (shaders/tile_classification.glsl says why).
    let converged_here = stable && !flipped && !shadow_moved_here && pure_moments(m);
    let variance = if converged_here && converged(m.w, x, s.converged_samples as f64) {
        0.0
    } else {
        super::filter::unconverged_variance(io, variance)
    };
    (m, DVec2::new(shadow, variance), contradicted)
}

/// A pixel's hit distance counts towards its tile's blocker estimate when finite and positive.
pub fn usable_hit_distance(d: f64) -> bool {
    d > 0.0 && d < f64::INFINITY
}

/// Penumbra guidance: the mean distance to the occluders the shadowed pixels within +-8 px of a tile (the window
/// of the uniform-tile test: the tile and one tile column either side, two tile rows above and below) hit; -1
/// when none of them has a usable distance. A tile's estimate, not a pixel's: one 1-spp hit distance is as noisy
/// as the mask, and the penumbra's width varies slowly along an edge.
pub fn tile_blocker<Io: Read + ?Sized>(io: &Io, tile: Coord) -> f64 {
    let (mut sum, mut count) = (0.0, 0u32);
    for dy in -2..=2 {
        for dx in -1..=1 {
            let t = [tile[0] + dx, tile[1] + dy];
            let valid = tile_valid_bits(io, t);
            if valid == 0 {
                continue;
            }
            // Pixels with a ray that hit: not exactly lit.
            let shadowed = !exact_word(io, t, true) & valid;
            for bit in (0..TILE[0] * TILE[1]).filter(|b| shadowed >> b & 1 != 0) {
                let d = io.read_hit_distance([t[0] * TILE[0] + bit % TILE[0], t[1] * TILE[1] + bit / TILE[0]]);
                if usable_hit_distance(d) {
                    sum += d;
                    count += 1;
                }
            }
        }
    }
    if count > 0 { sum / count as f64 } else { -1.0 }
}

/// Runs tile classification over the render rectangle.
pub fn run<Io: Read + Write>(io: &mut Io) {
    let e = io.extent();
    let max_samples = io.settings().max_history_samples as f64;
    let tiles = tile_count(io);
    // The run features' pipelines tell a shadow that moved (`shadow_moved`), from last frame's moments.
    let tells = io.settings().tells_moving_shadows();
    let moved: Vec<bool> = (0..tiles[0] * tiles[1]).map(|i| tells && shadow_moved(io, [i % tiles[0], i / tiles[0]])).collect();
    let evidence = group_evidence(io);
    for ty in 0..tiles[1] {
        for tx in 0..tiles[0] {
            let tile = [tx, ty];
            let state = if has_receiver(io, tile) { uniform_state(io, tile) } else { 1 };
            let meta = match state {
                0 => 0,
                1 => TILE_CLEARED | TILE_LIT,
                _ => TILE_CLEARED,
            };
            io.write_tile_meta(tile, meta);
            // Hard tiles told by time: last frame's counts decide; this frame's is written, and cleared below where
            // a receiver contradicts (with the run features only, as the GPU's DNSR_SPEC_STABLE_HISTORY).
            let runs = io.settings().uses_runs();
            let quiet = runs && quiet_tiles(io, tile);
            let mut count = quiet_count(io, tile);
            if state == 0 && io.penumbra().is_some() {
                let blocker = tile_blocker(io, tile);
                io.write_tile_blocker(tile, blocker);
            }
            for y in ty * TILE[1]..((ty + 1) * TILE[1]).min(e[1]) {
                for x in tx * TILE[0]..((tx + 1) * TILE[0]).min(e[0]) {
                    let p = [x, y];
                    let depth = io.read_depth(p);
                    let receiver = is_receiver(depth);
                    let (moments, result) = if state != 0 {
                        let value = if state == 1 { 1.0 } else { 0.0 };
                        let run = if state == 1 { MAX_SAMPLE_RUN as f64 } else { -(MAX_SAMPLE_RUN as f64) };
                        let m = if receiver { DVec4::new(value, 0.0, max_samples, run) } else { DVec4::ZERO };
                        (m, if receiver { DVec2::new(value, 0.0) } else { SKY_SIGNAL })
                    } else if !receiver {
                        (DVec4::ZERO, SKY_SIGNAL)
                    } else {
                        let group = evidence[group_index(e, p)];
                        let (m, r, contradicted) = temporal(io, p, depth, moved[(ty * tiles[0] + tx) as usize], quiet, group);
                        if contradicted {
                            count = 0;
                        }
                        (m, r)
                    };
                    io.write_moments(p, moments);
                    io.write_reprojection(p, result);
                }
            }
            if runs {
                io.write_tile_quiet(tile, count);
            }
        }
    }
}
