// dnsr standard callbacks: the Get/Read/Write functions the pass cores call, implemented over dnsr's standard
// bindings. The pass entry files include dnsr_callbacks_default.glsl, which includes this file; an engine with an
// unusual G-buffer replaces dnsr_callbacks_default.glsl with its own (docs/callbacks.md). To change only the
// G-buffer depth and normal reads it defines DNSR_ENGINE_DEPTH_NORMALS, includes this file, then declares
// dnsr_depth and dnsr_normals (bindings 4 and 6) and dnsr_read_depth / dnsr_read_normal itself.
//
// The entry file defines exactly one of DNSR_PASS_PREPARE, DNSR_PASS_TILE_CLASSIFICATION, DNSR_PASS_FILTER,
// DNSR_PASS_CLASSIFY (the hybrid-shadows classifier)
// before including the callbacks, so each pass declares only the resources it touches.
//
// Coordinates handed to callbacks are relative to the render rectangle; callbacks add its offset.

#ifndef DNSR_CALLBACKS_STANDARD_GLSL
#define DNSR_CALLBACKS_STANDARD_GLSL

#extension GL_EXT_samplerless_texture_functions : require

#include "generated/dnsr_constants.glsl"
#include "dnsr_precision.glsl"
#include "dnsr_storage.glsl"

layout(set = 0, binding = 0, std140) uniform DnsrConstantsBlock { DnsrFrameConstants dnsr_constants; };

// ---- Get: constants ------------------------------------------------------------------------------------------
ivec2 dnsr_get_extent() { return ivec2(dnsr_constants.rect.zw); }
vec2 dnsr_get_inv_extent() { return dnsr_constants.inv_extent.xy; }
ivec2 dnsr_get_offset() { return ivec2(dnsr_constants.rect.xy); }
mat4 dnsr_get_projection_inverse() { return dnsr_constants.projection_inverse; }
mat4 dnsr_get_reprojection_matrix() { return dnsr_constants.reprojection; }
mat4 dnsr_get_view_projection_inverse() { return dnsr_constants.view_projection_inverse; }
vec3 dnsr_get_eye() { return dnsr_constants.eye_depth_sigma.xyz; }
float dnsr_get_depth_similarity_sigma() { return dnsr_constants.eye_depth_sigma.w; }
bool dnsr_get_is_reset() { return (dnsr_constants.flags.x & DNSR_FLAG_RESET) != 0u; }
bool dnsr_get_is_depth_inverted() { return (dnsr_constants.flags.x & DNSR_FLAG_DEPTH_INVERTED) != 0u; }
bool dnsr_get_is_lit_bit_mask() { return (dnsr_constants.flags.x & DNSR_FLAG_LIT_BIT_MASK) != 0u; }
// Checkerboard input: this frame's rays were traced for the pixels with (x + y) % 2 == phase.
bool dnsr_get_is_checkerboard() { return (dnsr_constants.flags.x & DNSR_FLAG_CHECKERBOARD) != 0u; }
// Whether the host gave the light's position (ShadowsDispatch::light_position), and that homogeneous point.
bool dnsr_get_has_light_position() { return (dnsr_constants.flags.x & DNSR_FLAG_LIGHT_POSITION) != 0u; }
vec4 dnsr_get_light_position() { return dnsr_constants.light_position; }
// With it: the sine of the light's angular radius (0: a light of no size).
float dnsr_get_light_sin_radius() { return dnsr_constants.light_extent.x; }
int dnsr_get_checkerboard_phase() { return int(dnsr_constants.flags.y); }
// Whether pixel p (render-rectangle coordinates: its offset is a whole number of tiles, so the parity is the
// image's) was traced this frame by a checkerboard input.
bool dnsr_is_traced(ivec2 p) { return ((p.x + p.y) & 1) == dnsr_get_checkerboard_phase(); }
vec4 dnsr_get_disocclusion_settings() { return dnsr_constants.disocclusion; }
vec4 dnsr_get_rejection_settings() { return dnsr_constants.rejection; }
float dnsr_get_signal_scale() { return dnsr_constants.rejection.w; }
vec4 dnsr_get_temporal_settings() { return dnsr_constants.temporal; }
vec4 dnsr_get_filter_settings() { return dnsr_constants.filtering; }
vec4 dnsr_get_run_settings() { return dnsr_constants.runs; }
vec4 dnsr_get_moving_settings() { return dnsr_constants.moving; }
// x: tan(light angular diameter / 2); a pixel's world size at linear depth z is y + z * z; w: the filter's sigma
// in penumbra half-widths.
vec4 dnsr_get_penumbra_settings() { return dnsr_constants.penumbra; }

// World-space unit normal of a stored one (normalsUnpackMul / Add), or vec3(0) when it is not usable (zero, NaN,
// Inf): a zero normal matches nothing in the edge stops, so a broken G-buffer texel cannot spread into its
// neighbours.
vec3 dnsr_decode_normal(vec3 stored) {
    vec3 n = stored * dnsr_constants.motion_normals.z + dnsr_constants.motion_normals.w;
    float len2 = dot(n, n);
    return (len2 > 1e-12 && len2 < 1e30) ? n * inversesqrt(len2) : vec3(0.0);
}

// Decoded host G-buffer reads shared by the classification and filter passes.
#if (defined(DNSR_PASS_TILE_CLASSIFICATION) || defined(DNSR_PASS_FILTER) || defined(DNSR_PASS_CLASSIFY)) && !defined(DNSR_ENGINE_DEPTH_NORMALS)
layout(set = 0, binding = 4) uniform texture2D dnsr_depth;
layout(set = 0, binding = 6) uniform texture2D dnsr_normals;

float dnsr_read_depth(ivec2 p) { return texelFetch(dnsr_depth, p + dnsr_get_offset(), 0).r; }
vec3 dnsr_read_normal(ivec2 p) { return dnsr_decode_normal(texelFetch(dnsr_normals, p + dnsr_get_offset(), 0).xyz); }
#endif

#ifdef DNSR_PASS_PREPARE
layout(set = 0, binding = 2, r32ui) uniform writeonly uimage2D dnsr_tile_mask_out;

ivec2 dnsr_get_tile_offset() { return dnsr_get_offset() / ivec2(DNSR_TILE_WIDTH, DNSR_TILE_HEIGHT); }
#ifndef DNSR_VISIBILITY_INPUT
layout(set = 0, binding = 1) uniform utexture2D dnsr_hit_mask;
uint dnsr_read_hit_mask(ivec2 tile) { return texelFetch(dnsr_hit_mask, tile + dnsr_get_tile_offset(), 0).r; }
#endif
void dnsr_write_tile_mask(ivec2 tile, uint lit_bits) { imageStore(dnsr_tile_mask_out, tile + dnsr_get_tile_offset(), uvec4(lit_bits)); }
#ifdef DNSR_VISIBILITY_INPUT
// Visibility input (a context created with a visibility input): the fraction of the pixel's shadow rays that
// reached the light, in [0, 1] (the core clamps, and reads NaN as 0); prepare writes the tile words of exactly
// lit pixels (the tile mask) and of exactly shadowed ones (the dark mask) from it.
layout(set = 0, binding = 24) uniform texture2D dnsr_visibility;
float dnsr_read_visibility(ivec2 p) { return texelFetch(dnsr_visibility, p + dnsr_get_offset(), 0).r; }
#endif
#if defined(DNSR_VISIBILITY_INPUT) || defined(DNSR_CHECKERBOARD_INPUT)
layout(set = 0, binding = 25, r32ui) uniform writeonly uimage2D dnsr_tile_dark_out;
void dnsr_write_tile_dark(ivec2 tile, uint dark_bits) { imageStore(dnsr_tile_dark_out, tile + dnsr_get_tile_offset(), uvec4(dark_bits)); }
#endif
#ifdef DNSR_CHECKERBOARD_INPUT
// Checkerboard input: prepare reconstructs every pixel's visibility from the half of the pixels traced this frame,
// into an internal image that classification reads as a visibility input.
layout(set = 0, binding = 27, r32f) uniform writeonly image2D dnsr_visibility_out;
void dnsr_write_visibility(ivec2 p, float v) { imageStore(dnsr_visibility_out, p + dnsr_get_offset(), vec4(v)); }
#endif
#endif

// The moments' storage format: one word per pixel (dnsr_pack_moments); a visibility input's moments keep their sum
// of squared deviations in a second (float32 bits).
#ifdef DNSR_VISIBILITY_INPUT
#define DNSR_MOMENTS_FORMAT rg32ui
#else
#define DNSR_MOMENTS_FORMAT r32ui
#endif

#ifdef DNSR_PASS_TILE_CLASSIFICATION
layout(set = 0, binding = 3) uniform utexture2D dnsr_tile_mask;
layout(set = 0, binding = 5) uniform texture2D dnsr_velocity;
#ifdef DNSR_HOST_PREVIOUS_GBUFFER
// The host's own previous frame (ContextCreateInfo::host_previous_gbuffer): its depth and normals as it gave them
// last frame, in the formats of this frame's (dnsr_read_previous_depth and dnsr_read_previous_normal linearise and
// decode them, in tile_classification.glsl). An engine that reads its G-buffer itself
// (DNSR_ENGINE_DEPTH_NORMALS) declares these two and their reads as well.
#ifndef DNSR_ENGINE_DEPTH_NORMALS
layout(set = 0, binding = 7) uniform texture2D dnsr_previous_depth;
layout(set = 0, binding = 67) uniform texture2D dnsr_previous_normals;
float dnsr_read_host_previous_depth(ivec2 p) { return texelFetch(dnsr_previous_depth, p + dnsr_get_offset(), 0).r; }
vec3 dnsr_read_host_previous_normal(ivec2 p) { return dnsr_decode_normal(texelFetch(dnsr_previous_normals, p + dnsr_get_offset(), 0).xyz); }
#endif
#else
layout(set = 0, binding = 7) uniform utexture2D dnsr_previous_depth;
#endif
layout(set = 0, binding = 9) uniform utexture2D dnsr_previous_moments;
layout(set = 0, binding = 10, DNSR_MOMENTS_FORMAT) uniform writeonly uimage2D dnsr_moments;
layout(set = 0, binding = 11) uniform texture2D dnsr_history;
layout(set = 0, binding = 12, DNSR_INTERMEDIATE_FORMAT) uniform writeonly image2D dnsr_reprojection;
layout(set = 0, binding = 13, r32ui) uniform writeonly uimage2D dnsr_tile_meta_out;

ivec2 dnsr_get_tile_offset() { return dnsr_get_offset() / ivec2(DNSR_TILE_WIDTH, DNSR_TILE_HEIGHT); }
uint dnsr_read_tile_mask(ivec2 tile) { return texelFetch(dnsr_tile_mask, tile + dnsr_get_tile_offset(), 0).r; }
#ifdef DNSR_VISIBILITY_INPUT
// Visibility input: each pixel's visibility (see the prepare pass), and the words of exactly shadowed pixels
// prepare wrote (the tile mask holds the exactly lit ones).
layout(set = 0, binding = 24) uniform texture2D dnsr_visibility;
layout(set = 0, binding = 26) uniform utexture2D dnsr_tile_dark;
float dnsr_read_visibility(ivec2 p) { return texelFetch(dnsr_visibility, p + dnsr_get_offset(), 0).r; }
uint dnsr_read_tile_dark(ivec2 tile) { return texelFetch(dnsr_tile_dark, tile + dnsr_get_tile_offset(), 0).r; }
#endif
// Screen-uv displacement from this pixel to where its surface was last frame (prev_uv = uv + velocity).
vec2 dnsr_read_velocity(ivec2 p) {
    return texelFetch(dnsr_velocity, p + dnsr_get_offset(), 0).xy * dnsr_constants.motion_normals.xy;
}
#ifndef DNSR_HOST_PREVIOUS_GBUFFER
// Last frame's linear depth and unit normal (vec3(0): none) at p, as its depth copy holds them
// (dnsr_pack_depth_copy).
float dnsr_read_previous_depth(ivec2 p) { return dnsr_depth_copy_depth(texelFetch(dnsr_previous_depth, p + dnsr_get_offset(), 0).r); }
vec3 dnsr_read_previous_normal(ivec2 p) { return dnsr_depth_copy_normal(texelFetch(dnsr_previous_depth, p + dnsr_get_offset(), 0).r); }
#endif
// The first word of p's moments as stored (dnsr_pack_moments; 0: no receiver's).
uint dnsr_read_previous_moments_word(ivec2 p) { return texelFetch(dnsr_previous_moments, p + dnsr_get_offset(), 0).x; }
// (mean, sum of squared deviations, sample count, run of identical samples: +n lit, -n shadowed).
vec4 dnsr_read_previous_moments(ivec2 p) {
    uvec2 v = texelFetch(dnsr_previous_moments, p + dnsr_get_offset(), 0).xy;
    vec4 m = dnsr_unpack_moments(v.x);
#ifdef DNSR_VISIBILITY_INPUT
    m.y = uintBitsToFloat(v.y);
#endif
    return m;
}
float dnsr_read_history_texel(ivec2 p) { return texelFetch(dnsr_history, p + dnsr_get_offset(), 0).r; }
// Bilinear history at a rect-relative uv, clamped to the rectangle's edge: four texels blended with float weights.
// Not the sampler's filter: its weights have only subTexelPrecisionBits of sub-texel resolution (8 on NVIDIA), and
// the history moves the rejection, which scales the stored moments, so the parity suite failed on NVIDIA under
// sub-pixel camera motion (a stored sum of squared deviations 4 float16 steps from the reference's).
float dnsr_read_history(vec2 uv) {
    vec2 t = uv * vec2(dnsr_get_extent()) - 0.5;
    vec2 f = t - floor(t);
    ivec2 base = ivec2(floor(t));
    ivec2 last = dnsr_get_extent() - 1;
    float h00 = dnsr_read_history_texel(clamp(base, ivec2(0), last));
    float h10 = dnsr_read_history_texel(clamp(base + ivec2(1, 0), ivec2(0), last));
    float h01 = dnsr_read_history_texel(clamp(base + ivec2(0, 1), ivec2(0), last));
    float h11 = dnsr_read_history_texel(clamp(base + ivec2(1, 1), ivec2(0), last));
    return mix(mix(h00, h10, f.x), mix(h01, h11, f.x), f.y);
}
void dnsr_write_moments(ivec2 p, vec4 m) { imageStore(dnsr_moments, p + dnsr_get_offset(), uvec4(dnsr_pack_moments(m), floatBitsToUint(m.y), 0u, 0u)); }
void dnsr_write_reprojection(ivec2 p, vec2 mean_var) { imageStore(dnsr_reprojection, p + dnsr_get_offset(), dnsr_encode_signal(mean_var, dnsr_get_signal_scale())); }
void dnsr_write_tile_meta(ivec2 tile, uint meta) { imageStore(dnsr_tile_meta_out, tile + dnsr_get_tile_offset(), uvec4(meta)); }
// Each tile's frames since one of its receivers' samples contradicted last frame's (Settings::hard_tile_frames):
// last frame's, and this frame's, which classification's tile writer stores and its contradicting receivers clear
// (both atomics on the one word: the barriers between order them).
layout(set = 0, binding = 20) uniform utexture2D dnsr_previous_tile_quiet;
layout(set = 0, binding = 63, r32ui) uniform uimage2D dnsr_tile_quiet;
uint dnsr_read_previous_tile_quiet(ivec2 tile) { return texelFetch(dnsr_previous_tile_quiet, tile + dnsr_get_tile_offset(), 0).r; }
void dnsr_write_tile_quiet(ivec2 tile, uint frames) { imageAtomicExchange(dnsr_tile_quiet, tile + dnsr_get_tile_offset(), frames); }
void dnsr_clear_tile_quiet(ivec2 tile) { imageAtomicAnd(dnsr_tile_quiet, tile + dnsr_get_tile_offset(), 0u); }
// Penumbra guidance: the host's distance to the first occluder (read where the mask says the ray hit), and each
// tile's blocker estimate for the filter (-1: unknown).
layout(set = 0, binding = 21) uniform texture2D dnsr_hit_distance;
layout(set = 0, binding = 22, r32f) uniform writeonly image2D dnsr_tile_blocker_out;
float dnsr_read_hit_distance(ivec2 p) { return texelFetch(dnsr_hit_distance, p + dnsr_get_offset(), 0).r; }
void dnsr_write_tile_blocker(ivec2 tile, float distance) { imageStore(dnsr_tile_blocker_out, tile + dnsr_get_tile_offset(), vec4(distance)); }
// The host's output, written here for cleared tiles only (their final value is known; later filter passes skip
// them).
layout(set = 0, binding = 17, DNSR_OUTPUT_FORMAT) uniform writeonly image2D dnsr_output;
void dnsr_write_output(ivec2 p, float shadow) { imageStore(dnsr_output, p + dnsr_get_offset(), vec4(shadow)); }
#endif

#ifdef DNSR_PASS_FILTER
layout(push_constant) uniform DnsrPushBlock { DnsrFilterPush dnsr_push; };
layout(set = 0, binding = 14) uniform utexture2D dnsr_tile_meta;
// A sampler so that the later passes can gather the variances of 2x2 texels in one fetch.
layout(set = 0, binding = 15) uniform sampler2D dnsr_filter_input;
layout(set = 0, binding = 16, DNSR_INTERMEDIATE_FORMAT) uniform writeonly image2D dnsr_filter_output;
// The depth copy of this frame (binding 8, which the first pass writes), sampled by the later passes as their guide.
layout(set = 0, binding = 19) uniform utexture2D dnsr_guide;
#ifdef DNSR_FINAL_PASS
layout(set = 0, binding = 17, DNSR_OUTPUT_FORMAT) uniform writeonly image2D dnsr_output;
// This frame's moments, read only by the debug views.
layout(set = 0, binding = 18) uniform utexture2D dnsr_debug_moments;
#endif
#ifndef DNSR_LATER_PASS
// This frame's linear depth (-1: no receiver) and normal, for the later filter passes (dnsr_read_guide) and the
// next frame's classification (dnsr_read_previous_depth, dnsr_read_previous_normal). Written by the first filter
// pass, after this frame's classification has read last frame's from the same image: one image, not two.
layout(set = 0, binding = 8, r32ui) uniform writeonly uimage2D dnsr_depth_copy;
void dnsr_write_depth_copy(ivec2 p, float linear_depth, vec3 normal) {
    imageStore(dnsr_depth_copy, p + dnsr_get_offset(), uvec4(dnsr_pack_depth_copy(linear_depth, normal)));
}
// This frame's moments as classification stored them, and the image the next frame's classification reads them
// from (dnsr_read_previous_moments), which this pass writes once classification has read last frame's: one kept
// image, the other transient. Copied as stored words (the second one with a visibility input's fractions).
layout(set = 0, binding = 64) uniform utexture2D dnsr_frame_moments;
layout(set = 0, binding = 65, DNSR_MOMENTS_FORMAT) uniform writeonly uimage2D dnsr_kept_moments;
uvec2 dnsr_read_frame_moments(ivec2 p) { return texelFetch(dnsr_frame_moments, p + dnsr_get_offset(), 0).xy; }
void dnsr_write_kept_moments(ivec2 p, uvec2 words) { imageStore(dnsr_kept_moments, p + dnsr_get_offset(), uvec4(words, 0u, 0u)); }
// The next frame's history: this pass's mean alone (the next frame's classification blends nothing else). Its
// variance reaches the later passes through the filter output, a transient image (with a hit mask, the frame
// moments' memory, which this pass has read at the pixel by then).
layout(set = 0, binding = 66, DNSR_HISTORY_FORMAT) uniform writeonly image2D dnsr_history_out;
void dnsr_write_history(ivec2 p, float mean) { imageStore(dnsr_history_out, p + dnsr_get_offset(), vec4(mean)); }
#endif

int dnsr_get_filter_step() { return int(dnsr_push.pass.x); }
bool dnsr_get_write_internal() { return (dnsr_push.pass.y & DNSR_PASS_WRITE_INTERNAL) != 0u; }
bool dnsr_get_skip_cleared() { return (dnsr_push.pass.y & DNSR_PASS_SKIP_CLEARED) != 0u; }
// The later passes' per-pixel geometry, (linear depth or -1, normal): this frame's depth copy, which the first pass
// wrote.
vec4 dnsr_read_guide(ivec2 p) {
    uint v = texelFetch(dnsr_guide, p + dnsr_get_offset(), 0).r;
    return vec4(dnsr_depth_copy_depth(v), dnsr_depth_copy_normal(v));
}
uint dnsr_read_tile_meta(ivec2 tile) { return texelFetch(dnsr_tile_meta, tile + dnsr_get_offset() / ivec2(DNSR_TILE_WIDTH, DNSR_TILE_HEIGHT), 0).r; }
layout(set = 0, binding = 23) uniform texture2D dnsr_tile_blocker;
float dnsr_read_tile_blocker(ivec2 tile) { return texelFetch(dnsr_tile_blocker, tile + dnsr_get_offset() / ivec2(DNSR_TILE_WIDTH, DNSR_TILE_HEIGHT), 0).r; }
vec2 dnsr_read_filter_input(ivec2 p) { return dnsr_decode_signal(texelFetch(dnsr_filter_input, p + dnsr_get_offset(), 0).xy, dnsr_get_signal_scale()); }
// Variances of the 2x2 texels around the texel corner at the top left of pixel `corner`.
vec4 dnsr_gather_filter_variance(ivec2 corner) {
    vec2 uv = vec2(corner + dnsr_get_offset()) * dnsr_constants.inv_extent.zw;
    return dnsr_decode_variances(textureGather(dnsr_filter_input, uv, 1), dnsr_get_signal_scale());
}
void dnsr_write_filter_output(ivec2 p, vec2 mean_var) { imageStore(dnsr_filter_output, p + dnsr_get_offset(), dnsr_encode_signal(mean_var, dnsr_get_signal_scale())); }
#ifdef DNSR_FINAL_PASS
void dnsr_write_output(ivec2 p, float shadow) { imageStore(dnsr_output, p + dnsr_get_offset(), vec4(shadow)); }
uint dnsr_get_debug_view() { return dnsr_push.pass.w; }
vec4 dnsr_read_debug_moments(ivec2 p) { return dnsr_unpack_moments(texelFetch(dnsr_debug_moments, p + dnsr_get_offset(), 0).x); }
#endif

#ifdef DNSR_LIGHT_SLOTS_VARIANT
// Several lights per dispatch (the filter_later_lights variants, which a record of several lights runs for its
// later filter passes): DNSR_LIGHT_SLOTS slots, each one light's per-light images. Slot 0 is the bindings above;
// slot s > 0 has six bindings from 40 + 6 (s - 1), named with the suffix _s. A dispatch fills the first
// dnsr_get_light_count() slots; the others are bound to slot 0's images and never touched.
#define DNSR_LIGHT_SLOT(S, B) \
    layout(set = 0, binding = B) uniform utexture2D dnsr_tile_meta_##S; \
    layout(set = 0, binding = B + 1) uniform texture2D dnsr_tile_blocker_##S; \
    layout(set = 0, binding = B + 2) uniform sampler2D dnsr_filter_input_##S; \
    layout(set = 0, binding = B + 3, DNSR_INTERMEDIATE_FORMAT) uniform writeonly image2D dnsr_filter_output_##S;
#ifdef DNSR_FINAL_PASS
#define DNSR_LIGHT_SLOT_FINAL(S, B) \
    layout(set = 0, binding = B + 4, DNSR_OUTPUT_FORMAT) uniform writeonly image2D dnsr_output_##S; \
    layout(set = 0, binding = B + 5) uniform utexture2D dnsr_debug_moments_##S;
#else
#define DNSR_LIGHT_SLOT_FINAL(S, B)
#endif
DNSR_LIGHT_SLOT(1, 40) DNSR_LIGHT_SLOT_FINAL(1, 40)
DNSR_LIGHT_SLOT(2, 46) DNSR_LIGHT_SLOT_FINAL(2, 46)
DNSR_LIGHT_SLOT(3, 52) DNSR_LIGHT_SLOT_FINAL(3, 52)

#if DNSR_LIGHT_SLOTS != 4
#error "the slot bindings above are written out for four slots"
#endif

// Slot l's expression e0..e3. Each loop over the slots unrolls, so l is a constant and the choice folds away.
#define DNSR_BY_SLOT(l, e0, e1, e2, e3) ((l) == 0 ? (e0) : (l) == 1 ? (e1) : (l) == 2 ? (e2) : (e3))

int dnsr_get_light_count() { return int(dnsr_push.lights.x); }
bool dnsr_get_light_guided(int l) { return ((dnsr_push.lights.y >> uint(l)) & 1u) != 0u; }
vec4 dnsr_get_light_penumbra_settings(int l) {
    return vec4(dnsr_push.light_tan_half_angle[l], dnsr_constants.penumbra.yzw);
}
uint dnsr_read_light_tile_meta(int l, ivec2 tile) {
    ivec2 t = tile + dnsr_get_offset() / ivec2(DNSR_TILE_WIDTH, DNSR_TILE_HEIGHT);
    return DNSR_BY_SLOT(l, texelFetch(dnsr_tile_meta, t, 0).r, texelFetch(dnsr_tile_meta_1, t, 0).r,
                        texelFetch(dnsr_tile_meta_2, t, 0).r, texelFetch(dnsr_tile_meta_3, t, 0).r);
}
float dnsr_read_light_tile_blocker(int l, ivec2 tile) {
    ivec2 t = tile + dnsr_get_offset() / ivec2(DNSR_TILE_WIDTH, DNSR_TILE_HEIGHT);
    return DNSR_BY_SLOT(l, texelFetch(dnsr_tile_blocker, t, 0).r, texelFetch(dnsr_tile_blocker_1, t, 0).r,
                        texelFetch(dnsr_tile_blocker_2, t, 0).r, texelFetch(dnsr_tile_blocker_3, t, 0).r);
}
vec2 dnsr_read_light_filter_input(int l, ivec2 p) {
    ivec2 q = p + dnsr_get_offset();
    return dnsr_decode_signal(DNSR_BY_SLOT(l, texelFetch(dnsr_filter_input, q, 0), texelFetch(dnsr_filter_input_1, q, 0),
                        texelFetch(dnsr_filter_input_2, q, 0), texelFetch(dnsr_filter_input_3, q, 0)).xy, dnsr_get_signal_scale());
}
vec4 dnsr_gather_light_filter_variance(int l, ivec2 corner) {
    vec2 uv = vec2(corner + dnsr_get_offset()) * dnsr_constants.inv_extent.zw;
    vec4 v = DNSR_BY_SLOT(l, textureGather(dnsr_filter_input, uv, 1), textureGather(dnsr_filter_input_1, uv, 1),
                          textureGather(dnsr_filter_input_2, uv, 1), textureGather(dnsr_filter_input_3, uv, 1));
    return dnsr_decode_variances(v, dnsr_get_signal_scale());
}
void dnsr_write_light_filter_output(int l, ivec2 p, vec2 mean_var) {
    ivec2 q = p + dnsr_get_offset();
    vec4 v = dnsr_encode_signal(mean_var, dnsr_get_signal_scale());
    if (l == 0) imageStore(dnsr_filter_output, q, v);
    else if (l == 1) imageStore(dnsr_filter_output_1, q, v);
    else if (l == 2) imageStore(dnsr_filter_output_2, q, v);
    else imageStore(dnsr_filter_output_3, q, v);
}
#ifdef DNSR_FINAL_PASS
void dnsr_write_light_output(int l, ivec2 p, float shadow) {
    ivec2 q = p + dnsr_get_offset();
    if (l == 0) imageStore(dnsr_output, q, vec4(shadow));
    else if (l == 1) imageStore(dnsr_output_1, q, vec4(shadow));
    else if (l == 2) imageStore(dnsr_output_2, q, vec4(shadow));
    else imageStore(dnsr_output_3, q, vec4(shadow));
}
vec4 dnsr_read_light_debug_moments(int l, ivec2 p) {
    ivec2 q = p + dnsr_get_offset();
    return dnsr_unpack_moments(DNSR_BY_SLOT(l, texelFetch(dnsr_debug_moments, q, 0), texelFetch(dnsr_debug_moments_1, q, 0),
                        texelFetch(dnsr_debug_moments_2, q, 0), texelFetch(dnsr_debug_moments_3, q, 0)).x);
}
#endif
#endif
#endif

#ifdef DNSR_PASS_CLASSIFY
// The hybrid-shadows classifier: its own constants next to the frame constants, the cascades' shadow maps (separate
// images, or the layers of one array image with DNSR_CASCADE_ARRAY), and its outputs: the host's hit mask
// (prefilled with the verdicts), the tile list and the counts (dnsr's buffers, as texel buffers so that reflection
// sees them).
layout(set = 0, binding = 28, std140) uniform DnsrClassifyBlock { DnsrClassifyConstants dnsr_classify_constants; };
layout(set = 0, binding = 29, r32ui) uniform writeonly uimage2D dnsr_hit_mask_out;
layout(set = 0, binding = 30, rgba32ui) uniform writeonly uimageBuffer dnsr_tile_list;
layout(set = 0, binding = 31, r32ui) uniform uimageBuffer dnsr_tile_count;
#ifdef DNSR_CASCADE_ARRAY
layout(set = 0, binding = 62) uniform texture2DArray dnsr_cascades;
ivec2 dnsr_get_cascade_size(int c) { return textureSize(dnsr_cascades, 0).xy; }
float dnsr_read_cascade_depth(int c, ivec2 texel) { return texelFetch(dnsr_cascades, ivec3(texel, c), 0).r; }
#else
layout(set = 0, binding = 58) uniform texture2D dnsr_cascade_0;
layout(set = 0, binding = 59) uniform texture2D dnsr_cascade_1;
layout(set = 0, binding = 60) uniform texture2D dnsr_cascade_2;
layout(set = 0, binding = 61) uniform texture2D dnsr_cascade_3;
ivec2 dnsr_get_cascade_size(int c) {
    return c == 0 ? textureSize(dnsr_cascade_0, 0) : c == 1 ? textureSize(dnsr_cascade_1, 0)
         : c == 2 ? textureSize(dnsr_cascade_2, 0) : textureSize(dnsr_cascade_3, 0);
}
float dnsr_read_cascade_depth(int c, ivec2 texel) {
    return c == 0 ? texelFetch(dnsr_cascade_0, texel, 0).r : c == 1 ? texelFetch(dnsr_cascade_1, texel, 0).r
         : c == 2 ? texelFetch(dnsr_cascade_2, texel, 0).r : texelFetch(dnsr_cascade_3, texel, 0).r;
}
#endif
mat4 dnsr_get_cascade_matrix(int c) {
    return c == 0 ? dnsr_classify_constants.cascade0 : c == 1 ? dnsr_classify_constants.cascade1 : c == 2 ? dnsr_classify_constants.cascade2 : dnsr_classify_constants.cascade3;
}
vec4 dnsr_get_cascade_units(int c) { return dnsr_classify_constants.cascade_units[c]; }
vec3 dnsr_get_cascade_axis_u(int c) { return dnsr_classify_constants.cascade_axes_u[c].xyz; }
vec3 dnsr_get_cascade_axis_v(int c) { return dnsr_classify_constants.cascade_axes_v[c].xyz; }
int dnsr_get_cascade_count() { return int(dnsr_classify_constants.settings.x); }
int dnsr_get_classify_taps() { return int(dnsr_classify_constants.settings.y); }
uint dnsr_get_tile_cutoff() { return dnsr_classify_constants.settings.z; }
bool dnsr_get_classify_flag(uint flag) { return (dnsr_classify_constants.settings.w & flag) != 0u; }
vec3 dnsr_get_light_direction() { return dnsr_classify_constants.light.xyz; }
float dnsr_get_light_tan_half_angle() { return dnsr_classify_constants.light.w; }
ivec2 dnsr_get_tile_offset() { return dnsr_get_offset() / ivec2(DNSR_TILE_WIDTH, DNSR_TILE_HEIGHT); }
void dnsr_write_hit_mask(ivec2 tile, uint word) { imageStore(dnsr_hit_mask_out, tile + dnsr_get_tile_offset(), uvec4(word)); }
// Appends a tile record; the counts hold (tiles, 1, 1, tiles) then (32 x tiles, 1, 1, 0).
void dnsr_append_tile(uvec4 record) {
    int index = int(imageAtomicAdd(dnsr_tile_count, 0, 1u));
    imageAtomicAdd(dnsr_tile_count, 3, 1u);
    imageAtomicAdd(dnsr_tile_count, 4, 32u);
    imageStore(dnsr_tile_list, index, record);
}
#endif

#endif
