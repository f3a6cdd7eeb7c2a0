// options.cpp: see options.h.
#include "options.h"

#include "denoiser.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace {

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
    "  --light-elevation DEG   light 0's elevation above the horizon, 1..90 (default 50)\n"
    "  --light-azimuth DEG     light 0's direction around the up axis from the starting view's, -360..360\n"
    "                          (default 100: shadows fall where the camera sees them)\n"
    "  --light-motion          start with the light moving (key L toggles it)\n"
    "  --lights N              1 or 2 lights (default 1). The second (light 1) is the first (light 0) turned 100\n"
    "                          degrees about the up axis: same elevation, size and kind (a point light the same\n"
    "                          distance from the scene's centre). Each has its own shadow rays, dnsr history and\n"
    "                          output; both are denoised in one dnsr_lights_record call and light the composite.\n"
    "                          Headless: also {noisy,denoised,reference}_light1.png and report.json's per_light\n"
    "  --normal-detail A       bumps on every surface's shading normal, as a normal map gives: tilted by up to\n"
    "                          A x 60 degrees, in a pattern whose period is 4% of the scene's radius (default 0). The\n"
    "                          shadow rays' facing test uses them too, as engines' do; dnsr sees them in its normals\n"
    "  --normal-detail-for all|dnsr  dnsr: the bumps go to dnsr's normals alone (--gbuffer packed: its RG16 normals),\n"
    "                          the shadows and the reference keep the smooth ones (default: all)\n"
    "  --gbuffer default|packed  packed: keep linear depth and octahedral RG16 normals, and run dnsr's passes\n"
    "                          compiled against examples-c/custom_gbuffer's callbacks (default: default)\n"
    "  --rays N                shadow rays per pixel, 1..64 (default 1: the hit mask; more: their lit fraction as\n"
    "                          per-pixel visibility, DNSR_SHADOW_INPUT_VISIBILITY)\n"
    "  --checkerboard          half a ray per pixel: each frame traces only the pixels with (x + y) % 2 == frame % 2\n"
    "                          (DNSR_SHADOW_INPUT_CHECKERBOARD); dnsr gives the others their traced neighbours' mean,\n"
    "                          and so does the noisy view. Takes --rays 1 and --gbuffer default\n"
    "  --hit-distance on|off   penumbra guidance: give dnsr each shadow ray's distance to its nearest occluder and\n"
    "                          the light's angular diameter (DNSR_DISPATCH_USE_HIT_DISTANCE; default on; key H)\n"
    "  --hard-light on|off     tell dnsr when the light has no size (--light-angle 0): DNSR_DISPATCH_HARD_LIGHT, its\n"
    "                          rays are exact and are the output (default on; off: dnsr filters them as any light)\n"
    "  --light-position on|off tell dnsr where the light is (DNSR_DISPATCH_USE_LIGHT_POSITION): receivers turned away\n"
    "                          from it keep their shadowed rays (default on; off: as the FidelityFX layer, whose\n"
    "                          dispatch has no light)\n"
    "  --reference-samples N   shadow rays per pixel of the reference, 1..65536 (default 256)\n"
    "  --save-reference FILE   headless: also write the last frame's reference (and depth) to FILE (--lights 1)\n"
    "  --load-reference FILE   headless: measure against FILE's reference instead of rendering one (same scene,\n"
    "                          size, frames, light and camera: the run fails if the last frame's depth differs;\n"
    "                          --lights 1)\n"
    "  --view NAME             window mode: first view (noisy, denoised, reference, composite, tiles, or dnsr's\n"
    "                          debug views classification, samples, variance, disocclusion, run; keys 1-9, U)\n"
    "  --orbit-speed DEG       headless: camera orbit per frame in degrees, -45..45 (default 0.25; 0 = static)\n"
    "  --pan F                 headless: the camera moves sideways by F x its distance per frame, -0.1..0.1\n"
    "                          (default 0)\n"
    "  --hybrid                hybrid shadows: cascaded shadow maps decide what they can, dnsr's classifier lists\n"
    "                          the 8x4 tiles whose other pixels need a ray, and only those are traced (one\n"
    "                          directional light, --rays 1, --gbuffer default; key C). With penumbra guidance\n"
    "                          only the traced pixels have a hit distance (dnsr averages the known ones)\n"
    "  --cascades N            hybrid: shadow-map cascades, 1..4 (default 2)\n"
    "  --cascade-size N        hybrid: texels per cascade side, 64..8192 (default: the render size's larger side\n"
    "                          rounded up to a power of two)\n"
    "  --taps N                hybrid: the classifier's blocker-search taps, 8, 16, 24 or 32 (default 24)\n"
    "  --tile-cutoff N         hybrid: a tile is traced only with more than N pixels to trace, 0..31 (default 0);\n"
    "                          the others keep the verdict most of their taps give\n"
    "  --blocker-offset F      hybrid: how far (in scene radii, 0..1) a cascade depth must be in front of a\n"
    "                          receiver's tangent plane to block it (default: two texels of the finest cascade)\n"
    "  --reverse-rays          hybrid: trace from the light's end of the classifier's interval towards the surface\n"
    "                          (with --hit-distance off: guidance needs the occluder nearest the surface)\n"
    "  --debug-view NAME       headless: the last frame's dnsr output is its debug view NAME (classification,\n"
    "                          samples, variance, disocclusion or run: each pixel's run of identical samples;\n"
    "                          the window's keys 6-9 and U) instead of the shadow:\n"
    "                          denoised.png and every denoised figure of report.json (which names the view) then\n"
    "                          show the view. A run without it is the same up to that frame\n"
    "  --preset NAME           dnsr's settings: fast, balanced (the FidelityFX values) or quality (default)\n"
    "  --set NAME=VALUE[,...]  change single dnsr settings after the preset filled them, by their DnsrSettings\n"
    "                          field names (include/dnsr.h), e.g. --set hardTileFrames=4,filterPasses=1; dnsr\n"
    "                          checks the values (dnsr_context_set_settings); report.json lists them\n"
    "  --validate              enable VK_LAYER_KHRONOS_validation; any validation message makes the exit status 1\n"
    "                          (the Vulkan loader's own notices are shown but not counted)\n"
    "  -h, --help              print this and exit\n"
    "environment: VIEWER_DEVICE=<substring of the device name> picks a Vulkan device (default: the first)\n"
    "window keys: left-drag orbit, scroll zoom, R reset view (a camera cut: dnsr's history restarts),\n"
    "             1 noisy, 2 denoised, 3 reference (accumulates while nothing moves), 4 composite,\n"
    "             5 hit-mask density per tile, 6 dnsr tile classification, 7 dnsr sample count,\n"
    "             8 dnsr variance, 9 dnsr disocclusion, U dnsr run of identical samples, L toggle light\n"
    "             motion, H toggle penumbra guidance (hit distances), N the other light in views 1-3, 5-9\n"
    "             and U (--lights 2), C toggle hybrid mode,\n"
    "             0 hybrid: what decided each pixel, T hybrid: pixels traced per tile, Esc/Q quit\n"
    "exit status: 0 success, 1 a Vulkan/dnsr failure or (with --validate) a validation message,\n"
    "             2 a bad command line, or a scene or reference file the viewer cannot load\n";

uint32_t parseCount(const char *flag, const char *value, uint32_t min, uint32_t max)
{
    char *end = nullptr;
    long v = std::strtol(value, &end, 10);
    if (!*value || *end || v < long(min) || v > long(max))
        throw UsageError(std::string(flag) + " wants a number in " + std::to_string(min) + ".." + std::to_string(max) +
                         ", got '" + value + "'");
    return static_cast<uint32_t>(v);
}

float parseNumber(const char *flag, const char *value, float min, float max)
{
    char *end = nullptr;
    float v = std::strtof(value, &end);
    if (!*value || *end || !(v >= min && v <= max))
        throw UsageError(std::string(flag) + " wants a number in " + std::to_string(min) + ".." + std::to_string(max) +
                         ", got '" + value + "'");
    return v;
}

}  // namespace

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
        } else if (a == "--light-elevation") {
            o.lightElevationDeg = parseNumber("--light-elevation", value(), 1.0f, 90.0f);
        } else if (a == "--light-azimuth") {
            o.lightAzimuthDeg = parseNumber("--light-azimuth", value(), -360.0f, 360.0f);
        } else if (a == "--pan") {
            o.panPerFrame = parseNumber("--pan", value(), -0.1f, 0.1f);
        } else if (a == "--orbit-speed") {
            const char *v = value();
            char *end = nullptr;
            o.orbitDegPerFrame = std::strtof(v, &end);
            if (!*v || *end || !(std::fabs(o.orbitDegPerFrame) <= 45.0f))
                throw UsageError(std::string("--orbit-speed wants degrees in -45..45, got '") + v + "'");
        } else if (a == "--view") {
            std::string v = value();
            const char *names[] = {"noisy",   "denoised",     "reference", "composite", "tiles", "classification",
                                   "samples", "variance",     "disocclusion", "hybrid", "traced", "run"};
            auto it = std::find(std::begin(names), std::end(names), v);
            if (it == std::end(names))
                throw UsageError("--view wants noisy, denoised, reference, composite, tiles, classification, samples, "
                                 "variance, disocclusion, hybrid, traced or run, got '" + v + "'");
            o.view = static_cast<View>(it - std::begin(names));
        } else if (a == "--preset") {
            std::string v = value();
            const char *names[] = {"fast", "balanced", "quality"};  // DNSR_PRESET_FAST, _BALANCED, _QUALITY
            auto it = std::find(std::begin(names), std::end(names), v);
            if (it == std::end(names)) throw UsageError("--preset wants fast, balanced or quality, got '" + v + "'");
            o.preset = static_cast<DnsrPreset>(it - std::begin(names));
        } else if (a == "--debug-view") {
            std::string v = value();
            auto it = std::find_if(std::begin(kDnsrViews), std::end(kDnsrViews),
                                   [&](const DnsrViewName &d) { return v == d.name; });
            if (it == std::end(kDnsrViews))
                throw UsageError("--debug-view wants classification, samples, variance, disocclusion or run, got '" + v +
                                 "'");
            o.debugView = it->view;
        } else if (a == "--set") {
            std::string list = value();
            for (size_t at = 0; at <= list.size();) {
                size_t end = std::min(list.find(',', at), list.size());
                std::string item = list.substr(at, end - at);
                size_t eq = item.find('=');
                std::string name = item.substr(0, eq);
                if (eq == std::string::npos || !isDenoiserSetting(name))
                    throw UsageError("--set wants NAME=VALUE with NAME one of " + denoiserSettingNames() + ", got '" +
                                     item + "'");
                const char *number = item.c_str() + eq + 1;
                char *rest = nullptr;
                double v = std::strtod(number, &rest);
                if (!*number || *rest || !std::isfinite(v))
                    throw UsageError("--set " + name + " wants a finite number, got '" + number + "'");
                if (name == "filterPasses" && !(v >= 0.0 && v == std::floor(v)))
                    throw UsageError("--set filterPasses wants a whole number of passes, got '" + std::string(number) + "'");
                o.settings.emplace_back(name, v);
                at = end + 1;
            }
        } else if (a == "--normal-detail") {
            o.normalDetail = parseNumber("--normal-detail", value(), 0.0f, 1.0f);
        } else if (a == "--normal-detail-for") {
            const std::string v = value();
            if (v != "all" && v != "dnsr") throw UsageError("--normal-detail-for wants all or dnsr, got '" + v + "'");
            o.normalDetailDnsrOnly = v == "dnsr";
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
        } else if (a == "--hard-light") {
            std::string v = value();
            if (v != "on" && v != "off") throw UsageError("--hard-light wants on or off, got '" + v + "'");
            o.hardLight = v == "on";
        } else if (a == "--light-position") {
            std::string v = value();
            if (v != "on" && v != "off") throw UsageError("--light-position wants on or off, got '" + v + "'");
            o.lightPosition = v == "on";
        } else if (a == "--hybrid") {
            o.hybrid = true;
        } else if (a == "--cascades") {
            o.cascades = parseCount("--cascades", value(), 1, 4);
        } else if (a == "--cascade-size") {
            o.cascadeSize = parseCount("--cascade-size", value(), 64, 8192);
        } else if (a == "--taps") {
            const char *v = value();
            o.taps = parseCount("--taps", v, 8, 32);
            if (o.taps % 8) throw UsageError(std::string("--taps wants 8, 16, 24 or 32, got '") + v + "'");
        } else if (a == "--tile-cutoff") {
            o.tileCutoff = parseCount("--tile-cutoff", value(), 0, 31);
        } else if (a == "--blocker-offset") {
            const char *v = value();
            char *end = nullptr;
            o.blockerOffset = std::strtof(v, &end);
            if (!*v || *end || !(o.blockerOffset >= 0.0f && o.blockerOffset <= 1.0f))
                throw UsageError(std::string("--blocker-offset wants scene radii in 0..1, got '") + v + "'");
        } else if (a == "--reverse-rays") {
            o.reverseRays = true;
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
    if (o.normalDetailDnsrOnly && !o.packedGbuffer) throw UsageError("--normal-detail-for dnsr takes --gbuffer packed");
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
    if (!o.headless && o.debugView != View::Composite)
        throw UsageError("--debug-view is for --headless (the window shows the debug views on keys 6-9 and U, or --view)");
    if (!o.headless && !(o.saveReference.empty() && o.loadReference.empty()))
        throw UsageError("--save-reference and --load-reference are for --headless");
    if (!o.saveReference.empty() && !o.loadReference.empty())
        throw UsageError("--save-reference and --load-reference exclude each other");
    // A reference file holds one light's reference (its format predates --lights).
    if (o.lights > 1 && !(o.saveReference.empty() && o.loadReference.empty()))
        throw UsageError("--save-reference and --load-reference take one light (--lights 1)");
    if (o.hybrid) {
        std::string why = hybridUnsupported(o);
        if (!why.empty()) throw UsageError("--hybrid " + why);
    }
    return o;
}

std::string hybridUnsupported(const Options &o)
{
    if (o.pointLight) return "takes the directional light (dnsr's classifier reads a sun's cascaded shadow maps)";
    if (o.lights > 1) return "takes one light (--lights 1): the viewer traces cascades for one sun";
    if (o.rays > 1 || o.checkerboard)
        return "takes one ray per pixel (--rays 1, no --checkerboard): the classifier prefills a full hit mask";
    return "";
}
