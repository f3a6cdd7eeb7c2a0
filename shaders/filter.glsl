// filter: one pass of the edge-avoiding a-trous filter (3x3 taps at +-step), in two variants. The first pass
// (step 1) reads its group and a one-pixel apron into shared memory once and writes the depth copy (linear depth
// and normal per pixel in one word), which is the later passes' guide; the later passes (DNSR_LATER_PASS) fetch
// every tap, guide and signal, straight from the images through the texture cache. Why two variants, on an H100 at
// 4K (BENCHMARKS.md change log): one shader holding both paths slowed the later passes from 0.383 / 0.371 to
// 0.454 / 0.477 ms although they never touch the apron, and an apron for their variance blur alone slowed them too
// (their taps cannot wait for a barrier). An apron sized for the widest step was 3-5x slower still, and in 16x16
// groups an apron of one step, every tap from shared memory, took Quality's pass 1 from 0.256 to 0.346 ms on an H200
// (docs/bench/h200-2026-11-30-later-apron: the taps' fetches are most of the pass, but the texture cache serves them
// faster than a load and a barrier do).
//
// The later passes' light-slot variant (DNSR_LIGHT_SLOTS_VARIANT, which a record of several lights runs) filters up
// to DNSR_LIGHT_SLOTS lights per dispatch: per tap the guide fetch and the depth, normal and kernel factors once,
// each light's signal per light. Each light's arithmetic is the single-light one, term for term, so its result is
// bit for bit the same. The helpers below take the light `l` they work on (always 0 in the single-light variants).
#ifndef DNSR_FILTER_GLSL
#define DNSR_FILTER_GLSL

// The loops over the lights unroll: each light's resources are then chosen at compile time.
#extension GL_EXT_control_flow_attributes : require

// Linear depth of a receiver, -1 for sky.
float dnsr_tap_depth(ivec2 p) {
    return dnsr_receiver_linear_depth(p, dnsr_read_depth(p));
}

// Penumbra guidance: 1 / (2 sigma^2) of the Gaussian over tap distance that keeps the kernel within the penumbra
// the tile's blockers cast on a receiver at linear depth zc; 0 (no narrowing) without guidance or blocker.
float dnsr_penumbra_falloff_of(float blocker, vec4 pen, float zc) {
    if (blocker < 0.0) return 0.0;
    float footprint = dnsr_pixel_footprint(pen, zc);
    if (!(footprint > 0.0)) return 0.0;
    float sigma = blocker * pen.x / footprint * pen.w;
    return 0.5 / max(sigma * sigma, 1e-20);
}
float dnsr_penumbra_falloff(ivec2 p, float zc) {
    if (!DNSR_SPEC_PENUMBRA_GUIDED) return 0.0;
    return dnsr_penumbra_falloff_of(dnsr_read_tile_blocker(p / DNSR_TILE_SIZE), dnsr_get_penumbra_settings(), zc);
}

// Light l's resources: a slot of the light-slot variants, the single-light bindings otherwise.
#ifdef DNSR_LIGHT_SLOTS_VARIANT
vec2 dnsr_pass_filter_input(int l, ivec2 p) { return dnsr_read_light_filter_input(l, p); }
vec4 dnsr_pass_gather_variance(int l, ivec2 corner) { return dnsr_gather_light_filter_variance(l, corner); }
float dnsr_pass_penumbra_falloff(int l, ivec2 p, float zc) {
    if (!DNSR_SPEC_PENUMBRA_GUIDED || !dnsr_get_light_guided(l)) return 0.0;
    return dnsr_penumbra_falloff_of(dnsr_read_light_tile_blocker(l, p / DNSR_TILE_SIZE), dnsr_get_light_penumbra_settings(l), zc);
}
bool dnsr_pass_hard(int l, ivec2 p, float zc) {
    float blocker = dnsr_read_light_tile_blocker(l, p / DNSR_TILE_SIZE);
    return dnsr_get_light_guided(l)
        && (dnsr_hard_penumbra(blocker, dnsr_get_light_penumbra_settings(l), zc) || dnsr_no_blocker(blocker));
}
void dnsr_pass_write_filter_output(int l, ivec2 p, vec2 mean_var) { dnsr_write_light_filter_output(l, p, mean_var); }
#ifdef DNSR_FINAL_PASS
void dnsr_pass_write_output(int l, ivec2 p, float shadow) { dnsr_write_light_output(l, p, shadow); }
vec4 dnsr_pass_debug_moments(int l, ivec2 p) { return dnsr_read_light_debug_moments(l, p); }
#endif
#else
vec2 dnsr_pass_filter_input(int l, ivec2 p) { return dnsr_read_filter_input(p); }
vec4 dnsr_pass_gather_variance(int l, ivec2 corner) { return dnsr_gather_filter_variance(corner); }
float dnsr_pass_penumbra_falloff(int l, ivec2 p, float zc) { return dnsr_penumbra_falloff(p, zc); }
bool dnsr_pass_hard(int l, ivec2 p, float zc) {
    float blocker = dnsr_read_tile_blocker(p / DNSR_TILE_SIZE);
    // A light of no size (ShadowsDispatch::hard_light) runs the first filter pass alone: the later passes do not
    // declare DNSR_SPEC_HARD_LIGHT (a runtime test there cost them 2-4% at 4K on an H100).
#ifdef DNSR_LATER_PASS
    return dnsr_hard_penumbra(blocker, dnsr_get_penumbra_settings(), zc) || dnsr_no_blocker(blocker);
#else
    return DNSR_SPEC_HARD_LIGHT || dnsr_hard_penumbra(blocker, dnsr_get_penumbra_settings(), zc) || dnsr_no_blocker(blocker);
#endif
}
void dnsr_pass_write_filter_output(int l, ivec2 p, vec2 mean_var) { dnsr_write_filter_output(p, mean_var); }
#ifdef DNSR_FINAL_PASS
void dnsr_pass_write_output(int l, ivec2 p, float shadow) { dnsr_write_output(p, shadow); }
vec4 dnsr_pass_debug_moments(int l, ivec2 p) { return dnsr_read_debug_moments(p); }
#endif
#endif

// The moments of a pixel whose value is known exactly (a cleared tile's receiver: its value, no deviation, a full
// history, the longest run of that value; vec4(0): no receiver's). Filter pass 0 keeps them for the next frame;
// tile classification stores no frame moments for such pixels (4 B/px fewer where tiles are cleared or sky).
vec4 dnsr_cleared_moments(bool receiver, bool lit) {
    float run = lit ? float(DNSR_MAX_SAMPLE_RUN) : -float(DNSR_MAX_SAMPLE_RUN);
    return receiver ? vec4(lit ? 1.0 : 0.0, 0.0, dnsr_get_temporal_settings().z, run) : vec4(0.0);
}

#ifdef DNSR_FINAL_PASS
// The debug views: what the output shows instead of the shadow (see DebugView in src/dispatch.rs).
float dnsr_debug_value(int l, uint view, ivec2 p, bool receiver, uint meta, vec2 result) {
    bool cleared = (meta & DNSR_TILE_CLEARED) != 0u;
    if (view == DNSR_DEBUG_VIEW_TILE_CLASSIFICATION) {
        return !receiver ? 0.75 : (!cleared ? 0.5 : ((meta & DNSR_TILE_LIT) != 0u ? 1.0 : 0.0));
    }
    if (view == DNSR_DEBUG_VIEW_VARIANCE) return clamp(sqrt(max(result.y, 0.0)), 0.0, 1.0);
    // A cleared tile's receivers hold a full history and the longest run (dnsr_cleared_moments): with one filter
    // pass their frame moments, which these views would read, were not stored.
    vec4 m = !receiver ? vec4(0.0)
                       : (cleared ? dnsr_unpack_moments(dnsr_pack_moments(dnsr_cleared_moments(true, false)))
                                  : dnsr_pass_debug_moments(l, p));
    float n = m.z;
    if (view == DNSR_DEBUG_VIEW_SAMPLE_COUNT) return clamp(n / dnsr_get_temporal_settings().z, 0.0, 1.0);
    // The run as stored: a run that this frame's sample broke is kept as its length and a half (the flip rule's
    // mark), shown as its whole samples.
    if (view == DNSR_DEBUG_VIEW_SAMPLE_RUN) return clamp(floor(abs(m.w)) / dnsr_get_temporal_settings().z, 0.0, 1.0);
    return receiver && !cleared && n <= 1.0 ? 1.0 : 0.0; // DNSR_DEBUG_VIEW_DISOCCLUSION
}
#endif

void dnsr_filter_write(int l, ivec2 p, vec2 result, bool receiver, uint meta) {
#ifndef DNSR_LATER_PASS
    dnsr_write_history(p, result.x);
#endif
    if (dnsr_get_write_internal()) dnsr_pass_write_filter_output(l, p, result);
#ifdef DNSR_FINAL_PASS
    uint view = dnsr_get_debug_view();
    float contrast = dnsr_get_filter_settings().z;
    dnsr_pass_write_output(l, p, view == DNSR_DEBUG_VIEW_NONE ? pow(result.x, max(contrast - result.y, 1.0))
                                                              : dnsr_debug_value(l, view, p, receiver, meta, result));
#endif
}

// Value of a pixel in a cleared tile: sky is lit, receivers take the tile's value.
vec2 dnsr_cleared_value(bool receiver, uint meta) {
    return receiver ? vec2((meta & DNSR_TILE_LIT) != 0u ? 1.0 : 0.0, 0.0) : DNSR_SKY_SIGNAL;
}

#ifndef DNSR_LATER_PASS
// From world position w of pixel q to that of the nearer (in world space) of its receiver neighbours along `axis`,
// signed as +axis; vec3(0) where neither neighbour is a receiver.
vec3 dnsr_surface_tangent(ivec2 q, vec3 w, ivec2 axis) {
    vec3 best = vec3(0.0);
    float best_length = -1.0;
    for (int s = -1; s <= 1; s += 2) {
        ivec2 r = q + axis * s;
        if (!dnsr_inside(r)) continue;
        float d = dnsr_read_depth(r);
        if (!dnsr_is_receiver(d)) continue;
        vec3 t = (dnsr_world_position(r, d) - w) * float(s);
        float l = dot(t, t);
        if (best_length < 0.0 || l < best_length) {
            best = t;
            best_length = l;
        }
    }
    return best;
}
// The cosine within which the first pass takes geometric normals (Settings::geometric_normal_degrees; above 1:
// off, the G-buffer's normals). Only with the run features: behind a runtime test alone, the code's registers cost
// Balanced, which never takes them, 0.010 ms at 4K on an H100 (36 -> 47 registers).
float dnsr_geometric_normal_min_cos() { return DNSR_SPEC_STABLE_HISTORY ? dnsr_get_moving_settings().w : 2.0; }
// The normal the first pass weighs receiver q's taps by (device depth `depth`, G-buffer normal `shading`): the
// plane through its nearer neighbour along each axis, on the side of `shading`, where that lies within
// acos(dnsr_geometric_normal_min_cos()) of `shading` (a normal map's tilt: the depth knows one plane); `shading`
// where it does not (a feature of 1-2 px, whose neighbours are another surface, or a crease) or where an axis has
// no receiver neighbour.
vec3 dnsr_geometric_normal(ivec2 q, float depth, vec3 shading) {
    vec3 w = dnsr_world_position(q, depth);
    vec3 n = cross(dnsr_surface_tangent(q, w, ivec2(1, 0)), dnsr_surface_tangent(q, w, ivec2(0, 1)));
    float l = dot(n, n);
    if (!(l > 0.0) || isinf(l)) return shading;
    n *= inversesqrt(l);
    float c = dot(n, shading);
    return abs(c) >= dnsr_geometric_normal_min_cos() ? (c < 0.0 ? -n : n) : shading;
}

// The first pass (step 1) reads its group's pixels and a one-pixel apron into shared memory once: every pixel's
// 3x3 neighbourhood, its taps and its variance-blur footprint, instead of nine fetches per pixel. It writes the
// depth copy, the later passes' guide. One light only (l is 0): a first pass for several lights (their signals in
// shared memory side by side) was slower on an H100 than one dispatch per light (BENCHMARKS.md).
const ivec2 DNSR_APRON_SIZE = DNSR_WIDE_GROUP_SIZE + 2;
const int DNSR_APRON_COUNT = DNSR_APRON_SIZE.x * DNSR_APRON_SIZE.y;
shared vec2 dnsr_apron_signal[DNSR_APRON_COUNT];
shared float dnsr_apron_depth[DNSR_APRON_COUNT];
shared vec3 dnsr_apron_normal[DNSR_APRON_COUNT];

void dnsr_load_apron(ivec2 origin, int invocation) {
    for (int i = invocation; i < DNSR_APRON_COUNT; i += DNSR_WIDE_GROUP_INVOCATIONS) {
        ivec2 q = origin - 1 + ivec2(i % DNSR_APRON_SIZE.x, i / DNSR_APRON_SIZE.x);
        bool inside = dnsr_inside(q);
        dnsr_apron_signal[i] = inside ? dnsr_read_filter_input(q) : DNSR_SKY_SIGNAL;
        float z = inside ? dnsr_tap_depth(q) : -1.0;
        dnsr_apron_depth[i] = z;
        vec3 normal = z >= 0.0 ? dnsr_read_normal(q) : vec3(0.0);
        dnsr_apron_normal[i] = z >= 0.0 && dnsr_geometric_normal_min_cos() <= 1.0 ? dnsr_geometric_normal(q, dnsr_read_depth(q), normal) : normal;
    }
}

int dnsr_apron_index(ivec2 lid, int i, int j) { return (lid.y + 1 + j) * DNSR_APRON_SIZE.x + lid.x + 1 + i; }

vec2 dnsr_center_signal(int l, ivec2 p, ivec2 lid) { return dnsr_apron_signal[dnsr_apron_index(lid, 0, 0)]; }
// Variances of the 3x3 neighbourhood, row by row (the sky's -1 outside the rectangle).
void dnsr_variance_neighbourhood(int l, ivec2 p, ivec2 lid, vec2 c, out float v[9]) {
    for (int k = 0; k < 9; ++k) v[k] = dnsr_apron_signal[dnsr_apron_index(lid, k % 3 - 1, k / 3 - 1)].y;
}
// Tap (i, j): its signal, and its guide (linear depth or -1, normal: dnsr_geometric_normal's).
void dnsr_tap(int l, ivec2 p, ivec2 lid, int i, int j, int step, out vec2 signal, out vec4 guide) {
    int k = dnsr_apron_index(lid, i, j);
    signal = dnsr_apron_signal[k];
    guide = vec4(dnsr_apron_depth[k], dnsr_apron_normal[k]);
}

// Tile metadata of the group's tiles.
const ivec2 DNSR_BLOCK_TILES = DNSR_GROUP_SIZE / DNSR_TILE_SIZE;
const ivec2 DNSR_META_TILES = (DNSR_WIDE_GROUP_SIZE / DNSR_GROUP_SIZE) * DNSR_BLOCK_TILES;
shared uint dnsr_meta[DNSR_META_TILES.y][DNSR_META_TILES.x];

bool dnsr_block_cleared(ivec2 m) { return (dnsr_meta[m.y][m.x] & dnsr_meta[m.y + 1][m.x] & DNSR_TILE_CLEARED) != 0u; }
#else
// The later passes (step 2 and up) fetch every tap from the images through the texture cache: a tap is the depth
// copy the first pass wrote (its guide) and the signal. (An apron for their variance blur slowed them: their taps
// cannot wait for a barrier.)
vec2 dnsr_center_signal(int l, ivec2 p, ivec2 lid) { return dnsr_pass_filter_input(l, p); }
// Variances of the 3x3 neighbourhood, row by row (the sky's -1 outside the rectangle): four gathers of 2x2
// texels instead of eight fetches.
// From the gathers at the corners p, p + (1, 0), p + (0, 1), p + (1, 1) (a gather at corner q returns
// (q + (-1, 0), q, q + (0, -1), q + (-1, -1)) as (x, y, z, w)) and the centre's signal c.
void dnsr_gathered_neighbourhood(ivec2 p, vec4 a, vec4 b, vec4 d, vec4 e, vec2 c, out float v[9]) {
    v = float[9](a.w, a.z, b.z, a.x, c.y, b.y, d.x, d.y, e.y);
    for (int k = 0; k < 9; ++k) {
        if (!dnsr_inside(p + ivec2(k % 3 - 1, k / 3 - 1))) v[k] = DNSR_SKY_SIGNAL.y;
    }
}
void dnsr_variance_neighbourhood(int l, ivec2 p, ivec2 lid, vec2 c, out float v[9]) {
    dnsr_gathered_neighbourhood(p, dnsr_pass_gather_variance(l, p), dnsr_pass_gather_variance(l, p + ivec2(1, 0)),
                                dnsr_pass_gather_variance(l, p + ivec2(0, 1)), dnsr_pass_gather_variance(l, p + ivec2(1, 1)), c, v);
}
void dnsr_tap(int l, ivec2 p, ivec2 lid, int i, int j, int step, out vec2 signal, out vec4 guide) {
    ivec2 q = p + ivec2(i, j) * step;
    // Both fetches at once: the signal's does not wait for the guide's.
    guide = dnsr_read_guide(q);
    signal = dnsr_pass_filter_input(l, q);
}
#endif


// 1 / sigma of the shadow edge stop: the variances of the 3x3 receivers (told apart by their signal, see
// DNSR_SKY_SIGNAL) blurred, at least the floor `sigma_floor`.
float dnsr_inv_shadow_sigma(float v[9], float sigma_floor) {
    float vsum = 0.0, vweight = 0.0;
    for (int j = -1; j <= 1; ++j) {
        for (int i = -1; i <= 1; ++i) {
            float s = v[(j + 1) * 3 + i + 1];
            if (!dnsr_is_receiver_signal(vec2(0.0, s))) continue;
            float w = 1.0 / float(4 << (abs(i) + abs(j)));
            vsum += w * s;
            vweight += w;
        }
    }
    return 1.0 / max(sqrt(max(vsum / vweight, 0.0)), sigma_floor);
}

// A converged pixel (variance 0) at least half of whose other 3x3 receivers are converged too passes through the
// filter as its run's value (the side of 0.5 its stable-clamped value lies on): its samples resolve it, and so do
// its neighbours', so this is no penumbra where a run of identical samples happened by chance (a pixel of
// visibility 0.95 shows 8 lit samples in a row two times in three, one with no other sample in its history far less
// often, and half of its neighbours at once rarely). The half, not all of them: a shadowed receiver next to a
// background in penumbra has its own surface on one side only. Other converged pixels are filtered like any other.
bool dnsr_passes_through(vec2 c, float v[9]) {
    if (!dnsr_converged_on() || !dnsr_converged_signal(c)) return false;
    int receivers = 0, converged = 0;
    for (int k = 0; k < 9; ++k) {
        if (k == 4 || v[k] < 0.0) continue;  // the centre; sky's -1
        receivers += 1;
        converged += v[k] == 0.0 ? 1 : 0;
    }
    return 2 * converged >= receivers;
}
vec2 dnsr_run_signal(vec2 c) { return vec2(c.x >= 0.5 ? 1.0 : 0.0, 0.0); }

// The filtered (mean, variance) of receiver p (linear depth zc, normal nc) in a tile that is not cleared. A final
// pixel (dnsr_final_signal) is its own result and no neighbour's tap: its lit neighbours would grey it, and it them
// (bumps turned away from the light under a host that tests its rays against them: docs/do-no-harm.md,
// "Normal-mapped normals").
vec2 dnsr_filter_receiver(int l, ivec2 p, ivec2 lid, int step, float zc, vec3 nc) {
    vec4 settings = dnsr_get_filter_settings();
    float kernel[2] = float[2](1.0, settings.x);
    float normal_power = settings.y;
    vec2 c = dnsr_center_signal(l, p, lid);
    if (dnsr_final_signal(c) || (dnsr_converged_signal(c) && dnsr_pass_hard(l, p, zc))) return c;
    float v[9];
    dnsr_variance_neighbourhood(l, p, lid, c, v);
    if (dnsr_passes_through(c, v)) return dnsr_run_signal(c);
    float inv_sigma = dnsr_inv_shadow_sigma(v, settings.w);
    float inv_depth_sigma = 1.0 / dnsr_get_depth_similarity_sigma();
    float falloff = dnsr_pass_penumbra_falloff(l, p, zc);
    float weight_sum = 1.0;
    float mean_sum = c.x;
    float var_sum = c.y;
    for (int j = -1; j <= 1; ++j) {
        for (int i = -1; i <= 1; ++i) {
            if (i == 0 && j == 0) continue;
            if (!dnsr_inside(p + ivec2(i, j) * step)) continue;
            vec2 n;
            vec4 g;
            dnsr_tap(l, p, lid, i, j, step, n, g);
            float zq = g.x;
            if (zq < 0.0 || dnsr_final_signal(n)) continue;
            // The shadow and depth edge stops and the penumbra kernel share one exp.
            float w = kernel[abs(i)] * kernel[abs(j)]
                    * exp(-(abs(c.x - n.x) * inv_sigma + abs(zc - zq) * inv_depth_sigma
                            + float((i * i + j * j) * step * step) * falloff))
                    * pow(max(dot(nc, g.yzw), 0.0), normal_power);
            weight_sum += w;
            mean_sum += w * n.x;
            var_sum += w * w * n.y;
        }
    }
    return vec2(clamp(mean_sum / weight_sum, 0.0, 1.0), dnsr_unconverged_variance(max(var_sum / (weight_sum * weight_sum), 0.0)));
}

// Pixel p of a block that is not cleared (its tile's metadata `meta`, its guide).
void dnsr_filter_active(int l, ivec2 p, ivec2 lid, int step, uint meta, vec4 guide) {
    float zc = guide.x;
    vec2 result = zc < 0.0 ? DNSR_SKY_SIGNAL
                : ((meta & DNSR_TILE_CLEARED) != 0u ? dnsr_cleared_value(true, meta)
                                                   : dnsr_filter_receiver(l, p, lid, step, zc, guide.yzw));
    dnsr_filter_write(l, p, result, zc >= 0.0, meta);
}

#ifndef DNSR_LATER_PASS
// The first pass over a group of DNSR_WIDE_GROUP_SIZE pixels.
void dnsr_filter(ivec2 gid, ivec2 lid) {
    ivec2 origin = gid * DNSR_WIDE_GROUP_SIZE;
    ivec2 p = origin + lid;
    int invocation = lid.y * DNSR_WIDE_GROUP_SIZE.x + lid.x;

    ivec2 tiles = (dnsr_get_extent() + DNSR_TILE_SIZE - 1) / DNSR_TILE_SIZE;
    ivec2 base_tile = origin / DNSR_TILE_SIZE;
    for (int i = invocation; i < DNSR_META_TILES.x * DNSR_META_TILES.y; i += DNSR_WIDE_GROUP_INVOCATIONS) {
        ivec2 m = ivec2(i % DNSR_META_TILES.x, i / DNSR_META_TILES.x);
        ivec2 t = base_tile + m;
        bool inside = all(greaterThanEqual(t, ivec2(0))) && all(lessThan(t, tiles));
        // Tiles outside the rectangle count as cleared: they hold no pixel to filter.
        dnsr_meta[m.y][m.x] = inside ? dnsr_read_tile_meta(t) : DNSR_TILE_CLEARED;
    }
    // The pixel's depth and normal (the depth copy's) fetched before the barrier, so that they arrive with the
    // tiles' metadata: fetched after it, an all-lit frame's pass took 0.128 ms at 4K on an H200 instead of 0.087.
    // Clamped: an invocation outside the rectangle returns below.
    ivec2 fetched = min(p, dnsr_get_extent() - 1);
    float depth = dnsr_read_depth(fetched);
    vec3 normal = dnsr_read_normal(fetched);
    // This frame's moments: classification stored them for receivers in tiles it did not clear only, the others'
    // are known (dnsr_cleared_moments). Fetched whatever the pixel, with its depth: a fetch that waits for the
    // depth or the tile's metadata made this pass 0.017 ms slower at 4K on an H200 where every tile is active
    // (docs/bench/h200-2026-11-30-cleared-moments).
    uvec2 stored = dnsr_read_frame_moments(fetched);
    barrier();

    // The apron is loaded when any block of the group is not cleared (the whole group decides alike, so the
    // barrier is reached by every invocation or by none).
    bool any_active = false;
    for (int by = 0; by < DNSR_WIDE_GROUP_SIZE.y / DNSR_GROUP_SIZE.y; ++by) {
        for (int bx = 0; bx < DNSR_WIDE_GROUP_SIZE.x / DNSR_GROUP_SIZE.x; ++bx) {
            any_active = any_active || !dnsr_block_cleared(ivec2(bx, by) * DNSR_BLOCK_TILES);
        }
    }
    if (any_active) {
        dnsr_load_apron(origin, invocation);
        barrier();
    }

    if (!dnsr_inside(p)) return;
    ivec2 m = (lid / DNSR_GROUP_SIZE) * DNSR_BLOCK_TILES;
    uint meta = dnsr_meta[m.y + (lid.y % DNSR_GROUP_SIZE.y) / DNSR_TILE_SIZE.y][m.x];
    bool receiver = dnsr_is_receiver(depth);
    // This frame's moments, kept for the next frame's classification (which reads them at other pixels than its
    // own, so classification cannot update them in place).
    vec4 known = dnsr_cleared_moments(receiver, (meta & DNSR_TILE_LIT) != 0u);
    dnsr_write_kept_moments(p, receiver && (meta & DNSR_TILE_CLEARED) == 0u ? stored
                                                                            : uvec2(dnsr_pack_moments(known), floatBitsToUint(known.y)));
    // The later passes weigh their taps by these, and next frame's classification compares its reprojected depth
    // and its normal with them (the depth copy): kept as a linear depth, which a 16-bit float code holds finely
    // enough at any scale (the device depth needs 32 bits), and a normal in 8+8 bits. Written here, not in
    // classification, which reads last frame's from the same image.
    float linear_depth = dnsr_linear_depth(dnsr_uv_to_ndc(dnsr_pixel_uv(p)), depth);
    if (dnsr_block_cleared(m)) {
        // Everywhere, cleared blocks included: the later passes tap them, and the next frame reads them. So are the
        // history and the signal (this pass never skips cleared blocks: the history is not in place, and writing
        // the signal only where the second pass reads it, near tiles that are not cleared, measured slower on an
        // H200, docs/performance.md).
        dnsr_write_depth_copy(p, receiver ? linear_depth : -1.0, receiver ? normal : vec3(0.0));
        dnsr_filter_write(0, p, dnsr_cleared_value(receiver, meta), receiver, meta);
        return;
    }
    int k = dnsr_apron_index(lid, 0, 0);
    vec4 guide = vec4(dnsr_apron_depth[k], dnsr_apron_normal[k]);
    // The G-buffer's normal, which next frame's classification compares with its own. (The geometric normal here
    // too, the later passes' guide, with classification comparing its own geometric normal: the scene family's
    // mean RMSE 2.6% worse with the G-buffer's normals, 1.8% better with normal-mapped ones, docs/do-no-harm.md.)
    dnsr_write_depth_copy(p, guide.x, receiver ? normal : vec3(0.0));
    dnsr_filter_active(0, p, lid, 1, meta, guide);
}
#else
// A later pass over a group of DNSR_WIDE_GROUP_SIZE pixels: each 8x8 block on its own.
void dnsr_filter(ivec2 gid, ivec2 lid) {
    ivec2 origin = gid * DNSR_WIDE_GROUP_SIZE + (lid / DNSR_GROUP_SIZE) * DNSR_GROUP_SIZE;
    ivec2 p = gid * DNSR_WIDE_GROUP_SIZE + lid;
    if (!dnsr_inside(p)) return;

    // Both tiles of the block cleared (uniform or no receivers): nothing to filter, no neighbourhood to read.
    ivec2 tile = origin / DNSR_TILE_SIZE;
    uint meta_top = dnsr_read_tile_meta(tile);
    uint meta_bottom = origin.y + DNSR_TILE_SIZE.y < dnsr_get_extent().y ? dnsr_read_tile_meta(tile + ivec2(0, 1)) : meta_top;
    uint meta = p.y - origin.y < DNSR_TILE_SIZE.y ? meta_top : meta_bottom;
    if ((meta_top & meta_bottom & DNSR_TILE_CLEARED) != 0u) {
        // Cleared values are already where this pass would write them (classification wrote the output and the
        // reprojection image): nothing to do.
        if (dnsr_get_skip_cleared()) return;
        bool receiver = dnsr_is_receiver(dnsr_read_depth(p));
        dnsr_filter_write(0, p, dnsr_cleared_value(receiver, meta), receiver, meta);
        return;
    }
    dnsr_filter_active(0, p, lid, dnsr_get_filter_step(), meta, dnsr_read_guide(p));
}

#ifdef DNSR_LIGHT_SLOTS_VARIANT
// A later pass for several lights at once (one per slot): per tap the guide is fetched and the depth, normal and
// kernel factors are computed once for every light; each light fetches only its signal. Each light's arithmetic is
// dnsr_filter_receiver's, term for term.
void dnsr_filter_lights(ivec2 gid, ivec2 lid) {
    ivec2 origin = gid * DNSR_WIDE_GROUP_SIZE + (lid / DNSR_GROUP_SIZE) * DNSR_GROUP_SIZE;
    ivec2 p = gid * DNSR_WIDE_GROUP_SIZE + lid;
    if (!dnsr_inside(p)) return;
    int count = dnsr_get_light_count();

    // Each light's tile metadata, and whether both tiles of its block are cleared.
    ivec2 tile = origin / DNSR_TILE_SIZE;
    bool has_bottom = origin.y + DNSR_TILE_SIZE.y < dnsr_get_extent().y;
    bool top_half = p.y - origin.y < DNSR_TILE_SIZE.y;
    uint meta[DNSR_LIGHT_SLOTS];
    bool block_cleared[DNSR_LIGHT_SLOTS];
    bool any_active = false, any_cleared = false;
    [[unroll]] for (int l = 0; l < DNSR_LIGHT_SLOTS; ++l) {
        meta[l] = DNSR_TILE_CLEARED;
        block_cleared[l] = true;
        if (l >= count) continue;
        uint top = dnsr_read_light_tile_meta(l, tile);
        uint bottom = has_bottom ? dnsr_read_light_tile_meta(l, tile + ivec2(0, 1)) : top;
        meta[l] = top_half ? top : bottom;
        block_cleared[l] = (top & bottom & DNSR_TILE_CLEARED) != 0u;
        any_active = any_active || !block_cleared[l];
        any_cleared = any_cleared || block_cleared[l];
    }

    // Lights whose block is cleared: as dnsr_filter's (nothing to do when the values are in place).
    if (any_cleared && !dnsr_get_skip_cleared()) {
        bool receiver = dnsr_is_receiver(dnsr_read_depth(p));
        [[unroll]] for (int l = 0; l < DNSR_LIGHT_SLOTS; ++l) {
            if (l < count && block_cleared[l]) dnsr_filter_write(l, p, dnsr_cleared_value(receiver, meta[l]), receiver, meta[l]);
        }
    }
    if (!any_active) return;

    vec4 guide = dnsr_read_guide(p);
    float zc = guide.x;
    vec3 nc = guide.yzw;
    int step = dnsr_get_filter_step();
    vec4 settings = dnsr_get_filter_settings();
    float kernel[2] = float[2](1.0, settings.x);
    float normal_power = settings.y;
    float inv_depth_sigma = 1.0 / dnsr_get_depth_similarity_sigma();

    // The lights this pixel filters, and each one's centre, edge-stop sigma and penumbra falloff.
    // A light whose pixel passes through (converged among converged neighbours, or under a hard penumbra) keeps
    // its pass-through signal in c.
    bool filtering[DNSR_LIGHT_SLOTS], passes[DNSR_LIGHT_SLOTS];
    vec2 c[DNSR_LIGHT_SLOTS];
    float inv_sigma[DNSR_LIGHT_SLOTS], falloff[DNSR_LIGHT_SLOTS];
    float weight_sum[DNSR_LIGHT_SLOTS], mean_sum[DNSR_LIGHT_SLOTS], var_sum[DNSR_LIGHT_SLOTS];
    [[unroll]] for (int l = 0; l < DNSR_LIGHT_SLOTS; ++l) {
        filtering[l] = l < count && !block_cleared[l] && zc >= 0.0 && (meta[l] & DNSR_TILE_CLEARED) == 0u;
        passes[l] = false;
        c[l] = vec2(0.0);
        inv_sigma[l] = falloff[l] = 0.0;
        if (!filtering[l]) continue;
        c[l] = dnsr_center_signal(l, p, lid);
        // As in dnsr_filter_receiver: a final pixel, a hard penumbra's sample (flagged converged), or a converged
        // pixel among converged ones, is the result alone.
        if (dnsr_final_signal(c[l]) || (dnsr_converged_signal(c[l]) && dnsr_pass_hard(l, p, zc))) {
            filtering[l] = false;
            passes[l] = true;
            continue;
        }
        float v[9];
        dnsr_variance_neighbourhood(l, p, lid, c[l], v);
        if (dnsr_passes_through(c[l], v)) {
            filtering[l] = false;
            passes[l] = true;
            c[l] = dnsr_run_signal(c[l]);
            continue;
        }
        inv_sigma[l] = dnsr_inv_shadow_sigma(v, settings.w);
        falloff[l] = dnsr_pass_penumbra_falloff(l, p, zc);
    }
    [[unroll]] for (int l = 0; l < DNSR_LIGHT_SLOTS; ++l) {
        weight_sum[l] = 1.0;
        mean_sum[l] = c[l].x;
        var_sum[l] = c[l].y;
    }
    for (int j = -1; j <= 1; ++j) {
        for (int i = -1; i <= 1; ++i) {
            if (i == 0 && j == 0) continue;
            ivec2 q = p + ivec2(i, j) * step;
            if (!dnsr_inside(q)) continue;
            vec4 g = dnsr_read_guide(q);
            float zq = g.x;
            if (zq < 0.0) continue;
            float kernel_weight = kernel[abs(i)] * kernel[abs(j)];
            float depth_term = abs(zc - zq) * inv_depth_sigma;
            float distance2 = float((i * i + j * j) * step * step);
            float normal_weight = pow(max(dot(nc, g.yzw), 0.0), normal_power);
            [[unroll]] for (int l = 0; l < DNSR_LIGHT_SLOTS; ++l) {
                if (!filtering[l]) continue;
                vec2 n = dnsr_pass_filter_input(l, q);
                if (dnsr_final_signal(n)) continue;
                float w = kernel_weight * exp(-(abs(c[l].x - n.x) * inv_sigma[l] + depth_term + distance2 * falloff[l]))
                        * normal_weight;
                weight_sum[l] += w;
                mean_sum[l] += w * n.x;
                var_sum[l] += w * w * n.y;
            }
        }
    }
    [[unroll]] for (int l = 0; l < DNSR_LIGHT_SLOTS; ++l) {
        if (l >= count || block_cleared[l]) continue;
        vec2 result = zc < 0.0 ? DNSR_SKY_SIGNAL
                    : passes[l] ? c[l]
                    : (!filtering[l] ? dnsr_cleared_value(true, meta[l])
                                     : vec2(clamp(mean_sum[l] / weight_sum[l], 0.0, 1.0),
                                            dnsr_unconverged_variance(max(var_sum[l] / (weight_sum[l] * weight_sum[l]), 0.0))));
        dnsr_filter_write(l, p, result, zc >= 0.0, meta[l]);
    }
}
#endif
#endif

#endif
