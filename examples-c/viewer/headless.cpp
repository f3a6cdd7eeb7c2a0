// headless.cpp: see headless.h.
#include "headless.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "png_output.h"
#include "report.h"
#include "session.h"

namespace {

// The measurements of the last frame, each light against its reference: the one just rendered, or the loaded one.
Measurements measureLastFrame(Session &s, const ReferenceFile *loaded)
{
    const Options &opt = s.opt;
    Measurements m;
    for (uint32_t l = 0; l < s.renderer.lightCount(); l++)
        m.shadows.push_back(readShadows(s.renderer, l, opt.width, opt.height));
    ShadowImages &light0 = m.shadows[0];
    m.referenceSamples = s.renderer.referenceCount();
    if (loaded) {  // one light (parseOptions)
        // The depth shows whether this run's last frame is the one the reference was rendered for.
        size_t differ = 0;
        for (size_t i = 0; i < light0.depth.size(); i++)
            differ += std::memcmp(&light0.depth[i], &loaded->depth[i], 4) != 0;
        if (differ)
            throw VulkanError(opt.loadReference + ": the reference was rendered for another view (" +
                              std::to_string(differ) + " pixels' depth differ: scene, frames, orbit or device)");
        light0.reference = loaded->visibility;
        m.referenceSamples = loaded->samples;
        m.referenceLoaded = true;
    } else if (!opt.saveReference.empty()) {
        saveReference(opt.saveReference, light0, m.referenceSamples);
    }
    for (const ShadowImages &light : m.shadows) m.errors.push_back(measure(light));
    m.traced = tracedStats(s.renderer, light0);
    return m;
}

// Occluded rays per 8x4 tile, as view 5 of the window shows it: green = all lit, blue = all occluded (the tiles
// dnsr's classification can skip), orange = mixed (darker = more occluded), sky grey. Out of the rays traced: with
// --checkerboard, half the tile's pixels.
std::vector<uint8_t> tileImage(const Renderer &renderer, const ShadowImages &s)
{
    const uint32_t w = s.width, h = s.height;
    const int traced = __builtin_popcount(renderer.tracedBits());
    std::vector<uint8_t> tiles(size_t(w) * h * 3);
    for (uint32_t y = 0; y < h; y++)
        for (uint32_t x = 0; x < w; x++) {
            size_t i = size_t(y) * w + x;
            uint32_t word = renderer.readHitMask(0)[(y / 4) * renderer.tilesX() + x / 8];
            int occluded = __builtin_popcount(word);
            float t = float(occluded) / float(traced);
            float rgb[3] = {1.0f - 0.2f * t, 0.8f - 0.5f * t, 0.3f - 0.2f * t};
            if (occluded == 0) rgb[0] = 0.2f, rgb[1] = 0.7f, rgb[2] = 0.3f;
            if (occluded == traced) rgb[0] = 0.2f, rgb[1] = 0.3f, rgb[2] = 0.8f;
            float shade = s.receiver[i] ? 1.0f : 0.6f;
            if (x % 8 == 0 || y % 4 == 0) shade *= 0.75f;  // tile grid
            for (int c = 0; c < 3; c++) tiles[3 * i + c] = uint8_t(rgb[c] * shade * 255.0f + 0.5f);
        }
    return tiles;
}

// Hybrid mode, what decided each pixel, as view 0 of the window shows it: pale = lit and dark blue = shadowed by the
// cascades, orange = lit and dark red = occluded by a ray; sky grey; the traced tiles' grid drawn.
std::vector<uint8_t> hybridImage(const Renderer &renderer, const ShadowImages &s)
{
    const uint32_t w = s.width, h = s.height;
    std::vector<uint8_t> out(size_t(w) * h * 3);
    for (uint32_t y = 0; y < h; y++)
        for (uint32_t x = 0; x < w; x++) {
            size_t i = size_t(y) * w + x, tile = (y / 4) * renderer.tilesX() + x / 8;
            uint32_t bit = 1u << ((y % 4) * 8 + x % 8), traced = renderer.readTraced()[tile];
            bool ray = traced & bit, lit = !(renderer.readHitMask(0)[tile] & bit);
            float rgb[3] = {0.5f, 0.5f, 0.5f};
            auto set = [&](float r, float g, float b) { rgb[0] = r, rgb[1] = g, rgb[2] = b; };
            if (s.receiver[i]) {
                if (ray) lit ? set(1.0f, 0.6f, 0.15f) : set(0.55f, 0.1f, 0.08f);
                else lit ? set(0.85f, 0.85f, 0.8f) : set(0.15f, 0.2f, 0.45f);
            }
            float shade = traced && (x % 8 == 0 || y % 4 == 0) ? 0.7f : 1.0f;
            for (int c = 0; c < 3; c++) out[3 * i + c] = uint8_t(rgb[c] * shade * 255.0f + 0.5f);
        }
    return out;
}

// noisy.png, denoised.png, reference.png per light (light i > 0 with the suffix _light<i>), then light 0's
// composite.png, strip.png and tiles.png.
void writeImages(const std::string &dir, const Renderer &renderer, const Measurements &m, bool hybrid)
{
    const ShadowImages &s = m.shadows[0];
    const uint32_t w = s.width, h = s.height;
    for (uint32_t l = 0; l < m.shadows.size(); l++) {
        std::string suffix = l ? "_light" + std::to_string(l) : "";
        savePng(dir + "noisy" + suffix + ".png", w, h, 1, toGray8(m.shadows[l].noisy));
        savePng(dir + "denoised" + suffix + ".png", w, h, 1, toGray8(m.shadows[l].denoised));
        savePng(dir + "reference" + suffix + ".png", w, h, 1, toGray8(m.shadows[l].reference));
    }
    std::vector<uint8_t> noisy = toGray8(s.noisy), denoised = toGray8(s.denoised), reference = toGray8(s.reference);
    std::vector<uint8_t> composite = rgbaToRgb(renderer.readDisplay(), size_t(w) * h);
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
    savePng(dir + "tiles.png", w, h, 3, tileImage(renderer, s));
    if (hybrid) savePng(dir + "hybrid.png", w, h, 3, hybridImage(renderer, s));
}

ViewerTimings medianTimings(const std::vector<ViewerTimings> &frames)
{
    ViewerTimings out;
    if (frames.empty()) return out;
    double ViewerTimings::*fields[] = {&ViewerTimings::primary,   &ViewerTimings::cascades, &ViewerTimings::classify,
                                       &ViewerTimings::shadow,    &ViewerTimings::reference, &ViewerTimings::dnsr,
                                       &ViewerTimings::composite};
    for (auto field : fields) {
        std::vector<double> v;
        for (const ViewerTimings &t : frames) v.push_back(t.*field);
        std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
        out.*field = v[v.size() / 2];
    }
    return out;
}

void printSummary(const Session &s, const Measurements &m, const std::string &dir)
{
    const ErrorStats &e = m.errors[0];
    if (s.hybrid)
        std::printf("viewer: hybrid: %zu of %zu receivers traced (%.1f%%), %zu of %zu tiles; decided without a ray: "
                    "%zu against the reference's majority, mean error %.4f; GPU ms: cascades %.3f, classify %.3f, "
                    "listed rays %.3f\n",
                    m.traced.traced, m.traced.receivers,
                    m.traced.receivers ? 100.0 * double(m.traced.traced) / double(m.traced.receivers) : 0.0,
                    m.traced.listedTiles, m.traced.tiles, m.traced.decidedWrong, m.traced.decidedMeanError,
                    s.renderer.viewerTimings.cascades,
                    s.renderer.viewerTimings.classify, s.renderer.viewerTimings.shadow);
    if (s.opt.debugView != View::Composite)
        std::printf("viewer: --debug-view: the last frame's dnsr output is the debug view, not the shadow: denoised.png "
                    "and every denoised figure below and in report.json show the view\n");
    std::printf("viewer: %u frames, penumbra guidance %s; RMSE vs %u-ray reference over %zu pixels: noisy %.4f "
                "(%.1f dB), denoised %.4f (%.1f dB)\n",
                s.opt.frames, s.light.hitDistance ? "on" : "off", m.referenceSamples, e.pixels, e.rmseNoisy,
                psnr(e.rmseNoisy), e.rmseDenoised, psnr(e.rmseDenoised));
    std::printf("viewer: lit pixels within %d px of a shadowed one (%zu): darkening vs the reference, worst "
                "%.2f, mean %.2f (1/255)\n",
                kCreaseRadius, e.creasePixels, e.creaseMax, e.creaseMean);
    for (uint32_t l = 1; l < m.errors.size(); l++)
        std::printf("viewer: light %u: RMSE noisy %.4f (%.1f dB), denoised %.4f (%.1f dB)\n", l, m.errors[l].rmseNoisy,
                    psnr(m.errors[l].rmseNoisy), m.errors[l].rmseDenoised, psnr(m.errors[l].rmseDenoised));
    const DnsrPassTimings &t = s.renderer.dnsrTimings;
    std::string filters;
    for (uint32_t p = 0; p < t.filterPasses && p < 4; p++) {
        char ms[32];
        std::snprintf(ms, sizeof ms, "%s%.4f", p ? ", " : "", t.filterMs[p]);
        filters += ms;
    }
    std::printf("viewer: dnsr GPU ms (frame %llu): prepare %.3f, tiles %.3f, filter [%s], total %.3f\n",
                static_cast<unsigned long long>(t.frame), t.prepareMs, t.tileClassificationMs, filters.c_str(),
                t.totalMs);
    std::printf("viewer: wrote %s{noisy,denoised,reference,composite,strip,tiles%s}.png%s and report.json\n",
                dir.c_str(), s.hybrid ? ",hybrid" : "", m.shadows.size() > 1 ? ", {noisy,denoised,reference}_light1.png" : "");
}

}  // namespace

int runHeadless(VulkanContext &ctx, const Options &opt, const Scene &scene, const ReferenceFile *reference)
{
    Session s(opt, scene, ctx);
    ctx.create(contextOptions(opt));
    s.createRenderer();

    std::vector<ViewerTimings> timings;  // per frame after the first
    for (uint32_t f = 0; f < opt.frames; f++) {
        bool last = f + 1 == opt.frames;
        Orbit o = s.orbit;
        o.yaw += radians(opt.orbitDegPerFrame) * f;  // a slow orbit: dnsr must reproject its history every frame
        // --pan: eye and target move together along the view's right vector (a strafing camera).
        Vec3 right{std::cos(s.orbit.yaw), 0, -std::sin(s.orbit.yaw)};
        o.target = o.target + right * (opt.panPerFrame * s.orbit.distance * float(f));
        if (s.light.moving) s.light.azimuth += radians(0.5f);
        FrameInput in = makeFrame(s.scene, o, s.light, opt.width, opt.height);
        in.cameraCut = f == 0;
        // --debug-view: dnsr writes the view instead of the last frame's shadow (the frames before are unchanged).
        in.display = last && s.opt.debugView != View::Composite ? s.opt.debugView : View::Composite;
        in.hybrid = s.hybrid;
        // The reference, for the frame that is measured only: many rays per pixel from the same G-buffer (none when
        // it comes from --load-reference).
        in.resetReference = last;
        in.referenceSamples = last && !reference ? opt.referenceSamples : 0;
        VkCommandBuffer cmd = ctx.beginOneTimeCommands();
        s.renderer.recordFrame(cmd, in);
        if (last) s.renderer.recordReadback(cmd);
        ctx.submitAndWait(cmd);
        s.renderer.afterFrame();
        if (f > 0) timings.push_back(s.renderer.viewerTimings);
    }

    std::filesystem::create_directories(opt.outDir);
    const std::string dir = opt.outDir + "/";
    Measurements m = measureLastFrame(s, reference);
    m.medianTimings = medianTimings(timings);
    m.medianFrames = timings.size();
    writeImages(dir, s.renderer, m, s.hybrid);
    writeReport(dir + "report.json", s, m);
    printSummary(s, m, dir);
    return 0;
}
