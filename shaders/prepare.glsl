// prepare: the host's hit mask (FidelityFX convention, bit = 1 means the ray hit an occluder) becomes dnsr's
// internal tile mask (bit = 1 means lit). With a visibility input (DNSR_VISIBILITY_INPUT) it writes two words per
// tile instead: the pixels whose visibility is exactly 1 (the tile mask) and exactly 0 (the dark mask), which the
// uniform-tile test and the window sums of classification read. One invocation per 8x4 tile.
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
#else
    dnsr_write_tile_mask(tile, ~dnsr_read_hit_mask(tile));
#endif
}

#endif
