// cascades.cpp: see cascades.h.
#include "cascades.h"

#include <algorithm>
#include <cmath>

namespace {

Vec3 unproject(const Mat4 &invViewProj, float x, float y, float z)
{
    float v[4] = {x, y, z, 1.0f}, r[4] = {};
    for (int row = 0; row < 4; row++)
        for (int col = 0; col < 4; col++) r[row] += invViewProj.at(row, col) * v[col];
    return Vec3{r[0], r[1], r[2]} * (1.0f / r[3]);
}

}  // namespace

CascadeSet fitCascades(const Mat4 &invViewProj, Vec3 eye, Vec3 toLight, Vec3 sceneCenter, float sceneRadius,
                       uint32_t count, uint32_t size)
{
    CascadeSet set;
    set.count = std::clamp(count, 1u, kMaxCascades);
    const Vec3 l = normalize(toLight);
    const Vec3 t = normalize(cross(l, std::fabs(l.y) > 0.99f ? Vec3{1, 0, 0} : Vec3{0, 1, 0}));
    const Vec3 b = cross(l, t);
    // The rays start a little outside the scene's sphere on the light's side and reach as far past it.
    const float margin = 1e-3f * sceneRadius;
    const float lightPlane = dot(sceneCenter, l) + sceneRadius + margin;
    set.depthRange = 2.0f * (sceneRadius + margin);

    // The view frustum's far corners, and how far the scene reaches along the view axis.
    const Vec3 forward = normalize(unproject(invViewProj, 0, 0, 1) - eye);
    Vec3 farCorner[4];
    for (int k = 0; k < 4; k++) farCorner[k] = unproject(invViewProj, k & 1 ? 1.0f : -1.0f, k & 2 ? 1.0f : -1.0f, 1.0f);
    const float reach = std::max(dot(sceneCenter - eye, forward) + sceneRadius, 1e-3f * sceneRadius);
    auto corner = [&](int k, float viewDepth) {
        Vec3 d = farCorner[k] - eye;
        return eye + d * (viewDepth / dot(d, forward));
    };
    // Split depths between a logarithmic and a uniform spacing (the usual "practical" split): finer near the eye.
    float split[kMaxCascades + 1] = {0};
    const float first = 0.05f * reach;
    for (uint32_t i = 1; i <= set.count; i++) {
        float f = float(i) / float(set.count);
        split[i] = 0.6f * first * std::pow(reach / first, f) + 0.4f * reach * f;
    }
    split[set.count] = reach;

    for (uint32_t i = 0; i < set.count; i++) {
        Vec3 points[8];
        Vec3 center{0, 0, 0};
        for (int k = 0; k < 8; k++) {
            points[k] = corner(k & 3, split[i + (k >> 2)]);
            center = center + points[k] * 0.125f;
        }
        float radius = 0;
        for (const Vec3 &p : points) radius = std::max(radius, length(p - center));
        if (radius >= sceneRadius) center = sceneCenter, radius = sceneRadius;  // the whole scene is smaller
        const float texel = 2.0f * radius / float(size);
        const float cu = std::floor(dot(center, t) / texel) * texel, cv = std::floor(dot(center, b) / texel) * texel;
        Cascade &c = set.cascades[i];
        c.origin = t * (cu - radius) + b * (cv - radius) + l * lightPlane;
        c.axisU = t * (2.0f * radius);
        c.axisV = b * (2.0f * radius);
        // u = (p - origin) . t / width, v likewise, depth = (lightPlane - p . l) / depthRange.
        const float inv = 1.0f / (2.0f * radius);
        const Vec3 rows[3] = {t * inv, b * inv, l * (-1.0f / set.depthRange)};
        const float offsets[3] = {-(cu - radius) * inv, -(cv - radius) * inv, lightPlane / set.depthRange};
        Mat4 &m = c.worldToShadow;
        for (int row = 0; row < 3; row++) {
            m.at(row, 0) = rows[row].x, m.at(row, 1) = rows[row].y, m.at(row, 2) = rows[row].z;
            m.at(row, 3) = offsets[row];
        }
    }
    return set;
}
