// prepare: the host's hit mask (FidelityFX convention, bit = 1 means the ray hit an occluder) becomes dnsr's
// internal tile mask (bit = 1 means lit). One invocation per 8x4 tile.
#ifndef DNSR_PREPARE_GLSL
#define DNSR_PREPARE_GLSL

void dnsr_prepare(ivec2 tile) {
    ivec2 tiles = (dnsr_get_extent() + DNSR_TILE_SIZE - 1) / DNSR_TILE_SIZE;
    if (any(greaterThanEqual(tile, tiles))) return;
    dnsr_write_tile_mask(tile, ~dnsr_read_hit_mask(tile));
}

#endif
