// classify (hybrid shadows): decides from the cascaded shadow maps which pixels are surely lit or surely shadowed, so
// that the engine traces rays only for the others. One workgroup per column of 4 8x4 tiles. Per pixel: sky is lit, a
// surface facing away from the light is shadowed; otherwise the first cascade containing the pixel is searched for
// blockers at DNSR_CLASSIFY_DISC taps within the penumbra the light's angular size allows (its radius grows with the
// distance from the cascade's near plane, the farthest a blocker can be). Every tap in front of the receiver: shadowed;
// none (when lit pixels may be rejected): lit; else the pixel needs a ray. The tile's mask of pixels to trace, with the
// ray interval the blockers bound, is appended to the tile list when it has more than the cut-off; the hit mask gets
// the verdicts (pixels to trace of a listed tile: bit 0, for the engine's trace to OR into; of a tile below the
// cut-off: the majority of their taps). The reference is src/reference/classify.rs.
#ifndef DNSR_CLASSIFY_GLSL
#define DNSR_CLASSIFY_GLSL

// Per tile of the workgroup.
shared uint s_inside[DNSR_CLASSIFY_TILES_PER_GROUP];
shared uint s_lit[DNSR_CLASSIFY_TILES_PER_GROUP];
shared uint s_trace[DNSR_CLASSIFY_TILES_PER_GROUP];
shared uint s_guess_lit[DNSR_CLASSIFY_TILES_PER_GROUP];
// Non-negative floats order like their bit patterns, so the interval's end is a uint atomic.
shared uint s_max_t[DNSR_CLASSIFY_TILES_PER_GROUP];

const uint DNSR_VERDICT_LIT = 0u;
const uint DNSR_VERDICT_SHADOWED = 1u;
const uint DNSR_VERDICT_TRACE = 2u;

struct DnsrVerdict {
    uint kind;
    // For a pixel to trace: whether most of its taps saw no blocker (its bit if its tile is not listed).
    bool guess_lit;
    // Where the ray of a pixel to trace may end (world units from the receiver along the light).
    float max_t;
};

DnsrVerdict dnsr_classify_pixel(ivec2 p) {
    const float infinity = uintBitsToFloat(0x7f800000u);
    DnsrVerdict v = DnsrVerdict(DNSR_VERDICT_LIT, true, infinity);
    float depth = dnsr_read_depth(p);
    if (!dnsr_is_receiver(depth)) {
        return v;
    }
    vec3 to_light = dnsr_get_light_direction();
    vec3 n = dnsr_read_normal(p);
    // An unusable normal (zero) decides nothing: the cascades decide alone.
    if (n != vec3(0.0) && dot(n, to_light) <= 0.0) {
        v.kind = DNSR_VERDICT_SHADOWED;
        return v;
    }
    v.kind = DNSR_VERDICT_TRACE;
    vec3 world = dnsr_world_position(p, depth);
    int cascade = -1;
    vec3 s = vec3(0.0);
    for (int c = 0; c < dnsr_get_cascade_count(); ++c) {
        s = (dnsr_get_cascade_matrix(c) * vec4(world, 1.0)).xyz;
        if (all(greaterThan(s.xy, vec2(0.0))) && all(lessThan(s.xy, vec2(1.0)))) {
            cascade = c;
            break;
        }
    }
    // Outside every cascade (or a position that is not finite): nothing is known, the pixel is traced.
    if (cascade < 0) {
        return v;
    }
    // Depths as distances from the light's near plane, in the cascade's depth units, whatever its convention.
    bool inverted = dnsr_get_classify_flag(DNSR_CLASSIFY_CASCADES_INVERTED);
    vec4 units = dnsr_get_cascade_units(cascade);
    float z = inverted ? 1.0 - s.z : s.z;
    float radius = dnsr_get_light_tan_half_angle() * max(z, 0.0) / units.x;
    ivec2 size = dnsr_get_cascade_size(cascade);
    // One texel more than the penumbra, so that a blocker at its edge is not missed between taps.
    vec2 reach = radius * units.yz * vec2(size) + 1.0;
    vec2 centre = s.xy * vec2(size);
    // The receiver's tangent plane: a tap is compared with the plane's depth under it, not the receiver's, so that
    // a surface sloping away from the light is not its own blocker across the search disc (a slope-scaled bias).
    // `plane` is how much deeper the plane lies per texel along u and v. A slope (tan of the angle between normal
    // and light) beyond DNSR_CLASSIFY_MAX_SLOPE is flattened to it: the uphill side then counts as a blocker and the
    // pixel is traced rather than guessed.
    vec2 plane = vec2(0.0);
    if (n != vec3(0.0)) {
        float facing = dot(n, to_light);
        float across = length(n - facing * to_light);
        vec2 rise = vec2(dot(n, dnsr_get_cascade_axis_u(cascade)), dot(n, dnsr_get_cascade_axis_v(cascade)));
        plane = rise / max(facing, across / DNSR_CLASSIFY_MAX_SLOPE) * units.x / vec2(size);
    }
    float limit = z - units.w;
    float nearest_light = infinity;
    int valid = 0;
    int blocking = 0;
    for (int k = 0; k < dnsr_get_classify_taps(); ++k) {
        ivec2 texel = ivec2(floor(centre + DNSR_CLASSIFY_DISC[k] * reach));
        if (any(lessThan(texel, ivec2(0))) || any(greaterThanEqual(texel, size))) {
            continue;
        }
        float d = dnsr_read_cascade_depth(cascade, texel);
        d = inverted ? 1.0 - d : d;
        valid += 1;
        if (d < limit + dot(plane, vec2(texel) + 0.5 - centre)) {
            blocking += 1;
            nearest_light = min(nearest_light, d);
        }
    }
    if (valid > 0 && blocking == valid) {
        v.kind = DNSR_VERDICT_SHADOWED;
        return v;
    }
    if (valid > 0 && blocking == 0 && dnsr_get_classify_flag(DNSR_CLASSIFY_REJECT_LIT)) {
        v.kind = DNSR_VERDICT_LIT;
        return v;
    }
    v.guess_lit = 2 * blocking < valid;
    if (blocking > 0 && dnsr_get_classify_flag(DNSR_CLASSIFY_BOUND_INTERVAL)) {
        // Just past the blocker nearest the light, widened by the penumbra radius (the engine's jittered rays lean
        // by up to that much). The ray starts at the receiver: a blocker nearer than the blocker offset, or thinner
        // than the taps' spacing, is invisible to the cascades, and only a ray from the surface finds it.
        float along = (z - nearest_light + units.w) / units.x;
        v.max_t = sqrt(along * along + radius * radius);
    }
    return v;
}

// Group `group` holds tiles (group.x, group.y * DNSR_CLASSIFY_TILES_PER_GROUP + k); invocation `lid` is pixel
// lid % tile size of tile k = lid.y / tile height.
void dnsr_classify(ivec2 group, ivec2 lid) {
    int k = lid.y / DNSR_TILE_HEIGHT;
    ivec2 tile = ivec2(group.x, group.y * DNSR_CLASSIFY_TILES_PER_GROUP + k);
    ivec2 in_tile = ivec2(lid.x, lid.y % DNSR_TILE_HEIGHT);
    bool first = in_tile == ivec2(0);
    if (first) {
        s_inside[k] = 0u;
        s_lit[k] = 0u;
        s_trace[k] = 0u;
        s_guess_lit[k] = 0u;
        s_max_t[k] = 0u;
    }
    barrier();
    ivec2 p = tile * DNSR_TILE_SIZE + in_tile;
    if (dnsr_inside(p)) {
        DnsrVerdict v = dnsr_classify_pixel(p);
        uint bit = 1u << dnsr_tile_bit(p);
        atomicOr(s_inside[k], bit);
        if (v.kind == DNSR_VERDICT_LIT) {
            atomicOr(s_lit[k], bit);
        } else if (v.kind == DNSR_VERDICT_TRACE) {
            atomicOr(s_trace[k], bit);
            if (v.guess_lit) atomicOr(s_guess_lit[k], bit);
            atomicMax(s_max_t[k], floatBitsToUint(v.max_t));
        }
    }
    barrier();
    // A tile with no pixel inside the render rectangle lies below it (the last row of groups): nothing to write.
    if (first && s_inside[k] != 0u) {
        uint trace = s_trace[k];
        bool listed = uint(bitCount(trace)) > dnsr_get_tile_cutoff();
        uint traced = listed ? trace : 0u;
        uint lit = s_lit[k] | (listed ? 0u : s_guess_lit[k]);
        dnsr_write_hit_mask(tile, dnsr_get_is_lit_bit_mask() ? lit : s_inside[k] & ~lit & ~traced);
        if (listed) {
            ivec2 t = tile + dnsr_get_tile_offset();
            dnsr_append_tile(uvec4(uint(t.x) | (uint(t.y) << 16), trace, 0u, s_max_t[k]));
        }
    }
}

#endif
