//! prepare (shaders/prepare.glsl): the FidelityFX hit mask (1 = occluded) becomes the lit-bit tile mask.

use super::{Read, Write, TILE};

/// Runs prepare over every tile of the render rectangle.
pub fn run<Io: Read + Write>(io: &mut Io) {
    let e = io.extent();
    for ty in 0..(e[1] + TILE[1] - 1) / TILE[1] {
        for tx in 0..(e[0] + TILE[0] - 1) / TILE[0] {
            let word = io.read_hit_mask([tx, ty]);
            io.write_tile_mask([tx, ty], !word);
        }
    }
}
