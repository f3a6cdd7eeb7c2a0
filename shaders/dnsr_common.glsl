// Helpers shared by the pass cores. They only call dnsr_get_* callbacks, never touch a binding.
#ifndef DNSR_COMMON_GLSL
#define DNSR_COMMON_GLSL

// Tiles are DNSR_TILE_WIDTH x DNSR_TILE_HEIGHT (8x4) pixels packed into one uint; bit (y % 4) * 8 + (x % 8).
const ivec2 DNSR_TILE_SIZE = ivec2(DNSR_TILE_WIDTH, DNSR_TILE_HEIGHT);
// A block: two stacked tiles, the unit of the cleared-or-not decision the filter reads.
const ivec2 DNSR_GROUP_SIZE = ivec2(DNSR_GROUP_WIDTH, DNSR_GROUP_HEIGHT);
// The workgroup of classification and the filter passes: several blocks, so that few groups are launched where most
// blocks are cleared and return at once.
const ivec2 DNSR_WIDE_GROUP_SIZE = ivec2(DNSR_WIDE_GROUP_WIDTH, DNSR_WIDE_GROUP_HEIGHT);
const int DNSR_WIDE_GROUP_INVOCATIONS = DNSR_WIDE_GROUP_WIDTH * DNSR_WIDE_GROUP_HEIGHT;
#include "dnsr_specialization.glsl"

uint dnsr_tile_bit(ivec2 p) { return uint((p.y % DNSR_TILE_HEIGHT) * DNSR_TILE_WIDTH + (p.x % DNSR_TILE_WIDTH)); }

bool dnsr_inside(ivec2 p) { return all(greaterThanEqual(p, ivec2(0))) && all(lessThan(p, dnsr_get_extent())); }

// A shadow receiver has geometry: depth strictly between the clear values of both depth conventions.
// NaN depth fails both comparisons and counts as sky.
bool dnsr_is_receiver(float depth) { return depth > 0.0 && depth < 1.0; }

// The (mean, variance) every pass stores for sky and other non-receivers: lit, and a negative variance that marks
// "no receiver", so the filter's variance blur tells receivers apart without reading depth. Receivers' variances
// are never negative.
const vec2 DNSR_SKY_SIGNAL = vec2(1.0, -1.0);
bool dnsr_is_receiver_signal(vec2 signal) { return signal.y >= 0.0; }
// A final receiver's variance: its value is exact (a receiver turned away from the whole light whose ray hit, see
// tile_classification.glsl), so every filter pass returns it as it is and leaves it out of its neighbours' taps and
// variance blur, as it does the sky. Its variance is DNSR_FINAL_VARIANCE (dnsr_storage.glsl). Only with the run
// features: Balanced never has a final pixel, and with the tests it took 1.067 -> 1.099 ms at 4K on an H100, without
// them 1.089 (docs/bench/h200-2026-12-07-final-pixels).
#if defined(DNSR_PASS_TILE_CLASSIFICATION) || defined(DNSR_PASS_FILTER)
bool dnsr_final_signal(vec2 signal) { return dnsr_stores_finals() && dnsr_is_final_variance(signal.y); }
#endif
// With converged pixels on (Settings::converged_samples, dnsr_get_run_settings().z > 0): a converged pixel's signal
// has variance exactly 0 (the filter may pass it through, see dnsr_passes_through); every other receiver stores at
// least DNSR_MIN_UNCONVERGED_VARIANCE, so that float rounding cannot make it look converged.
bool dnsr_converged_on() { return dnsr_get_run_settings().z > 0.0; }
// With float16 intermediates the floor is the smallest normal float16 (a subnormal may be flushed to 0 on store).
#ifdef DNSR_FP16
const float DNSR_MIN_UNCONVERGED_VARIANCE = 1.0 / float(DNSR_UNCONVERGED_VARIANCE_INV_FP16);
#else
const float DNSR_MIN_UNCONVERGED_VARIANCE = 1.0 / float(DNSR_UNCONVERGED_VARIANCE_INV);
#endif
bool dnsr_converged_signal(vec2 signal) { return signal.y == 0.0; }
float dnsr_unconverged_variance(float variance) {
    return dnsr_converged_on() ? max(variance, DNSR_MIN_UNCONVERGED_VARIANCE) : variance;
}

#if defined(DNSR_PASS_TILE_CLASSIFICATION) || defined(DNSR_PASS_FILTER)
// Penumbra guidance: the world-space size of a pixel at linear depth zc (pen: the penumbra constants; <= 0 where the
// projection gives none).
float dnsr_pixel_footprint(vec4 pen, float zc) { return pen.y + pen.z * zc; }

// Penumbra guidance, Settings::hard_penumbra_pixels (run settings w): the blockers near a tile, `blocker` away on
// average (-1: none known), cast a penumbra narrower than that many pixels either side of its edge on a receiver at
// linear depth zc (pen: the light's penumbra constants), and lie DNSR_HARD_PENUMBRA_MIN_BLOCKER_PIXELS pixel
// footprints or more from it (src/passes/mod.rs says why). One ray resolves such a pixel: its output is its sample.
// A light of no size (angular size 0) casts no penumbra at all: one ray resolves every pixel, whether its tile knows
// a blocker or not (faces turned from the light) and however near (contact shadows). (Written as one condition with
// the others: an early `return true` for it made lavapipe, Mesa 22.3, leak JIT memory on every dispatch, which the
// minimal example's LeakSanitizer run caught.)
bool dnsr_hard_penumbra(float blocker, vec4 pen, float zc) {
    float radius = dnsr_get_run_settings().w;
    if (!DNSR_SPEC_PENUMBRA_GUIDED || !(radius > 0.0) || !(blocker >= 0.0 || pen.x == 0.0)) return false;
    float footprint = dnsr_pixel_footprint(pen, zc);
    return footprint > 0.0 && blocker * pen.x < radius * footprint
        && (pen.x == 0.0 || blocker >= float(DNSR_HARD_PENUMBRA_MIN_BLOCKER_PIXELS) * footprint);
}

// Penumbra guidance, Settings::hard_penumbra_pixels: no blocker known anywhere within +-8 px of the tile (every
// shadowed pixel there is a face turned from the light, or the window holds none): its samples are exact.
bool dnsr_no_blocker(float blocker) {
    return DNSR_SPEC_PENUMBRA_GUIDED && dnsr_get_run_settings().w > 0.0 && blocker < 0.0;
}
#endif

// Vulkan NDC: uv (0,0) is the top-left corner and maps to ndc (-1,-1).
vec2 dnsr_uv_to_ndc(vec2 uv) { return uv * 2.0 - 1.0; }
vec2 dnsr_pixel_uv(ivec2 p) { return (vec2(p) + 0.5) * dnsr_get_inv_extent(); }

// Distance along the view axis, from the inverse projection. Infinite for an infinite far plane's far depth.
float dnsr_linear_depth(vec2 ndc, float depth) {
    vec4 v = dnsr_get_projection_inverse() * vec4(ndc, depth, 1.0);
    return abs(v.z / v.w);
}

// World-space position of pixel q at device depth `depth`.
vec3 dnsr_world_position(ivec2 q, float depth) {
    vec4 h = dnsr_get_view_projection_inverse() * vec4(dnsr_uv_to_ndc(dnsr_pixel_uv(q)), depth, 1.0);
    return h.xyz / h.w;
}

// Pixel p's linear depth where `depth` (its device depth) is a receiver's, -1 for sky.
float dnsr_receiver_linear_depth(ivec2 p, float depth) {
    return dnsr_is_receiver(depth) ? dnsr_linear_depth(dnsr_uv_to_ndc(dnsr_pixel_uv(p)), depth) : -1.0;
}

// A stored visibility as the passes use it: clamped to [0, 1], NaN read as 0 (shadowed).
float dnsr_sanitize_visibility(float v) { return v >= 0.0 ? min(v, 1.0) : 0.0; }

bool dnsr_finite(float x) { return !isnan(x) && !isinf(x); }
bool dnsr_finite(vec2 x) { return dnsr_finite(x.x) && dnsr_finite(x.y); }

#endif
