// filter: one pass of the edge-avoiding a-trous filter (3x3 taps at +-step). The group loads its 8x8 pixels plus
// a step-wide apron into shared memory once, with depth already linearised and normals decoded, so each tap
// costs shared-memory reads only.
#ifndef DNSR_FILTER_GLSL
#define DNSR_FILTER_GLSL

const int DNSR_SHARED_SIDE = 8 + 2 * int(DNSR_MAX_FILTER_STEP);
const int DNSR_SHARED_COUNT = DNSR_SHARED_SIDE * DNSR_SHARED_SIDE;

shared real2 s_signal[DNSR_SHARED_COUNT];   // (mean, variance)
shared float s_depth[DNSR_SHARED_COUNT];    // linear depth; negative = sky or outside the rectangle
// Normals stay fp32: the edge stop raises their dot product to the 32nd power, which turns half-precision
// rounding into percent-level weight errors.
shared vec3 s_normal[DNSR_SHARED_COUNT];
int g_side;

int dnsr_shared_index(ivec2 s) { return s.y * g_side + s.x; }

void dnsr_filter_load(ivec2 region_origin) {
    int count = g_side * g_side;
    for (int i = int(gl_LocalInvocationIndex); i < count; i += 64) {
        ivec2 p = region_origin + ivec2(i % g_side, i / g_side);
        float depth = dnsr_inside(p) ? dnsr_read_depth(p) : 0.0;
        bool receiver = dnsr_inside(p) && dnsr_is_receiver(depth);
        vec2 signal = receiver ? dnsr_read_filter_input(p) : vec2(1.0, 0.0);
        s_signal[i] = real2(signal);
        s_depth[i] = receiver ? dnsr_linear_depth(dnsr_uv_to_ndc(dnsr_pixel_uv(p)), depth) : -1.0;
        s_normal[i] = receiver ? dnsr_read_normal(p) : vec3(0.0);
    }
}

// 3x3 Gaussian of the variance (center 1/4, cross 1/8, corner 1/16) over receivers only.
float dnsr_blurred_variance(ivec2 s) {
    float sum = 0.0, weight = 0.0;
    for (int j = -1; j <= 1; ++j) {
        for (int i = -1; i <= 1; ++i) {
            int k = dnsr_shared_index(s + ivec2(i, j));
            if (s_depth[k] < 0.0) continue;
            float w = 1.0 / float(4 << (abs(i) + abs(j)));
            sum += w * float(s_signal[k].y);
            weight += w;
        }
    }
    return sum / weight;
}

#ifdef DNSR_FINAL_PASS
// The debug views: what the output shows instead of the shadow (see DebugView in src/dispatch.rs).
float dnsr_debug_value(uint view, ivec2 p, bool receiver, uint meta, vec2 result) {
    bool cleared = (meta & DNSR_TILE_CLEARED) != 0u;
    if (view == DNSR_DEBUG_VIEW_TILE_CLASSIFICATION) {
        return !receiver ? 0.75 : (!cleared ? 0.5 : ((meta & DNSR_TILE_LIT) != 0u ? 1.0 : 0.0));
    }
    if (view == DNSR_DEBUG_VIEW_VARIANCE) return clamp(sqrt(max(result.y, 0.0)), 0.0, 1.0);
    float n = receiver ? dnsr_read_debug_moments(p).z : 0.0;
    if (view == DNSR_DEBUG_VIEW_SAMPLE_COUNT) return clamp(n / dnsr_get_temporal_settings().z, 0.0, 1.0);
    return receiver && !cleared && n <= 1.0 ? 1.0 : 0.0; // DNSR_DEBUG_VIEW_DISOCCLUSION
}
#endif

void dnsr_filter_write(ivec2 p, vec2 result, bool receiver, uint meta) {
    if (dnsr_get_write_internal()) dnsr_write_filter_output(p, result);
#ifdef DNSR_FINAL_PASS
    uint view = dnsr_get_debug_view();
    float contrast = dnsr_get_filter_settings().z;
    dnsr_write_output(p, view == DNSR_DEBUG_VIEW_NONE ? pow(result.x, max(contrast - result.y, 1.0))
                                                      : dnsr_debug_value(view, p, receiver, meta, result));
#endif
}

// Value of a pixel in a cleared tile: sky is lit, receivers take the tile's value.
vec2 dnsr_cleared_value(bool receiver, uint meta) {
    return vec2(!receiver || (meta & DNSR_TILE_LIT) != 0u ? 1.0 : 0.0, 0.0);
}

void dnsr_filter(ivec2 gid, ivec2 lid) {
    int step = dnsr_get_filter_step();
    g_side = 8 + 2 * step;
    ivec2 origin = gid * 8;
    ivec2 p = origin + lid;

    // Both tiles of the group cleared (uniform or no receivers): nothing to filter, no neighbourhood to load.
    // The condition is the same for every invocation of the group, so the barrier below stays uniform.
    ivec2 tile = origin / DNSR_TILE_SIZE;
    uint meta_top = dnsr_read_tile_meta(tile);
    uint meta_bottom = origin.y + 4 < dnsr_get_extent().y ? dnsr_read_tile_meta(tile + ivec2(0, 1)) : meta_top;
    if ((meta_top & meta_bottom & DNSR_TILE_CLEARED) != 0u) {
        if (!dnsr_inside(p)) return;
        bool receiver = dnsr_is_receiver(dnsr_read_depth(p));
        uint meta = lid.y < 4 ? meta_top : meta_bottom;
        dnsr_filter_write(p, dnsr_cleared_value(receiver, meta), receiver, meta);
        return;
    }

    dnsr_filter_load(origin - step);
    barrier();

    if (!dnsr_inside(p)) return;
    ivec2 s = lid + step;
    int center = dnsr_shared_index(s);
    uint meta = lid.y < 4 ? meta_top : meta_bottom;

    vec2 result;
    if (s_depth[center] < 0.0) {
        result = vec2(1.0, 0.0);
    } else if ((meta & DNSR_TILE_CLEARED) != 0u) {
        result = dnsr_cleared_value(true, meta);
    } else {
        // Storage (shared memory, intermediate images) follows the path's precision; the weights and sums are
        // accumulated in fp32, which keeps the fp16 path within 2e-3 of the f64 reference.
        vec4 settings = dnsr_get_filter_settings();
        float kernel[2] = float[2](1.0, settings.x);
        float normal_power = settings.y;
        vec2 c = vec2(s_signal[center]);
        float zc = s_depth[center];
        vec3 nc = s_normal[center];
        float inv_sigma = 1.0 / max(sqrt(max(dnsr_blurred_variance(s), 0.0)), settings.w);
        float inv_depth_sigma = 1.0 / dnsr_get_depth_similarity_sigma();

        float weight_sum = 1.0;
        float mean_sum = c.x;
        float var_sum = c.y;
        for (int j = -1; j <= 1; ++j) {
            for (int i = -1; i <= 1; ++i) {
                if (i == 0 && j == 0) continue;
                ivec2 q = p + ivec2(i, j) * step;
                if (!dnsr_inside(q)) continue;
                int k = dnsr_shared_index(s + ivec2(i, j) * step);
                float zq = s_depth[k];
                if (zq < 0.0) continue;
                vec2 n = vec2(s_signal[k]);
                float w = kernel[abs(i)] * kernel[abs(j)]
                        * exp(-abs(c.x - n.x) * inv_sigma)
                        * exp(-abs(zc - zq) * inv_depth_sigma)
                        * pow(max(dot(nc, s_normal[k]), 0.0), normal_power);
                weight_sum += w;
                mean_sum += w * n.x;
                var_sum += w * w * n.y;
            }
        }
        result = vec2(clamp(mean_sum / weight_sum, 0.0, 1.0), max(var_sum / (weight_sum * weight_sum), 0.0));
    }
    dnsr_filter_write(p, result, s_depth[center] >= 0.0, meta);
}

#endif
