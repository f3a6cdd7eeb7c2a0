// tile classification: decides per 8x4 tile whether temporal work is needed at all (no receiver, or a uniform
// +-8 px neighbourhood), and for the rest reprojects, tracks temporal moments and blends the clamped history with
// the current 1-spp sample.
#ifndef DNSR_TILE_CLASSIFICATION_GLSL
#define DNSR_TILE_CLASSIFICATION_GLSL
// [[dont_flatten]]: a branch the compiler keeps where both sides would otherwise run for every invocation.
#extension GL_EXT_control_flow_attributes : require

// Local moments use a 17x17 window (radius DNSR_MOMENT_RADIUS = 8, generated from the host's constant). Not a
// runtime setting: the shared tile window below is sized for it, and the uniform-tile test looks at exactly this
// neighbourhood.
//
// One group covers DNSR_WIDE_GROUP_SIZE pixels (several blocks of two tiles each). Tile words around the group:
// its tile columns and one more either side, its tile rows and two more above and below (8 px each way).
const ivec2 DNSR_GROUP_TILES = DNSR_WIDE_GROUP_SIZE / DNSR_TILE_SIZE;
const ivec2 DNSR_WINDOW_TILES = DNSR_GROUP_TILES + ivec2(2, 4);
const int DNSR_WINDOW_ROWS = DNSR_WIDE_GROUP_SIZE.y + 2 * DNSR_MOMENT_RADIUS;

// Lit bits of the window's tiles: exactly lit pixels (v = 1) with a visibility input.
shared uint s_words[DNSR_WINDOW_TILES.y][DNSR_WINDOW_TILES.x];
// The window is as many pixels wide as tall.
const int DNSR_WINDOW_COLUMNS = DNSR_WINDOW_TILES.x * DNSR_TILE_WIDTH;
#ifdef DNSR_VISIBILITY_INPUT
// Visibility input (DNSR_VISIBILITY_INPUT): each window pixel's visibility in [0, 1] (0 outside the rectangle),
// and the bits of exactly shadowed pixels (v = 0) for the uniform test.
shared float s_visibility[DNSR_WINDOW_ROWS][DNSR_WINDOW_COLUMNS];
shared uint s_dark[DNSR_WINDOW_TILES.y][DNSR_WINDOW_TILES.x];
#endif
// Horizontal pass of the separable Gaussian for the group's columns over its window rows, as float bits:
// x = weighted lit count, y = weight of the taps inside the render rectangle. With the surface window y holds
// the weighted lit count and the weight over the row's surface instead, each a 16-bit fixed-point number
// (dnsr_surface_sums; the whole window's weight is then the column's g_inside_weight per row). With a visibility
// input: x = weighted sum of visibilities, y = of their squares (the weight is the column's g_inside_weight).
// Bits, so that the surface window's normal codes can borrow it first (two window pixels per entry).
shared uvec2 s_hsum[DNSR_WINDOW_ROWS][DNSR_WIDE_GROUP_WIDTH];
vec2 dnsr_hsum(int row, int column) { return uintBitsToFloat(s_hsum[row][column]); }
#ifndef DNSR_VISIBILITY_INPUT
// The surface window (dnsr_window_and_surface_moments): with the run features and without penumbra guidance (with it the
// scene family measured 12 scenes better and 14 worse: the blockers' distance already bounds the penumbra).
const bool DNSR_SURFACE_WINDOW = DNSR_SPEC_STABLE_HISTORY && !DNSR_SPEC_PENUMBRA_GUIDED;
// Bit k of window row r: window pixels (k, r) and (k + 1, r) do not lie on one surface (dnsr_same_surface).
// Little shared memory on purpose: classification's time on an H100 rose 12% with 10 KB per group and 36% with
// 12.4 KB (7.6 KB before; up to 9.2 KB cost nothing), every preset alike.
shared uint s_row_breaks[DNSR_WINDOW_ROWS];
// Bit k of group column c: window pixels (c + radius, k) and (c + radius, k + 1) do not.
shared uint s_column_breaks[DNSR_WIDE_GROUP_WIDTH];
#endif
// Closeness key (smaller = closer to the camera) and velocity of each pixel, for the 2x2 quad vote.
shared float s_quad_key[DNSR_WIDE_GROUP_HEIGHT][DNSR_WIDE_GROUP_WIDTH];
shared vec2 s_quad_velocity[DNSR_WIDE_GROUP_HEIGHT][DNSR_WIDE_GROUP_WIDTH];
shared uint s_tile_has_receiver[DNSR_GROUP_TILES.y][DNSR_GROUP_TILES.x];
// dnsr_uniform_state of the group's tiles (the receiver test aside), computed once per tile.
shared uint s_uniform[DNSR_GROUP_TILES.y][DNSR_GROUP_TILES.x];
// Per window tile, from its word where it is loaded: bit 0 every valid pixel exactly lit, bit 1 every one exactly
// shadowed (both for a tile outside the rectangle). The tile writers' uniform test then ANDs 15 of them; testing
// the 15 words against their valid bits itself kept a cleared group waiting on one invocation per tile.
shared uint s_window_uniform[DNSR_WINDOW_TILES.y][DNSR_WINDOW_TILES.x];
// First tile of the group's window (same for every invocation of the group).
ivec2 g_window_base;

// A shadow that moved over a still surface (DNSR_SPEC_MOVING_SHADOWS): per window tile, this frame's samples (in
// units of DNSR_MOVING_SAMPLE_UNIT per sample) on the pixels whose last frame's moments are not empty, and those moments' summed terms
// (dnsr_moment_terms); per tile of the group, whether the shadow moved there (dnsr_shadow_moved).
shared uint s_moving_samples[DNSR_WINDOW_TILES.y][DNSR_WINDOW_TILES.x];
shared uint s_moving_terms[DNSR_WINDOW_TILES.y][DNSR_WINDOW_TILES.x];
shared uint s_moved[DNSR_GROUP_TILES.y][DNSR_GROUP_TILES.x];
// Per tile of the group, whether the 3x3 tiles around it were all quiet long enough (dnsr_quiet_tiles); last frame's
// quiet counts of the window's tiles (the group's tiles and their neighbours), loaded with the tile words.
shared uint s_hard_tile[DNSR_GROUP_TILES.y][DNSR_GROUP_TILES.x];
shared uint s_quiet[DNSR_WINDOW_TILES.y][DNSR_WINDOW_TILES.x];
// Whether a receiver of the group whose G-buffer normal faces away from the light, inside a plane that faces it
// (dnsr_plane_normal), has a lit sample this frame: the host's rays do not test its normals (normal-mapped ones),
// so a shadowed sample of such a receiver is not exact (dnsr_plane_faces_light).
shared uint s_lit_against_normal;
// Whether a receiver of the group whose G-buffer normal faces away from the whole light (N.L below -sin of its
// angular radius) has a lit sample this frame: the host's rays do not test those normals, so no shadowed sample of
// the group is made final (a wrong normal would keep it from the filter).
shared uint s_lit_away_from_disc;

// Penumbra guidance: every window tile's (sum, count) of usable hit distances over its shadowed pixels, summed
// from DNSR_HIT_PARTS partial sums of DNSR_HIT_PIXELS pixels each. The partial sums borrow s_hsum before the
// moment sums fill it.
const int DNSR_WINDOW_TILE_COUNT = DNSR_WINDOW_TILES.x * DNSR_WINDOW_TILES.y;
const int DNSR_HIT_PARTS = DNSR_WIDE_GROUP_INVOCATIONS / DNSR_WINDOW_TILE_COUNT;
const int DNSR_HIT_PIXELS = DNSR_TILE_WIDTH * DNSR_TILE_HEIGHT / DNSR_HIT_PARTS;
shared vec2 s_hit[DNSR_WINDOW_TILES.y][DNSR_WINDOW_TILES.x];

void dnsr_store_hit_part(int i, vec2 part) { s_hsum[i / DNSR_WIDE_GROUP_WIDTH][i % DNSR_WIDE_GROUP_WIDTH] = floatBitsToUint(part); }
vec2 dnsr_load_hit_part(int i) { return dnsr_hsum(i / DNSR_WIDE_GROUP_WIDTH, i % DNSR_WIDE_GROUP_WIDTH); }

ivec2 dnsr_tile_count() { return (dnsr_get_extent() + DNSR_TILE_SIZE - 1) / DNSR_TILE_SIZE; }

// Bits of a tile whose pixels lie inside the render rectangle (0 for a tile outside it).
uint dnsr_tile_valid_bits(ivec2 tile) {
    if (any(lessThan(tile, ivec2(0))) || any(greaterThanEqual(tile, dnsr_tile_count()))) return 0u;
    if (all(lessThanEqual((tile + 1) * DNSR_TILE_SIZE, dnsr_get_extent()))) return 0xFFFFFFFFu;
    ivec2 n = min(dnsr_get_extent() - tile * DNSR_TILE_SIZE, DNSR_TILE_SIZE);
    uint row = n.x >= 8 ? 0xFFu : ((1u << uint(n.x)) - 1u);
    uint bits = 0u;
    for (int r = 0; r < n.y; ++r) bits |= row << uint(8 * r);
    return bits;
}

ivec2 dnsr_window_base_tile(ivec2 group_origin) { return (group_origin / DNSR_TILE_SIZE) - ivec2(1, 2); }

// The hit-mask variant and the visibility variant (DNSR_VISIBILITY_INPUT) differ in the functions below, each
// written twice rather than folded into one: the hit-mask variant's code stays exactly what it was before the
// visibility input existed (one shared version cost it 4.6% of its time on an H100).
#ifdef DNSR_VISIBILITY_INPUT
// This frame's sample of the group's pixel `lid`: its visibility.
float dnsr_window_sample(ivec2 lid) { return s_visibility[lid.y + DNSR_MOMENT_RADIUS][lid.x + DNSR_MOMENT_RADIUS]; }

// Only exact samples (0 or 1) extend runs of identical samples: a pixel whose rays disagreed lies in a penumbra.
bool dnsr_is_exact(float x) { return x == 0.0 || x == 1.0; }
#else
// Lit bit of a pixel in the group's window. The caller ensures the pixel is inside the render rectangle.
float dnsr_window_lit(ivec2 p, ivec2 base_tile) {
    ivec2 w = (p >> ivec2(3, 2)) - base_tile;
    return float((s_words[w.y][w.x] >> dnsr_tile_bit(p)) & 1u);
}
#endif

// Gaussian weights of the local-moment window, computed once per invocation (the loops over them unroll, so the
// table lives in registers).
float g_moment_weight[DNSR_MOMENT_RADIUS + 1];

void dnsr_init_moment_weights() {
    for (int i = 0; i <= DNSR_MOMENT_RADIUS; ++i) {
        g_moment_weight[i] = exp(-dnsr_get_temporal_settings().w * float(i * i) / 81.0);
    }
}

float dnsr_moment_weight(int i) { return g_moment_weight[abs(i)]; }

// Weight of the taps of the invocation's column inside the render rectangle, per window row.
float g_inside_weight;

#ifdef DNSR_VISIBILITY_INPUT

// Spatial mean and variance of the visibilities around p (normalised over taps inside the rectangle): the
// weighted mean of their squares, not mean - mean^2 as for a binary mask.
vec2 dnsr_local_moments(ivec2 p, ivec2 lid) {
    vec2 sum = vec2(0.0);
    float rows = 0.0;
    for (int j = -DNSR_MOMENT_RADIUS; j <= DNSR_MOMENT_RADIUS; ++j) {
        float w = dnsr_moment_weight(j);
        sum += w * dnsr_hsum(lid.y + DNSR_MOMENT_RADIUS + j, lid.x);
        int y = p.y + j;
        rows += y >= 0 && y < dnsr_get_extent().y ? w : 0.0;
    }
    float weight = max(rows * g_inside_weight, 1e-20);
    float mean = sum.x / weight;
    return vec2(mean, max(sum.y / weight - mean * mean, 0.0));
}
#else
// A unit normal (or vec3(0): sky, unknown) as three signed 10-bit integers of scale DNSR_SURFACE_NORMAL_SCALE in
// one word. floor(v + 0.5), not round(): GLSL leaves round()'s halves to the implementation.
uint dnsr_normal_code(vec3 n) {
    uvec3 c = uvec3(ivec3(floor(n * float(DNSR_SURFACE_NORMAL_SCALE) + 0.5))) & 1023u;
    return c.x | (c.y << 10) | (c.z << 20);
}

ivec3 dnsr_normal_code_components(uint code) {
    int c = int(code);
    return ivec3(bitfieldExtract(c, 0, 10), bitfieldExtract(c, 10, 10), bitfieldExtract(c, 20, 10));
}

// Two normal codes of one surface: within acos(DNSR_TURNED_NORMAL_COS_PERCENT / 100) of each other, as an exact
// integer test (sky and unknown normals, code 0, never are).
bool dnsr_same_surface(uint a, uint b) {
    ivec3 u = dnsr_normal_code_components(a), v = dnsr_normal_code_components(b);
    return u.x * v.x + u.y * v.y + u.z * v.z >= DNSR_SURFACE_DOT_MIN;
}

// The normal code of window pixel w, while s_hsum holds them.
uint dnsr_window_code(ivec2 w) {
    uvec2 pair = s_hsum[w.y][w.x >> 1];
    return (w.x & 1) == 0 ? pair.x : pair.y;
}

// The bits first..last around bit `at` that no break separates from it (bit k of `breaks`: k and k + 1 apart).
ivec2 dnsr_unbroken_run(uint breaks, int at) {
    uint below = (1u << uint(at)) - 1u;
    int first = (breaks & below) == 0u ? 0 : findMSB(breaks & below) + 1;
    int last = (breaks & ~below) == 0u ? 31 : findLSB(breaks & ~below);
    return ivec2(first, last);
}

uint dnsr_run_bits(ivec2 run) {
    uint to_last = run.y >= 31 ? 0xFFFFFFFFu : (1u << uint(run.y + 1)) - 1u;
    return to_last & ~((1u << uint(run.x)) - 1u);
}

// A row's weighted lit count and weight over its surface, as 16-bit fixed-point numbers of scale
// DNSR_SURFACE_SUM_SCALE in one word: 4 bytes instead of 8 keep classification within the shared memory that
// costs nothing (s_row_breaks).
uint dnsr_pack_surface_sums(vec2 sums) {
    uvec2 q = uvec2(floor(sums * float(DNSR_SURFACE_SUM_SCALE) + 0.5));
    return q.x | (q.y << 16);
}

vec2 dnsr_surface_sums(uint packed) {
    return vec2(packed & 0xFFFFu, packed >> 16) / float(DNSR_SURFACE_SUM_SCALE);
}

// Mean and variance of a binary mask from its weighted lit count and weight.
vec2 dnsr_binary_moments(float lit, float weight) {
    float mean = lit / max(weight, 1e-20);
    return vec2(mean, max(mean - mean * mean, 0.0));
}

// Spatial mean and variance of the binary mask around p (normalised over taps inside the rectangle).
vec2 dnsr_local_moments(ivec2 lid) {
    vec2 sum = vec2(0.0);
    for (int j = -DNSR_MOMENT_RADIUS; j <= DNSR_MOMENT_RADIUS; ++j) {
        sum += dnsr_moment_weight(j) * dnsr_hsum(lid.y + DNSR_MOMENT_RADIUS + j, lid.x);
    }
    return dnsr_binary_moments(sum.x, sum.y);
}

// With the surface window: xy the whole window's mean and variance (its weight: the column's g_inside_weight times
// the rows inside the rectangle), zw the same over p's own surface: the taps that a chain of neighbours on one
// surface (dnsr_same_surface, adjacent pixels) joins to p, separably: up and down p's column, then along each row
// from its pixel in p's column. Across a crease, a fin or a silhouette the window otherwise mixes in the other
// face's samples: the clamp then holds an edge pixel's history towards the other face's value, and pixels whose
// input was exact turn soft.
vec4 dnsr_window_and_surface_moments(ivec2 p, ivec2 lid) {
    ivec2 rows = dnsr_unbroken_run(s_column_breaks[lid.x], lid.y + DNSR_MOMENT_RADIUS);
    vec2 window = vec2(0.0);
    vec2 surface = vec2(0.0);
    for (int j = -DNSR_MOMENT_RADIUS; j <= DNSR_MOMENT_RADIUS; ++j) {
        int row = lid.y + DNSR_MOMENT_RADIUS + j;
        float w = dnsr_moment_weight(j);
        int y = p.y + j;
        window += vec2(w * dnsr_hsum(row, lid.x).x, y >= 0 && y < dnsr_get_extent().y ? w : 0.0);
        if (row >= rows.x && row <= rows.y) surface += w * dnsr_surface_sums(s_hsum[row][lid.x].y);
    }
    return vec4(dnsr_binary_moments(window.x, window.y * g_inside_weight), dnsr_binary_moments(surface.x, surface.y));
}
#endif

// 0: mixed, 1: every valid pixel within +-8 px of the group's tile `t` is exactly lit, 2: every one is exactly
// shadowed.
uint dnsr_uniform_state(ivec2 t) {
    uint both = 3u;
    for (int r = 0; r < 5; ++r) {
        for (int c = 0; c < 3; ++c) both &= s_window_uniform[t.y + r][t.x + c];
    }
    return (both & 1u) != 0u ? 1u : ((both & 2u) != 0u ? 2u : 0u);
}

// 0: the group's tile `t` needs temporal work, 1: cleared lit (no receiver, or all lit), 2: cleared shadowed.
uint dnsr_tile_state(ivec2 t) { return s_tile_has_receiver[t.y][t.x] == 0u ? 1u : s_uniform[t.y][t.x]; }

// Scales a Welford state (mean kept) to represent `f` times as many samples.
void dnsr_scale_moments(inout vec4 m, float f) { m.y *= f; m.z *= f; }

// The run of identical samples after sample x, from the run before it: +n when the last n samples were lit, -n
// when they were shadowed, at most DNSR_MAX_SAMPLE_RUN long. A run that breaks a stable run (at least
// `stable_after` samples) of the other value carries a half: n + 0.5, until it is confirmed.
float dnsr_sample_run(float previous, float x, float stable_after) {
    float longest = float(DNSR_MAX_SAMPLE_RUN);
    bool lit = x >= 0.5;
    if (lit ? previous > 0.0 : previous < 0.0) {
        float n = min(abs(previous) + 1.0, longest);
        return lit ? n : -n;
    }
    float start = stable_after > 0.0 && abs(previous) >= stable_after ? 1.5 : 1.0;
    return lit ? start : -start;
}

#ifdef DNSR_VISIBILITY_INPUT
// The run after a sample that is not exact (a pixel whose rays disagreed): no run of identical samples, but a
// stable run it interrupts is broken (a marker of half a sample of the other value), and a break already under way
// stays one, so that the first exact sample of the other value after a penumbra passed restarts the history as it
// does after a single ray.
float dnsr_fractional_run(float previous, float stable_after) {
    float n = abs(previous);
    if (stable_after > 0.0 && n >= stable_after) return previous > 0.0 ? -0.5 : 0.5;
    if (fract(n) == 0.5) return previous > 0.0 ? 0.5 : -0.5;
    return 0.0;
}
#endif

bool dnsr_usable_hit_distance(float d) { return d > 0.0 && d < 1.0 / 0.0; }

// Penumbra guidance, first half: invocation `thread` sums the usable hit distances of its share of one window
// tile's shadowed pixels. Followed by a barrier and dnsr_reduce_hit_parts.
void dnsr_sum_hit_part(int thread) {
    int k = thread / DNSR_HIT_PARTS;
    ivec2 w = ivec2(k % DNSR_WINDOW_TILES.x, k / DNSR_WINDOW_TILES.x);
    ivec2 tile = g_window_base + w;
    // Pixels with a ray that hit: not exactly lit.
    uint shadowed = ~s_words[w.y][w.x] & dnsr_tile_valid_bits(tile);
    vec2 part = vec2(0.0);
    for (int i = 0; i < DNSR_HIT_PIXELS; ++i) {
        int bit = (thread % DNSR_HIT_PARTS) * DNSR_HIT_PIXELS + i;
        if (((shadowed >> uint(bit)) & 1u) == 0u) continue;
        float d = dnsr_read_hit_distance(tile * DNSR_TILE_SIZE + ivec2(bit % DNSR_TILE_WIDTH, bit / DNSR_TILE_WIDTH));
        if (dnsr_usable_hit_distance(d)) part += vec2(d, 1.0);
    }
    dnsr_store_hit_part(thread, part);
}

// Second half: one invocation per window tile adds its parts up, in order.
void dnsr_reduce_hit_parts(int thread) {
    if (thread >= DNSR_WINDOW_TILE_COUNT) return;
    vec2 sum = vec2(0.0);
    for (int i = 0; i < DNSR_HIT_PARTS; ++i) sum += dnsr_load_hit_part(thread * DNSR_HIT_PARTS + i);
    s_hit[thread / DNSR_WINDOW_TILES.x][thread % DNSR_WINDOW_TILES.x] = sum;
}

// The group's tile `t`: mean hit distance over the +-8 px window (the uniform test's), -1 when none is known.
float dnsr_tile_blocker(ivec2 t) {
    vec2 sum = vec2(0.0);
    for (int r = 0; r < 5; ++r) {
        for (int c = 0; c < 3; ++c) sum += s_hit[t.y + r][t.x + c];
    }
    return sum.y > 0.0 ? sum.x / sum.y : -1.0;
}

// A previous run that is stable (stable_after > 0 samples or more) and of the same value as sample x, which is
// exact.
bool dnsr_stable_agreeing(float run, float x, float stable_after) {
#ifdef DNSR_VISIBILITY_INPUT
    if (!dnsr_is_exact(x)) return false;
#endif
    return stable_after > 0.0 && abs(run) >= stable_after && (x >= 0.5 ? run > 0.0 : run < 0.0);
}

// The bilinear blend of a footprint's four texels (x, then y) at t (texel units, centres at integers): what
// dnsr_read_history returns for the same position.
float dnsr_bilinear(float texels[4], vec2 t) {
    vec2 f = t - floor(t);
    return mix(mix(texels[0], texels[1], f.x), mix(texels[2], texels[3], f.x), f.y);
}

// Texel k of the bilinear footprint whose top-left texel is `footprint` (k & 1: the right column, k & 2: the lower
// row), clamped to the rectangle, and its bilinear weight at fraction f of the history position past that texel.
ivec2 dnsr_footprint_texel(ivec2 footprint, int k) { return clamp(footprint + ivec2(k & 1, k >> 1), ivec2(0), dnsr_get_extent() - 1); }
float dnsr_footprint_weight(vec2 f, int k) { return ((k & 1) != 0 ? f.x : 1.0 - f.x) * ((k & 2) != 0 ? f.y : 1.0 - f.y); }

#ifdef DNSR_HOST_PREVIOUS_GBUFFER
// Last frame's linear depth (-1: no receiver) and normal from the host's previous depth and normals, as read: a
// depth copy's rounding of them (its depth code and octahedral normal) cost Quality's classification 0.05 ms of
// 0.61 at 4K on an H200 under a panning camera, for no gain (docs/bench/h200-2026-11-30-host-previous). Linearised
// with this frame's inverse projection, as the reprojected depth they are compared with is (its jitter does not
// move a linear depth). The normal is read only where last frame had a receiver (the depth test passed there, or
// its moments hold samples), so the sky's normal is never asked for.
float dnsr_read_previous_depth(ivec2 p) { return dnsr_receiver_linear_depth(p, dnsr_read_host_previous_depth(p)); }
vec3 dnsr_read_previous_normal(ivec2 p) { return dnsr_read_host_previous_normal(p); }
#endif

// The normal of the plane that receiver q (device depth `depth`) lies inside, on the side of its G-buffer normal
// `shading`: both its neighbours along each axis are receivers on one line through it (within about 8 degrees);
// vec3(0) elsewhere (an edge, a crease, a feature of 1-2 px, whose neighbours give another surface's plane).
vec3 dnsr_plane_normal(ivec2 q, float depth, vec3 shading) {
    vec3 w = dnsr_world_position(q, depth);
    vec3 tangent[2];
    for (int a = 0; a < 2; ++a) {
        ivec2 axis = ivec2(1 - a, a);
        ivec2 r0 = q - axis, r1 = q + axis;
        if (!dnsr_inside(r0) || !dnsr_inside(r1)) return vec3(0.0);
        float d0 = dnsr_read_depth(r0), d1 = dnsr_read_depth(r1);
        if (!dnsr_is_receiver(d0) || !dnsr_is_receiver(d1)) return vec3(0.0);
        vec3 back = w - dnsr_world_position(r0, d0), ahead = dnsr_world_position(r1, d1) - w;
        float cross_term = dot(back, ahead);
        if (!(cross_term > 0.0) || cross_term * cross_term < float(DNSR_PLANE_LINE_COS2_PERCENT) / 100.0 * dot(back, back) * dot(ahead, ahead)) return vec3(0.0);
        tangent[a] = back + ahead;
    }
    vec3 n = cross(tangent[0], tangent[1]);
    float l = dot(n, n);
    if (!(l > 0.0) || isinf(l)) return vec3(0.0);
    n *= inversesqrt(l);
    return dot(n, shading) < 0.0 ? -n : n;
}

// Receiver p (device depth `depth`), whose G-buffer normal `shading` faces away from the light at `to_light`, lies inside a plane that faces it: its ray left from a surface that sees the light, and the
// G-buffer's normal is tilted past the light by a normal map.
bool dnsr_plane_faces_light(ivec2 p, float depth, vec3 shading, vec3 to_light) {
    return dot(dnsr_plane_normal(p, depth, shading), to_light) > 0.0;
}

// From world point `world` to the light at homogeneous position `light` (ShadowsDispatch::light_position).
vec3 dnsr_to_light(vec4 light, vec3 world) { return light.xyz - light.w * world; }

// Normal `n` faces away from every point of the light's disc seen along `to_light`: N.L below -sin(angular radius).
bool dnsr_faces_away_from_disc(vec3 n, vec3 to_light) { return dot(n, to_light) < -dnsr_get_light_sin_radius() * length(to_light); }

// Normals a and b (last frame's, this frame's) both known and more than acos(DNSR_TURNED_NORMAL_COS_PERCENT / 100)
// apart.
bool dnsr_normal_turned(vec3 a, vec3 b) {
    return dot(a, a) > 0.0 && dot(b, b) > 0.0 && dot(a, b) < float(DNSR_TURNED_NORMAL_COS_PERCENT) / 100.0;
}

// How much of its linear depth a footprint texel of this surface may differ by per pixel of distance from the
// history position, beyond the disocclusion test's threshold: DNSR_FOOTPRINT_SLOPE_PERCENT of a plane's change at
// the surface's angle to the view (its tan, at most DNSR_FOOTPRINT_MAX_SLOPE).
float dnsr_texel_depth_slope(float depth, float n_dot_v) {
    float tan_angle = min(sqrt(max(1.0 - n_dot_v * n_dot_v, 0.0)) / max(n_dot_v, 1e-3), float(DNSR_FOOTPRINT_MAX_SLOPE));
    return float(DNSR_FOOTPRINT_SLOPE_PERCENT) / 100.0 * dnsr_pixel_footprint(dnsr_get_penumbra_settings(), depth) * tan_angle;
}

// A run whose value is exact sample x's (any length).
bool dnsr_sign_agreeing(float run, float x) {
#ifdef DNSR_VISIBILITY_INPUT
    if (!dnsr_is_exact(x)) return false;
#endif
    return x >= 0.5 ? run > 0.0 : run < 0.0;
}

// Moments whose every sample had one value: the run covers the whole count (and is no break marker), and the
// mean is exactly the run's value, or the run is at least twice the count. The run alone does not tell: a rejected
// history keeps its run but not its count, and a handed-over run (stable_after) can exceed a count that a
// disocclusion restarted, so under a moving camera penumbra pixels whose moments held both values counted as pure
// and converged, and skipped the filter (make accuracy's disocclusion family, member 2000: 0.0531 -> 0.0445). The mean
// alone is too strict: it never returns exactly to 0 or 1, so a pixel that once saw the other value would never
// converge again (a still penumbra tail, seed 1002 of the viewer family: worse than its input); a run twice the
// count outweighs what the moments remember of that sample.
bool dnsr_pure(vec4 mq) {
    return mq.z > 0.0 && abs(mq.w) >= mq.z && fract(abs(mq.w)) == 0.0
        && (mq.x == (mq.w > 0.0 ? 1.0 : 0.0) || abs(mq.w) >= 2.0 * mq.z);
}

// A run of at least `converged_after` (> 0) identical samples that this frame's x does not contradict (x is the
// run's value, or with a checkerboard input an untraced pixel's neighbour mean on the run's side of 0.5: never
// compared for equality, which float rounding of that mean could flip).
bool dnsr_converged(float run, float x, float converged_after) {
    return converged_after > 0.0 && abs(run) >= converged_after && abs(x - (run > 0.0 ? 1.0 : 0.0)) < 0.5;
}

// Last frame resolved the 4x4 texels around history position t (the bilinear footprint and one texel beyond it
// each way): every receiver texel there held one value in all its samples, converged_after or more of the other
// value than x (any number of x's own). No penumbra lies there, so a change of sample that its neighbours share is
// an edge or a thin feature that the moving camera put on this pixel (or that last frame's pixel centres missed),
// not noise.
// All 16 texels are read, no early exit: runtime exits in this pass have made lavapipe leak memory every frame.
bool dnsr_resolved_area(vec2 t, float x, float converged_after) {
    ivec2 base = ivec2(floor(t)) - 1;
    bool resolved = true;
    for (int k = 0; k < 16; ++k) {
        ivec2 q = clamp(base + ivec2(k & 3, k >> 2), ivec2(0), dnsr_get_extent() - 1);
        vec4 mq = dnsr_read_previous_moments(q);
        bool settled = dnsr_pure(mq) && (dnsr_sign_agreeing(mq.w, x) || abs(mq.w) >= converged_after);
        resolved = resolved && (!(mq.z > 0.0) || settled);
    }
    return resolved;
}

// Whether two or more of the 8 pixels around p inside the rectangle hold exactly sample x this frame (sky pixels
// count by their mask bit: the test reads this frame's samples alone, from the window in shared memory).
bool dnsr_two_neighbours_share(ivec2 p, ivec2 lid, float x) {
    int sharing = 0;
    for (int j = -1; j <= 1; ++j) {
        for (int i = -1; i <= 1; ++i) {
            ivec2 d = ivec2(i, j);
            if ((i == 0 && j == 0) || !dnsr_inside(p + d)) continue;
#ifdef DNSR_VISIBILITY_INPUT
            sharing += dnsr_window_sample(lid + d) == x ? 1 : 0;
#else
            sharing += dnsr_window_lit(p + d, g_window_base) == x ? 1 : 0;
#endif
        }
    }
    return sharing >= 2;
}

// What a pixel's stored moments (their first word: dnsr_pack_moments) add to its window tile's sums: its mean (the
// unorm14 code over 16: DNSR_MOVING_SAMPLE_UNIT is one sample) in the low half, its Bernoulli variance mean * (1 - mean) (code *
// (max - code) over 2^16) in the high half; at most 1024 each, so a tile's 32 pixels fit 16 bits. Integers: the
// sums do not depend on the order of the atomics, and the CPU reference sums the same terms.
uint dnsr_moment_terms(uint word) {
    uint code = word & DNSR_MOMENTS_MEAN_MAX;
    return ((code + 8u) >> 4) | (((code * (DNSR_MOMENTS_MEAN_MAX - code)) >> 16) << 16);
}

// Four window pixels per invocation, consecutive in one row of one window tile: their previous moments' terms and
// this frame's samples on them, added to their window tile's sums (dnsr_shadow_moved). Only pixels whose moments
// are not empty (a receiver's) count: the sky's mask bits mean nothing.
const int DNSR_MOVING_PIXELS = DNSR_WINDOW_ROWS * DNSR_WINDOW_COLUMNS / DNSR_WIDE_GROUP_INVOCATIONS;
void dnsr_sum_previous_moments(int thread) {
    ivec2 w = ivec2(thread % (DNSR_WINDOW_COLUMNS / DNSR_MOVING_PIXELS) * DNSR_MOVING_PIXELS,
                    thread / (DNSR_WINDOW_COLUMNS / DNSR_MOVING_PIXELS));
    uint words[DNSR_MOVING_PIXELS];
    for (int k = 0; k < DNSR_MOVING_PIXELS; ++k) {
        ivec2 q = g_window_base * DNSR_TILE_SIZE + w + ivec2(k, 0);
        words[k] = dnsr_inside(q) ? dnsr_read_previous_moments_word(q) : 0u;
    }
    ivec2 t = w / DNSR_TILE_SIZE;
    uint samples = 0u, terms = 0u;
    for (int k = 0; k < DNSR_MOVING_PIXELS; ++k) {
        if (words[k] == 0u) continue;
        terms += dnsr_moment_terms(words[k]);
#ifdef DNSR_VISIBILITY_INPUT
        samples += uint(floor(s_visibility[w.y][w.x + k] * float(DNSR_MOVING_SAMPLE_UNIT) + 0.5));
#else
        samples += ((s_words[t.y][t.x] >> uint((w.y % DNSR_TILE_HEIGHT) * DNSR_TILE_WIDTH + (w.x + k) % DNSR_TILE_WIDTH)) & 1u) * DNSR_MOVING_SAMPLE_UNIT;
#endif
    }
    atomicAdd(s_moving_samples[t.y][t.x], samples);
    atomicAdd(s_moving_terms[t.y][t.x], terms);
}

// Whether the shadow moved over the tile's neighbourhood (one tile either side, two above and below: the window
// tiles around it) since last frame: this frame's samples differ from last frame's accumulated means there by more
// than Settings::moving_shadow_sigmas of their Bernoulli spread, plus DNSR_MOVING_MARGIN_SAMPLES. The accumulated
// means, not last frame's samples: they hold the few frames the history holds, so the spread is this frame's alone
// (`make accuracy`'s moving family, at 3 deviations: median ratio to the input 0.326 this way, 0.444 against last
// frame's samples; docs/do-no-harm.md). No early return on the settings: with one, lavapipe (Mesa 22.3) leaked
// memory frame after frame.
bool dnsr_shadow_moved(ivec2 own_tile) {
    uint samples = 0u, means = 0u, variances = 0u;
    for (int dy = 0; dy <= 4; ++dy) {
        for (int dx = 0; dx <= 2; ++dx) {
            ivec2 w = own_tile + ivec2(dx, dy);
            samples += s_moving_samples[w.y][w.x];
            means += s_moving_terms[w.y][w.x] & 0xFFFFu;
            variances += s_moving_terms[w.y][w.x] >> 16;
        }
    }
    float change = abs(float(samples) - float(means)) / float(DNSR_MOVING_SAMPLE_UNIT);
    float variance = float(variances) * (65536.0 / float(DNSR_MOMENTS_MEAN_MAX * DNSR_MOMENTS_MEAN_MAX));
    float sigmas = dnsr_get_moving_settings().x;
    return sigmas > 0.0 && !dnsr_get_is_reset() && change > sigmas * sqrt(variance) + float(DNSR_MOVING_MARGIN_SAMPLES);
}

// A pixel of a cleared tile: its value is known exactly; keep the state of the next frame consistent with it. Its
// moments are known from the tile's metadata too: filter pass 0 keeps them (dnsr_cleared_moments), so this frame's
// are not written.
void dnsr_write_cleared(ivec2 p, bool receiver, uint state, bool tile_writer) {
    float value = state == 1u ? 1.0 : 0.0;
    if (tile_writer) dnsr_write_tile_meta(p / DNSR_TILE_SIZE, DNSR_TILE_CLEARED | (state == 1u ? DNSR_TILE_LIT : 0u));
    dnsr_write_reprojection(p, receiver ? vec2(value, 0.0) : DNSR_SKY_SIGNAL);
    dnsr_write_output(p, receiver ? value : 1.0);
}

// Hard tiles told by time (Settings::hard_tile_frames): a world point in a hard shadow keeps its value from frame to
// frame, one in a penumbra changes it at random, and one frame's samples cannot tell a narrow penumbra from a hard
// edge (docs/do-no-harm.md, "A spatial test for hard shadows in one frame"). The tile writer of the group's tile
// `own` (at image tile t) stores this frame's count of quiet frames (last frame's plus one; 0 on a reset) and returns
// whether the 3x3 tiles around it all had at least hard_tile_frames of them last frame (s_quiet); a receiver that
// contradicts clears its tile's count later (dnsr_clear_tile_quiet), after the barriers between (memoryBarrierImage
// before the last). Last frame's counts are fetched once per window tile, with the tile words: fetched per tile
// writer, nine each, they cost all-lit frames 0.06 ms at 4K on an H200, and a second fetch site for the tile's own
// count made lavapipe (Mesa 22.3) leak memory every frame (the million-frame test: +130 MB/s).
bool dnsr_quiet_tiles(ivec2 own, ivec2 t) {
    uint frames = uint(dnsr_get_moving_settings().z);
    bool reset = dnsr_get_is_reset();
    uint least = 0xFFFFFFFFu;
    for (int k = 0; k < 9; ++k) least = min(least, s_quiet[own.y + 1 + k / 3][own.x + k % 3]);
    dnsr_write_tile_quiet(t, reset ? 0u : min(s_quiet[own.y + 2][own.x + 1] + 1u, uint(DNSR_MAX_QUIET_FRAMES)));
    return frames > 0u && !reset && least >= frames;
}

// Whether last frame's samples (the sign of each texel's run) around history position t contradict this frame's
// sample x, on a pixel that is not disoccluded and whose footprint's texels (weighed at 1/16 or more) are all
// receivers on its surface: under a still camera (one texel) that texel's sample differs; under a moving one every
// footprint texel's does and no receiver of the 3x3 texels around t holds x (a sub-pixel feature the moving camera
// brought onto a pixel centre is no contradiction: the 2x2 footprint alone took a grille's dots for noise), or
// every footprint texel held both values, each at least DNSR_MIXED_TEXEL_SPREAD_PERCENT percent of its
// DNSR_MIXED_TEXEL_SAMPLES or more samples (a wide penumbra under a moving camera, whose 3x3 texels seldom agree).
bool dnsr_contradicts(vec2 t, float x, int texels, int other, int mixed) {
    if (texels == 1) return other == 1;
    if (mixed == texels) return true;
    if (other < texels) return false;
    for (int k = 0; k < 9; ++k) {
        ivec2 q = clamp(ivec2(floor(t + 0.5)) - 1 + ivec2(k % 3, k / 3), ivec2(0), dnsr_get_extent() - 1);
        vec4 mq = dnsr_read_previous_moments(q);
        if (mq.z > 0.0 && (mq.w > 0.0) == (x >= 0.5)) return false;
    }
    return true;
}

void dnsr_tile_classification(ivec2 gid, ivec2 lid) {
    ivec2 origin = gid * DNSR_WIDE_GROUP_SIZE;
    ivec2 p = origin + lid;
    int thread = lid.y * DNSR_WIDE_GROUP_WIDTH + lid.x;
    g_window_base = dnsr_window_base_tile(origin);
    bool inside = dnsr_inside(p);
    bool inverted = dnsr_get_is_depth_inverted();
    ivec2 own_tile = lid / DNSR_TILE_SIZE;
    bool tile_writer = all(equal(lid % DNSR_TILE_SIZE, ivec2(0)));

    if (thread < DNSR_WINDOW_TILES.x * DNSR_WINDOW_TILES.y) {
        ivec2 w = ivec2(thread % DNSR_WINDOW_TILES.x, thread / DNSR_WINDOW_TILES.x);
        ivec2 tile = g_window_base + w;
        uint valid = dnsr_tile_valid_bits(tile);
        uint word = valid != 0u ? dnsr_read_tile_mask(tile) : 0u;
#ifndef DNSR_VISIBILITY_INPUT
        // A hit mask is the host's, read as it is (no prepare pass): FidelityFX's convention sets occluded bits.
        if (!dnsr_get_is_lit_bit_mask()) word = valid != 0u ? ~word : 0u;
#endif
        s_words[w.y][w.x] = word;
        // Outside the tile grid: the nearest tile's count (the 3x3 test clamps to the grid).
        if (DNSR_SPEC_STABLE_HISTORY) s_quiet[w.y][w.x] = dnsr_read_previous_tile_quiet(clamp(tile, ivec2(0), dnsr_tile_count() - 1));
        if (DNSR_SPEC_MOVING_SHADOWS) {
            s_moving_samples[w.y][w.x] = 0u;
            s_moving_terms[w.y][w.x] = 0u;
        }
#ifdef DNSR_VISIBILITY_INPUT
        uint dark = valid != 0u ? dnsr_read_tile_dark(tile) : 0u;
        s_dark[w.y][w.x] = dark;
        bool shadowed = (dark & valid) == valid;
#else
        bool shadowed = (word & valid) == 0u;
#endif
        s_window_uniform[w.y][w.x] = ((word & valid) == valid ? 1u : 0u) | (shadowed ? 2u : 0u);
    }
#ifdef DNSR_VISIBILITY_INPUT
    // The window's visibilities, loaded with the words (behind the same barrier) although a group whose tiles are
    // all cleared does not use them: after the clearing decision they would cost the group another round trip
    // to memory (an H100 at 4K: classification 0.611 ms that way).
    for (int i = thread; i < DNSR_WINDOW_ROWS * DNSR_WINDOW_COLUMNS; i += DNSR_WIDE_GROUP_INVOCATIONS) {
        ivec2 w = ivec2(i % DNSR_WINDOW_COLUMNS, i / DNSR_WINDOW_COLUMNS);
        ivec2 q = g_window_base * DNSR_TILE_SIZE + w;
        s_visibility[w.y][w.x] = dnsr_inside(q) ? dnsr_sanitize_visibility(dnsr_read_visibility(q)) : 0.0;
    }
#endif
    if (tile_writer) s_tile_has_receiver[own_tile.y][own_tile.x] = 0u;
    if (thread == 0) s_lit_against_normal = s_lit_away_from_disc = 0u;

    float depth = inside ? dnsr_read_depth(p) : 0.0;
    bool receiver = inside && dnsr_is_receiver(depth);
    s_quad_key[lid.y][lid.x] = receiver ? (inverted ? -depth : depth) : 1e30;
    barrier();
    // A count, though only whether it is 0 matters: the add measured faster than an or of the flag on an H200
    // (classification of an all-lit frame at 4K 0.133 -> 0.124 ms, docs/bench/h200-2026-11-30-receiver-count;
    // likely the compiler combining one subgroup's adds to one address, not measured apart).
    if (receiver) atomicAdd(s_tile_has_receiver[own_tile.y][own_tile.x], 1u);
    if (tile_writer) s_uniform[own_tile.y][own_tile.x] = dnsr_uniform_state(own_tile);
    if (DNSR_SPEC_STABLE_HISTORY && tile_writer) s_hard_tile[own_tile.y][own_tile.x] = inside && dnsr_quiet_tiles(own_tile, p / DNSR_TILE_SIZE) ? 1u : 0u;
    barrier();
    // Every tile of the group cleared (no receiver, or a uniform neighbourhood): their values are known exactly
    // and no moments are needed. Same condition for the whole group, so the barrier below stays uniform.
    bool all_cleared = true;
    for (int ty = 0; ty < DNSR_GROUP_TILES.y; ++ty) {
        for (int tx = 0; tx < DNSR_GROUP_TILES.x; ++tx) all_cleared = all_cleared && dnsr_tile_state(ivec2(tx, ty)) != 0u;
    }
    if (all_cleared) {
        if (inside) dnsr_write_cleared(p, receiver, dnsr_tile_state(own_tile), tile_writer);
        return;
    }

    // Read by the quad vote after the next barrier.
    s_quad_velocity[lid.y][lid.x] = receiver ? dnsr_read_velocity(p) : vec2(0.0);
    // A lit receiver facing away from the light by its G-buffer normal, inside a plane that faces it: the host's
    // rays do not test the normals here (a normal map's, which tilt past the light), and a shadowed sample of such
    // a receiver is a penumbra's, not the face's own shadow.
    if (DNSR_SPEC_STABLE_HISTORY && receiver && dnsr_get_has_light_position()) {
#ifdef DNSR_VISIBILITY_INPUT
        bool lit = dnsr_window_sample(lid) == 1.0 && !(dnsr_get_is_checkerboard() && !dnsr_is_traced(p));
#else
        bool lit = dnsr_window_lit(p, g_window_base) == 1.0;
#endif
        if (lit) {
            vec3 to_light = dnsr_to_light(dnsr_get_light_position(), dnsr_world_position(p, depth));
            vec3 shading = dnsr_read_normal(p);
            if (dot(shading, to_light) < 0.0 && dnsr_plane_faces_light(p, depth, shading, to_light)) s_lit_against_normal = 1u;
            if (dnsr_faces_away_from_disc(shading, to_light)) s_lit_away_from_disc = 1u;
        }
    }
    if (DNSR_SPEC_MOVING_SHADOWS) dnsr_sum_previous_moments(thread);
#ifndef DNSR_VISIBILITY_INPUT
    // The surface window's breaks, after the clearing decision: a group whose tiles are all cleared never reads
    // the window's normals (an all-lit frame would pay four normal and depth reads per pixel). The normal codes
    // borrow s_hsum, as two words per entry.
    if (DNSR_SURFACE_WINDOW) {
        // Every depth and normal fetched first, at clamped coordinates: no fetch waits for another's result (the
        // normal for the depth's receiver test, the next pixel for the last), so the group waits for one round trip.
        const int pairs = DNSR_WINDOW_ROWS * DNSR_WINDOW_COLUMNS / 2 / DNSR_WIDE_GROUP_INVOCATIONS;
        float depths[2 * pairs];
        vec3 normals[2 * pairs];
        for (int j = 0; j < 2 * pairs; ++j) {
            int i = thread + (j >> 1) * DNSR_WIDE_GROUP_INVOCATIONS;
            ivec2 q = g_window_base * DNSR_TILE_SIZE + ivec2(i % (DNSR_WINDOW_COLUMNS / 2) * 2 + (j & 1), i / (DNSR_WINDOW_COLUMNS / 2));
            ivec2 fetched = clamp(q, ivec2(0), dnsr_get_extent() - 1);
            depths[j] = dnsr_read_depth(fetched);
            normals[j] = dnsr_read_normal(fetched);
            depths[j] = fetched == q ? depths[j] : 0.0;
        }
        for (int j = 0; j < pairs; ++j) {
            int i = thread + j * DNSR_WIDE_GROUP_INVOCATIONS;
            ivec2 w = ivec2(i % (DNSR_WINDOW_COLUMNS / 2) * 2, i / (DNSR_WINDOW_COLUMNS / 2));
            uvec2 codes = uvec2(0u);
            for (int k = 0; k < 2; ++k) codes[k] = dnsr_is_receiver(depths[2 * j + k]) ? dnsr_normal_code(normals[2 * j + k]) : 0u;
            s_hsum[w.y][w.x >> 1] = codes;
        }
        if (thread < DNSR_WINDOW_ROWS) s_row_breaks[thread] = 0u;
        if (thread < DNSR_WIDE_GROUP_WIDTH) s_column_breaks[thread] = 0u;
        barrier();
        if (DNSR_SPEC_MOVING_SHADOWS && tile_writer) s_moved[own_tile.y][own_tile.x] = dnsr_shadow_moved(own_tile) ? 1u : 0u;
        // Eight neighbour pairs per invocation, one byte of a window row's or a group column's breaks: four
        // invocations share a word's atomic (one per pair, 31 of them, cost 0.055 ms more at 4K on an H100).
        const int chunks = DNSR_WINDOW_COLUMNS / 8;
        if (thread < (DNSR_WINDOW_ROWS + DNSR_WIDE_GROUP_WIDTH) * chunks) {
            bool in_row = thread < DNSR_WINDOW_ROWS * chunks;
            int line = (in_row ? thread : thread - DNSR_WINDOW_ROWS * chunks) / chunks;
            int first = (thread % chunks) * 8;
            ivec2 step = in_row ? ivec2(1, 0) : ivec2(0, 1);
            ivec2 w = in_row ? ivec2(first, line) : ivec2(line + DNSR_MOMENT_RADIUS, first);
            // The byte's nine codes first: where they are all equal (most of a plane, or sky), no pair needs a test
            // (a branch, not a select computing both: classification 0.824 -> 0.804 ms at 4K on an H100).
            uint codes[9];
            bool equal = true;
            for (int k = 0; k < 9; ++k) {
                codes[k] = dnsr_window_code(w + min(k, DNSR_WINDOW_COLUMNS - 1 - first) * step);
                equal = equal && codes[k] == codes[0];
            }
            uint byte_bits = first + 8 > DNSR_WINDOW_COLUMNS - 1 ? 0x7Fu : 0xFFu;
            uint breaks = codes[0] != 0u ? 0u : byte_bits << uint(first);
            [[dont_flatten]] if (!equal) {
                breaks = 0u;
                for (int k = 0; k < 8 && first + k < DNSR_WINDOW_COLUMNS - 1; ++k) {
                    // Equal codes (a plane) need no products; two sky pixels are no surface.
                    bool joined = codes[k] == codes[k + 1] ? codes[k] != 0u : dnsr_same_surface(codes[k], codes[k + 1]);
                    breaks |= joined ? 0u : 1u << uint(first + k);
                }
            }
            if (in_row) atomicOr(s_row_breaks[line], breaks);
            else atomicOr(s_column_breaks[line], breaks);
        }
        // The codes are read before the horizontal pass overwrites them.
        barrier();
    }
#endif

    // The verdict needs every window tile's sums: after the surface window's first barrier where it runs, else
    // after a barrier of its own.
#ifdef DNSR_VISIBILITY_INPUT
    const bool own_barrier = DNSR_SPEC_MOVING_SHADOWS;
#else
    const bool own_barrier = DNSR_SPEC_MOVING_SHADOWS && !DNSR_SURFACE_WINDOW;
#endif
    if (own_barrier) {
        barrier();
        if (tile_writer) s_moved[own_tile.y][own_tile.x] = dnsr_shadow_moved(own_tile) ? 1u : 0u;
    }

    bool guided = DNSR_SPEC_PENUMBRA_GUIDED;
    if (guided) {
        dnsr_sum_hit_part(thread);
        barrier();
        dnsr_reduce_hit_parts(thread);
        // The partial sums are read before s_hsum is overwritten; s_hit is read after the barrier that follows the
        // moment sums.
        barrier();
    }

    // Horizontal Gaussian over DNSR_WINDOW_ROWS / height window rows per invocation.
    dnsr_init_moment_weights();
    // Window pixel columns origin.x - 8 .. origin.x + width + 7 as the bits of a row; pixel columns outside the
    // render rectangle are masked out of both the lit count and the weight.
    int first_column = max(DNSR_MOMENT_RADIUS - origin.x, 0);
    int end_column = min(dnsr_get_extent().x - origin.x + DNSR_MOMENT_RADIUS, 32);
    uint below_end = end_column >= 32 ? 0xFFFFFFFFu : (1u << uint(end_column)) - 1u;
    uint columns_inside = below_end & ~((1u << uint(first_column)) - 1u);
    // Weight of the taps inside the rectangle: the same for every row, and the full window away from its edges.
    uint own = uint(lid.x + DNSR_MOMENT_RADIUS);
    float inside_weight = 0.0;
    for (int i = -DNSR_MOMENT_RADIUS; i <= DNSR_MOMENT_RADIUS; ++i) {
        inside_weight += dnsr_moment_weight(i) * float((columns_inside >> uint(int(own) + i)) & 1u);
    }
    g_inside_weight = inside_weight;
    for (int row = lid.y; row < DNSR_WINDOW_ROWS; row += DNSR_WIDE_GROUP_HEIGHT) {
        int y = origin.y - DNSR_MOMENT_RADIUS + row;
        vec2 sum = vec2(0.0);
        if (y >= 0 && y < dnsr_get_extent().y) {
#ifdef DNSR_VISIBILITY_INPUT
            // Columns outside the rectangle hold 0: they add nothing, and inside_weight leaves them out.
            for (int i = -DNSR_MOMENT_RADIUS; i <= DNSR_MOMENT_RADIUS; ++i) {
                float v = s_visibility[row][int(own) + i];
                sum += dnsr_moment_weight(i) * vec2(v, v * v);
            }
#else
            int wy = (y >> 2) - g_window_base.y;
            uint shift = uint(8 * (y & 3));
            uint lit = 0u;
            for (int c = 0; c < DNSR_WINDOW_TILES.x; ++c) lit |= ((s_words[wy][c] >> shift) & 0xFFu) << uint(8 * c);
            lit &= columns_inside;
            // Symmetric weights: one multiply per distance.
            float lit_sum = dnsr_moment_weight(0) * float((lit >> own) & 1u);
            for (int i = 1; i <= DNSR_MOMENT_RADIUS; ++i) {
                float pair = float(((lit >> (own - uint(i))) & 1u) + ((lit >> (own + uint(i))) & 1u));
                lit_sum += dnsr_moment_weight(i) * pair;
            }
            sum = vec2(lit_sum, inside_weight);
            // The row's surface: the taps that no break separates from the row's pixel in this column.
            if (DNSR_SURFACE_WINDOW) {
                uint taps = dnsr_run_bits(dnsr_unbroken_run(s_row_breaks[row], int(own)));
                // Most rows lie on one surface across the window: the sums above, exactly (on an H100 at 4K this
                // and the equal codes above took 0.079 ms off classification's 0.95).
                vec2 surface_sums = vec2(lit_sum, inside_weight);
                uint window_bits = ((2u << uint(2 * DNSR_MOMENT_RADIUS)) - 1u) << (own - uint(DNSR_MOMENT_RADIUS));
                if ((taps & window_bits) != window_bits) {
                    uint on = lit & taps;
                    surface_sums = dnsr_moment_weight(0) * vec2((on >> own) & 1u, 1.0);
                    for (int i = 1; i <= DNSR_MOMENT_RADIUS; ++i) {
                        uvec2 pair = uvec2(on, taps) >> (own - uint(i)) & 1u;
                        pair += uvec2(on, taps) >> (own + uint(i)) & 1u;
                        surface_sums += dnsr_moment_weight(i) * vec2(pair);
                    }
                }
                sum.y = uintBitsToFloat(dnsr_pack_surface_sums(surface_sums));
            }
#endif
        }
        s_hsum[row][lid.x] = floatBitsToUint(sum);
    }
    // The tile writers' quiet counts (dnsr_quiet_tiles) stored before any receiver clears one; here, not after the
    // stores, so that no invocation waits for them.
    if (DNSR_SPEC_STABLE_HISTORY) memoryBarrierImage();
    barrier();
    if (!inside) return;

    uint uniform_state = dnsr_tile_state(own_tile);
    float max_samples = dnsr_get_temporal_settings().z;

    if (uniform_state != 0u) {
        dnsr_write_cleared(p, receiver, uniform_state, tile_writer);
        return;
    }
    float blocker = guided ? dnsr_tile_blocker(own_tile) : -1.0;
    if (tile_writer) {
        dnsr_write_tile_meta(p / DNSR_TILE_SIZE, 0u);
        if (guided) dnsr_write_tile_blocker(p / DNSR_TILE_SIZE, blocker);
    }
    if (!receiver) {
        // No moments either: a sky pixel's are empty, which filter pass 0 keeps (dnsr_cleared_moments).
        dnsr_write_reprojection(p, DNSR_SKY_SIGNAL);
        return;
    }

    vec4 disocc = dnsr_get_disocclusion_settings();
    vec4 reject = dnsr_get_rejection_settings();
    vec4 temporal = dnsr_get_temporal_settings();
#ifdef DNSR_VISIBILITY_INPUT
    vec2 local = dnsr_local_moments(p, lid);
    // The flip rule's mean: the whole window's.
    float window_mean = local.x;
    float x = dnsr_window_sample(lid);
    // Checkerboard input: a pixel not traced this frame holds its neighbours' mean, not a sample of its own.
    bool untraced = dnsr_get_is_checkerboard() && !dnsr_is_traced(p);
#else
    vec2 local;
    // The flip rule keeps the whole window's mean: without the sky's lit samples, bright penumbra pixels beside a
    // silhouette broke their runs towards shadow (docs/do-no-harm.md, "Sky left out of the local moments").
    float window_mean;
    if (DNSR_SURFACE_WINDOW) {
        vec4 moments = dnsr_window_and_surface_moments(p, lid);
        window_mean = moments.x;
        // The whole window where p's own normal is unknown (its surface is then p alone).
        local = dot(dnsr_read_normal(p), dnsr_read_normal(p)) > 0.0 ? moments.zw : moments.xy;
    } else {
        local = dnsr_local_moments(lid);
        window_mean = local.x;
    }
    float x = dnsr_window_lit(p, g_window_base);
#endif

    // Velocity of the closest receiver of the 2x2 quad: thin foreground keeps its own motion at silhouettes.
    ivec2 q = lid & ~1;
    ivec2 best = lid;
    for (int j = 0; j < 2; ++j) {
        for (int i = 0; i < 2; ++i) {
            if (s_quad_key[q.y + j][q.x + i] < s_quad_key[best.y][best.x]) best = q + ivec2(i, j);
        }
    }
    vec2 uv = dnsr_pixel_uv(p);
    vec2 ndc = dnsr_uv_to_ndc(uv);
    vec2 velocity = s_quad_velocity[best.y][best.x];
    vec2 history_uv = uv + velocity;
    // A pixel that moves under 1 / DNSR_STILL_MOTION_INV_PIXELS px (the moving shadow's clamp below).
    vec2 motion = velocity * vec2(dnsr_get_extent() * int(DNSR_STILL_MOTION_INV_PIXELS));
    bool still = dot(motion, motion) < 1.0;

    // Disocclusion: where the camera motion puts this surface last frame, was the same depth there?
    vec4 prev_clip = dnsr_get_reprojection_matrix() * vec4(ndc, depth, 1.0);
    vec3 prev_ndc = prev_clip.xyz / prev_clip.w;
    vec2 prev_uv = prev_ndc.xy * 0.5 + 0.5;
    vec4 world = dnsr_get_view_projection_inverse() * vec4(ndc, depth, 1.0);
    vec3 view_dir = normalize(dnsr_get_eye() - world.xyz / world.w);
    vec3 normal = dnsr_read_normal(p);
    float n_dot_v = clamp(dot(normal, view_dir), 0.0, 1.0);
    // The receiver faces away from the light (ShadowsDispatch::light_position): decided here, where its position
    // and normal are at hand, and used at the end (keeping them live until then cost Quality's classification
    // 16% at 4K on an H200). (NaN, where a point light sits on the surface, turns nothing away.)
    vec3 to_light = dnsr_to_light(dnsr_get_light_position(), world.xyz / world.w);
    bool faces_away = DNSR_SPEC_STABLE_HISTORY && dnsr_get_has_light_position() && dot(normal, to_light) < 0.0
        && !(x == 0.0 && s_lit_against_normal != 0u && dnsr_plane_faces_light(p, depth, normal, to_light));
    // ... and away from every point of the light's disc: N.L below -sin(angular radius).
    bool faces_away_from_disc = faces_away && s_lit_away_from_disc == 0u && dnsr_faces_away_from_disc(normal, to_light);
    float threshold = mix(disocc.x, disocc.y, pow(1.0 - n_dot_v, disocc.z));
    bool on_screen = dnsr_finite(prev_uv) && dnsr_finite(history_uv) && prev_clip.w > 0.0
        && all(greaterThanEqual(prev_uv, vec2(0.0))) && all(lessThan(prev_uv, vec2(1.0)))
        && all(greaterThanEqual(history_uv, vec2(0.0))) && all(lessThan(history_uv, vec2(1.0)));
    bool disoccluded = dnsr_get_is_reset() || !on_screen;
    // Without the run features (Balanced), what last frame left for this pixel is fetched before the disocclusion
    // test decides whether it is used (at clamped positions; off screen it is fetched and not used), so that the
    // pixel waits for one round trip to memory, not three (the depth copy, then the nearest texel's moments, then
    // the bilinear history): Balanced's classification 0.317 -> 0.297 ms at 4K on an H200. With them (Fast,
    // Quality) each stays where it is used: fetched here with the footprint's moments and normals, or only the
    // depth copy and the nearest texel, they took classification from 64 to 78 registers and 0.707 to 0.762-0.781
    // ms (BENCHMARKS.md change log).
    ivec2 last_texel = dnsr_get_extent() - 1;
    ivec2 prev_p = clamp(ivec2(prev_uv * vec2(dnsr_get_extent())), ivec2(0), last_texel);
    float previous_depth = DNSR_SPEC_STABLE_HISTORY ? 0.0 : dnsr_read_previous_depth(prev_p);
    ivec2 hp = clamp(ivec2(history_uv * vec2(dnsr_get_extent())), ivec2(0), last_texel);
    vec4 nearest = DNSR_SPEC_STABLE_HISTORY ? vec4(0.0) : dnsr_read_previous_moments(hp);
    vec2 t = history_uv * vec2(dnsr_get_extent()) - 0.5;
    ivec2 footprint = ivec2(floor(t));
    float texel_history[4];
    if (!DNSR_SPEC_STABLE_HISTORY) {
        [[unroll]] for (int k = 0; k < 4; ++k) {
            texel_history[k] = dnsr_read_history_texel(dnsr_footprint_texel(footprint, k));
        }
    }
    // The history footprint's texels that hold another surface, one bit each (with the run features): turned, or
    // at another depth. A texel of this surface lies within the disocclusion test's depth range, widened by
    // DNSR_FOOTPRINT_SLOPE_PERCENT of what a plane through this point at its angle to the view changes over the
    // texel's distance (dnsr_texel_depth_slope). Decided with the disocclusion test, whose values it takes: kept
    // until the blend below, they took classification from 64 to 79 registers and 0.786 to 0.913 ms at 4K on an
    // H200.
    uint other_surface = 0u;
    if (!disoccluded) {
        float expected = dnsr_linear_depth(prev_ndc.xy, prev_ndc.z);
        if (DNSR_SPEC_STABLE_HISTORY) previous_depth = dnsr_read_previous_depth(prev_p);
        // Written so that NaN or infinite depths count as disoccluded.
        disoccluded = !(abs(previous_depth - expected) < threshold * expected);
        if (DNSR_SPEC_STABLE_HISTORY && !disoccluded) {
            float slope = dnsr_texel_depth_slope(expected, n_dot_v);
            vec2 f = t - floor(t);
            [[unroll]] for (int k = 0; k < 4; ++k) {
                float weight = dnsr_footprint_weight(f, k);
                if (weight < 1.0 / 16.0) continue;
                ivec2 q = dnsr_footprint_texel(footprint, k);
                bool other = dnsr_normal_turned(dnsr_read_previous_normal(q), normal)
                    || !(abs(dnsr_read_previous_depth(q) - expected) < threshold * expected + length(vec2(q) - t) * slope);
                other_surface |= other ? 1u << k : 0u;
            }
        }
    }

    // Temporal moments (Welford), restarted on disocclusion, count bounded by max_samples.
    float stable_after = dnsr_get_run_settings().x;
    float converged_after = dnsr_get_run_settings().z;
    vec4 m = vec4(0.0);
    // A resolved change (see below): this frame's sample stands alone.
    bool resolved = false;
    // This sample contradicts last frame's around its history position (dnsr_contradicts).
    bool contradicted = false;
    // History blended from the texels that agree (run_history.y > 0), when only some of them do.
    vec2 run_history = vec2(0.0);
    if (!disoccluded) {
        m = DNSR_SPEC_STABLE_HISTORY ? dnsr_read_previous_moments(hp) : nearest;
        // The depth test passes a surface at the same distance that faces another way (the other face of a crease
        // or a fin, a thin receiver beside a lit one): where the nearest texel's normal turned, its moments are
        // another surface's. Start again, or (below) continue the heaviest texel of the footprint that kept this
        // surface's normal (the scene family, unguided Quality: mean RMSE -6%, worse than the input 42 -> 40).
        // With the run features only: Balanced keeps the FidelityFX behaviour.
        bool turned = DNSR_SPEC_STABLE_HISTORY && dnsr_normal_turned(dnsr_read_previous_normal(hp), normal);
        if (turned) m = vec4(0.0);
#ifdef DNSR_VISIBILITY_INPUT
        // The neighbours' mean says nothing about the edge a stable pixel resolves: an untraced stable pixel takes
        // its run's value as this frame's sample (and keeps its run, below), unless its neighbours' mean lies more
        // than 0.5 from that value (most of them hold the other one: the shadow moved over it). Without this Quality's error on hard edges rose twentyfold at
        // half a ray per pixel.
        bool run_contradicted = abs(x - (m.w > 0.0 ? 1.0 : 0.0)) > 0.5;
        if (untraced && !run_contradicted && stable_after > 0.0 && abs(m.w) >= stable_after && abs(m.w) <= float(DNSR_MAX_SAMPLE_RUN)) {
            x = m.w > 0.0 ? 1.0 : 0.0;
        }
#endif
        // A moving camera puts history_uv between texels, and next to a hard edge the bilinear footprint lies
        // across it. The texels whose stable run holds this sample's value are where this surface point was: blend
        // the history from them alone. (A texel weighed at under 1/16 does not count; the bound also keeps float
        // rounding at texel centres out. Taking their moments too, instead of the nearest texel's, left the
        // viewer's orbiting fins at RMSE 0.036 after 64 frames against 0.022 without.)
        // Texels without a receiver (sky: no samples, mq.z == 0) leave the blend too: their lit sky signal would
        // brighten a shadowed receiver along every silhouette against the background.
        // (No runtime condition beside the specialization: with one, lavapipe leaked memory every frame.)
        if (DNSR_SPEC_STABLE_HISTORY) {
            vec2 f = t - floor(t);
            float all_weight = 0.0;
            // Texels weighed at 1/16 or more: one where the camera stood still.
            int texels = 0;
            vec2 receivers = vec2(0.0);
            // The texel of the longest pure run that agrees with x (every sample of its moments identical): its
            // moments and history. (Keeping only its position and reading them again after the loop ran faster on
            // an H100, 0.560 -> 0.497 ms at 4K, but the extra fetch sites made lavapipe leak memory every frame.)
            vec4 pure = vec4(0.0);
            float pure_history = 0.0;
            // Every receiver texel resolved: of the other value (one of them is) pure and converged, of this
            // sample's value pure or converged.
            bool all_resolved = true;
            bool any_other = false;
            bool all_pure = true;
            // The heaviest receiver texel whose normal did not turn: its moments, where the nearest texel turned.
            vec4 kept = vec4(0.0);
            float kept_weight = 0.0;
            // Receiver texels whose last sample was not x, and those that held both values (dnsr_contradicts).
            int other_texels = 0;
            int mixed_texels = 0;
            // Unrolled: classification 0.866 -> 0.851 ms at 4K on an H200 (64 registers either way; the same hint
            // on the 9- and 16-texel loops changed nothing).
            [[unroll]] for (int k = 0; k < 4; ++k) {
                float weight = dnsr_footprint_weight(f, k);
                ivec2 q = dnsr_footprint_texel(footprint, k);
                if (weight < 1.0 / 16.0) continue;
                vec4 mq = dnsr_read_previous_moments(q);
                all_weight += weight;
                ++texels;
                // A turned texel holds another surface: it leaves the blend as the sky does. So does one at another
                // depth (the disocclusion test took the nearest texel alone): beside a silhouette over a parallel
                // face (a box's lit top over the shadowed ground) the footprint held both, and a young pixel's
                // history took the other face's value (docs/do-no-harm.md, "Footprint texels at this depth").
                if (!(mq.z > 0.0) || (other_surface & (1u << k)) != 0u) continue;
                if (weight > kept_weight) {
                    kept = mq;
                    kept_weight = weight;
                }
                float texel = dnsr_read_history_texel(q);
                receivers += vec2(weight * texel, weight);
                other_texels += (mq.w > 0.0) != (x >= 0.5) ? 1 : 0;
                mixed_texels += mq.z >= float(DNSR_MIXED_TEXEL_SAMPLES)
                    && abs(mq.x - 0.5) <= float(DNSR_MIXED_TEXEL_SPREAD_PERCENT) / 100.0 ? 1 : 0;
                bool agreeing = dnsr_sign_agreeing(mq.w, x);
                bool texel_pure = dnsr_pure(mq);
                bool converged_run = abs(mq.w) >= converged_after;
                all_resolved = all_resolved && (agreeing ? texel_pure || converged_run : texel_pure && converged_run);
                any_other = any_other || !agreeing;
                all_pure = all_pure && texel_pure;
                if (texel_pure && agreeing && abs(mq.w) > abs(pure.w)) {
                    pure = mq;
                    pure_history = texel;
                }
                if (!dnsr_stable_agreeing(mq.w, x, stable_after)) continue;
                run_history += vec2(weight * texel, weight);
            }
            // A hard edge or a thin feature (a 1-px shadow line) under a moving camera: the nearest texel lies
            // across it. Where the nearest texel's samples all held the other value and so did every receiver
            // texel of the footprint, each its own (a hard edge between two resolved sides, not a penumbra),
            // continue the agreeing texel whose samples all agree, moments and history: its run alone would leave
            // the other side's samples in the moments, and the pixel would never count as pure (converged) again.
            // Inside a penumbra the flip rule leaves short pure runs of the other value, and without the condition
            // on the whole footprint a penumbra pixel took a lit neighbour's pure moments, converged, and passed
            // its history on the same way next frame (make accuracy, disocclusion 2000: 0.0445 -> 0.0417).
            if (turned) m = kept;
            contradicted = texels > 0 && !(receivers.y < all_weight) && dnsr_contradicts(t, x, texels, other_texels, mixed_texels);
            bool adopt = pure.z > 0.0 && !dnsr_sign_agreeing(m.w, x) && dnsr_pure(m) && all_pure;
            // Elsewhere, where the nearest texel lies across the edge from this surface point (a moving camera at
            // a silhouette or a crease), the pixel stays stable: it continues a stable run of stable_after samples,
            // no longer. Handing over the agreeing texel's whole run let runs grow from texel to texel in a
            // penumbra (each frame some texel of the footprint agrees), until they covered moments that held both
            // values and the pixel counted as pure and converged (scene family, 10-degree penumbra under an
            // orbiting camera, seed 1047: Quality RMSE 0.105 -> 0.060).
            if (run_history.y > 0.0 && !dnsr_stable_agreeing(m.w, x, stable_after)) m.w = (x >= 0.5 ? 1.0 : -1.0) * stable_after;
            if (adopt) m = pure;
            // A silhouette under a moving camera, between resolved surfaces: the footprint holds sky, its receiver
            // texels of the other value held it in all their samples (converged_after or more), the ones of this
            // sample's value in all their samples or their last converged_after, and two neighbours share this
            // sample (a stray sample of a penumbra seldom has them). This sample is the answer: the history and
            // the filter would only blend it with the other side (the scene family's sky scenes under a panning
            // camera: seed 1092 RMSE 0.148 -> 0.059). Away from the sky the footprint's test alone also takes the
            // umbra side of a penumbra for a hard edge (the family's penumbrae under a moving camera lost 5-30%):
            // there the whole 4x4 area around it must be resolved, and the camera must have moved (a footprint of
            // more than one texel). Then a hard edge or a 1-px shadow line under a sizeless light that the camera
            // moved onto this pixel is this sample too (seed 1051, a wire's shadow under an orbiting camera: RMSE
            // 0.029 -> 0.022; 17 scenes better, one worse by 2%). Under a still camera the same area test took
            // penumbra tails, where the flip rule leaves pure runs, for edges (a still 3-degree light lost 3%).
#ifdef DNSR_VISIBILITY_INPUT
            bool resolvable = dnsr_is_exact(x) && !untraced;
#else
            bool resolvable = true;
#endif
            resolved = converged_after > 0.0 && resolvable && any_other && all_resolved
                    && dnsr_two_neighbours_share(p, lid, x);
            if (resolved && !(receivers.y < all_weight)) {
                resolved = texels > 1 && dnsr_resolved_area(t, x, converged_after);
            }
            // Continue the agreeing texel whose samples all agree, or start from this sample.
            if (resolved) {
                m = pure;
                run_history = vec2(pure.z > 0.0 ? pure_history : x, 1.0);
            // Only where the footprint is split: elsewhere the plain blend stands.
            } else if (!(run_history.y > 0.0 && run_history.y < all_weight)) {
                run_history = adopt ? vec2(pure_history, 1.0)
                            : (receivers.y > 0.0 && receivers.y < all_weight ? receivers : vec2(0.0));
            }
        }
        if (!(m.z >= 0.0 && m.z <= max_samples && m.y >= 0.0 && m.y < 1e30 && dnsr_finite(m.x)
              && abs(m.w) <= float(DNSR_MAX_SAMPLE_RUN))) {
            m = vec4(0.0);
            run_history = vec2(0.0);
        }
    }
    if (m.z > max_samples - 1.0) dnsr_scale_moments(m, (max_samples - 1.0) / m.z);
    // Welford's update in a form that stays exact when the history's count is tiny (rejected history is scaled
    // towards 0): (x - old mean)(x - new mean) = delta^2 * previous / n, and the sample variance divides by the
    // previous count instead of forming n - 1 (1 + 6e-6 - 1 keeps two digits in fp32).
    float previous = m.z;
    float delta = x - m.x;
    m.z += 1.0;
    m.x += delta / m.z;
    m.y += delta * delta * (previous / m.z);
    float variance = previous > 0.0 ? m.y / previous : 1.0;
    float flip_after = floor(dnsr_get_run_settings().y);
#ifdef DNSR_VISIBILITY_INPUT
    bool exact = dnsr_is_exact(x);
    // An untraced pixel's run neither grows nor breaks: it had no sample of its own.
    if (!untraced) m.w = exact ? dnsr_sample_run(m.w, x, stable_after) : dnsr_fractional_run(m.w, stable_after);
#else
    m.w = dnsr_sample_run(m.w, x, stable_after);
#endif
    // Enough identical samples in a row: the input resolves this pixel (a hard edge, say), and the local
    // distribution, which straddles the edge, must not pull its history (nor reject it).
    bool stable = stable_after > 0.0 && abs(m.w) >= stable_after;
    // flip_after samples of the other value right after a stable run, or the first one where the local
    // distribution already leans to it: the shadow moved over this pixel, and its history holds the old value.
    // Restart from the new samples, the history from the local mean. (A few samples of the other value also occur
    // in a penumbra close to 0 or 1, where the local mean stays on the old side.)
    bool breaking = flip_after > 0.0 && fract(abs(m.w)) == 0.5;
#ifdef DNSR_VISIBILITY_INPUT
    // Not on a sample that is not exact: it broke the run, but which way the shadow went is not known yet.
    breaking = breaking && exact && !untraced;
#endif
    bool flipped = breaking && (abs(m.w) == flip_after + 0.5 || abs(x - window_mean) < 0.5);
    if (flipped) {
        float n = floor(abs(m.w));
        m = vec4(x, 0.0, n, x >= 0.5 ? n : -n);
        variance = n > 1.0 ? 0.0 : 1.0;
    }

    // History clamped to the local distribution; a history far outside it loses its sample count. Tighter where
    // the shadow moved over this still pixel (dnsr_shadow_moved): its history holds where the shadow was. (Not on a
    // moving camera's pixels: they reach other surface points, where a still shadow's samples differ from the
    // texels' means too.)
    float sigma = sqrt(local.y);
    bool shadow_moved_here = DNSR_SPEC_MOVING_SHADOWS && still && s_moved[own_tile.y][own_tile.x] != 0u;
    float clamp_sigmas = shadow_moved_here ? dnsr_get_moving_settings().y : disocc.w;
    float history = disoccluded ? local.x
                  : (run_history.y > 0.0 ? run_history.x / run_history.y
                                        : (DNSR_SPEC_STABLE_HISTORY ? dnsr_read_history(history_uv) : dnsr_bilinear(texel_history, t)));
    if (!dnsr_finite(history)) history = local.x;
    // A stable pixel's history is clamped to what its run allows instead: after n identical samples the
    // visibility lies within DNSR_RUN_CLAMP_SAMPLES / n of them (the rule of three: 95% confidence for 3).
    float run_width = float(DNSR_RUN_CLAMP_SAMPLES) / abs(m.w);
    float clamped = flipped ? local.x
                  : (stable || resolved ? clamp(history, x - run_width, x + run_width)
                            : clamp(history, local.x - clamp_sigmas * sigma, local.x + clamp_sigmas * sigma));
    float d = stable || flipped || resolved ? 0.0 : (history - local.x) / max(clamp_sigmas * sigma, reject.y);
    dnsr_scale_moments(m, exp(-d * d / reject.x));

    // Not on a stable pixel: its samples resolve it, and the local variance (which straddles the edge) would let
    // the filter blur the edge (viewer, still camera: Quality RMSE 0.0332 -> 0.0285, lit pixels next to shadow
    // darkened by 5.6 -> 2.2 / 255 on average).
    if (m.z < reject.z && !stable) variance = max(variance, local.y) * max(reject.z - m.z, 1.0);
    float history_weight = sqrt(max(temporal.x - m.z, 0.0) / temporal.x);
    float shadow = mix(clamped, x, mix(temporal.y, 1.0, history_weight));
    // Converged (Settings::converged_samples, on a stable pixel): variance 0 tells the filter that the input may
    // resolve this pixel; the filter decides from its neighbours (dnsr_passes_through). The value stays the
    // temporal one: a penumbra pixel of visibility 0.95 shows 8 lit samples in a row two times in three, and its
    // run's value would bias it. Behind the run features' specialization: as a runtime branch alone it slowed
    // Balanced's classification, which never takes it, by 9% on an H100 at 4K. Not where the shadow moved over this
    // still pixel: its run restarted when the shadow passed (the flip rule), and a short run there is as often a
    // penumbra's few identical samples as a resolved edge (make accuracy's moving family: 0.327 -> 0.301 of the
    // input's error; docs/do-no-harm.md, "Quality's run rules taken apart").
    if (DNSR_SPEC_STABLE_HISTORY) {
        variance = stable && !flipped && !shadow_moved_here && dnsr_pure(m) && dnsr_converged(m.w, x, dnsr_get_run_settings().z) ? 0.0
                 : dnsr_unconverged_variance(variance);
    }

    // A resolved pixel is this sample, flagged converged: the filter passes it through among converged neighbours.
    if (resolved) {
        shadow = x;
        variance = 0.0;
    }
    // Under a light of no size (ShadowsDispatch::hard_light), or a penumbra narrower than
    // Settings::hard_penumbra_pixels, this sample resolves the pixel: it is the output (variance 0: converged), and
    // the filter passes it through (dnsr_pass_hard). The moments go on as before, for the frame the blockers move
    // away or the light gains a size. Not on an untraced pixel of a checkerboard input: its value is its
    // neighbours' mean, not a ray of its own.
    bool own_sample = true;
#ifdef DNSR_VISIBILITY_INPUT
    own_sample = !untraced;
    // A sample that is not exact contradicts nothing: it lies in a penumbra, whose tiles are not hard anyway.
    contradicted = contradicted && dnsr_is_exact(x) && own_sample;
#endif
    // In a tile whose 3x3 tiles were quiet long enough, a pixel that does not contradict last frame is resolved
    // by its sample (Settings::hard_tile_frames). A disoccluded one too: it has no history, and filtering it with
    // its neighbours blurred the hard edges that a moving camera uncovers (scene family, Quality not told that its
    // light is hard: worse than the input 32 -> 23; docs/do-no-harm.md, "Disoccluded pixels of hard tiles").
    bool quiet = false;
    if (DNSR_SPEC_STABLE_HISTORY) {
        if (contradicted) dnsr_clear_tile_quiet(p / DNSR_TILE_SIZE);
        // Not under penumbra guidance: its hit distances tell hard penumbrae (dnsr_hard_penumbra), and the quiet tiles
        // of its penumbrae took the guided family's median ratio to the input from 0.70 to 0.81. The counts go on.
        quiet = !guided && s_hard_tile[own_tile.y][own_tile.x] != 0u && !contradicted;
    }
    // A receiver turned away from the light (ShadowsDispatch::light_position) whose ray hit cannot see the light:
    // its sample is exact, and the history and the filter would only blend it with the lit face beside it (a
    // pole's or a sphere's dark side against the sky). A ray that reached the light may come from a normal-mapped
    // face: it is filtered as any other. So is a shadowed one where the G-buffer's normal is tilted past the light
    // inside a plane that faces it, in a group where such a receiver's ray reached the light: the host does not test
    // its rays against normal-mapped normals, and the shadow is a penumbra's. (Without that group's evidence the
    // host may test them, and the sample is exact: normal-mapped scene family, bumps in the shadows too, mean RMSE
    // 0.0348 -> 0.0427 with the plane alone; docs/do-no-harm.md, "Normal-mapped normals".) With the run features
    // only: Balanced keeps the FidelityFX behaviour.
    // Turned away from the whole disc, it is final (not in a quiet tile, whose samples pass through anyway): the
    // filter returns it as it is and leaves it out of its neighbours' taps, where its lit neighbours would grey it
    // (the host tests its rays against normal-mapped normals: every bump turned away is a shadowed dot). Turned
    // away from the light's centre only, part of the disc still reaches it, and it is filtered as now (a fin
    // under a 10-degree light). Nor in a group where a receiver turned away from the whole disc has a lit sample
    // (s_lit_away_from_disc): the host's rays do not test the normals there, and a wrong normal would keep the
    // pixel from the filter (bumps in dnsr's normals alone: docs/do-no-harm.md, "Normal-mapped normals").
    bool turned_away = faces_away && x == 0.0;
    if (own_sample && (quiet || turned_away || DNSR_SPEC_HARD_LIGHT
                       || dnsr_hard_penumbra(blocker, dnsr_get_penumbra_settings(), dnsr_linear_depth(ndc, depth))
                       || dnsr_no_blocker(blocker))) {
        shadow = x;
        variance = turned_away && faces_away_from_disc && !quiet ? DNSR_FINAL_VARIANCE : 0.0;
    }
    dnsr_write_moments(p, m);
    dnsr_write_reprojection(p, vec2(shadow, variance));
}

#endif
