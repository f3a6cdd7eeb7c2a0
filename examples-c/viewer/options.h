// options.h: the viewer's command line (--help prints every option and key).
#pragma once

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "renderer.h"

#ifndef VIEWER_DEFAULT_SCENE
#define VIEWER_DEFAULT_SCENE "scenes/default.gltf"
#endif

struct Options {
    std::string scene = VIEWER_DEFAULT_SCENE;
    bool headless = false;
    bool validate = false;
    uint32_t frames = 0;  // 0: headless default 16, window: run until closed
    uint32_t width = 0, height = 0;
    std::string outDir = "out/viewer";
    std::string screenshot;
    bool pointLight = false;
    bool packedGbuffer = false;
    // Normal-map-like detail on the shading normals (RendererSettings::normalDetail), 0..1.
    float normalDetail = 0.0f;
    bool normalDetailDnsrOnly = false;  // --normal-detail-for dnsr: in dnsr's packed normals alone
    uint32_t rays = 1;  // shadow rays per pixel (more than 1: DNSR_SHADOW_INPUT_VISIBILITY)
    bool checkerboard = false;  // half a ray per pixel (DNSR_SHADOW_INPUT_CHECKERBOARD)
    uint32_t lights = 1;  // more than 1: the others derived from the first, all denoised by one dnsr_lights_record
    float lightAngleDeg = 3.0f;
    bool hitDistance = true;  // penumbra guidance (DNSR_DISPATCH_USE_HIT_DISTANCE)
    bool hardLight = true;    // tell dnsr when the light has no size (DNSR_DISPATCH_HARD_LIGHT)
    bool lightPosition = true;  // tell dnsr where the light is (DNSR_DISPATCH_USE_LIGHT_POSITION)
    bool lightMotion = false;
    uint32_t referenceSamples = 256;
    std::string saveReference, loadReference;  // headless: the reference, written to / read from a file
    float orbitDegPerFrame = 0.25f;
    float panPerFrame = 0;  // headless: camera (eye and target) moves sideways by this fraction of its distance
    float lightElevationDeg = 50.0f;
    float lightAzimuthDeg = 100.0f;  // around the up axis from the starting view's direction
    DnsrPreset preset = DNSR_PRESET_QUALITY;
    std::vector<std::pair<std::string, double>> settings;  // --set: DnsrSettings fields changed after the preset
    View view = View::Composite;  // window mode: the view shown first
    // Headless: the last frame's dnsr output is this debug view (View::DnsrTiles..DnsrDisocclusion, DnsrSampleRun) instead of the
    // shadow; Composite: none.
    View debugView = View::Composite;
    // Hybrid shadows (RendererSettings::hybrid): start in hybrid mode, and its settings.
    bool hybrid = false;
    uint32_t cascades = 2, cascadeSize = 0, taps = 24, tileCutoff = 0;
    float blockerOffset = -1.0f;  // in scene radii; negative: two texels of the finest cascade
    bool reverseRays = false;
};

// Whether the options allow hybrid mode: dnsr's classifier takes one directional light's hit mask, traced one ray
// per pixel, with the default G-buffer. Empty when they do, else why not.
std::string hybridUnsupported(const Options &options);

// A bad command line: main prints the message and exits with status 2.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Throws UsageError; prints the usage and exits 0 for --help.
Options parseOptions(int argc, char **argv);
