//! The ꟻLIP image-difference metric (NVIDIA): the difference a viewer perceives when flipping back and forth
//! between a test image and its reference, per pixel, from 0 (indistinguishable) to 1 (maximal). Unlike a
//! per-pixel error it weighs differences by what the eye resolves, so faint noise and sharpened edges count for
//! what they look like. Shadow visibilities are viewed as sRGB grey on a display at the default viewing distance
//! ([`nv_flip::DEFAULT_PIXELS_PER_DEGREE`], about 0.7 m from a 0.7 m wide 4K monitor).

/// Mean LDR ꟻLIP error of `test` against `reference`, over the pixels where `mask` is true (every pixel when
/// `None`).
///
/// Both images are shadow visibilities, one per pixel, row-major, `width * height` long. They are shown the way
/// a display shows a linear visibility: clamped to [0, 1] (NaN as 0, fully shadowed), sRGB-encoded and rounded
/// to 8 bits. Returns 0 when no pixel is selected. FLIP filters over neighbourhoods (about 10 pixels at the
/// default viewing distance), so a difference just outside the mask still raises the error of the pixels inside
/// it.
///
/// # Panics
///
/// If `test`, `reference` or `mask` is not `width * height` long.
pub fn mean_flip(test: &[f32], reference: &[f32], width: u32, height: u32, mask: Option<&[bool]>) -> f64 {
    let n = width as usize * height as usize;
    assert_eq!(test.len(), n, "mean_flip: test is not width * height");
    assert_eq!(reference.len(), n, "mean_flip: reference is not width * height");
    if let Some(m) = mask {
        assert_eq!(m.len(), n, "mean_flip: mask is not width * height");
    }
    // Never hand the C++ library an empty image; an empty selection has no error to average either.
    if n == 0 || mask.is_some_and(|m| !m.contains(&true)) {
        return 0.0;
    }
    let errors = nv_flip::flip(
        grey_rgb8(reference, width, height),
        grey_rgb8(test, width, height),
        nv_flip::DEFAULT_PIXELS_PER_DEGREE,
    )
    .to_vec();
    // FlipPool only averages whole images, so the masked mean is taken here (in f64: a 4K frame has 8M terms).
    let (sum, count) = errors
        .iter()
        .enumerate()
        .filter(|&(i, _)| mask.is_none_or(|m| m[i]))
        .fold((0.0f64, 0usize), |(s, c), (_, &e)| (s + e as f64, c + 1));
    sum / count as f64
}

/// The 8-bit sRGB grey image a display would show for linear visibilities `v`.
fn grey_rgb8(v: &[f32], width: u32, height: u32) -> nv_flip::FlipImageRgb8 {
    let rgb: Vec<u8> = v.iter().flat_map(|&x| [srgb8(x); 3]).collect();
    nv_flip::FlipImageRgb8::with_data(width, height, &rgb)
}

/// Linear [0, 1] to an 8-bit sRGB code. FLIP assumes sRGB input; feeding it linear values would overweight the
/// dark end, where shadow noise is least visible.
fn srgb8(x: f32) -> u8 {
    // `clamp` passes NaN through, and the cast would turn it into 0 silently anyway; make the choice explicit.
    let x = if x.is_nan() { 0.0 } else { x.clamp(0.0, 1.0) };
    let s = if x <= 0.003_130_8 { 12.92 * x } else { 1.055 * x.powf(1.0 / 2.4) - 0.055 };
    (s * 255.0).round() as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    const W: u32 = 64;
    const H: u32 = 64;

    /// Blocky penumbrae: hard 0/1 blocks plus a ramp, so both edges and smooth gradients are compared.
    fn pattern() -> Vec<f32> {
        (0..W * H)
            .map(|i| {
                let (x, y) = (i % W, i / W);
                if y < H / 2 { ((x / 8 + y / 8) % 2) as f32 } else { x as f32 / (W - 1) as f32 }
            })
            .collect()
    }

    #[test]
    fn srgb_encoding() {
        assert_eq!(srgb8(0.0), 0);
        assert_eq!(srgb8(1.0), 255);
        // Linear 0.5 is the familiar sRGB 188, not 128.
        assert_eq!(srgb8(0.5), 188);
        assert_eq!(srgb8(f32::NAN), 0);
        assert_eq!(srgb8(-3.0), 0);
        assert_eq!(srgb8(f32::INFINITY), 255);
    }

    #[test]
    fn identical_is_zero() {
        let a = pattern();
        let e = mean_flip(&a, &a, W, H, None);
        assert!(e.abs() < 1e-6, "identical images: {e}");
    }

    #[test]
    fn inverse_is_large() {
        let a = pattern();
        let inv: Vec<f32> = a.iter().map(|v| 1.0 - v).collect();
        let e = mean_flip(&inv, &a, W, H, None);
        assert!(e > 0.5, "inverse: {e}");
        // Uniform black against uniform white is as different as two images get.
        let (black, white) = (vec![0.0; (W * H) as usize], vec![1.0; (W * H) as usize]);
        let e = mean_flip(&black, &white, W, H, None);
        assert!(e > 0.5, "black vs white: {e}");
    }

    #[test]
    fn small_offset_is_small() {
        let a = pattern();
        let inv: Vec<f32> = a.iter().map(|v| 1.0 - v).collect();
        let offset: Vec<f32> = a.iter().map(|v| v + 0.03).collect();
        let small = mean_flip(&offset, &a, W, H, None);
        let large = mean_flip(&inv, &a, W, H, None);
        assert!(small > 1e-4 && small < 0.2 && small < large, "offset {small}, inverse {large}");
    }

    #[test]
    fn mask_restricts_the_mean() {
        let a = pattern();
        // Differences only in the left quarter; the mask keeps the right half, beyond FLIP's ~10-pixel filters.
        let b: Vec<f32> =
            a.iter().enumerate().map(|(i, &v)| if (i as u32 % W) < W / 4 { 1.0 - v } else { v }).collect();
        let right: Vec<bool> = (0..W * H).map(|i| i % W >= W / 2).collect();
        let left: Vec<bool> = right.iter().map(|m| !m).collect();
        let inside = mean_flip(&b, &a, W, H, Some(&right));
        let outside = mean_flip(&b, &a, W, H, Some(&left));
        assert!(inside < 1e-6, "difference outside the mask leaked in: {inside}");
        assert!(outside > 0.2, "difference inside the mask: {outside}");
        let all = vec![true; (W * H) as usize];
        assert_eq!(mean_flip(&b, &a, W, H, Some(&all)), mean_flip(&b, &a, W, H, None));
        assert_eq!(mean_flip(&b, &a, W, H, Some(&vec![false; (W * H) as usize])), 0.0);
    }

    #[test]
    fn nan_is_black() {
        let a = pattern();
        let mut b = a.clone();
        b[5] = f32::NAN;
        let mut c = a.clone();
        c[5] = 0.0;
        let e = mean_flip(&b, &a, W, H, None);
        assert!(e.is_finite());
        assert_eq!(e, mean_flip(&c, &a, W, H, None));
    }
}
