//! prepare (shaders/prepare.glsl): the FidelityFX hit mask (1 = occluded) becomes the lit-bit tile mask; a
//! visibility input becomes the words of each tile's exactly lit (tile mask) and exactly shadowed (dark mask)
//! pixels; a checkerboard input is first reconstructed into a visibility input.

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

/// Checkerboard input: a traced pixel keeps its lit bit; the others take the mean of the lit bits of their four
/// neighbours (all traced) inside the rectangle, 0.5 when there is none.
fn reconstruct<Io: Read + ?Sized>(io: &Io, p: Coord) -> f64 {
    let e = io.extent();
    let lit = |q: Coord| (!io.read_hit_mask([q[0] / TILE[0], q[1] / TILE[1]]) >> super::tile_bit(q)) & 1;
    if io.is_traced(p) {
        return lit(p) as f64;
    }
    let neighbours = [[-1, 0], [1, 0], [0, -1], [0, 1]].map(|d| [p[0] + d[0], p[1] + d[1]]);
    let inside: Vec<Coord> = neighbours.into_iter().filter(|q| q[0] >= 0 && q[1] >= 0 && q[0] < e[0] && q[1] < e[1]).collect();
    if inside.is_empty() {
        return 0.5;
    }
    inside.iter().map(|&q| lit(q) as f64).sum::<f64>() / inside.len() as f64
}

/// Runs prepare over every tile of the render rectangle.
pub fn run<Io: Read + Write>(io: &mut Io) {
    let e = io.extent();
    if io.checkerboard_phase().is_some() {
        for y in 0..e[1] {
            for x in 0..e[0] {
                let v = reconstruct(io, [x, y]);
                io.write_visibility([x, y], v);
            }
        }
    }
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
