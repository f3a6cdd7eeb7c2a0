// metrics.h: how far the viewer's shadows are from the reference: the per-pixel shadows of the last frame read
// back, their error against the reference, and reference files (--save-reference / --load-reference) that let
// several runs be measured against one expensive reference.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "renderer.h"

// "No darkening across creases": a lit face next to a shadowed one must stay as lit as the reference says. Over
// the receivers the reference holds fully lit (>= 254.5/255) within kCreaseRadius pixels (a square window) of a
// receiver it holds mostly shadowed (< 0.5), the darkening reference - denoised, in 1/255 units: its worst and its
// mean. Creases (a face turned away from the light next to a lit one) and contact shadows are where such pixels
// are; a filter that averages across the edge darkens them.
constexpr int kCreaseRadius = 3;

// "Do no harm" (docs/viewer-accuracy.md): the absolute error, in 1/255 units, over one class of pixels.
struct ClassError {
    size_t pixels = 0;
    double mean = 0, p99 = 0, max = 0;
    size_t over1 = 0;  // pixels off by more than 1/255
};

// Silhouettes: receivers the reference holds exactly shadowed within kSilhouetteRadius pixels of the sky or of a
// depth discontinuity (a neighbour more than kSilhouetteDepthJump farther or nearer, relative).
constexpr int kSilhouetteRadius = 2;
constexpr double kSilhouetteDepthJump = 0.1;

struct ErrorStats {
    double rmseNoisy = 0, rmseDenoised = 0;
    size_t pixels = 0;
    size_t creasePixels = 0;
    double creaseMax = 0, creaseMean = 0;  // darkening, in 1/255 units
    // Receivers the 1-spp input already has right: the reference is exactly 0 or 1 (every reference ray agrees)
    // and so is this frame's sample.
    ClassError exact;
    ClassError silhouette;
    ClassError crease;  // the crease pixels above, absolute error
    // Thin features: exact pixels whose value runs at most 2 px along x or y between pixels of the other exact
    // value (1-2 px stripes, lines); contrast kept = 1 - mean absolute error over them.
    size_t thinPixels = 0;
    double thinContrastKept = 1;
};

// In dB, for an error of signals in 0..1; 100 for no error at all.
double psnr(double rmse);

// FNV-1a, 64 bits: fingerprints that report.json carries, so that tests can compare runs bit for bit.
uint64_t fnv1a(const void *data, size_t bytes);

// Per-pixel shadow values (1 = lit) of one light in the last frame, from the readback.
struct ShadowImages {
    uint32_t width = 0, height = 0;
    std::vector<float> noisy, denoised, reference, depth;
    std::vector<bool> receiver;  // depth < 1: the pixels the error is measured on
    // Fingerprints of the hit mask and of dnsr's output as read back (float bits, before any clamping or rounding),
    // so that runs can be compared bit for bit.
    uint64_t hitMaskHash = 0, denoisedHash = 0;
};

// Which receivers' shadow rays the last frame traced (hybrid mode: the listed ones; otherwise all of them).
// Of the pixels decided without a ray: how many the reference finds mostly on the other side (lit < 0.5 where the
// verdict is lit, or > 0.5 where it is shadowed), and their mean absolute error against it.
struct TracedStats {
    size_t receivers = 0, traced = 0;  // pixels
    size_t tiles = 0, listedTiles = 0;  // 8x4 tiles; listed: with a traced pixel
    size_t decidedWrong = 0;
    double decidedMeanError = 0;
};
TracedStats tracedStats(const Renderer &r, const ShadowImages &s);

// Light `light`'s shadows from the renderer's readback (after recordReadback and the GPU's completion).
ShadowImages readShadows(const Renderer &r, uint32_t light, uint32_t w, uint32_t h);

// The error over the receivers, and the crease darkening (kCreaseRadius).
ErrorStats measure(const ShadowImages &s);

// --save-reference / --load-reference: a reference rendered once, measured against by later runs (other presets,
// guidance on or off) of the same scene, size, frames, light and camera. The file: "dnsrref1", then width, height
// and rays per pixel (uint32), then per pixel the depth and the reference visibility (float32; host byte order).
// The depth lets a later run check it renders the very same last frame.
struct ReferenceFile {
    uint32_t width = 0, height = 0, samples = 0;
    std::vector<float> depth, visibility;
};

// Throws VulkanError when the file cannot be written.
void saveReference(const std::string &path, const ShadowImages &s, uint32_t samples);
// Throws std::runtime_error with a one-line reason.
ReferenceFile loadReference(const std::string &path);
