// report.cpp: see report.h.
#include "report.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>

namespace {

// ordered_json: the fields stay in the order written here, the order the report has always had.
using Json = nlohmann::ordered_json;

// A measurement as the report has always given it: rounded to `decimals` (the precision it carries), 0 if not
// finite (JSON has no NaN).
double rounded(double v, int decimals)
{
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, std::isfinite(v) ? v : 0.0);
    return std::strtod(buf, nullptr);
}

std::string hex16(uint64_t v)
{
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
    return buf;
}

Json rmse(const ErrorStats &e)
{
    return {{"noisy", rounded(e.rmseNoisy, 6)}, {"denoised", rounded(e.rmseDenoised, 6)}};
}

}  // namespace

void writeReport(const std::string &path, const Session &session, const Measurements &m)
{
    const Options &opt = session.opt;
    const Renderer &renderer = session.renderer;
    const ErrorStats &e = m.errors[0];
    Json r;
    r["device"] = session.ctx.properties.deviceName;
    r["dnsr_version"] = std::to_string(DNSR_VERSION_MAJOR) + "." + std::to_string(DNSR_VERSION_MINOR) + "." +
                        std::to_string(DNSR_VERSION_PATCH);
    r["push_descriptor"] = session.ctx.pushDescriptorEnabled;
    r["scene"] = opt.scene;
    r["triangles"] = renderer.triangles;
    r["bvh_nodes"] = renderer.bvhNodes;
    r["width"] = opt.width;
    r["height"] = opt.height;
    r["frames"] = opt.frames;
    r["light"] = session.light.point ? "point" : "directional";
    r["light_angle_deg"] = rounded(opt.lightAngleDeg, 2);
    // Penumbra guidance, and the angular diameter (radians) it passed to dnsr.
    FrameInput last = makeFrame(session.scene, session.orbit, session.light, opt.width, opt.height);
    r["hit_distance"] = session.light.hitDistance;
    r["light_angular_size_rad"] = rounded(last.lightAngularSize, 6);
    r["hard_light"] = last.hardLight;
    r["light_position"] = last.lightPosition;
    const char *presets[] = {"fast", "balanced", "quality"};
    r["preset"] = presets[opt.preset];
    // --debug-view: the last frame's dnsr output, and every "denoised" figure below, is this view, not the shadow.
    DnsrDebugView debug = dnsrDebugView(opt.debugView);
    r["debug_view"] = debug != DNSR_DEBUG_VIEW_NONE ? Json(kDnsrViews[debug - DNSR_DEBUG_VIEW_TILE_CLASSIFICATION].name)
                                                   : Json(nullptr);
    if (!opt.settings.empty()) {
        auto &set = r["settings"];
        for (const auto &[name, value] : opt.settings) set[name] = value;
    }
    r["gbuffer"] = opt.packedGbuffer ? "packed" : "default";
    r["rays_per_pixel"] = opt.rays;
    r["checkerboard"] = opt.checkerboard;
    // Hybrid shadows: its settings, and how many of the receivers' shadow rays were traced in the last frame (all
    // of them without it).
    const Renderer &rr = session.renderer;
    r["hybrid"] = !session.hybrid ? Json(nullptr)
                                  : Json{{"cascades", opt.cascades},
                                         {"cascade_size", rr.cascadeSize()},
                                         {"taps", opt.taps},
                                         {"tile_cutoff", opt.tileCutoff},
                                         {"blocker_offset_scene_radii",
                                          opt.blockerOffset < 0 ? Json("2 texels") : Json(rounded(opt.blockerOffset, 6))},
                                         {"reverse_rays", opt.reverseRays}};
    const TracedStats &ts = m.traced;
    r["traced"] = {{"receivers", ts.receivers},
                   {"rays", ts.traced},
                   {"fraction", rounded(ts.receivers ? double(ts.traced) / double(ts.receivers) : 0.0, 6)},
                   {"rays_saved", ts.receivers - ts.traced},
                   {"tiles", ts.tiles},
                   {"tiles_traced", ts.listedTiles},
                   {"decided_wrong", ts.decidedWrong},
                   {"decided_mean_abs_error", rounded(ts.decidedMeanError, 6)}};
    r["reference_samples"] = m.referenceSamples;
    r["reference_file"] = m.referenceLoaded ? Json(opt.loadReference) : Json(nullptr);
    r["pixels_compared"] = e.pixels;
    r["rmse"] = rmse(e);
    r["psnr_db"] = {{"noisy", rounded(psnr(e.rmseNoisy), 3)}, {"denoised", rounded(psnr(e.rmseDenoised), 3)}};
    r["crease"] = {{"radius_px", kCreaseRadius},
                   {"pixels", e.creasePixels},
                   {"max_darkening_255", rounded(e.creaseMax, 3)},
                   {"mean_darkening_255", rounded(e.creaseMean, 3)}};
    // "Do no harm": absolute errors in 1/255 units over the pixel classes of metrics.h.
    auto classError = [](const ClassError &c) {
        return Json{{"pixels", c.pixels}, {"mean_255", rounded(c.mean, 3)}, {"p99_255", rounded(c.p99, 3)},
                    {"max_255", rounded(c.max, 3)}, {"over_1_255", c.over1}};
    };
    r["exact"] = classError(e.exact);
    r["silhouette"] = classError(e.silhouette);
    r["crease_abs"] = classError(e.crease);
    r["thin"] = {{"pixels", e.thinPixels}, {"contrast_kept", rounded(e.thinContrastKept, 4)}};
    // Every light (light 0's numbers repeat the ones above): where it is, its mean denoised shadow over the
    // receivers, its error, and fingerprints (FNV-1a of the raw readback) of its hit mask and denoised shadow.
    r["lights"] = m.shadows.size();
    Json perLight = Json::array();
    for (uint32_t l = 0; l < m.shadows.size(); l++) {
        const ShadowImages &s = m.shadows[l];
        double mean = 0;
        for (size_t i = 0; i < s.receiver.size(); i++) mean += s.receiver[i] ? s.denoised[i] : 0.0;
        const Vec3 &v = last.lights[l];
        Json light;
        light["light"] = l;
        light[session.light.point ? "position" : "direction"] = {rounded(v.x, 6), rounded(v.y, 6), rounded(v.z, 6)};
        light["denoised_mean"] = rounded(m.errors[l].pixels ? mean / double(m.errors[l].pixels) : 0.0, 6);
        light["rmse"] = rmse(m.errors[l]);
        light["hit_mask_fnv1a"] = hex16(s.hitMaskHash);
        light["denoised_fnv1a"] = hex16(s.denoisedHash);
        perLight.push_back(light);
    }
    r["per_light"] = perLight;
    const DnsrPassTimings &t = renderer.dnsrTimings;
    Json filters = Json::array();
    for (uint32_t p = 0; p < t.filterPasses && p < 4; p++) filters.push_back(rounded(t.filterMs[p], 4));
    r["dnsr_gpu_ms"] = {{"frame", renderer.haveDnsrTimings ? t.frame : 0},
                        {"prepare", rounded(t.prepareMs, 4)},
                        {"tile_classification", rounded(t.tileClassificationMs, 4)},
                        {"filter", filters},
                        {"total", rounded(t.totalMs, 4)},
                        {"classify", rounded(renderer.dnsrClassifyMs, 4)}};
    const ViewerTimings &v = renderer.viewerTimings;
    r["viewer_gpu_ms"] = {{"primary", rounded(v.primary, 4)},   {"cascades", rounded(v.cascades, 4)},
                          {"classify", rounded(v.classify, 4)}, {"shadow", rounded(v.shadow, 4)},
                          {"reference", rounded(v.reference, 4)}, {"dnsr", rounded(v.dnsr, 4)},
                          {"composite", rounded(v.composite, 4)}};
    const ViewerTimings &med = m.medianTimings;
    r["viewer_gpu_ms_median"] = {{"frames", m.medianFrames},
                                 {"primary", rounded(med.primary, 4)},
                                 {"cascades", rounded(med.cascades, 4)},
                                 {"classify", rounded(med.classify, 4)},
                                 {"shadow", rounded(med.shadow, 4)},
                                 {"dnsr", rounded(med.dnsr, 4)},
                                 {"composite", rounded(med.composite, 4)}};
    r["dnsr_memory_bytes"] = renderer.dnsrMemoryBytes();

    // A scene path need not be UTF-8: replace what is not, instead of failing the run.
    std::ofstream f(path);
    f << r.dump(2, ' ', false, Json::error_handler_t::replace) << '\n';
    f.close();
    if (!f) throw VulkanError("cannot write " + path);
}
