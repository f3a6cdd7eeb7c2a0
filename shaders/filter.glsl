// filter: one pass of the edge-avoiding a-trous filter (3x3 taps at +-step). Every tap is read straight from the
// images through the texture cache. (A shared-memory apron sized for the widest step was 3-5x slower on an H100:
// 1.40 / 1.65 / 2.20 ms against 0.46 / 0.44 / 0.41 ms per pass at 4K; the loads before its barrier serialise and
// its 14 KB per 64 invocations limit occupancy, while neighbouring groups share taps in L1 anyway.)
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

    if (!dnsr_inside(p)) return;
    uint meta = lid.y < 4 ? meta_top : meta_bottom;
    float zc = dnsr_tap_depth(p);

    vec2 result;
    if (zc < 0.0) {
        result = DNSR_SKY_SIGNAL;
    } else if ((meta & DNSR_TILE_CLEARED) != 0u) {
        result = dnsr_cleared_value(true, meta);
    } else {
        vec4 settings = dnsr_get_filter_settings();
        float kernel[2] = float[2](1.0, settings.x);
        float normal_power = settings.y;
        vec2 c = dnsr_read_filter_input(p);
        vec3 nc = dnsr_read_normal(p);
        // The 3x3 neighbourhood at step 1: the variance blur's footprint (receivers told apart by their signal,
        // see DNSR_SKY_SIGNAL), and the taps of the first pass.
        vec2 nb_signal[9];
        float vsum = 0.0, vweight = 0.0;
        for (int j = -1; j <= 1; ++j) {
            for (int i = -1; i <= 1; ++i) {
                int k = (j + 1) * 3 + (i + 1);
                ivec2 q = p + ivec2(i, j);
                nb_signal[k] = dnsr_inside(q) ? dnsr_read_filter_input(q) : DNSR_SKY_SIGNAL;
                if (!dnsr_is_receiver_signal(nb_signal[k])) continue;
                float w = 1.0 / float(4 << (abs(i) + abs(j)));
                vsum += w * nb_signal[k].y;
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
                int k = (j + 1) * 3 + (i + 1);
                // Depth is read whatever the signal says, so that its fetch does not wait for the signal's.
                float zq = dnsr_tap_depth(q);
                vec2 n = step == 1 ? nb_signal[k] : (zq < 0.0 ? vec2(0.0) : dnsr_read_filter_input(q));
                if (zq < 0.0) continue;
                // The shadow and depth edge stops share one exp.
                float w = kernel[abs(i)] * kernel[abs(j)]
                        * exp(-(abs(c.x - n.x) * inv_sigma + abs(zc - zq) * inv_depth_sigma))
                        * pow(max(dot(nc, dnsr_read_normal(q)), 0.0), normal_power);
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
