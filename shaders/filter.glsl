// filter: one pass of the edge-avoiding a-trous filter (3x3 taps at +-step). A step-1 pass reads its group's
// pixels and a one-pixel apron into shared memory once (every tap and the variance blur come from there); later
// passes read every tap straight from the images through the texture cache. (On an H100 at 4K the apron took the
// step-1 pass from 0.344 to 0.256 ms but slowed the later passes, where it serves only the variance blur, from
// 0.383 / 0.371 to 0.408 / 0.431 ms: their taps cannot wait for a barrier. An apron sized for the widest step was
// 3-5x slower still: its loads serialise before the barrier and its 14 KB per 64 invocations limit occupancy.)
#ifndef DNSR_FILTER_GLSL
#define DNSR_FILTER_GLSL

// Linear depth of a receiver, -1 for sky.
float dnsr_tap_depth(ivec2 p) {
    float depth = dnsr_read_depth(p);
    return dnsr_is_receiver(depth) ? dnsr_linear_depth(dnsr_uv_to_ndc(dnsr_pixel_uv(p)), depth) : -1.0;
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
    return receiver ? vec2((meta & DNSR_TILE_LIT) != 0u ? 1.0 : 0.0, 0.0) : DNSR_SKY_SIGNAL;
}

// The group's pixels and a one-pixel apron: every pixel's 3x3 neighbourhood (its taps and variance-blur footprint
// in a step-1 pass), read from the images once per group instead of nine times per pixel.
const ivec2 DNSR_APRON_SIZE = DNSR_GROUP_SIZE + 2;
const int DNSR_APRON_COUNT = DNSR_APRON_SIZE.x * DNSR_APRON_SIZE.y;
shared vec2 dnsr_apron_signal[DNSR_APRON_COUNT];
shared float dnsr_apron_depth[DNSR_APRON_COUNT];
shared vec3 dnsr_apron_normal[DNSR_APRON_COUNT];

int dnsr_apron_index(ivec2 lid) { return (lid.y + 1) * DNSR_APRON_SIZE.x + lid.x + 1; }

void dnsr_load_apron(ivec2 origin, int invocation) {
    for (int i = invocation; i < DNSR_APRON_COUNT; i += DNSR_GROUP_SIZE.x * DNSR_GROUP_SIZE.y) {
        ivec2 q = origin - 1 + ivec2(i % DNSR_APRON_SIZE.x, i / DNSR_APRON_SIZE.x);
        bool inside = dnsr_inside(q);
        dnsr_apron_signal[i] = inside ? dnsr_read_filter_input(q) : DNSR_SKY_SIGNAL;
        float z = inside ? dnsr_tap_depth(q) : -1.0;
        dnsr_apron_depth[i] = z;
        dnsr_apron_normal[i] = z >= 0.0 ? dnsr_read_normal(q) : vec3(0.0);
    }
}

void dnsr_filter(ivec2 gid, ivec2 lid) {
    int step = dnsr_get_filter_step();
    ivec2 origin = gid * DNSR_GROUP_SIZE;
    ivec2 p = origin + lid;

    // Both tiles of the group cleared (uniform or no receivers): nothing to filter, no neighbourhood to read.
    ivec2 tile = origin / DNSR_TILE_SIZE;
    uint meta_top = dnsr_read_tile_meta(tile);
    uint meta_bottom = origin.y + 4 < dnsr_get_extent().y ? dnsr_read_tile_meta(tile + ivec2(0, 1)) : meta_top;
    if ((meta_top & meta_bottom & DNSR_TILE_CLEARED) != 0u) {
        // Cleared values are already where this pass would write them (classification wrote the output and the
        // reprojection image): nothing to do.
        if (dnsr_get_skip_cleared()) return;
        if (!dnsr_inside(p)) return;
        bool receiver = dnsr_is_receiver(dnsr_read_depth(p));
        uint meta = lid.y < 4 ? meta_top : meta_bottom;
        dnsr_filter_write(p, dnsr_cleared_value(receiver, meta), receiver, meta);
        return;
    }

    // The whole group reaches this barrier: the branch above depends on the group alone, the step on the pass.
    bool step_one = step == 1;
    if (step_one) {
        dnsr_load_apron(origin, lid.y * DNSR_GROUP_SIZE.x + lid.x);
        barrier();
    }

    if (!dnsr_inside(p)) return;
    uint meta = lid.y < 4 ? meta_top : meta_bottom;
    int center = dnsr_apron_index(lid);
    float zc = step_one ? dnsr_apron_depth[center] : dnsr_tap_depth(p);

    vec2 result;
    if (zc < 0.0) {
        result = DNSR_SKY_SIGNAL;
    } else if ((meta & DNSR_TILE_CLEARED) != 0u) {
        result = dnsr_cleared_value(true, meta);
    } else {
        vec4 settings = dnsr_get_filter_settings();
        float kernel[2] = float[2](1.0, settings.x);
        float normal_power = settings.y;
        vec2 c = step_one ? dnsr_apron_signal[center] : dnsr_read_filter_input(p);
        vec3 nc = step_one ? dnsr_apron_normal[center] : dnsr_read_normal(p);
        // Variance blur over the 3x3 receivers (told apart by their signal, see DNSR_SKY_SIGNAL).
        float vsum = 0.0, vweight = 0.0;
        for (int j = -1; j <= 1; ++j) {
            for (int i = -1; i <= 1; ++i) {
                ivec2 q = p + ivec2(i, j);
                vec2 s = step_one ? dnsr_apron_signal[center + j * DNSR_APRON_SIZE.x + i]
                                  : (dnsr_inside(q) ? dnsr_read_filter_input(q) : DNSR_SKY_SIGNAL);
                if (!dnsr_is_receiver_signal(s)) continue;
                float w = 1.0 / float(4 << (abs(i) + abs(j)));
                vsum += w * s.y;
                vweight += w;
            }
        }
        float inv_sigma = 1.0 / max(sqrt(max(vsum / vweight, 0.0)), settings.w);
        float inv_depth_sigma = 1.0 / dnsr_get_depth_similarity_sigma();
        float weight_sum = 1.0;
        float mean_sum = c.x;
        float var_sum = c.y;
        for (int j = -1; j <= 1; ++j) {
            for (int i = -1; i <= 1; ++i) {
                if (i == 0 && j == 0) continue;
                ivec2 q = p + ivec2(i, j) * step;
                if (!dnsr_inside(q)) continue;
                float zq;
                vec2 n;
                vec3 nq;
                if (step_one) {
                    int k = center + j * DNSR_APRON_SIZE.x + i;
                    zq = dnsr_apron_depth[k];
                    n = dnsr_apron_signal[k];
                    nq = dnsr_apron_normal[k];
                } else {
                    // Depth is read whatever the signal says, so that its fetch does not wait for the signal's.
                    zq = dnsr_tap_depth(q);
                    n = zq < 0.0 ? vec2(0.0) : dnsr_read_filter_input(q);
                    nq = zq < 0.0 ? vec3(0.0) : dnsr_read_normal(q);
                }
                if (zq < 0.0) continue;
                // The shadow and depth edge stops share one exp.
                float w = kernel[abs(i)] * kernel[abs(j)]
                        * exp(-(abs(c.x - n.x) * inv_sigma + abs(zc - zq) * inv_depth_sigma))
                        * pow(max(dot(nc, nq), 0.0), normal_power);
                weight_sum += w;
                mean_sum += w * n.x;
                var_sum += w * w * n.y;
            }
        }
        result = vec2(clamp(mean_sum / weight_sum, 0.0, 1.0), max(var_sum / (weight_sum * weight_sum), 0.0));
    }
    dnsr_filter_write(p, result, zc >= 0.0, meta);
}

#endif
