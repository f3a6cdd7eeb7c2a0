// prepare: with a visibility input (DNSR_VISIBILITY_INPUT) it writes two words per tile: the pixels whose
// visibility is exactly 1 (the tile mask) and exactly 0 (the dark mask), which the uniform-tile test and the window
// sums of classification read. With a checkerboard input (DNSR_CHECKERBOARD_INPUT) it first reconstructs each
// pixel's visibility from the half of the pixels traced this frame (a traced pixel keeps its bit, the others take
// the mean of their four traced neighbours) and writes it for classification, which then runs as for a visibility
// input. One invocation per 8x4 tile (per pixel for the checkerboard input). A hit mask does not go through it:
// classification reads the host's words as they are and inverts FidelityFX's occluded bits itself (the variant
// without either define, hit mask -> lit-bit tile mask, is what the CPU reference's prepare models; a hit-mask
// context creates it but never dispatches it).
#ifndef DNSR_PREPARE_GLSL
#define DNSR_PREPARE_GLSL

#ifdef DNSR_CHECKERBOARD_INPUT
// The checkerboard input runs one invocation per pixel in groups of DNSR_WIDE_GROUP_SIZE. The lit words of the
// group's tiles and of the tiles around them (every pixel's four neighbours lie within) are loaded once into shared
// memory; the tile words are built with shared-memory atomics. At 4K on an H100 this takes 0.076 ms; one invocation
// per tile reconstructing its 32 pixels in turn took 0.180 ms, 8x8 groups 0.097-0.130 ms (BENCHMARKS.md).
const ivec2 DNSR_GROUP_TILES = DNSR_WIDE_GROUP_SIZE / DNSR_TILE_SIZE;
shared uint s_words[DNSR_GROUP_TILES.y + 2][DNSR_GROUP_TILES.x + 2];
shared uint s_lit[DNSR_GROUP_TILES.y][DNSR_GROUP_TILES.x];
shared uint s_dark[DNSR_GROUP_TILES.y][DNSR_GROUP_TILES.x];

void dnsr_prepare_checkerboard(ivec2 p, ivec2 lid) {
    ivec2 first_tile = (p - lid) / DNSR_TILE_SIZE - 1;
    ivec2 tiles = (dnsr_get_extent() + DNSR_TILE_SIZE - 1) / DNSR_TILE_SIZE;
    int i = lid.y * DNSR_WIDE_GROUP_WIDTH + lid.x;
    const int columns = DNSR_GROUP_TILES.x + 2;
    if (i < columns * (DNSR_GROUP_TILES.y + 2)) {
        ivec2 w = ivec2(i % columns, i / columns);
        ivec2 t = first_tile + w;
        uint word = all(greaterThanEqual(t, ivec2(0))) && all(lessThan(t, tiles)) ? dnsr_read_hit_mask(t) : 0u;
        s_words[w.y][w.x] = dnsr_get_is_lit_bit_mask() ? word : ~word;
    }
    ivec2 own = lid / DNSR_TILE_SIZE;
    bool tile_writer = all(equal(lid % DNSR_TILE_SIZE, ivec2(0)));
    if (tile_writer) {
        s_lit[own.y][own.x] = 0u;
        s_dark[own.y][own.x] = 0u;
    }
    barrier();
    if (dnsr_inside(p)) {
        // A traced pixel keeps its sample; the others (all four neighbours traced) take their neighbours' mean.
        // Every neighbour is read on both paths: half the invocations of every subgroup take each.
        const ivec2 offsets[5] = ivec2[5](ivec2(0, 0), ivec2(-1, 0), ivec2(1, 0), ivec2(0, -1), ivec2(0, 1));
        float bits[5];
        float count = 0.0;
        for (int k = 0; k < 5; ++k) {
            ivec2 q = p + offsets[k];
            ivec2 w = q / DNSR_TILE_SIZE - first_tile;
            bool inside = dnsr_inside(q);
            bits[k] = inside ? float((s_words[w.y][w.x] >> dnsr_tile_bit(q)) & 1u) : 0.0;
            count += k > 0 && inside ? 1.0 : 0.0;
        }
        // No neighbour inside a one-pixel rectangle: nothing is known.
        float mean = count > 0.0 ? (bits[1] + bits[2] + bits[3] + bits[4]) / count : 0.5;
        float v = dnsr_is_traced(p) ? bits[0] : mean;
        dnsr_write_visibility(p, v);
        uint bit = 1u << dnsr_tile_bit(p);
        if (v == 1.0) atomicOr(s_lit[own.y][own.x], bit);
        if (v == 0.0) atomicOr(s_dark[own.y][own.x], bit);
    }
    barrier();
    if (tile_writer && dnsr_inside(p)) {
        dnsr_write_tile_mask(p / DNSR_TILE_SIZE, s_lit[own.y][own.x]);
        dnsr_write_tile_dark(p / DNSR_TILE_SIZE, s_dark[own.y][own.x]);
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
