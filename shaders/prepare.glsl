// prepare: the host's hit mask (FidelityFX convention, bit = 1 means the ray hit an occluder) becomes dnsr's
// internal tile mask (bit = 1 means lit). With a visibility input (DNSR_VISIBILITY_INPUT) it writes two words per
// tile instead: the pixels whose visibility is exactly 1 (the tile mask) and exactly 0 (the dark mask), which the
// uniform-tile test and the window sums of classification read. With a checkerboard input
// (DNSR_CHECKERBOARD_INPUT) it first reconstructs each pixel's visibility from the half of the pixels traced this
// frame (a traced pixel keeps its bit, the others take the mean of their four traced neighbours) and writes it for
// classification, which then runs as for a visibility input. One invocation per 8x4 tile.
#ifndef DNSR_PREPARE_GLSL
#define DNSR_PREPARE_GLSL

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
#elif defined(DNSR_CHECKERBOARD_INPUT)
    // Lit bits of the tile and of its four neighbours (outside the tile grid: none), which hold every pixel's
    // four neighbours.
    const ivec2 offsets[5] = ivec2[5](ivec2(0, 0), ivec2(-1, 0), ivec2(1, 0), ivec2(0, -1), ivec2(0, 1));
    uint words[5];
    for (int k = 0; k < 5; ++k) {
        ivec2 t = tile + offsets[k];
        uint word = all(greaterThanEqual(t, ivec2(0))) && all(lessThan(t, tiles)) ? dnsr_read_hit_mask(t) : 0u;
        words[k] = dnsr_get_is_lit_bit_mask() ? word : ~word;
    }
    uint lit = 0u, dark = 0u;
    for (int bit = 0; bit < DNSR_TILE_WIDTH * DNSR_TILE_HEIGHT; ++bit) {
        ivec2 p = tile * DNSR_TILE_SIZE + ivec2(bit % DNSR_TILE_WIDTH, bit / DNSR_TILE_WIDTH);
        if (!dnsr_inside(p)) continue;
        // A traced pixel keeps its sample; the others (all four neighbours traced) take their neighbours' mean.
        bool traced = ((p.x + p.y) & 1) == dnsr_get_checkerboard_phase();
        float sum = 0.0, count = 0.0;
        for (int k = traced ? 0 : 1; k < (traced ? 1 : 5); ++k) {
            ivec2 q = p + offsets[k];
            if (!dnsr_inside(q)) continue;
            ivec2 t = q >> ivec2(3, 2);
            int w = t == tile ? 0 : (t.x < tile.x ? 1 : (t.x > tile.x ? 2 : (t.y < tile.y ? 3 : 4)));
            sum += float((words[w] >> dnsr_tile_bit(q)) & 1u);
            count += 1.0;
        }
        // No neighbour inside a one-pixel rectangle: nothing is known.
        float v = count > 0.0 ? sum / count : 0.5;
        dnsr_write_visibility(p, v);
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
