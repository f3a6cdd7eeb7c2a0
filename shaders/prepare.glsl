// prepare: the host's hit mask (FidelityFX convention, bit = 1 means the ray hit an occluder) becomes dnsr's
// internal tile mask (bit = 1 means lit). With a visibility input (DNSR_VISIBILITY_INPUT) it writes two words per
// tile instead: the pixels whose visibility is exactly 1 (the tile mask) and exactly 0 (the dark mask), which the
// uniform-tile test and the window sums of classification read. With a checkerboard input
// (DNSR_CHECKERBOARD_INPUT) it first reconstructs each pixel's visibility from the half of the pixels traced this
// frame (a traced pixel keeps its bit, the others take the mean of their four traced neighbours) and writes it for
// classification, which then runs as for a visibility input. One invocation per 8x4 tile (per pixel for the
// checkerboard input).
#ifndef DNSR_PREPARE_GLSL
#define DNSR_PREPARE_GLSL

#ifdef DNSR_CHECKERBOARD_INPUT
// The checkerboard input runs one invocation per pixel; each tile's first invocation gathers the tile's words from
// the pixels' flags in shared memory (one invocation per tile reconstructing and writing 32 pixels in turn took
// 0.18 ms at 4K on an H100, shared-memory atomics into the two words 0.097 ms).
const int DNSR_PREPARE_PIXELS = DNSR_GROUP_WIDTH * DNSR_GROUP_HEIGHT;
// Per pixel of the group: bit 0 exactly lit, bit 1 exactly shadowed (0 outside the rectangle).
shared uint s_exact[DNSR_PREPARE_PIXELS];

// Lit bit of pixel q (inside the rectangle) in the host's mask.
uint dnsr_lit_at(ivec2 q) {
    uint word = dnsr_read_hit_mask(q / DNSR_TILE_SIZE);
    return ((dnsr_get_is_lit_bit_mask() ? word : ~word) >> dnsr_tile_bit(q)) & 1u;
}

void dnsr_prepare_checkerboard(ivec2 p, ivec2 lid) {
    uint exact = 0u;
    if (dnsr_inside(p)) {
        // A traced pixel keeps its sample; the others (all four neighbours traced) take their neighbours' mean.
        bool traced = ((p.x + p.y) & 1) == dnsr_get_checkerboard_phase();
        float v;
        if (traced) {
            v = float(dnsr_lit_at(p));
        } else {
            const ivec2 offsets[4] = ivec2[4](ivec2(-1, 0), ivec2(1, 0), ivec2(0, -1), ivec2(0, 1));
            float sum = 0.0, count = 0.0;
            for (int k = 0; k < 4; ++k) {
                ivec2 q = p + offsets[k];
                if (!dnsr_inside(q)) continue;
                sum += float(dnsr_lit_at(q));
                count += 1.0;
            }
            // No neighbour inside a one-pixel rectangle: nothing is known.
            v = count > 0.0 ? sum / count : 0.5;
        }
        dnsr_write_visibility(p, v);
        exact = uint(v == 1.0) | (uint(v == 0.0) << 1u);
    }
    // The group's pixels row by row: a tile's 32 pixels are 32 consecutive entries, in tile-bit order.
    s_exact[lid.y * DNSR_GROUP_WIDTH + lid.x] = exact;
    barrier();
    if (lid.x == 0 && lid.y % DNSR_TILE_HEIGHT == 0 && dnsr_inside(p)) {
        uint lit = 0u, dark = 0u;
        for (int bit = 0; bit < DNSR_TILE_WIDTH * DNSR_TILE_HEIGHT; ++bit) {
            uint e = s_exact[lid.y * DNSR_GROUP_WIDTH + bit];
            lit |= (e & 1u) << uint(bit);
            dark |= (e >> 1u) << uint(bit);
        }
        dnsr_write_tile_mask(p / DNSR_TILE_SIZE, lit);
        dnsr_write_tile_dark(p / DNSR_TILE_SIZE, dark);
    }
}
#endif

void dnsr_prepare(ivec2 tile) {
    ivec2 tiles = (dnsr_get_extent() + DNSR_TILE_SIZE - 1) / DNSR_TILE_SIZE;
    if (any(greaterThanEqual(tile, tiles))) return;
#ifdef DNSR_VISIBILITY_INPUT
    uint lit = 0u, dark = 0u;
    for (int bit = 0; bit < DNSR_TILE_WIDTH * DNSR_TILE_HEIGHT; ++bit) {
        ivec2 p = tile * DNSR_TILE_SIZE + ivec2(bit % DNSR_TILE_WIDTH, bit / DNSR_TILE_WIDTH);
        if (!dnsr_inside(p)) continue;
        float v = dnsr_sanitize_visibility(dnsr_read_visibility(p));
        lit |= uint(v == 1.0) << uint(bit);
        dark |= uint(v == 0.0) << uint(bit);
    }
    dnsr_write_tile_mask(tile, lit);
    dnsr_write_tile_dark(tile, dark);
#else
    dnsr_write_tile_mask(tile, ~dnsr_read_hit_mask(tile));
#endif
}

#endif
