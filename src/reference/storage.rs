//! The compact formats dnsr stores its per-pixel state in, rounded exactly as shaders/dnsr_storage.glsl rounds them:
//! the reference keeps each stored value as the GPU reads it back. The GPU rounds its float32 value, the reference
//! its f64 value (through float32, as the GPU holds it), so a stored value can differ by one step of its format
//! where the two land on either side of a rounding boundary.

use crate::packing::{COUNT_CODE_OFFSET, COUNT_MAX, COUNT_SHIFT, COUNT_SUBNORMAL_CODES, COUNT_SUBNORMAL_SCALE};
use crate::packing::{MOMENTS_COUNT_BITS, MOMENTS_MEAN_BITS, MOMENTS_MEAN_MAX, MOMENTS_RUN_BITS, MOMENTS_RUN_SHIFT};
use glam::{DVec2, DVec3, DVec4};

/// `v` >= 0 rounded to the nearest float16 value, ties to even, as float32 bits are rounded
/// (`dnsr_round_half`): 0 below 2^-14 (no subnormals), at most 65504.
pub fn round_half(v: f64) -> f64 {
    let v = v as f32;
    if !(v >= 6.103_515_6e-5) {
        return 0.0;
    }
    let b = v.min(65504.0).to_bits();
    f32::from_bits((b + 0x0FFF + ((b >> 13) & 1)) & 0xFFFF_E000) as f64
}

/// Converts f32 to an IEEE half (round to nearest even; NaN stays NaN, overflow goes to infinity).
pub fn f32_to_f16(x: f32) -> u16 {
    let bits = x.to_bits();
    let sign = ((bits >> 16) & 0x8000) as u16;
    if x.is_nan() {
        return sign | 0x7E00;
    }
    let a = x.abs();
    if a >= 65520.0 {
        return sign | 0x7C00;
    }
    if a < 6.103_515_6e-5 {
        // Subnormal: multiples of 2^-24.
        return sign | (a * 16_777_216.0).round_ties_even() as u16;
    }
    let exp = ((bits >> 23) & 0xFF) as i32 - 127 + 15;
    let mant = bits & 0x7F_FFFF;
    let half = ((exp as u32) << 10) | (mant >> 13);
    let rest = mant & 0x1FFF;
    let round = (rest > 0x1000 || (rest == 0x1000 && half & 1 == 1)) as u32;
    sign | (half + round) as u16
}

/// Converts an IEEE half to f32.
pub fn f16_to_f32(h: u16) -> f32 {
    let sign = if h & 0x8000 != 0 { -1.0 } else { 1.0 };
    let exp = ((h >> 10) & 0x1f) as i32;
    let mant = (h & 0x3ff) as f32;
    sign * match exp {
        0 => mant * 2f32.powi(-24),
        31 => if mant == 0.0 { f32::INFINITY } else { f32::NAN },
        e => (1.0 + mant / 1024.0) * 2f32.powi(e - 15),
    }
}

fn unorm16(v: f64) -> u32 {
    ((v as f32).clamp(0.0, 1.0) as f64 * 65535.0 + 0.5).floor() as u32
}

fn from_unorm16(u: u32) -> f64 {
    u as f64 / 65535.0
}

/// A linear depth's 16-bit code (`dnsr_pack_linear_depth`, the depth copy's low bits): a float of 6 exponent and 10
/// mantissa bits from 2^-16 to 2^48, rounded to nearest from the depth as float32. Code 0 is no receiver (a negative
/// depth: the sky's -1); a receiver below the range takes code 1, above it, infinite and NaN the last.
pub fn pack_linear_depth(z: f64) -> u32 {
    use crate::state::{DEPTH_CODE_MAX, DEPTH_CODE_OFFSET, DEPTH_CODE_SHIFT};
    if z < 0.0 {
        return 0;
    }
    let b = ((z as f32).abs().to_bits() + (1 << (DEPTH_CODE_SHIFT - 1))) >> DEPTH_CODE_SHIFT;
    if b <= DEPTH_CODE_OFFSET { 1 } else { (b - DEPTH_CODE_OFFSET).min(DEPTH_CODE_MAX) }
}

/// A depth code's linear depth (`dnsr_unpack_linear_depth`): -1 for code 0, no receiver.
pub fn unpack_linear_depth(code: u32) -> f64 {
    use crate::state::{DEPTH_CODE_OFFSET, DEPTH_CODE_SHIFT};
    if code == 0 { -1.0 } else { f32::from_bits((code + DEPTH_CODE_OFFSET) << DEPTH_CODE_SHIFT) as f64 }
}

/// A linear depth as the next frame reads it back from the depth copy.
pub fn stored_linear_depth(z: f64) -> f64 {
    unpack_linear_depth(pack_linear_depth(z))
}

/// A sample count's 9-bit float code (`dnsr_pack_count`: 4 exponent bits, 5 mantissa bits, subnormals below
/// 2^-7; whole counts exact up to 64, at most 252), rounded half up from its float32 value.
pub fn pack_count(c: f64) -> u32 {
    let c = c as f32;
    let c = if c > 0.0 { c.min(COUNT_MAX as f32) } else { 0.0 }; // NaN too
    let subnormal = c * COUNT_SUBNORMAL_SCALE as f32;
    if subnormal < COUNT_SUBNORMAL_CODES as f32 {
        return (subnormal + 0.5).floor() as u32;
    }
    ((c.to_bits() + (1 << (COUNT_SHIFT - 1))) >> COUNT_SHIFT) - COUNT_CODE_OFFSET
}

/// A count code's value (`dnsr_unpack_count`).
pub fn unpack_count(code: u32) -> f64 {
    if code < COUNT_SUBNORMAL_CODES {
        code as f64 / COUNT_SUBNORMAL_SCALE as f64
    } else {
        f32::from_bits((code + COUNT_CODE_OFFSET) << COUNT_SHIFT) as f64
    }
}

/// Moments (mean, sum of squared deviations, sample count, run) packed as the GPU stores their first word
/// (`dnsr_pack_moments`): the mean as unorm14, the count (`pack_count`), twice the run as a signed 9-bit integer.
pub fn pack_moments(m: DVec4) -> u32 {
    let mean = ((m.x as f32).clamp(0.0, 1.0) as f64 * MOMENTS_MEAN_MAX as f64 + 0.5).floor() as u32;
    let run = ((m.w * 2.0) as i32) as u32 & ((1 << MOMENTS_RUN_BITS) - 1);
    mean | (pack_count(m.z) << MOMENTS_MEAN_BITS) | (run << MOMENTS_RUN_SHIFT)
}

/// A packed moments word read back; the sum of squared deviations is count * mean * (1 - mean), as with 0/1
/// samples (a visibility input's, stored apart, replaces it: `stored_moments`).
pub fn unpack_moments(v: u32) -> DVec4 {
    let code = v & MOMENTS_MEAN_MAX;
    let mean = if code == MOMENTS_MEAN_MAX { 1.0 } else { (code as f32 * (1.0 / MOMENTS_MEAN_MAX as f32)) as f64 };
    let count = unpack_count((v >> MOMENTS_MEAN_BITS) & ((1 << MOMENTS_COUNT_BITS) - 1));
    DVec4::new(mean, count * mean * (1.0 - mean), count, ((v as i32) >> MOMENTS_RUN_SHIFT) as f64 * 0.5)
}

/// Moments as a later frame reads them back: with `keep_sum` (a visibility input, whose samples are fractions)
/// the sum of squared deviations as its own float32 word, otherwise formed from the mean and the count.
pub fn stored_moments(m: DVec4, keep_sum: bool) -> DVec4 {
    let mut stored = unpack_moments(pack_moments(m));
    if keep_sum {
        stored.y = m.y as f32 as f64;
    }
    stored
}

/// The filter's signal (mean, variance) as the fp32 path stores it (R16G16_UNORM: the mean, and the standard
/// deviation over `scale`, `state::signal_scale` of the settings; the sky's variance -1 as the code 65535, a final
/// receiver's -2 as `state::SIGNAL_FINAL_CODE`), read back. A device's unorm write may take the other code next to
/// the value: parity allows one code.
pub fn stored_signal(v: DVec2, scale: f64) -> DVec2 {
    let mean = from_unorm16(unorm16(v.x));
    if v.y < 0.0 {
        return DVec2::new(mean, if super::final_signal(v) { super::FINAL_VARIANCE } else { -1.0 });
    }
    let max = crate::state::SIGNAL_MAX_DEVIATION_CODE as f64 / 65535.0;
    decode_signal([unorm16(mean), unorm16((v.y.sqrt() / scale).min(max))], scale)
}

/// A stored signal's two unorm16 codes read back as (mean, variance), as the shaders' dnsr_decode_signal does.
pub fn decode_signal(codes: [u32; 2], scale: f64) -> DVec2 {
    let d = from_unorm16(codes[1]) * scale;
    let variance = match codes[1] {
        c if c > crate::state::SIGNAL_SKY_CODE_ABOVE => -1.0,
        c if c > crate::state::SIGNAL_FINAL_CODE_ABOVE => super::FINAL_VARIANCE,
        _ => d * d,
    };
    DVec2::new(from_unorm16(codes[0]), variance)
}

/// The code of the zero normal (no usable normal) with `bits` a component: both codes at their minimum, which snorm
/// never writes (`dnsr_zero_normal`).
fn zero_normal(bits: u32) -> u32 {
    let low = 1 << (bits - 1);
    low | (low << bits)
}

fn snorm(v: f64, bits: u32) -> u32 {
    let scale = ((1 << (bits - 1)) - 1) as f64;
    (((v as f32).clamp(-1.0, 1.0) as f64 * scale + 0.5).floor() as i32 as u32) & ((1 << bits) - 1)
}

/// A unit normal (or zero) in 2 * `bits` bits: octahedral, two snorm codes (`dnsr_pack_octahedral`).
pub fn pack_octahedral(n: DVec3, bits: u32) -> u32 {
    let l1 = n.x.abs() + n.y.abs() + n.z.abs();
    if !(l1 > 0.0) {
        return zero_normal(bits);
    }
    let (mut ox, mut oy) = (n.x / l1, n.y / l1);
    if n.z < 0.0 {
        let sign = |v: f64| if v >= 0.0 { 1.0 } else { -1.0 };
        (ox, oy) = ((1.0 - oy.abs()) * sign(ox), (1.0 - ox.abs()) * sign(oy));
    }
    snorm(ox, bits) | (snorm(oy, bits) << bits)
}

/// A packed normal read back (unit length, or zero).
pub fn unpack_octahedral(u: u32, bits: u32) -> DVec3 {
    if u == zero_normal(bits) {
        return DVec3::ZERO;
    }
    let (drop, scale) = (32 - bits, ((1 << (bits - 1)) - 1) as f64);
    let (ox, oy) = (((u << drop) as i32 >> drop) as f64 / scale, ((u << (drop - bits)) as i32 >> drop) as f64 / scale);
    let mut n = DVec3::new(ox, oy, 1.0 - ox.abs() - oy.abs());
    let t = (-n.z).max(0.0);
    n.x += if n.x >= 0.0 { -t } else { t };
    n.y += if n.y >= 0.0 { -t } else { t };
    n.normalize()
}

/// A pixel's depth copy word (`dnsr_pack_depth_copy`, R32_UINT): its linear depth's code (-1, no receiver: code 0)
/// in the low `state::DEPTH_CODE_BITS`, its normal in the rest (`state::DEPTH_COPY_NORMAL_BITS` a component).
pub fn pack_depth_copy(linear_depth: f64, normal: DVec3) -> u32 {
    use crate::state::{DEPTH_CODE_BITS, DEPTH_COPY_NORMAL_BITS};
    pack_linear_depth(linear_depth) | (pack_octahedral(normal, DEPTH_COPY_NORMAL_BITS) << DEPTH_CODE_BITS)
}

/// A depth copy word read back: (linear depth or -1, normal).
pub fn unpack_depth_copy(v: u32) -> (f64, DVec3) {
    use crate::state::{DEPTH_CODE_BITS, DEPTH_CODE_MAX, DEPTH_COPY_NORMAL_BITS};
    (unpack_linear_depth(v & DEPTH_CODE_MAX), unpack_octahedral(v >> DEPTH_CODE_BITS, DEPTH_COPY_NORMAL_BITS))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn moments_keep_what_the_decisions_compare() {
        // The ends of the mean, whole and half runs of either sign up to the longest, whole counts up to 64: exact
        // (the sum of squared deviations of 0/1 samples follows from them).
        let longest = crate::settings::MAX_SAMPLE_RUN as f64;
        for m in [DVec4::new(1.0, 0.0, 32.0, longest), DVec4::new(0.0, 0.0, 64.0, -longest), DVec4::new(0.0, 0.0, 0.0, 0.0), DVec4::new(1.0, 0.0, 7.0, -3.5), DVec4::new(0.0, 0.0, 1.0, 2.5)] {
            assert_eq!(stored_moments(m, false), m);
        }
        // Others within one step of their format; a visibility input's sum as float32.
        let m = stored_moments(DVec4::new(0.3, 0.123_456, 17.3, 5.0), true);
        assert!((m.x - 0.3).abs() <= 0.5 / 16383.0 && m.y == 0.123_456f32 as f64 && (m.z - 17.3).abs() <= 0.5 / 2.0);
        assert_eq!(stored_moments(DVec4::new(0.3, 0.0, 10.0, 1.0), false).y, 10.0 * m.x * (1.0 - m.x));
        // The count's codes: monotonic, continuous across the subnormals, steps of 2 from 64, 252 the largest.
        let mut last = -1.0;
        for code in 0..512 {
            let c = unpack_count(code);
            assert!(c > last && pack_count(c) == code, "count code {code}: {c}");
            last = c;
        }
        assert_eq!((unpack_count(511), pack_count(1e9), pack_count(f64::NAN)), (252.0, 511, 0));
        assert_eq!((pack_count(65.0), pack_count(67.0)), (pack_count(66.0), pack_count(68.0))); // ties up
        assert_eq!(unpack_count(pack_count(127.0)), 128.0);
        assert_eq!(round_half(1e-6), 0.0);
        assert_eq!(round_half(1e9), 65504.0);
        assert_eq!(round_half(2049.0), 2048.0); // a tie, to even
        assert_eq!(round_half(2051.0), 2052.0);
    }

    /// 2000 unit vectors spread over the sphere, each with a number in [0, 1).
    fn sphere() -> impl Iterator<Item = (DVec3, f64)> {
        (0..2000).map(|i| {
            let (a, b) = (i as f64 * 0.618_033_988_7 % 1.0, i as f64 * 0.754_877_666 % 1.0);
            let z = 2.0 * a - 1.0;
            let r = (1.0 - z * z).sqrt();
            (DVec3::new(r * (6.283_185 * b).cos(), r * (6.283_185 * b).sin(), z), a)
        })
    }

    #[test]
    fn normals_round_trip_within_their_code() {
        let wide = |n| unpack_octahedral(pack_octahedral(n, 16), 16);
        assert_eq!(wide(DVec3::ZERO), DVec3::ZERO);
        let worst = sphere().map(|(n, _)| wide(n).angle_between(n)).fold(0.0, f64::max);
        assert!(worst < 1e-4, "octahedral snorm16 normal off by {worst} rad");
        // The depth copy's 8-bit normal: within about a degree, which the turned test (37 degrees) and the later
        // filter passes' normal edge stop need; the axes exact; zero stays zero; the depth keeps its code.
        for n in [DVec3::X, DVec3::NEG_Y, DVec3::Z, DVec3::NEG_Z] {
            assert!(unpack_depth_copy(pack_depth_copy(3.0, n)).1.distance(n) < 1e-9, "{n}");
        }
        let mut worst: f64 = 0.0;
        for (n, a) in sphere() {
            let (depth, stored) = unpack_depth_copy(pack_depth_copy(1.0 + a, n));
            assert_eq!(depth, stored_linear_depth(1.0 + a));
            worst = worst.max(stored.angle_between(n));
        }
        assert!(worst < 0.02, "octahedral 8-bit normal off by {worst} rad");
        assert_eq!(unpack_depth_copy(pack_depth_copy(2.0, DVec3::ZERO)).1, DVec3::ZERO);
        // No receiver is code 0, and reads back as -1; receivers never take it, however near.
        use crate::state::{DEPTH_CODE_BITS, DEPTH_CODE_MAX, DEPTH_COPY_NORMAL_BITS};
        let no_receiver = pack_octahedral(DVec3::ZERO, DEPTH_COPY_NORMAL_BITS) << DEPTH_CODE_BITS;
        assert_eq!((pack_depth_copy(-1.0, DVec3::ZERO), unpack_depth_copy(0).0), (no_receiver, -1.0));
        let ends = [0.0, 1e-30, f64::NAN, f64::INFINITY].map(pack_linear_depth);
        assert_eq!(ends, [1, 1, DEPTH_CODE_MAX, DEPTH_CODE_MAX]);
    }
}
