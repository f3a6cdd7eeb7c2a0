// main.cpp: the dnsr viewer. Loads a glTF scene, ray traces it in compute shaders (G-buffer + one shadow ray
// per pixel), denoises the shadow with dnsr and shows or saves the result.
//
//   dnsr_viewer [scene.gltf|scene.glb] [options]       window (GLFW): drag to orbit, scroll to zoom
//   dnsr_viewer --headless --frames 16 --out out/      PNGs + report.json, no window system needed
//
// Exit status: 0 success; 1 a Vulkan/dnsr failure or (with --validate) any validation message; 2 bad command
// line, a scene or --load-reference file the viewer cannot load (one line on stderr says why).
#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "png_write.h"
#include "renderer.h"
#include "scene_gltf.h"
#include "vk_context.h"

#ifndef VIEWER_DEFAULT_SCENE
#define VIEWER_DEFAULT_SCENE "scenes/default.gltf"
#endif

namespace {

constexpr float kPi = 3.14159265358979f;
float radians(float degrees) { return degrees * kPi / 180.0f; }

// ---- Command line ----

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
    uint32_t rays = 1;  // shadow rays per pixel (more than 1: DNSR_SHADOW_INPUT_VISIBILITY)
    bool checkerboard = false;  // half a ray per pixel (DNSR_SHADOW_INPUT_CHECKERBOARD)
    uint32_t lights = 1;  // more than 1: the others derived from the first, all denoised by one dnsr_lights_record
    float lightAngleDeg = 3.0f;
    bool hitDistance = true;  // penumbra guidance (DNSR_DISPATCH_USE_HIT_DISTANCE)
    bool lightMotion = false;
    uint32_t referenceSamples = 256;
    std::string saveReference, loadReference;  // headless: the reference, written to / read from a file
    float orbitDegPerFrame = 0.25f;
    DnsrPreset preset = DNSR_PRESET_BALANCED;
    View view = View::Composite;  // window mode: the view shown first
};

const char *kUsage =
    "usage: dnsr_viewer [SCENE.gltf|SCENE.glb] [options]\n"
    "  SCENE                   a glTF 2.0 file (default " VIEWER_DEFAULT_SCENE ")\n"
    "  --headless              render without a window; writes PNGs and report.json to --out\n"
    "  --frames N              frames to render, 1..1000000 (headless default 16; window: until closed)\n"
    "  --size WxH              render size, 8x8..8192x8192 (default 960x540 windowed, 320x192 headless)\n"
    "  --out DIR               headless output directory (default out/viewer)\n"
    "  --screenshot FILE       window mode: save the displayed image (PNG) after --frames N frames and exit\n"
    "  --point-light           a spherical point light instead of the directional light\n"
    "  --light-angle DEG       angular radius of the light, 0..30 (default 3; sets the penumbra width)\n"
    "  --light-motion          start with the light moving (key L toggles it)\n"
    "  --lights N              1 or 2 lights (default 1). The second (light 1) is the first (light 0) turned 100\n"
    "                          degrees about the up axis: same elevation, size and kind (a point light the same\n"
    "                          distance from the scene's centre). Each has its own shadow rays, dnsr history and\n"
    "                          output; both are denoised in one dnsr_lights_record call and light the composite.\n"
    "                          Headless: also {noisy,denoised,reference}_light1.png and report.json's per_light\n"
    "  --gbuffer default|packed  packed: keep linear depth and octahedral RG16 normals, and run dnsr's passes\n"
    "                          compiled against examples-c/custom_gbuffer's callbacks (default: default)\n"
    "  --rays N                shadow rays per pixel, 1..64 (default 1: the hit mask; more: their lit fraction as\n"
    "                          per-pixel visibility, DNSR_SHADOW_INPUT_VISIBILITY)\n"
    "  --checkerboard          half a ray per pixel: each frame traces only the pixels with (x + y) % 2 == frame % 2\n"
    "                          (DNSR_SHADOW_INPUT_CHECKERBOARD); dnsr gives the others their traced neighbours' mean,\n"
    "                          and so does the noisy view. Takes --rays 1 and --gbuffer default\n"
    "  --hit-distance on|off   penumbra guidance: give dnsr each shadow ray's distance to its nearest occluder and\n"
    "                          the light's angular diameter (DNSR_DISPATCH_USE_HIT_DISTANCE; default on; key H)\n"
    "  --reference-samples N   shadow rays per pixel of the reference, 1..65536 (default 256)\n"
    "  --save-reference FILE   headless: also write the last frame's reference (and depth) to FILE (--lights 1)\n"
    "  --load-reference FILE   headless: measure against FILE's reference instead of rendering one (same scene,\n"
    "                          size, frames, light and camera: the run fails if the last frame's depth differs;\n"
    "                          --lights 1)\n"
    "  --view NAME             window mode: first view (noisy, denoised, reference, composite, tiles, or dnsr's\n"
    "                          debug views classification, samples, variance, disocclusion; keys 1-9)\n"
    "  --orbit-speed DEG       headless: camera orbit per frame in degrees, -45..45 (default 0.25; 0 = static)\n"
    "  --preset NAME           dnsr's settings: fast, balanced (the FidelityFX defaults; default) or quality\n"
    "  --validate              enable VK_LAYER_KHRONOS_validation; any validation message makes the exit status 1\n"
    "                          (the Vulkan loader's own notices are shown but not counted)\n"
    "  -h, --help              print this and exit\n"
    "environment: VIEWER_DEVICE=<substring of the device name> picks a Vulkan device (default: the first)\n"
    "window keys: left-drag orbit, scroll zoom, R reset view (a camera cut: dnsr's history restarts),\n"
    "             1 noisy, 2 denoised, 3 reference (accumulates while nothing moves), 4 composite,\n"
    "             5 hit-mask density per tile, 6 dnsr tile classification, 7 dnsr sample count,\n"
    "             8 dnsr variance, 9 dnsr disocclusion, L toggle light motion, H toggle penumbra guidance\n"
    "             (hit distances), N the other light in views 1-3, 5-9 (--lights 2), Esc/Q quit\n"
    "exit status: 0 success, 1 a Vulkan/dnsr failure or (with --validate) a validation message,\n"
    "             2 a bad command line, or a scene or reference file the viewer cannot load\n";

struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

uint32_t parseCount(const char *flag, const char *value, uint32_t min, uint32_t max)
{
    char *end = nullptr;
    long v = std::strtol(value, &end, 10);
    if (!*value || *end || v < long(min) || v > long(max))
        throw UsageError(std::string(flag) + " wants a number in " + std::to_string(min) + ".." + std::to_string(max) +
                         ", got '" + value + "'");
    return static_cast<uint32_t>(v);
}

Options parseOptions(int argc, char **argv)
{
    Options o;
    bool haveScene = false;
    for (int i = 1; i < argc; i++) {
        std::string a = argv[i];
        auto value = [&]() -> const char * {
            if (i + 1 >= argc) throw UsageError(a + " needs a value");
            return argv[++i];
        };
        if (a == "--help" || a == "-h") {
            std::fputs(kUsage, stdout);
            std::exit(0);
        } else if (a == "--headless") {
            o.headless = true;
        } else if (a == "--validate") {
            o.validate = true;
        } else if (a == "--frames") {
            o.frames = parseCount("--frames", value(), 1, 1000000);
        } else if (a == "--size") {
            const char *v = value();
            unsigned w = 0, h = 0;
            char tail = 0;
            if (std::sscanf(v, "%ux%u%c", &w, &h, &tail) != 2 || w < 8 || h < 8 || w > 8192 || h > 8192)
                throw UsageError(std::string("--size wants WxH between 8x8 and 8192x8192, got '") + v + "'");
            o.width = w, o.height = h;
        } else if (a == "--out") {
            o.outDir = value();
        } else if (a == "--screenshot") {
            o.screenshot = value();
        } else if (a == "--point-light") {
            o.pointLight = true;
        } else if (a == "--light-angle") {
            const char *v = value();
            char *end = nullptr;
            o.lightAngleDeg = std::strtof(v, &end);
            if (!*v || *end || !(o.lightAngleDeg >= 0.0f && o.lightAngleDeg <= 30.0f))
                throw UsageError(std::string("--light-angle wants degrees in 0..30, got '") + v + "'");
        } else if (a == "--orbit-speed") {
            const char *v = value();
            char *end = nullptr;
            o.orbitDegPerFrame = std::strtof(v, &end);
            if (!*v || *end || !(std::fabs(o.orbitDegPerFrame) <= 45.0f))
                throw UsageError(std::string("--orbit-speed wants degrees in -45..45, got '") + v + "'");
        } else if (a == "--view") {
            std::string v = value();
            const char *names[] = {"noisy",          "denoised", "reference", "composite",   "tiles",
                                   "classification", "samples",  "variance",  "disocclusion"};
            auto it = std::find(std::begin(names), std::end(names), v);
            if (it == std::end(names))
                throw UsageError("--view wants noisy, denoised, reference, composite, tiles, classification, samples, "
                                 "variance or disocclusion, got '" + v + "'");
            o.view = static_cast<View>(it - std::begin(names));
        } else if (a == "--preset") {
            std::string v = value();
            const char *names[] = {"fast", "balanced", "quality"};  // DNSR_PRESET_FAST, _BALANCED, _QUALITY
            auto it = std::find(std::begin(names), std::end(names), v);
            if (it == std::end(names)) throw UsageError("--preset wants fast, balanced or quality, got '" + v + "'");
            o.preset = static_cast<DnsrPreset>(it - std::begin(names));
        } else if (a == "--gbuffer") {
            std::string v = value();
            if (v != "default" && v != "packed") throw UsageError("--gbuffer wants default or packed, got '" + v + "'");
            o.packedGbuffer = v == "packed";
        } else if (a == "--rays") {
            o.rays = parseCount("--rays", value(), 1, 64);
        } else if (a == "--checkerboard") {
            o.checkerboard = true;
        } else if (a == "--lights") {
            o.lights = parseCount("--lights", value(), 1, kMaxLights);
        } else if (a == "--hit-distance") {
            std::string v = value();
            if (v != "on" && v != "off") throw UsageError("--hit-distance wants on or off, got '" + v + "'");
            o.hitDistance = v == "on";
        } else if (a == "--light-motion") {
            o.lightMotion = true;
        } else if (a == "--reference-samples") {
            o.referenceSamples = parseCount("--reference-samples", value(), 1, 65536);
        } else if (a == "--save-reference") {
            o.saveReference = value();
        } else if (a == "--load-reference") {
            o.loadReference = value();
        } else if (!a.empty() && a[0] == '-') {
            throw UsageError("unknown option " + a);
        } else if (haveScene) {
            throw UsageError("more than one scene file given");
        } else {
            o.scene = a;
            haveScene = true;
        }
    }
    if (!o.width) {
        o.width = o.headless ? 320 : 960;
        o.height = o.headless ? 192 : 540;
    }
    if (o.headless && !o.frames) o.frames = 16;
    // The packed build's classification variants read the hit mask (examples-c/custom_gbuffer overrides those only).
    if (o.packedGbuffer && o.rays > 1) throw UsageError("--gbuffer packed takes one ray per pixel (--rays 1)");
    if (o.checkerboard && o.rays > 1)
        throw UsageError("--checkerboard takes --rays 1 (it traces half a ray per pixel into the hit mask; several "
                         "rays per pixel go to dnsr as visibility, another input)");
    // A checkerboard input is classified by the visibility variants too: dnsr takes the combination, but runs its
    // own variant on the packed depth and normals (every pixel came out lit).
    if (o.checkerboard && o.packedGbuffer)
        throw UsageError("--checkerboard takes --gbuffer default (dnsr then classifies tiles with its visibility "
                         "variants, which examples-c/custom_gbuffer does not compile against the packed G-buffer)");
    if (o.headless && !o.screenshot.empty()) throw UsageError("--screenshot is for window mode (headless writes PNGs)");
    if (!o.screenshot.empty() && !o.frames) throw UsageError("--screenshot needs --frames N");
    if (!o.headless && !(o.saveReference.empty() && o.loadReference.empty()))
        throw UsageError("--save-reference and --load-reference are for --headless");
    if (!o.saveReference.empty() && !o.loadReference.empty())
        throw UsageError("--save-reference and --load-reference exclude each other");
    // A reference file holds one light's reference (its format predates --lights).
    if (o.lights > 1 && !(o.saveReference.empty() && o.loadReference.empty()))
        throw UsageError("--save-reference and --load-reference take one light (--lights 1)");
    return o;
}

// ---- Camera and light ----

// An orbit camera: looks at `target` from `distance` away, at angles yaw (around +y) and pitch (above the
// horizon). The scene's own camera, when it has one, gives the starting orbit.
struct Orbit {
    Vec3 target;
    float yaw = 0, pitch = 0, distance = 1, fovY = 0.8f;

    Vec3 eye() const
    {
        return target + Vec3{std::cos(pitch) * std::sin(yaw), std::sin(pitch), std::cos(pitch) * std::cos(yaw)} *
                            distance;
    }
};

Orbit initialOrbit(const Scene &scene)
{
    Vec3 center = (scene.boundsMin + scene.boundsMax) * 0.5f;
    float radius = std::max(length(scene.boundsMax - scene.boundsMin) * 0.5f, 1e-3f);
    Orbit o;
    if (scene.hasCamera) {
        Vec3 eye = scene.cameraToWorld.transformPoint({0, 0, 0});
        Vec3 forward = normalize(scene.cameraToWorld.transformPoint({0, 0, -1}) - eye);
        if (isFinite(eye) && length(forward) > 0.5f) {
            // Orbit around the point of the view axis nearest to the scene's centre.
            float along = std::max(dot(center - eye, forward), 0.05f * radius);
            o.target = eye + forward * along;
            Vec3 back = eye - o.target;
            o.distance = length(back);
            o.pitch = std::asin(std::clamp(back.y / o.distance, -1.0f, 1.0f));
            o.yaw = std::atan2(back.x, back.z);
            o.fovY = scene.cameraYFov;
            return o;
        }
    }
    o.target = center;
    o.fovY = 0.8f;
    // 0.7 of the distance at which the bounding sphere would just fit: most scenes are flatter than a sphere.
    o.distance = 0.7f * radius / std::sin(o.fovY * 0.5f);
    o.pitch = radians(30.0f);
    o.yaw = radians(35.0f);
    return o;
}

// The lights: light 0 as the options place it, light i the same turned i x 100 degrees about the up axis (same
// elevation, angle and kind), so that every light's shadows fall elsewhere, in any scene, with any options.
struct LightState {
    bool point = false;
    float azimuth = 0, elevation = radians(50.0f);  // light 0's
    float angle = radians(3.0f);  // angular radius
    bool moving = false;
    bool hitDistance = true;  // penumbra guidance for dnsr

    Vec3 direction(uint32_t light) const
    {
        float a = azimuth + radians(100.0f) * float(light);
        return {std::cos(elevation) * std::sin(a), std::sin(elevation), std::cos(elevation) * std::cos(a)};
    }
};

struct SceneFrame {
    const Scene *scene = nullptr;
    Vec3 center;
    float radius = 1;
};

// The frame description for the renderer: camera matrices and light.
FrameInput makeFrame(const SceneFrame &sf, const Orbit &orbit, const LightState &light, uint32_t width, uint32_t height)
{
    FrameInput in;
    in.eye = orbit.eye();
    in.viewMatrix = lookAt(in.eye, orbit.target, {0, 1, 0});
    // A far plane behind the whole scene from anywhere on the orbit, and a near plane at 1% of the orbit distance:
    // with standard depth, a much closer near plane squeezes every receiver's depth against 1 and costs dnsr's
    // depth tests their precision (see reprojection() in vec_math.h).
    float zNear = std::max(orbit.distance * 0.01f, sf.radius * 1e-4f);
    float zFar = orbit.distance + 2.5f * sf.radius;
    in.projection = perspectiveVulkan(orbit.fovY, float(width) / float(height), zNear, zFar);
    in.pointLight = light.point;
    in.hitDistance = light.hitDistance;
    if (light.point) {
        // A sphere at half the scene radius from the centre; the angular radius is as seen from the centre. dnsr's
        // penumbra guidance takes one angular diameter for all receivers: the one seen from the centre, 2 asin(r / D)
        // (receivers farther from the light see it smaller, nearer ones larger).
        float dist = 0.5f * sf.radius;
        for (uint32_t i = 0; i < kMaxLights; i++) in.lights[i] = sf.center + light.direction(i) * dist;
        in.lightSize = dist * std::tan(light.angle);
        in.lightAngularSize = 2.0f * std::asin(std::min(in.lightSize / dist, 1.0f));
    } else {
        // Rays leave within a cone of half-angle light.angle (tan of it scales the disk): diameter 2 * angle.
        for (uint32_t i = 0; i < kMaxLights; i++) in.lights[i] = light.direction(i);
        in.lightSize = std::tan(light.angle);
        in.lightAngularSize = 2.0f * light.angle;
    }
    return in;
}

// ---- Measurements and output ----

// "No darkening across creases": a lit face next to a shadowed one must stay as lit as the reference says. Over
// the receivers the reference holds fully lit (>= 254.5/255) within kCreaseRadius pixels (a square window) of a
// receiver it holds mostly shadowed (< 0.5), the darkening reference - denoised, in 1/255 units: its worst and its
// mean. Creases (a face turned away from the light next to a lit one) and contact shadows are where such pixels
// are; a filter that averages across the edge darkens them.
constexpr int kCreaseRadius = 3;

struct ErrorStats {
    double rmseNoisy = 0, rmseDenoised = 0;
    size_t pixels = 0;
    size_t creasePixels = 0;
    double creaseMax = 0, creaseMean = 0;  // darkening, in 1/255 units
};

double psnr(double rmse) { return rmse > 0 ? std::min(100.0, -20.0 * std::log10(rmse)) : 100.0; }

// FNV-1a, 64 bits.
uint64_t fnv1a(const void *data, size_t bytes)
{
    uint64_t h = 0xcbf29ce484222325ull;
    for (size_t i = 0; i < bytes; i++) h = (h ^ static_cast<const uint8_t *>(data)[i]) * 0x100000001b3ull;
    return h;
}

// Per-pixel shadow values (1 = lit) of one light in the last frame, from the readback.
struct ShadowImages {
    uint32_t width = 0, height = 0;
    std::vector<float> noisy, denoised, reference, depth;
    std::vector<bool> receiver;  // depth < 1: the pixels the error is measured on
    // Fingerprints of the hit mask and of dnsr's output as read back (float bits, before any clamping or rounding),
    // so that runs can be compared bit for bit.
    uint64_t hitMaskHash = 0, denoisedHash = 0;
};

ShadowImages readShadows(const Renderer &r, uint32_t light, uint32_t w, uint32_t h)
{
    ShadowImages s;
    s.width = w, s.height = h;
    size_t n = size_t(w) * h;
    s.noisy.resize(n), s.denoised.resize(n), s.reference.resize(n), s.receiver.resize(n);
    s.depth.assign(r.readDepth(), r.readDepth() + n);
    const uint32_t *mask = r.readHitMask(light);
    auto bit = [](uint32_t x, uint32_t y) { return (y % 4) * 8 + x % 8; };  // in the 8x4 tile's word
    auto ray = [&](uint32_t x, uint32_t y) {
        return (mask[(y / 4) * r.tilesX() + x / 8] >> bit(x, y)) & 1u ? 0.0f : 1.0f;
    };
    float count = float(std::max(r.referenceCount(), 1u));
    for (uint32_t y = 0; y < h; y++)
        for (uint32_t x = 0; x < w; x++) {
            size_t i = size_t(y) * w + x;
            // A pixel --checkerboard did not trace gets its traced neighbours' mean, as dnsr reconstructs it (and
            // composite.comp's noisy view): the noisy error is that of what dnsr starts from.
            if ((r.tracedBits() >> bit(x, y)) & 1u) {
                s.noisy[i] = ray(x, y);
            } else {
                float sum = 0, traced = 0;
                if (x > 0) sum += ray(x - 1, y), traced++;
                if (x + 1 < w) sum += ray(x + 1, y), traced++;
                if (y > 0) sum += ray(x, y - 1), traced++;
                if (y + 1 < h) sum += ray(x, y + 1), traced++;
                s.noisy[i] = sum / traced;  // at least 2: the image is at least 8x8
            }
            s.denoised[i] = std::clamp(r.readDenoised(light)[i], 0.0f, 1.0f);
            s.reference[i] = r.readReferenceSum(light)[i] / count;
            s.receiver[i] = r.readDepth()[i] < 1.0f;
        }
    s.hitMaskHash = fnv1a(mask, size_t(r.tilesX()) * r.tilesY() * 4);
    s.denoisedHash = fnv1a(r.readDenoised(light), n * 4);
    return s;
}

ErrorStats measure(const ShadowImages &s)
{
    ErrorStats e;
    double noisy = 0, denoised = 0;
    for (size_t i = 0; i < s.receiver.size(); i++) {
        if (!s.receiver[i]) continue;
        noisy += double(s.noisy[i] - s.reference[i]) * (s.noisy[i] - s.reference[i]);
        denoised += double(s.denoised[i] - s.reference[i]) * (s.denoised[i] - s.reference[i]);
        e.pixels++;
    }
    if (e.pixels) {
        e.rmseNoisy = std::sqrt(noisy / e.pixels);
        e.rmseDenoised = std::sqrt(denoised / e.pixels);
    }

    const int w = int(s.width), h = int(s.height);
    auto shadowed = [&](int x, int y) {
        size_t i = size_t(y) * w + x;
        return s.receiver[i] && s.reference[i] < 0.5f;
    };
    double sum = 0, worst = -1e30;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            size_t i = size_t(y) * w + x;
            if (!s.receiver[i] || !(s.reference[i] >= 254.5f / 255.0f)) continue;
            bool nearShadow = false;
            for (int dy = -kCreaseRadius; dy <= kCreaseRadius && !nearShadow; dy++)
                for (int dx = -kCreaseRadius; dx <= kCreaseRadius && !nearShadow; dx++) {
                    int nx = x + dx, ny = y + dy;
                    nearShadow = nx >= 0 && ny >= 0 && nx < w && ny < h && shadowed(nx, ny);
                }
            if (!nearShadow) continue;
            double darkening = (double(s.reference[i]) - s.denoised[i]) * 255.0;
            sum += darkening;
            worst = std::max(worst, darkening);
            e.creasePixels++;
        }
    if (e.creasePixels) {
        e.creaseMax = worst;
        e.creaseMean = sum / double(e.creasePixels);
    }
    return e;
}

// --save-reference / --load-reference: a reference rendered once, measured against by later runs (other presets,
// guidance on or off) of the same scene, size, frames, light and camera. The file: "dnsrref1", then width, height
// and rays per pixel (uint32), then per pixel the depth and the reference visibility (float32; host byte order).
// The depth lets a later run check it renders the very same last frame.
struct ReferenceFile {
    uint32_t width = 0, height = 0, samples = 0;
    std::vector<float> depth, visibility;
};

const char kReferenceMagic[8] = {'d', 'n', 's', 'r', 'r', 'e', 'f', '1'};

void saveReference(const std::string &path, const ShadowImages &s, uint32_t samples)
{
    FILE *f = std::fopen(path.c_str(), "wb");
    uint32_t header[3] = {s.width, s.height, samples};
    size_t n = s.depth.size();
    bool ok = f && std::fwrite(kReferenceMagic, 8, 1, f) == 1 && std::fwrite(header, sizeof header, 1, f) == 1 &&
              std::fwrite(s.depth.data(), 4, n, f) == n && std::fwrite(s.reference.data(), 4, n, f) == n;
    if (f && std::fclose(f) != 0) ok = false;
    if (!ok) throw VulkanError("cannot write " + path);
}

// Throws std::runtime_error with a one-line reason.
ReferenceFile loadReference(const std::string &path)
{
    std::unique_ptr<FILE, int (*)(FILE *)> f(std::fopen(path.c_str(), "rb"), std::fclose);
    if (!f) throw std::runtime_error(path + ": cannot open the reference file");
    char magic[8];
    uint32_t header[3];
    if (std::fread(magic, 8, 1, f.get()) != 1 || std::memcmp(magic, kReferenceMagic, 8) != 0 ||
        std::fread(header, sizeof header, 1, f.get()) != 1 || header[0] < 1 || header[1] < 1 || header[0] > 8192 ||
        header[1] > 8192 || header[2] < 1)
        throw std::runtime_error(path + ": not a reference file written by --save-reference");
    ReferenceFile r{header[0], header[1], header[2], {}, {}};
    size_t n = size_t(r.width) * r.height;
    r.depth.resize(n), r.visibility.resize(n);
    if (std::fread(r.depth.data(), 4, n, f.get()) != n || std::fread(r.visibility.data(), 4, n, f.get()) != n ||
        std::fgetc(f.get()) != EOF)
        throw std::runtime_error(path + ": truncated or oversized reference file");
    return r;
}

std::vector<uint8_t> toGray8(const std::vector<float> &v)
{
    std::vector<uint8_t> out(v.size());
    for (size_t i = 0; i < v.size(); i++) out[i] = uint8_t(std::clamp(v[i], 0.0f, 1.0f) * 255.0f + 0.5f);
    return out;
}

std::vector<uint8_t> rgbaToRgb(const uint8_t *rgba, size_t pixels)
{
    std::vector<uint8_t> out(pixels * 3);
    for (size_t i = 0; i < pixels; i++)
        for (int c = 0; c < 3; c++) out[3 * i + c] = rgba[4 * i + c];
    return out;
}

void savePng(const std::string &path, uint32_t w, uint32_t h, int channels, const std::vector<uint8_t> &data)
{
    std::string error;
    if (!writePng(path, w, h, channels, data.data(), &error)) throw VulkanError(error);
}

std::string jsonString(const std::string &s)
{
    std::string out = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\') out += '\\', out += c;
        else if (static_cast<unsigned char>(c) < 0x20) out += ' ';
        else out += c;
    }
    return out + "\"";
}

std::string fmt(double v, int decimals = 4)
{
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, std::isfinite(v) ? v : 0.0);
    return buf;
}

// ---- The application ----

class App {
public:
    // `reference`: the reference loaded for --load-reference (outlives the App), or null.
    App(const Options &o, const ReferenceFile *reference) : opt_(o), loadedReference_(reference) {}
    ~App() { cleanup(); }

    int run(const Scene &scene)
    {
        scene_ = {&scene, (scene.boundsMin + scene.boundsMax) * 0.5f,
                  std::max(length(scene.boundsMax - scene.boundsMin) * 0.5f, 1e-3f)};
        orbit0_ = orbit_ = initialOrbit(scene);
        light_.point = opt_.pointLight;
        light_.angle = radians(opt_.lightAngleDeg);
        light_.moving = opt_.lightMotion;
        light_.hitDistance = opt_.hitDistance;
        view_ = opt_.view;
        // Light from the side of the starting view (100 degrees around from the camera), so that the shadows
        // fall where the camera sees them whatever the scene.
        light_.azimuth = orbit_.yaw + radians(100.0f);
        return opt_.headless ? runHeadless() : runWindow();
    }

    unsigned validationMessages() const { return ctx_.validationMessages; }

    void cleanup()
    {
        if (ctx_.device) vkDeviceWaitIdle(ctx_.device);
        renderer_.destroy();
        if (ctx_.device) {
            if (fence_) vkDestroyFence(ctx_.device, fence_, nullptr);
            if (imageAvailable_) vkDestroySemaphore(ctx_.device, imageAvailable_, nullptr);
            swapchain_.destroy(ctx_);
            fence_ = VK_NULL_HANDLE, imageAvailable_ = VK_NULL_HANDLE;
        }
        if (surface_) vkDestroySurfaceKHR(ctx_.instance, surface_, nullptr);
        surface_ = VK_NULL_HANDLE;
        ctx_.destroy();
        if (window_) glfwDestroyWindow(window_);
        window_ = nullptr;
        if (glfwStarted_) glfwTerminate();
        glfwStarted_ = false;
    }

private:
    void createRenderer()
    {
        RendererSettings rs;
        rs.width = opt_.width, rs.height = opt_.height;
        rs.sceneRadius = scene_.radius;
        rs.preset = opt_.preset;
        rs.packedGbuffer = opt_.packedGbuffer;
        rs.rays = opt_.rays;
        rs.checkerboard = opt_.checkerboard;
        rs.lights = opt_.lights;
        renderer_.create(ctx_, *scene_.scene, rs);
        std::printf("viewer: %s on %s, %ux%u, %u triangles, BVH %u nodes (depth %u), push descriptors %s\n",
                    opt_.scene.c_str(), ctx_.properties.deviceName, opt_.width, opt_.height, renderer_.triangles,
                    renderer_.bvhNodes, renderer_.bvhDepth, ctx_.pushDescriptorEnabled ? "on" : "off");
    }

    // ---------------- Headless ----------------

    int runHeadless()
    {
        VulkanContextOptions vo;
        vo.validate = opt_.validate;
        if (const char *d = std::getenv("VIEWER_DEVICE")) vo.deviceSubstring = d;
        ctx_.create(vo);
        createRenderer();

        for (uint32_t f = 0; f < opt_.frames; f++) {
            bool last = f + 1 == opt_.frames;
            Orbit o = orbit_;
            o.yaw += radians(opt_.orbitDegPerFrame) * f;  // a slow orbit: dnsr must reproject its history every frame
            if (light_.moving) light_.azimuth += radians(0.5f);
            FrameInput in = makeFrame(scene_, o, light_, opt_.width, opt_.height);
            in.cameraCut = f == 0;
            in.display = View::Composite;
            // The reference, for the frame that is measured only: many rays per pixel from the same G-buffer
            // (none when it comes from --load-reference).
            in.resetReference = last;
            in.referenceSamples = last && !loadedReference_ ? opt_.referenceSamples : 0;
            VkCommandBuffer cmd = ctx_.beginOneTimeCommands();
            renderer_.recordFrame(cmd, in);
            if (last) renderer_.recordReadback(cmd);
            ctx_.submitAndWait(cmd);
            renderer_.afterFrame();
        }
        writeHeadlessOutputs();
        return 0;
    }

    void writeHeadlessOutputs()
    {
        const uint32_t w = opt_.width, h = opt_.height;
        std::filesystem::create_directories(opt_.outDir);
        // Light 0's images and measurements give the single-light outputs; every light's are in per_light and, for
        // the lights after the first, in *_light<i>.png.
        std::vector<ShadowImages> shadows;
        for (uint32_t l = 0; l < renderer_.lightCount(); l++) shadows.push_back(readShadows(renderer_, l, w, h));
        ShadowImages &s = shadows[0];
        uint32_t referenceSamples = renderer_.referenceCount();
        if (loadedReference_) {  // one light (parseOptions)
            // main() checked the size; the depth shows whether this run's last frame is the reference's.
            size_t differ = 0;
            for (size_t i = 0; i < s.depth.size(); i++)
                differ += std::memcmp(&s.depth[i], &loadedReference_->depth[i], 4) != 0;
            if (differ)
                throw VulkanError(opt_.loadReference + ": the reference was rendered for another view (" +
                                  std::to_string(differ) + " pixels' depth differ: scene, frames, orbit or device)");
            s.reference = loadedReference_->visibility;
            referenceSamples = loadedReference_->samples;
        } else if (!opt_.saveReference.empty()) {
            saveReference(opt_.saveReference, s, referenceSamples);
        }
        std::vector<ErrorStats> errors;
        for (const ShadowImages &light : shadows) errors.push_back(measure(light));
        const ErrorStats &e = errors[0];
        const std::string dir = opt_.outDir + "/";
        for (uint32_t l = 0; l < shadows.size(); l++) {
            std::string suffix = l ? "_light" + std::to_string(l) : "";
            savePng(dir + "noisy" + suffix + ".png", w, h, 1, toGray8(shadows[l].noisy));
            savePng(dir + "denoised" + suffix + ".png", w, h, 1, toGray8(shadows[l].denoised));
            savePng(dir + "reference" + suffix + ".png", w, h, 1, toGray8(shadows[l].reference));
        }
        std::vector<uint8_t> noisy = toGray8(s.noisy), denoised = toGray8(s.denoised), reference = toGray8(s.reference);
        std::vector<uint8_t> composite = rgbaToRgb(renderer_.readDisplay(), size_t(w) * h);
        savePng(dir + "composite.png", w, h, 3, composite);

        // noisy | denoised | reference | composite, with a 2-pixel dark gap between panels.
        const uint32_t gap = 2, stripW = 4 * w + 3 * gap;
        std::vector<uint8_t> strip(size_t(stripW) * h * 3, 32);
        const std::vector<uint8_t> *gray[3] = {&noisy, &denoised, &reference};
        for (uint32_t y = 0; y < h; y++)
            for (uint32_t x = 0; x < w; x++) {
                size_t i = size_t(y) * w + x;
                for (int p = 0; p < 4; p++) {
                    uint8_t *dst = &strip[(size_t(y) * stripW + p * (w + gap) + x) * 3];
                    for (int c = 0; c < 3; c++) dst[c] = p < 3 ? (*gray[p])[i] : composite[3 * i + c];
                }
            }
        savePng(dir + "strip.png", stripW, h, 3, strip);

        // Occluded rays per 8x4 tile, as view 5 of the window shows it: green = all lit, blue = all occluded (the
        // tiles dnsr's classification can skip), orange = mixed (darker = more occluded), sky grey. Out of the rays
        // traced: with --checkerboard, half the tile's pixels.
        const int traced = __builtin_popcount(renderer_.tracedBits());
        std::vector<uint8_t> tiles(size_t(w) * h * 3);
        for (uint32_t y = 0; y < h; y++)
            for (uint32_t x = 0; x < w; x++) {
                size_t i = size_t(y) * w + x;
                uint32_t word = renderer_.readHitMask(0)[(y / 4) * renderer_.tilesX() + x / 8];
                int occluded = __builtin_popcount(word);
                float t = float(occluded) / float(traced);
                float rgb[3] = {1.0f - 0.2f * t, 0.8f - 0.5f * t, 0.3f - 0.2f * t};
                if (occluded == 0) rgb[0] = 0.2f, rgb[1] = 0.7f, rgb[2] = 0.3f;
                if (occluded == traced) rgb[0] = 0.2f, rgb[1] = 0.3f, rgb[2] = 0.8f;
                float shade = s.receiver[i] ? 1.0f : 0.6f;
                if (x % 8 == 0 || y % 4 == 0) shade *= 0.75f;  // tile grid
                for (int c = 0; c < 3; c++) tiles[3 * i + c] = uint8_t(rgb[c] * shade * 255.0f + 0.5f);
            }
        savePng(dir + "tiles.png", w, h, 3, tiles);

        const DnsrPassTimings &t = renderer_.dnsrTimings;
        const ViewerTimings &v = renderer_.viewerTimings;
        std::string filters;
        for (uint32_t p = 0; p < t.filterPasses && p < 4; p++) filters += (p ? ", " : "") + fmt(t.filterMs[p]);
        std::string json = "{\n";
        json += "  \"device\": " + jsonString(ctx_.properties.deviceName) + ",\n";
        json += "  \"dnsr_version\": \"" + std::to_string(DNSR_VERSION_MAJOR) + "." + std::to_string(DNSR_VERSION_MINOR) +
                "." + std::to_string(DNSR_VERSION_PATCH) + "\",\n";
        json += "  \"push_descriptor\": " + std::string(ctx_.pushDescriptorEnabled ? "true" : "false") + ",\n";
        json += "  \"scene\": " + jsonString(opt_.scene) + ",\n";
        json += "  \"triangles\": " + std::to_string(renderer_.triangles) + ",\n";
        json += "  \"bvh_nodes\": " + std::to_string(renderer_.bvhNodes) + ",\n";
        json += "  \"width\": " + std::to_string(w) + ",\n  \"height\": " + std::to_string(h) + ",\n";
        json += "  \"frames\": " + std::to_string(opt_.frames) + ",\n";
        json += "  \"light\": \"" + std::string(light_.point ? "point" : "directional") + "\",\n";
        json += "  \"light_angle_deg\": " + fmt(opt_.lightAngleDeg, 2) + ",\n";
        // Penumbra guidance, and the angular diameter (radians) it passed to dnsr.
        FrameInput last = makeFrame(scene_, orbit_, light_, w, h);
        json += "  \"hit_distance\": " + std::string(light_.hitDistance ? "true" : "false") + ",\n";
        json += "  \"light_angular_size_rad\": " + fmt(last.lightAngularSize, 6) + ",\n";
        const char *presets[] = {"fast", "balanced", "quality"};
        json += std::string("  \"preset\": \"") + presets[opt_.preset] + "\",\n";
        json += std::string("  \"gbuffer\": \"") + (opt_.packedGbuffer ? "packed" : "default") + "\",\n";
        json += "  \"rays_per_pixel\": " + std::to_string(opt_.rays) + ",\n";
        json += "  \"checkerboard\": " + std::string(opt_.checkerboard ? "true" : "false") + ",\n";
        json += "  \"reference_samples\": " + std::to_string(referenceSamples) + ",\n";
        json += "  \"reference_file\": " + (loadedReference_ ? jsonString(opt_.loadReference) : "null") + ",\n";
        json += "  \"pixels_compared\": " + std::to_string(e.pixels) + ",\n";
        json += "  \"rmse\": {\"noisy\": " + fmt(e.rmseNoisy, 6) + ", \"denoised\": " + fmt(e.rmseDenoised, 6) + "},\n";
        json += "  \"psnr_db\": {\"noisy\": " + fmt(psnr(e.rmseNoisy), 3) + ", \"denoised\": " +
                fmt(psnr(e.rmseDenoised), 3) + "},\n";
        json += "  \"crease\": {\"radius_px\": " + std::to_string(kCreaseRadius) + ", \"pixels\": " +
                std::to_string(e.creasePixels) + ", \"max_darkening_255\": " + fmt(e.creaseMax, 3) +
                ", \"mean_darkening_255\": " + fmt(e.creaseMean, 3) + "},\n";
        // Every light (light 0's numbers repeat the ones above): where it is, its mean denoised shadow over the
        // receivers, its error, and fingerprints (FNV-1a of the raw readback) of its hit mask and denoised shadow.
        json += "  \"lights\": " + std::to_string(shadows.size()) + ",\n  \"per_light\": [\n";
        for (uint32_t l = 0; l < shadows.size(); l++) {
            const ShadowImages &sl = shadows[l];
            double mean = 0;
            for (size_t i = 0; i < sl.receiver.size(); i++) mean += sl.receiver[i] ? sl.denoised[i] : 0.0;
            char hashes[128];
            std::snprintf(hashes, sizeof hashes, "\"hit_mask_fnv1a\": \"%016llx\", \"denoised_fnv1a\": \"%016llx\"",
                          static_cast<unsigned long long>(sl.hitMaskHash),
                          static_cast<unsigned long long>(sl.denoisedHash));
            const Vec3 &v = last.lights[l];
            json += "    {\"light\": " + std::to_string(l) + ", \"" + (light_.point ? "position" : "direction") +
                    "\": [" + fmt(v.x, 6) + ", " + fmt(v.y, 6) + ", " + fmt(v.z, 6) + "], \"denoised_mean\": " +
                    fmt(errors[l].pixels ? mean / double(errors[l].pixels) : 0.0, 6) + ", \"rmse\": {\"noisy\": " +
                    fmt(errors[l].rmseNoisy, 6) + ", \"denoised\": " + fmt(errors[l].rmseDenoised, 6) + "}, " +
                    hashes + "}" + (l + 1 < shadows.size() ? "," : "") + "\n";
        }
        json += "  ],\n";
        json += "  \"dnsr_gpu_ms\": {\"frame\": " + std::to_string(renderer_.haveDnsrTimings ? t.frame : 0) +
                ", \"prepare\": " + fmt(t.prepareMs) + ", \"tile_classification\": " + fmt(t.tileClassificationMs) +
                ", \"filter\": [" + filters + "], \"total\": " + fmt(t.totalMs) + "},\n";
        json += "  \"viewer_gpu_ms\": {\"primary\": " + fmt(v.primary) + ", \"shadow\": " + fmt(v.shadow) +
                ", \"reference\": " + fmt(v.reference) + ", \"dnsr\": " + fmt(v.dnsr) + ", \"composite\": " +
                fmt(v.composite) + "},\n";
        json += "  \"dnsr_memory_bytes\": " + std::to_string(renderer_.dnsrMemoryBytes()) + "\n}\n";
        FILE *f = std::fopen((dir + "report.json").c_str(), "w");
        if (!f || std::fputs(json.c_str(), f) < 0 || std::fclose(f) != 0)
            throw VulkanError("cannot write " + dir + "report.json");

        std::printf("viewer: %u frames, penumbra guidance %s; RMSE vs %u-ray reference over %zu pixels: noisy %.4f "
                    "(%.1f dB), denoised %.4f (%.1f dB)\n",
                    opt_.frames, light_.hitDistance ? "on" : "off", referenceSamples, e.pixels, e.rmseNoisy,
                    psnr(e.rmseNoisy), e.rmseDenoised, psnr(e.rmseDenoised));
        std::printf("viewer: lit pixels within %d px of a shadowed one (%zu): darkening vs the reference, worst "
                    "%.2f, mean %.2f (1/255)\n",
                    kCreaseRadius, e.creasePixels, e.creaseMax, e.creaseMean);
        for (uint32_t l = 1; l < shadows.size(); l++)
            std::printf("viewer: light %u: RMSE noisy %.4f (%.1f dB), denoised %.4f (%.1f dB)\n", l,
                        errors[l].rmseNoisy, psnr(errors[l].rmseNoisy), errors[l].rmseDenoised,
                        psnr(errors[l].rmseDenoised));
        std::printf("viewer: dnsr GPU ms (frame %llu): prepare %.3f, tiles %.3f, filter [%s], total %.3f\n",
                    static_cast<unsigned long long>(t.frame), t.prepareMs, t.tileClassificationMs, filters.c_str(),
                    t.totalMs);
        std::printf("viewer: wrote %s{noisy,denoised,reference,composite,strip,tiles}.png%s and report.json\n",
                    dir.c_str(), shadows.size() > 1 ? ", {noisy,denoised,reference}_light1.png" : "");
    }

    // ---------------- Window ----------------

    static App &self(GLFWwindow *w) { return *static_cast<App *>(glfwGetWindowUserPointer(w)); }

    void onKey(int key, int action)
    {
        if (action != GLFW_PRESS) return;
        switch (key) {
        case GLFW_KEY_ESCAPE:
        case GLFW_KEY_Q: glfwSetWindowShouldClose(window_, GLFW_TRUE); break;
        case GLFW_KEY_R:
            orbit_ = orbit0_;
            cameraCut_ = true;  // a jump: dnsr's history no longer matches
            break;
        case GLFW_KEY_1: view_ = View::Noisy; break;
        case GLFW_KEY_2: view_ = View::Denoised; break;
        case GLFW_KEY_3: view_ = View::Reference; break;
        case GLFW_KEY_4: view_ = View::Composite; break;
        case GLFW_KEY_5: view_ = View::TileDensity; break;
        case GLFW_KEY_6: view_ = View::DnsrTiles; break;
        case GLFW_KEY_7: view_ = View::DnsrSampleCount; break;
        case GLFW_KEY_8: view_ = View::DnsrVariance; break;
        case GLFW_KEY_9: view_ = View::DnsrDisocclusion; break;
        case GLFW_KEY_L: light_.moving = !light_.moving; break;
        case GLFW_KEY_H: light_.hitDistance = !light_.hitDistance; break;
        case GLFW_KEY_N: shownLight_ = (shownLight_ + 1) % opt_.lights; break;
        default: break;
        }
    }

    void onCursor(double x, double y)
    {
        if (dragging_) {
            orbit_.yaw -= radians(0.3f) * float(x - lastX_);
            orbit_.pitch = std::clamp(orbit_.pitch + radians(0.3f) * float(y - lastY_), radians(-85.0f), radians(85.0f));
        }
        lastX_ = x, lastY_ = y;
    }

    void createWindow()
    {
        glfwSetErrorCallback([](int, const char *msg) { std::fprintf(stderr, "glfw: %s\n", msg); });
        if (!glfwInit()) throw VulkanError("cannot initialise GLFW (no display? use --headless)");
        glfwStarted_ = true;
        if (!glfwVulkanSupported()) throw VulkanError("GLFW found no Vulkan loader");
        glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
        window_ = glfwCreateWindow(int(opt_.width), int(opt_.height), "dnsr viewer", nullptr, nullptr);
        if (!window_) throw VulkanError("cannot create a window");
        glfwSetWindowUserPointer(window_, this);
        glfwSetKeyCallback(window_, [](GLFWwindow *w, int key, int, int action, int) { self(w).onKey(key, action); });
        glfwSetCursorPosCallback(window_, [](GLFWwindow *w, double x, double y) { self(w).onCursor(x, y); });
        glfwSetMouseButtonCallback(window_, [](GLFWwindow *w, int button, int action, int) {
            if (button == GLFW_MOUSE_BUTTON_LEFT) self(w).dragging_ = action == GLFW_PRESS;
        });
        glfwSetScrollCallback(window_, [](GLFWwindow *w, double, double dy) {
            Orbit &o = self(w).orbit_;
            o.distance = std::clamp(o.distance * std::pow(0.9f, float(dy)), 1e-3f * self(w).scene_.radius,
                                    20.0f * self(w).scene_.radius);
        });
    }

    void recreateSwapchain()
    {
        int fbw = 0, fbh = 0;
        glfwGetFramebufferSize(window_, &fbw, &fbh);
        vkDeviceWaitIdle(ctx_.device);
        swapchain_.create(ctx_, surface_, uint32_t(std::max(fbw, 1)), uint32_t(std::max(fbh, 1)));
    }

    // Scales the display image onto the swapchain image and makes it presentable.
    void recordBlit(VkCommandBuffer cmd, uint32_t imageIndex)
    {
        VkImage target = swapchain_.images[imageIndex];
        auto b = vkStruct<VkImageMemoryBarrier>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER);
        b.srcAccessMask = 0;
        b.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        b.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;  // the previous contents are not needed
        b.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
        b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.image = target;
        b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        // Source stage TRANSFER: the acquire semaphore's wait is at the transfer stage, so this chains after it.
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0,
                             nullptr, 1, &b);
        const GpuImage &src = renderer_.displayImage();
        VkImageBlit region{};
        region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.srcOffsets[1] = {int32_t(src.width), int32_t(src.height), 1};
        region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.dstOffsets[1] = {int32_t(swapchain_.extent.width), int32_t(swapchain_.extent.height), 1};
        vkCmdBlitImage(cmd, src.image, VK_IMAGE_LAYOUT_GENERAL, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region,
                       VK_FILTER_NEAREST);  // nearest: the pixels dnsr produced, not a smoothed version of them
        b.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        b.dstAccessMask = 0;
        b.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
        b.newLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0, 0, nullptr, 0,
                             nullptr, 1, &b);
    }

    void updateTitle(double fps)
    {
        const char *names[] = {"noisy",
                               "denoised",
                               "reference",
                               "composite",
                               "tile density",
                               "dnsr tile classification (1 lit, 0 shadow, 0.5 filtered, 0.75 sky)",
                               "dnsr sample count",
                               "dnsr variance (std dev)",
                               "dnsr disocclusion (history restarted)"};
        char title[512];
        const DnsrPassTimings &t = renderer_.dnsrTimings;
        double filter = 0;
        for (uint32_t p = 0; p < t.filterPasses && p < 4; p++) filter += t.filterMs[p];
        const ViewerTimings &v = renderer_.viewerTimings;
        char view[64];
        std::snprintf(view, sizeof view, view_ == View::Reference ? "%s (%u rays/px)" : "%s", names[uint32_t(view_)],
                      renderer_.referenceCount());
        char shown[32] = "";  // the light the view shows (key N), where there is a choice
        if (opt_.lights > 1 && view_ != View::Composite) std::snprintf(shown, sizeof shown, ", light %u", shownLight_);
        std::snprintf(title, sizeof title,
                      "dnsr viewer | %s%s%s | guidance %s | dnsr GPU ms: prepare %.2f, tiles %.2f, filter %.2f (%u "
                      "passes), total %.2f | rays ms: primary %.2f, shadow %.2f | %.1f fps",
                      view, shown, light_.moving ? " | light moving" : "", light_.hitDistance ? "on" : "off",
                      t.prepareMs, t.tileClassificationMs, filter, t.filterPasses, t.totalMs, v.primary, v.shadow, fps);
        glfwSetWindowTitle(window_, title);
    }

    int runWindow()
    {
        createWindow();
        VulkanContextOptions vo;
        vo.validate = opt_.validate;
        if (const char *d = std::getenv("VIEWER_DEVICE")) vo.deviceSubstring = d;
        uint32_t count = 0;
        const char **glfwExtensions = glfwGetRequiredInstanceExtensions(&count);
        if (!glfwExtensions) throw VulkanError("GLFW cannot create Vulkan surfaces here");
        vo.instanceExtensions.assign(glfwExtensions, glfwExtensions + count);
        vo.deviceExtensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
        vo.canPresent = [](VkInstance instance, VkPhysicalDevice pd, uint32_t family) {
            return glfwGetPhysicalDevicePresentationSupport(instance, pd, family) == GLFW_TRUE;
        };
        ctx_.create(vo);
        VK_CHECK(glfwCreateWindowSurface(ctx_.instance, window_, nullptr, &surface_));
        VkBool32 supported = VK_FALSE;
        VK_CHECK(vkGetPhysicalDeviceSurfaceSupportKHR(ctx_.physicalDevice, ctx_.queueFamily, surface_, &supported));
        if (!supported) throw VulkanError("the chosen queue family cannot present to this window");
        recreateSwapchain();
        createRenderer();

        auto semInfo = vkStruct<VkSemaphoreCreateInfo>(VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO);
        VK_CHECK(vkCreateSemaphore(ctx_.device, &semInfo, nullptr, &imageAvailable_));
        auto fenceInfo = vkStruct<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
        VK_CHECK(vkCreateFence(ctx_.device, &fenceInfo, nullptr, &fence_));
        auto alloc = vkStruct<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
        alloc.commandPool = ctx_.commandPool;
        alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        alloc.commandBufferCount = 1;
        VkCommandBuffer cmd;
        VK_CHECK(vkAllocateCommandBuffers(ctx_.device, &alloc, &cmd));

        using Clock = std::chrono::steady_clock;
        auto lastTitle = Clock::now(), lastFrame = Clock::now();
        uint32_t framesSinceTitle = 0, frame = 0;
        Orbit lastOrbit = orbit_;
        float lastAzimuth = light_.azimuth;
        cameraCut_ = true;
        while (!glfwWindowShouldClose(window_)) {
            glfwPollEvents();
            int fbw = 0, fbh = 0;
            glfwGetFramebufferSize(window_, &fbw, &fbh);
            if (fbw == 0 || fbh == 0) {  // minimised: nothing to present to
                glfwWaitEvents();
                continue;
            }
            auto now = Clock::now();
            float dt = std::chrono::duration<float>(now - lastFrame).count();
            lastFrame = now;
            if (light_.moving) light_.azimuth += radians(20.0f) * std::min(dt, 0.1f);

            uint32_t imageIndex = 0;
            VkResult acquired = vkAcquireNextImageKHR(ctx_.device, swapchain_.swapchain, UINT64_MAX, imageAvailable_,
                                                      VK_NULL_HANDLE, &imageIndex);
            if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {
                recreateSwapchain();
                continue;
            }
            if (acquired != VK_SUBOPTIMAL_KHR) VK_CHECK(acquired);

            FrameInput in = makeFrame(scene_, orbit_, light_, opt_.width, opt_.height);
            in.cameraCut = cameraCut_;
            in.display = view_;
            in.shownLight = shownLight_;
            // The reference accumulates while nothing moves (view 3 shows it converging); any change restarts it.
            bool changed = std::memcmp(&lastOrbit, &orbit_, sizeof orbit_) != 0 || lastAzimuth != light_.azimuth;
            in.resetReference = changed || cameraCut_;
            uint32_t have = in.resetReference ? 0 : renderer_.referenceCount();
            if (view_ == View::Reference && have < opt_.referenceSamples)
                in.referenceSamples = std::min(8u, opt_.referenceSamples - have);
            lastOrbit = orbit_;
            lastAzimuth = light_.azimuth;
            cameraCut_ = false;

            VK_CHECK(vkResetCommandBuffer(cmd, 0));
            auto begin = vkStruct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
            begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
            VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
            renderer_.recordFrame(cmd, in);
            recordBlit(cmd, imageIndex);
            VK_CHECK(vkEndCommandBuffer(cmd));

            VkPipelineStageFlags waitStage = VK_PIPELINE_STAGE_TRANSFER_BIT;
            auto submit = vkStruct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
            submit.waitSemaphoreCount = 1;
            submit.pWaitSemaphores = &imageAvailable_;
            submit.pWaitDstStageMask = &waitStage;
            submit.commandBufferCount = 1;
            submit.pCommandBuffers = &cmd;
            submit.signalSemaphoreCount = 1;
            submit.pSignalSemaphores = &swapchain_.renderFinished[imageIndex];
            VK_CHECK(vkQueueSubmit(ctx_.queue, 1, &submit, fence_));

            auto present = vkStruct<VkPresentInfoKHR>(VK_STRUCTURE_TYPE_PRESENT_INFO_KHR);
            present.waitSemaphoreCount = 1;
            present.pWaitSemaphores = &swapchain_.renderFinished[imageIndex];
            present.swapchainCount = 1;
            present.pSwapchains = &swapchain_.swapchain;
            present.pImageIndices = &imageIndex;
            VkResult presented = vkQueuePresentKHR(ctx_.queue, &present);

            // One frame in flight: wait for this one before recording the next (and before reading timings).
            VK_CHECK(vkWaitForFences(ctx_.device, 1, &fence_, VK_TRUE, UINT64_MAX));
            VK_CHECK(vkResetFences(ctx_.device, 1, &fence_));
            renderer_.afterFrame();
            if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR) recreateSwapchain();
            else VK_CHECK(presented);

            frame++;
            framesSinceTitle++;
            double since = std::chrono::duration<double>(Clock::now() - lastTitle).count();
            if (since >= 1.0) {
                updateTitle(framesSinceTitle / since);
                lastTitle = Clock::now();
                framesSinceTitle = 0;
            }
            if (opt_.frames && frame >= opt_.frames) {
                if (!opt_.screenshot.empty()) saveScreenshot();
                break;
            }
        }
        vkDeviceWaitIdle(ctx_.device);
        vkFreeCommandBuffers(ctx_.device, ctx_.commandPool, 1, &cmd);
        return 0;
    }

    // Saves the image that was just blit to the window (the display image, at render size).
    void saveScreenshot()
    {
        VkCommandBuffer cmd = ctx_.beginOneTimeCommands();
        renderer_.recordReadback(cmd);
        ctx_.submitAndWait(cmd);
        savePng(opt_.screenshot, opt_.width, opt_.height, 3,
                rgbaToRgb(renderer_.readDisplay(), size_t(opt_.width) * opt_.height));
        std::printf("viewer: wrote %s after %u frames\n", opt_.screenshot.c_str(), opt_.frames);
    }

    Options opt_;
    const ReferenceFile *loadedReference_ = nullptr;
    SceneFrame scene_;
    Orbit orbit_, orbit0_;
    LightState light_;
    View view_ = View::Composite;
    uint32_t shownLight_ = 0;  // window mode: the light the views other than the composite show (key N)
    bool cameraCut_ = true;
    VulkanContext ctx_;
    Renderer renderer_;

    GLFWwindow *window_ = nullptr;
    bool glfwStarted_ = false;
    VkSurfaceKHR surface_ = VK_NULL_HANDLE;
    Swapchain swapchain_;
    VkSemaphore imageAvailable_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
    bool dragging_ = false;
    double lastX_ = 0, lastY_ = 0;
};

}  // namespace

int main(int argc, char **argv)
{
    Options options;
    try {
        options = parseOptions(argc, argv);
    } catch (const UsageError &e) {
        std::fprintf(stderr, "viewer: %s (see --help)\n", e.what());
        return 2;
    }

    Scene scene;
    try {
        scene = loadGltfScene(options.scene);
    } catch (const SceneError &e) {
        std::fprintf(stderr, "viewer: %s\n", e.what());
        return 2;
    } catch (const std::exception &e) {  // e.g. std::bad_alloc for absurd sizes in a malformed file
        std::fprintf(stderr, "viewer: %s: cannot load: %s\n", options.scene.c_str(), e.what());
        return 2;
    }

    ReferenceFile reference;
    if (!options.loadReference.empty()) {
        try {
            reference = loadReference(options.loadReference);
        } catch (const std::exception &e) {
            std::fprintf(stderr, "viewer: %s\n", e.what());
            return 2;
        }
        if (reference.width != options.width || reference.height != options.height) {
            std::fprintf(stderr, "viewer: %s: the reference is %ux%u, this run %ux%u\n",
                         options.loadReference.c_str(), reference.width, reference.height, options.width, options.height);
            return 2;
        }
    }

    int status = 1;
    unsigned validationMessages = 0;
    {
        App app(options, options.loadReference.empty() ? nullptr : &reference);
        try {
            status = app.run(scene);
        } catch (const std::exception &e) {
            std::fprintf(stderr, "viewer: %s\n", e.what());
            status = 1;
        }
        app.cleanup();  // before counting: destroying objects can itself produce validation messages
        validationMessages = app.validationMessages();
    }
    if (validationMessages) {
        std::fprintf(stderr, "viewer: %u validation message(s)\n", validationMessages);
        return 1;
    }
    return status;
}
