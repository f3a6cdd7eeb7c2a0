//! The packed words that several data modules read, below all of them: a hit-mask tile's pixels and the moments'
//! word. Settings bound their knobs by them, the state table sizes images by them, the passes and the CPU reference
//! pack and unpack with them (constants.rs generates them into GLSL), so none of those modules imports another for
//! them.

/// Pixels of one hit-mask tile (one uint32): 8 x 4. Generated into GLSL as DNSR_TILE_SIZE.
pub(crate) const TILE: [u32; 2] = [8, 4];

/// The moments' word (docs/performance.md, "moments in one word"): the mean as unorm of this many bits (bit 0 on),
/// the count as a float of `MOMENTS_COUNT_BITS` (above the mean), twice the run as a signed integer in the rest.
/// Generated into GLSL with the values derived from them, which shaders/dnsr_storage.glsl and
/// src/reference/storage.rs use alike.
pub(crate) const MOMENTS_MEAN_BITS: u32 = 14;
/// See `MOMENTS_MEAN_BITS`.
pub(crate) const MOMENTS_COUNT_BITS: u32 = 9;
/// The run's bits: the rest of the word.
pub(crate) const MOMENTS_RUN_BITS: u32 = 32 - MOMENTS_MEAN_BITS - MOMENTS_COUNT_BITS;
/// The run's first bit. (This and `COUNT_SHIFT`, `COUNT_SUBNORMAL_CODES` follow from the generated constants;
/// shaders/dnsr_storage.glsl derives the same three from them.)
pub(crate) const MOMENTS_RUN_SHIFT: u32 = MOMENTS_MEAN_BITS + MOMENTS_COUNT_BITS;
/// The mean's largest code (1.0).
pub(crate) const MOMENTS_MEAN_MAX: u32 = (1 << MOMENTS_MEAN_BITS) - 1;
/// The count's mantissa bits; the rest of `MOMENTS_COUNT_BITS` is its exponent.
pub(crate) const COUNT_MANTISSA_BITS: u32 = 5;
/// The count's smallest normal value is 2^-COUNT_MIN_NORMAL_BELOW_ONE; below it, subnormal steps of
/// 1 / COUNT_SUBNORMAL_SCALE.
pub(crate) const COUNT_MIN_NORMAL_BELOW_ONE: u32 = 7;
/// The float32 mantissa bits a normal count drops.
pub(crate) const COUNT_SHIFT: u32 = 23 - COUNT_MANTISSA_BITS;
/// The subnormal counts' codes: 0 up to this.
pub(crate) const COUNT_SUBNORMAL_CODES: u32 = 1 << COUNT_MANTISSA_BITS;
/// See `COUNT_MIN_NORMAL_BELOW_ONE`.
pub(crate) const COUNT_SUBNORMAL_SCALE: u32 = 1 << (COUNT_MIN_NORMAL_BELOW_ONE + COUNT_MANTISSA_BITS);
/// A normal count's code is its float32 bits' exponent and top mantissa bits less this (the float32 exponent of
/// the count's smallest normal value, less one, in code units).
pub(crate) const COUNT_CODE_OFFSET: u32 = (127 - COUNT_MIN_NORMAL_BELOW_ONE - 1) << COUNT_MANTISSA_BITS;
/// The largest count: every code bit set.
pub(crate) const COUNT_MAX: u32 = {
    let max_exponent = (1 << (MOMENTS_COUNT_BITS - COUNT_MANTISSA_BITS)) - 2 - COUNT_MIN_NORMAL_BELOW_ONE as i32;
    ((1 << (COUNT_MANTISSA_BITS + 1)) - 1) << (max_exponent - COUNT_MANTISSA_BITS as i32)
};
const _: () = assert!(COUNT_MAX == 252 && COUNT_CODE_OFFSET == 3808 && COUNT_SUBNORMAL_SCALE == 4096);
