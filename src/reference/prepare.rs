//! prepare (shaders/prepare.glsl): the FidelityFX hit mask (1 = occluded) becomes the lit-bit tile mask; a
//! visibility input becomes the words of each tile's exactly lit (tile mask) and exactly shadowed (dark mask)
//! pixels.

use super::{sanitize_visibility, Coord, Read, Write, TILE};

/// The bits of tile `tile` whose pixel inside the render rectangle has a visibility of exactly `value`.
fn visibility_word<Io: Read + ?Sized>(io: &Io, tile: Coord, value: f64) -> u32 {
    let e = io.extent();
    (0..TILE[0] * TILE[1]).fold(0, |bits, b| {
        let p = [tile[0] * TILE[0] + b % TILE[0], tile[1] * TILE[1] + b / TILE[0]];
        let hit = p[0] < e[0] && p[1] < e[1] && sanitize_visibility(io.read_visibility(p)) == value;
        bits | (hit as u32) << b
    })
}

/// Runs prepare over every tile of the render rectangle.
pub fn run<Io: Read + Write>(io: &mut Io) {
    let e = io.extent();
    for ty in 0..(e[1] + TILE[1] - 1) / TILE[1] {
        for tx in 0..(e[0] + TILE[0] - 1) / TILE[0] {
            if io.visibility_input() {
                let (lit, dark) = (visibility_word(io, [tx, ty], 1.0), visibility_word(io, [tx, ty], 0.0));
                io.write_tile_mask([tx, ty], lit);
                io.write_tile_dark([tx, ty], dark);
            } else {
                let word = io.read_hit_mask([tx, ty]);
                io.write_tile_mask([tx, ty], !word);
            }
        }
    }
}
