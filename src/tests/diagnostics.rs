//! Each integration diagnosis: a clean frame reports nothing; each planted mistake is reported.

use crate::reference::diagnostics::{diagnose, Diagnosis, HostFrame};
use crate::testing::scene::{render, Camera, FrameInputs};
use glam::{DMat4, DVec3};

fn host<'a>(f: &'a FrameInputs, inverted: bool) -> HostFrame<'a> {
    HostFrame {
        width: f.width,
        height: f.height,
        depth: &f.depth,
        normals: &f.normals,
        velocity: &f.velocity,
        motion_vector_scale: [1.0, 1.0],
        normals_unpack: [1.0, 0.0],
        projection_inverse: f.projection_inverse.as_dmat4(),
        reprojection: f.reprojection.as_dmat4(),
        view_projection_inverse: f.view_projection_inverse.as_dmat4(),
        eye: f.eye.as_dvec3(),
        depth_inverted: inverted,
    }
}

/// A camera panning and dollying over the plane, with sky at the side.
fn moving(inverted: bool) -> FrameInputs {
    let prev = Camera { inverted, ..Camera::above(0.0, 0.0, 10.0) };
    let cam = Camera { eye: prev.eye + DVec3::new(0.3, -0.2, 0.1), ..prev };
    render(64, 40, &cam, &prev, 4.0, &|_, _| 0.5, 1)
}

#[test]
fn clean_frames_report_nothing() {
    for inverted in [false, true] {
        let f = moving(inverted);
        assert_eq!(diagnose(&host(&f, inverted)), vec![], "inverted = {inverted}");
    }
}

#[test]
fn planted_mistakes_are_reported() {
    let f = moving(false);
    let check = |h: HostFrame, expect: fn(&Diagnosis) -> bool, what: &str| {
        let found = diagnose(&h);
        assert!(found.iter().any(expect), "{what}: got {found:?}");
        for d in &found {
            assert!(!d.to_string().is_empty());
            eprintln!("{what}: {d}");
        }
    };
    check(HostFrame { motion_vector_scale: [-1.0, -1.0], ..host(&f, false) }, |d| matches!(d, Diagnosis::VelocitySign { factor, .. } if *factor == -1.0), "negated velocity");
    check(HostFrame { motion_vector_scale: [0.5, 0.5], ..host(&f, false) }, |d| matches!(d, Diagnosis::VelocityScale { factor, .. } if *factor == 2.0), "half-scale velocity");
    // UNORM-packed normals decoded with the identity.
    let packed: Vec<[f32; 4]> = f.normals.iter().map(|n| n.map(|c| c * 0.5 + 0.5)).collect();
    check(HostFrame { normals: &packed, ..host(&f, false) }, |d| matches!(d, Diagnosis::NormalsNotUnit { looks_unorm: true, .. }), "UNORM normals, identity unpack");
    check(host(&f, true), |d| matches!(d, Diagnosis::DepthConvention { .. }), "inverted flag on standard depth");
    let g = moving(true);
    check(host(&g, false), |d| matches!(d, Diagnosis::DepthConvention { .. }), "standard flag on reverse-Z");
    // view_projection_inverse of a camera elsewhere (eye not moved with it).
    let shifted = DMat4::from_translation(DVec3::new(0.0, 3.0, 0.0)) * f.view_projection_inverse.as_dmat4();
    check(HostFrame { view_projection_inverse: shifted, ..host(&f, false) }, |d| matches!(d, Diagnosis::MatricesInconsistent { .. }), "mismatched matrices");
}
