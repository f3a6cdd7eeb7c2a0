//! Integration diagnostics: given one frame of the host's inputs (and, for motion, a camera that moved), report
//! the integration mistakes users of shadow denoisers make most, each with a plain message:
//! velocity sign or scale wrong, normals not unit length after unpacking, a depth-inverted flag that contradicts
//! the data, and matrices that disagree with each other.

use glam::{DMat4, DVec2, DVec3, DVec4};

/// One frame of host inputs, as the host would hand them to dnsr (raw, before dnsr's decoding).
#[derive(Clone, Debug)]
pub struct HostFrame<'a> {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Raw depth per pixel.
    pub depth: &'a [f32],
    /// Raw normal texels (rgb used) per pixel.
    pub normals: &'a [[f32; 4]],
    /// Raw motion vectors per pixel.
    pub velocity: &'a [[f32; 2]],
    /// The dispatch's motion vector scale.
    pub motion_vector_scale: [f32; 2],
    /// The dispatch's normal unpack multiplier and offset.
    pub normals_unpack: [f32; 2],
    /// Current clip -> view.
    pub projection_inverse: DMat4,
    /// Current clip -> previous clip.
    pub reprojection: DMat4,
    /// Current clip -> world.
    pub view_projection_inverse: DMat4,
    /// Eye in world space.
    pub eye: DVec3,
    /// The context's depth-inverted flag.
    pub depth_inverted: bool,
}

/// A likely integration mistake.
#[derive(Clone, Debug, PartialEq)]
pub enum Diagnosis {
    /// Motion vectors point the wrong way: `factor` (-1, or a negative scale) fits the camera motion far better.
    VelocitySign {
        /// Scale factor that fits best.
        factor: f64,
        /// Mean uv error with the vectors as given and with the factor applied.
        error: [f64; 2],
    },
    /// Motion vectors are scaled wrongly: `factor` times the given vectors fits the camera motion far better.
    VelocityScale {
        /// Scale factor that fits best.
        factor: f64,
        /// Mean uv error with the vectors as given and with the factor applied.
        error: [f64; 2],
    },
    /// Decoded normals are not unit length.
    NormalsNotUnit {
        /// Mean length after unpacking.
        mean_length: f64,
        /// Whether the raw values look UNORM-packed (all in [0, 1]) while the unpack is the identity.
        looks_unorm: bool,
    },
    /// The depth-inverted flag contradicts the projection or the data.
    DepthConvention {
        /// What contradicts the flag.
        evidence: &'static str,
    },
    /// projection_inverse, view_projection_inverse and eye describe different cameras.
    MatricesInconsistent {
        /// Largest relative difference of view distances found.
        relative_error: f64,
    },
}

impl std::fmt::Display for Diagnosis {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Diagnosis::VelocitySign { factor, error } => write!(
                f,
                "motion vectors point the wrong way: with motion_vector_scale multiplied by {factor} they match the \
                 camera motion (mean uv error {:.2e} instead of {:.2e}); dnsr expects previous uv = uv + v * scale",
                error[1], error[0]
            ),
            Diagnosis::VelocityScale { factor, error } => write!(
                f,
                "motion vectors are scaled wrongly: multiplying motion_vector_scale by {factor} matches the camera \
                 motion (mean uv error {:.2e} instead of {:.2e}); vectors must be in uv units after the scale",
                error[1], error[0]
            ),
            Diagnosis::NormalsNotUnit { mean_length, looks_unorm } => {
                write!(f, "normals are not unit length after unpacking (mean length {mean_length:.3})")?;
                if *looks_unorm {
                    write!(f, "; the raw values are all in [0, 1]: for UNORM-packed normals use unpack mul 2, add -1")?;
                }
                Ok(())
            }
            Diagnosis::DepthConvention { evidence } => write!(f, "the depth-inverted flag contradicts {evidence}"),
            Diagnosis::MatricesInconsistent { relative_error } => write!(
                f,
                "projection_inverse and view_projection_inverse/eye describe different cameras (view distances \
                 differ by up to {:.1}%); they must come from the same view and projection",
                relative_error * 100.0
            ),
        }
    }
}

fn receiver(d: f32) -> bool {
    d > 0.0 && d < 1.0
}

fn unproject(m: DMat4, ndc: DVec2, depth: f64) -> DVec3 {
    let p = m * DVec4::new(ndc.x, ndc.y, depth, 1.0);
    p.truncate() / p.w
}

/// Mean uv distance between the velocity-predicted previous position (vectors times `factor`) and the camera
/// reprojection's, over receivers; None when the camera did not move.
fn velocity_error(f: &HostFrame, factor: f64) -> Option<f64> {
    let (mut sum, mut n, mut motion) = (0.0, 0usize, 0.0);
    for y in (0..f.height).step_by(2) {
        for x in (0..f.width).step_by(2) {
            let i = (y * f.width + x) as usize;
            if !receiver(f.depth[i]) {
                continue;
            }
            let uv = DVec2::new((x as f64 + 0.5) / f.width as f64, (y as f64 + 0.5) / f.height as f64);
            let clip = f.reprojection * DVec4::new(uv.x * 2.0 - 1.0, uv.y * 2.0 - 1.0, f.depth[i] as f64, 1.0);
            let camera_prev = (clip.truncate().truncate() / clip.w) * 0.5 + 0.5;
            let v = DVec2::new(
                f.velocity[i][0] as f64 * f.motion_vector_scale[0] as f64,
                f.velocity[i][1] as f64 * f.motion_vector_scale[1] as f64,
            );
            sum += (uv + v * factor - camera_prev).length();
            motion += (camera_prev - uv).length();
            n += 1;
        }
    }
    (n > 0 && motion / n as f64 > 1e-4).then(|| sum / n as f64)
}

/// Runs every diagnosis on one frame.
pub fn diagnose(f: &HostFrame) -> Vec<Diagnosis> {
    let mut found = Vec::new();

    // Velocity: try a few sign and scale corrections against the camera reprojection.
    if let Some(as_given) = velocity_error(f, 1.0) {
        let candidates = [-1.0, 2.0, 0.5, -2.0, -0.5, 4.0, 0.25];
        let best = candidates
            .iter()
            .filter_map(|&k| velocity_error(f, k).map(|e| (k, e)))
            .min_by(|a, b| a.1.total_cmp(&b.1));
        if let Some((factor, error)) = best {
            if error < as_given * 0.25 {
                found.push(if factor < 0.0 {
                    Diagnosis::VelocitySign { factor, error: [as_given, error] }
                } else {
                    Diagnosis::VelocityScale { factor, error: [as_given, error] }
                });
            }
        }
    }

    // Normals: mean length after unpacking, over receivers.
    let [mul, add] = f.normals_unpack.map(|v| v as f64);
    let (mut length, mut n, mut all_unit_range) = (0.0, 0usize, true);
    for (i, raw) in f.normals.iter().enumerate() {
        if !receiver(f.depth[i]) {
            continue;
        }
        let r = DVec3::new(raw[0] as f64, raw[1] as f64, raw[2] as f64);
        if r.is_finite() {
            length += (r * mul + add).length();
            n += 1;
            all_unit_range &= r.min_element() >= 0.0 && r.max_element() <= 1.0;
        }
    }
    if n > 0 {
        let mean_length = length / n as f64;
        if (mean_length - 1.0).abs() > 0.05 {
            found.push(Diagnosis::NormalsNotUnit { mean_length, looks_unorm: all_unit_range && mul == 1.0 && add == 0.0 });
        }
    }

    // Depth convention: which end of the depth range the projection puts near, and where the background sits.
    let center = DVec2::ZERO;
    // 0.01 and 0.99 rather than 0 and 1: an infinite far plane maps one end to infinity.
    let (at_0, at_1) = (
        unproject(f.projection_inverse, center, 0.01).length(),
        unproject(f.projection_inverse, center, 0.99).length(),
    );
    let projection_inverted = at_1 < at_0;
    if at_0.is_finite() && at_1.is_finite() && projection_inverted != f.depth_inverted {
        found.push(Diagnosis::DepthConvention {
            evidence: if projection_inverted {
                "projection_inverse, which maps depth 1 to the near plane (reverse-Z): set the depth-inverted flag"
            } else {
                "projection_inverse, which maps depth 0 to the near plane (standard depth): clear the depth-inverted flag"
            },
        });
    } else {
        let (ones, zeros) = f.depth.iter().fold((0usize, 0usize), |(o, z), &d| (o + (d == 1.0) as usize, z + (d == 0.0) as usize));
        let (far, near) = if f.depth_inverted { (zeros, ones) } else { (ones, zeros) };
        if near > f.depth.len() / 100 && near > far * 4 {
            found.push(Diagnosis::DepthConvention {
                evidence: "the depth buffer, whose background sits at the value the flag calls near",
            });
        }
    }

    // Matrices: view-space distance from projection_inverse must equal the world distance to the eye.
    let mut worst: f64 = 0.0;
    for &depth in &[0.2, 0.5, 0.9, 0.99] {
        for &(x, y) in &[(-0.8, -0.8), (0.0, 0.0), (0.7, -0.3), (0.5, 0.9)] {
            let ndc = DVec2::new(x, y);
            let view = unproject(f.projection_inverse, ndc, depth).length();
            let world = (unproject(f.view_projection_inverse, ndc, depth) - f.eye).length();
            if view.is_finite() && world.is_finite() && view > 0.0 {
                worst = worst.max((view - world).abs() / view);
            }
        }
    }
    if worst > 0.01 {
        found.push(Diagnosis::MatricesInconsistent { relative_error: worst });
    }
    found
}
