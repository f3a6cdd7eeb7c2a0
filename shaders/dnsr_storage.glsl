// How dnsr packs the per-pixel state it keeps in compact formats (docs/performance.md, "State model"). The CPU
// reference rounds at the same points in the same way (src/reference/storage.rs): every rounding here is written
// out in integer or exact float steps, never left to a conversion whose rounding the Vulkan spec leaves open
// (imageStore to a float16 or unorm format, packHalf2x16, round()).
#ifndef DNSR_STORAGE_GLSL
#define DNSR_STORAGE_GLSL

#include "generated/dnsr_constants.glsl"
#include "dnsr_specialization.glsl"

// v >= 0 rounded to the nearest float16 value (ties to even), in float32: exact through packHalf2x16 on any
// implementation. Below the smallest normal float16 (2^-14) it is 0 (no subnormals, which a driver may flush);
// above the largest (65504) it is 65504.
float dnsr_round_half(float v) {
    if (!(v >= 6.103515625e-05)) return 0.0;
    uint b = floatBitsToUint(min(v, 65504.0));
    return uintBitsToFloat((b + 0x0FFFu + ((b >> 13) & 1u)) & 0xFFFFE000u);
}

// v in [0, 1] to a 16-bit unorm code: floor(v * 65535 + 0.5), ties up.
uint dnsr_unorm16(float v) { return uint(floor(clamp(v, 0.0, 1.0) * 65535.0 + 0.5)); }
// The code back; the ends are exact (0 and 1 are compared for equality: dnsr_pure).
float dnsr_from_unorm16(uint u) { return u == 65535u ? 1.0 : float(u) * (1.0 / 65535.0); }

// A linear depth (view units) in DNSR_DEPTH_CODE_BITS (16) bits: a float without sign bit, 6 exponent bits and
// DNSR_DEPTH_CODE_MANTISSA_BITS (10) mantissa bits, from 2^-16 to 2^48 (float32's bits shifted and offset, rounded to
// nearest). Neighbouring codes lie 0.049-0.098% apart, at most a tenth of the default disocclusion threshold (1%),
// at any scene scale (millimetres to light years), and the code reads back with two integer operations. Code 0 is
// no receiver (a negative depth: the sky's -1), and reads back as -1. Receivers' depths below the range take
// code 1; above it, infinite and NaN ones the last.
const uint DNSR_DEPTH_CODE_MAX = (1u << DNSR_DEPTH_CODE_BITS) - 1u;
uint dnsr_pack_linear_depth(float z) {
    if (z < 0.0) return 0u;
    uint b = (floatBitsToUint(abs(z)) + (1u << (DNSR_DEPTH_CODE_SHIFT - 1))) >> DNSR_DEPTH_CODE_SHIFT;
    return b <= DNSR_DEPTH_CODE_OFFSET ? 1u : min(b - DNSR_DEPTH_CODE_OFFSET, DNSR_DEPTH_CODE_MAX);
}
float dnsr_unpack_linear_depth(uint code) {
    return code == 0u ? -1.0 : uintBitsToFloat((code + DNSR_DEPTH_CODE_OFFSET) << DNSR_DEPTH_CODE_SHIFT);
}

// Moments (mean, sample count, run of identical samples) in one word, the image's first (R32_UINT with a hit
// mask: 4 bytes per pixel):
//   bits 0-13: the mean as unorm14;
//   bits 14-22: the sample count as a 9-bit float (4 exponent bits, 5 mantissa bits, subnormals: whole counts exact
//     up to 64, steps of 2 up to 128, Settings::max_history_samples' bound; the smallest step 2^-12);
//   bits 23-31: twice the run as a signed 9-bit integer (runs are whole or half samples, at most
//     DNSR_MAX_SAMPLE_RUN = 127).
// The sum of squared deviations is not stored: with samples of 0 or 1 it is count * mean * (1 - mean) (Welford's
// update and the rejection's scaling keep it so), which unpacking forms. A visibility input's samples are
// fractions: its moments keep the sum as float32 in a second word (R32G32_UINT), which the caller reads and writes.
// The mean's even steps matter more than its bits: a float mean near 1 would move in steps too coarse for an
// update of (x - mean) / 32 (float16: it stalls 1/256 short of its target); unorm14's stall is 1/1000 at 32 samples,
// and 0 and 1 (dnsr_pure compares them) are exact.
// The count's code from its float32 bits: the exponent and the top 5 mantissa bits, rounded half up by adding half
// of the dropped bits' weight (a carry moves into the exponent, the next binade's first code); the binade of 2^-7
// is code 32 onwards (exponent field 1). Below 2^-7, whole steps of 2^-12.
// The layout's numbers come from src/packing.rs (generated/dnsr_constants.glsl).
const uint DNSR_COUNT_SHIFT = 23u - DNSR_COUNT_MANTISSA_BITS; // float32 mantissa bits dropped
const uint DNSR_COUNT_SUBNORMAL_CODES = 1u << DNSR_COUNT_MANTISSA_BITS;
const uint DNSR_MOMENTS_RUN_SHIFT = DNSR_MOMENTS_MEAN_BITS + DNSR_MOMENTS_COUNT_BITS;
uint dnsr_pack_count(float c) {
    c = c > 0.0 ? min(c, float(DNSR_COUNT_MAX)) : 0.0; // NaN too
    float subnormal = c * float(DNSR_COUNT_SUBNORMAL_SCALE);
    if (subnormal < float(DNSR_COUNT_SUBNORMAL_CODES)) return uint(floor(subnormal + 0.5));
    return ((floatBitsToUint(c) + (1u << (DNSR_COUNT_SHIFT - 1u))) >> DNSR_COUNT_SHIFT) - DNSR_COUNT_CODE_OFFSET;
}
float dnsr_unpack_count(uint code) {
    return code < DNSR_COUNT_SUBNORMAL_CODES ? float(code) / float(DNSR_COUNT_SUBNORMAL_SCALE)
                                              : uintBitsToFloat((code + DNSR_COUNT_CODE_OFFSET) << DNSR_COUNT_SHIFT);
}
uint dnsr_pack_moments(vec4 m) {
    uint mean = uint(floor(clamp(m.x, 0.0, 1.0) * float(DNSR_MOMENTS_MEAN_MAX) + 0.5));
    uint run = uint(int(m.w * 2.0)) & ((1u << (32u - DNSR_MOMENTS_RUN_SHIFT)) - 1u);
    return mean | (dnsr_pack_count(m.z) << DNSR_MOMENTS_MEAN_BITS) | (run << DNSR_MOMENTS_RUN_SHIFT);
}
vec4 dnsr_unpack_moments(uint v) {
    uint mean_code = v & DNSR_MOMENTS_MEAN_MAX;
    float mean = mean_code == DNSR_MOMENTS_MEAN_MAX ? 1.0 : float(mean_code) * (1.0 / float(DNSR_MOMENTS_MEAN_MAX));
    float count = dnsr_unpack_count((v >> DNSR_MOMENTS_MEAN_BITS) & ((1u << DNSR_MOMENTS_COUNT_BITS) - 1u));
    return vec4(mean, count * mean * (1.0 - mean), count, float(int(v) >> int(DNSR_MOMENTS_RUN_SHIFT)) * 0.5);
}

// A unit normal (or vec3(0): no usable normal) in 2 * bits bits: octahedral, two snorm codes of `bits` bits each
// (floor(c * (2^(bits-1) - 1) + 0.5)); the code pair (-2^(bits-1), -2^(bits-1)), which snorm never writes, is the zero
// normal. The depth copy keeps DNSR_DEPTH_COPY_NORMAL_BITS (8) a component: within a degree of the normal.
uint dnsr_zero_normal(uint bits) { uint low = 1u << (bits - 1u); return low | (low << bits); }
uint dnsr_snorm(float v, uint bits) {
    float scale = float((1u << (bits - 1u)) - 1u);
    return uint(int(floor(clamp(v, -1.0, 1.0) * scale + 0.5))) & ((1u << bits) - 1u);
}
uint dnsr_pack_octahedral(vec3 n, uint bits) {
    float l1 = abs(n.x) + abs(n.y) + abs(n.z);
    if (!(l1 > 0.0)) return dnsr_zero_normal(bits);
    vec2 o = n.xy / l1;
    if (n.z < 0.0) o = (1.0 - abs(o.yx)) * vec2(o.x >= 0.0 ? 1.0 : -1.0, o.y >= 0.0 ? 1.0 : -1.0);
    return dnsr_snorm(o.x, bits) | (dnsr_snorm(o.y, bits) << bits);
}
vec3 dnsr_unpack_octahedral(uint u, uint bits) {
    if (u == dnsr_zero_normal(bits)) return vec3(0.0);
    int drop = int(32u - bits);
    vec2 o = vec2(float(int(u << uint(drop)) >> drop), float(int(u << uint(drop - int(bits))) >> drop))
           * (1.0 / float((1u << (bits - 1u)) - 1u));
    vec3 n = vec3(o, 1.0 - abs(o.x) - abs(o.y));
    float t = max(-n.z, 0.0);
    n.xy += vec2(n.x >= 0.0 ? -t : t, n.y >= 0.0 ? -t : t);
    return normalize(n);
}

// The depth copy (R32_UINT): the linear depth's code (dnsr_pack_linear_depth; -1, no receiver, is code 0) in the low
// DNSR_DEPTH_CODE_BITS bits and the normal in the rest (DNSR_DEPTH_COPY_NORMAL_BITS a component). Next frame's
// classification compares its reprojected depth with the first and its own normal with the second; this frame's
// later filter passes take both as their guide.
uint dnsr_pack_depth_copy(float linear_depth, vec3 normal) {
    return dnsr_pack_linear_depth(linear_depth) | (dnsr_pack_octahedral(normal, uint(DNSR_DEPTH_COPY_NORMAL_BITS)) << DNSR_DEPTH_CODE_BITS);
}
float dnsr_depth_copy_depth(uint v) { return dnsr_unpack_linear_depth(v & DNSR_DEPTH_CODE_MAX); }
vec3 dnsr_depth_copy_normal(uint v) { return dnsr_unpack_octahedral(v >> DNSR_DEPTH_CODE_BITS, uint(DNSR_DEPTH_COPY_NORMAL_BITS)); }

// The filter's signal (mean, variance) between its passes and as the next frame's history. The fp32 path stores
// it in R16G16_UNORM: the mean, and the standard deviation over `scale` (dnsr_get_signal_scale: it covers the
// largest variance the settings' boost can reach); the sky's variance -1 is the code 65535 (1.0, which every
// implementation writes exactly) and a final receiver's -2 the code DNSR_SIGNAL_FINAL_CODE. A unorm write may take
// either code next to the value (Vulkan leaves the rounding open), so deviations stay at or below
// DNSR_SIGNAL_MAX_DEVIATION_CODE, far from both. Variance 0 (converged) is code 0, exactly. The fp16 path stores
// both as float16 (R16G16_SFLOAT), where -1 and -2 are exact.
// A final receiver's variance (dnsr_final_signal in dnsr_common.glsl); the sky's is -1.
const float DNSR_FINAL_VARIANCE = -2.0;
bool dnsr_is_final_variance(float variance) { return variance < -1.5; }
#ifdef DNSR_FP16
vec4 dnsr_encode_signal(vec2 mean_var, float scale) { return vec4(mean_var, 0.0, 0.0); }
float dnsr_decode_variance(float stored, float scale) { return stored; }
#else
vec4 dnsr_encode_signal(vec2 mean_var, float scale) {
    float deviation = mean_var.y < 0.0 ? (dnsr_stores_finals() && dnsr_is_final_variance(mean_var.y) ? float(DNSR_SIGNAL_FINAL_CODE) / 65535.0 : 1.0)
                                        : min(sqrt(mean_var.y) / scale, float(DNSR_SIGNAL_MAX_DEVIATION_CODE) / 65535.0);
    return vec4(mean_var.x, deviation, 0.0, 0.0);
}
float dnsr_decode_variance(float stored, float scale) {
    float d = stored * scale;
    return stored > float(DNSR_SIGNAL_SKY_CODE_ABOVE) / 65535.0 ? -1.0
         : dnsr_stores_finals() && stored > float(DNSR_SIGNAL_FINAL_CODE_ABOVE) / 65535.0 ? DNSR_FINAL_VARIANCE : d * d;
}
#endif
vec2 dnsr_decode_signal(vec2 stored, float scale) { return vec2(stored.x, dnsr_decode_variance(stored.y, scale)); }
// Four stored variances at once (a textureGather of the second channel).
vec4 dnsr_decode_variances(vec4 stored, float scale) {
    return vec4(dnsr_decode_variance(stored.x, scale), dnsr_decode_variance(stored.y, scale),
                dnsr_decode_variance(stored.z, scale), dnsr_decode_variance(stored.w, scale));
}

#endif
