//! Images for people: the mask as pixels, error metrics, side-by-side strips, PNG output.

use super::scene::FrameInputs;
#[cfg(feature = "demo")]
use std::path::Path;

/// The 1-spp hit mask as one value per pixel: 1 lit, 0 shadowed. The mask follows the FidelityFX convention:
/// one u32 per 8x4 tile, bit (y % 4) * 8 + (x % 8) set when the shadow ray hit an occluder.
pub fn mask_to_image(f: &FrameInputs) -> Vec<f32> {
    let tiles_x = f.width.div_ceil(8);
    let mut out = Vec::with_capacity((f.width * f.height) as usize);
    for y in 0..f.height {
        for x in 0..f.width {
            let tile = f.mask[((y / 4) * tiles_x + x / 8) as usize];
            let occluded = tile >> ((y % 4) * 8 + (x % 8)) & 1 == 1;
            out.push(if occluded { 0.0 } else { 1.0 });
        }
    }
    out
}

/// Root-mean-square error against the truth over receiver pixels (NaN when there are none).
pub fn rmse(image: &[f32], truth: &[f32], receiver: &[bool]) -> f64 {
    let (mut sum, mut n) = (0.0, 0usize);
    for i in (0..truth.len()).filter(|&i| receiver[i]) {
        sum += (image[i] as f64 - truth[i] as f64).powi(2);
        n += 1;
    }
    (sum / n as f64).sqrt()
}

/// Images of one size laid out left to right with a grey gap between them.
pub fn side_by_side(w: u32, h: u32, images: &[&[f32]]) -> (u32, Vec<f32>) {
    const GAP: u32 = 4;
    let total = images.len() as u32 * (w + GAP) - GAP;
    let mut out = vec![0.5; (total * h) as usize];
    for (i, img) in images.iter().enumerate() {
        let x0 = i as u32 * (w + GAP);
        for y in 0..h {
            let src = &img[(y * w) as usize..((y + 1) * w) as usize];
            let dst = (y * total + x0) as usize;
            out[dst..dst + w as usize].copy_from_slice(src);
        }
    }
    (total, out)
}

/// Writes values in [0, 1] as an 8-bit grayscale PNG.
#[cfg(feature = "demo")]
pub fn write_png(path: &Path, w: u32, h: u32, values: &[f32]) -> Result<(), Box<dyn std::error::Error>> {
    let bytes: Vec<u8> = values.iter().map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8).collect();
    let file = std::fs::File::create(path).map_err(|e| format!("cannot create {}: {e}", path.display()))?;
    let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), w, h);
    encoder.set_color(png::ColorType::Grayscale);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header()?;
    writer.write_image_data(&bytes)?;
    writer.finish()?;
    Ok(())
}
