//! The SDK's clip space has y up: its shaders map a pixel's uv to NDC as (2 uv - 1) * (1, -1), and its Vulkan
//! sample draws with a negative-height viewport, so the matrices an SDK integration passes read and write y-up NDC.
//! dnsr reads Vulkan's (uv (0, 0) is NDC (-1, -1)). With F = diag(1, -1, 1, 1), F's own inverse, a matrix from
//! SDK clip space M becomes M F, and one between two SDK clip spaces R becomes F R F. Negating a row or a column is
//! exact, so dnsr then computes what it computes for the same camera given in Vulkan's convention, bit for bit.
//! (Measured before this: a pitching camera's history was lost, RMSE 0.083 against 0.068 with Vulkan-convention
//! matrices; static and panning cameras were unaffected.)

/// `m` (column-major, column vectors) times F: its second column negated.
pub(super) fn from_sdk_clip(mut m: [f32; 16]) -> [f32; 16] {
    for v in &mut m[4..8] {
        *v = -*v;
    }
    m
}

/// F `m` F: the second column and the second row negated (their shared element twice: unchanged).
pub(super) fn between_sdk_clips(m: [f32; 16]) -> [f32; 16] {
    let mut m = from_sdk_clip(m);
    for col in 0..4 {
        m[col * 4 + 1] = -m[col * 4 + 1];
    }
    m
}
