// metrics.cpp: see metrics.h.
#include "metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <vector>

namespace {

const char kReferenceMagic[8] = {'d', 'n', 's', 'r', 'r', 'e', 'f', '1'};

ClassError summarize(std::vector<double> errors)
{
    ClassError c;
    c.pixels = errors.size();
    if (errors.empty()) return c;
    double sum = 0;
    for (double x : errors) sum += x, c.over1 += x > 1.0, c.max = std::max(c.max, x);
    c.mean = sum / double(errors.size());
    size_t k = std::min(errors.size() - 1, size_t(0.99 * double(errors.size())));
    std::nth_element(errors.begin(), errors.begin() + k, errors.end());
    c.p99 = errors[k];
    return c;
}

// The classes of pixels the "do no harm" targets name: exact, silhouettes, creases, thin features.
void measureDoNoHarm(const ShadowImages &s, ErrorStats &e)
{
    const int w = int(s.width), h = int(s.height);
    auto at = [&](int x, int y) { return size_t(y) * w + x; };
    auto in = [&](int x, int y) { return x >= 0 && y >= 0 && x < w && y < h; };
    auto exactRef = [&](size_t i) { return s.receiver[i] && (s.reference[i] == 0.0f || s.reference[i] == 1.0f); };
    auto error255 = [&](size_t i) { return std::fabs(double(s.denoised[i]) - s.reference[i]) * 255.0; };
    // 1 - depth is proportional to 1 / linear depth for a perspective projection with the far plane well behind
    // the near one: its relative change is the linear depth's.
    auto jump = [&](size_t a, size_t b) {
        double za = 1.0 - s.depth[a], zb = 1.0 - s.depth[b];
        return std::fabs(za - zb) > kSilhouetteDepthJump * std::min(za, zb);
    };
    std::vector<double> exact, silhouette;
    double thinError = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            size_t i = at(x, y);
            if (!exactRef(i)) continue;
            if (s.noisy[i] == s.reference[i]) exact.push_back(error255(i));
            bool nearEdge = false;
            for (int dy = -kSilhouetteRadius; dy <= kSilhouetteRadius && !nearEdge; dy++)
                for (int dx = -kSilhouetteRadius; dx <= kSilhouetteRadius && !nearEdge; dx++)
                    nearEdge = in(x + dx, y + dy) && (!s.receiver[at(x + dx, y + dy)] || jump(i, at(x + dx, y + dy)));
            if (nearEdge && s.reference[i] == 0.0f) silhouette.push_back(error255(i));
            // A run of this value at most 2 px long along x or y, bounded by the other exact value on both sides.
            bool thin = false;
            for (int axis = 0; axis < 2 && !thin; axis++) {
                int ax = axis == 0, ay = axis == 1;
                auto other = [&](int k) {
                    int qx = x + ax * k, qy = y + ay * k;
                    if (!in(qx, qy)) return 0;  // 0: no bound; 1: the other value; 2: the same value
                    size_t q = at(qx, qy);
                    return !exactRef(q) ? 0 : (s.reference[q] != s.reference[i] ? 1 : 2);
                };
                for (int start = -1; start <= 0 && !thin; start++) {  // the run is [start, start + 1] or [0, 0]
                    int lo = other(start - 1), hi = other(start + 2);
                    bool mid = start == -1 ? other(-1) == 2 : other(1) == 2;
                    thin = mid && lo == 1 && hi == 1;
                }
                thin = thin || (other(-1) == 1 && other(1) == 1);
            }
            if (thin) thinError += error255(i) / 255.0, e.thinPixels++;
        }
    e.exact = summarize(std::move(exact));
    e.silhouette = summarize(std::move(silhouette));
    if (e.thinPixels) e.thinContrastKept = 1.0 - thinError / double(e.thinPixels);
}

}  // namespace

double psnr(double rmse) { return rmse > 0 ? std::min(100.0, -20.0 * std::log10(rmse)) : 100.0; }

uint64_t fnv1a(const void *data, size_t bytes)
{
    uint64_t h = 0xcbf29ce484222325ull;
    for (size_t i = 0; i < bytes; i++) h = (h ^ static_cast<const uint8_t *>(data)[i]) * 0x100000001b3ull;
    return h;
}

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
    std::vector<double> creaseErrors;
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
            creaseErrors.push_back(std::fabs(darkening));
            sum += darkening;
            worst = std::max(worst, darkening);
            e.creasePixels++;
        }
    if (e.creasePixels) {
        e.creaseMax = worst;
        e.creaseMean = sum / double(e.creasePixels);
    }
    e.crease = summarize(std::move(creaseErrors));
    measureDoNoHarm(s, e);
    return e;
}

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

TracedStats tracedStats(const Renderer &r, const ShadowImages &s)
{
    TracedStats t;
    const uint32_t *traced = r.readTraced();
    t.tiles = size_t(r.tilesX()) * r.tilesY();
    for (size_t i = 0; i < t.tiles; i++) t.listedTiles += traced[i] != 0;
    for (uint32_t y = 0; y < s.height; y++)
        for (uint32_t x = 0; x < s.width; x++) {
            size_t i = size_t(y) * s.width + x;
            if (!s.receiver[i]) continue;
            t.receivers++;
            if ((traced[(y / 4) * r.tilesX() + x / 8] >> ((y % 4) * 8 + x % 8)) & 1u) {
                t.traced++;
                continue;
            }
            double error = std::fabs(double(s.noisy[i]) - double(s.reference[i]));  // noisy: the verdict, 0 or 1
            t.decidedWrong += error > 0.5;
            t.decidedMeanError += error;
        }
    size_t decided = t.receivers - t.traced;
    if (decided) t.decidedMeanError /= double(decided);
    return t;
}
