// cascades.h: the cascaded shadow maps of hybrid shadows (--hybrid): where each cascade lies, and the matrix dnsr's
// classifier reads it through. An engine has these already (its shadow maps, rasterised); the viewer has no
// rasteriser, so cascade.comp traces them: per texel, one ray from the light's side of the scene straight down the
// light direction, its distance to the first surface stored as the depth.
#pragma once

#include <cstdint>

#include "vec_math.h"

constexpr uint32_t kMaxCascades = 4;  // DNSR_MAX_CASCADES

struct Cascade {
    // World position of texel corner (0, 0) on the plane the rays start from, and the world step across the whole
    // image along u and along v (both perpendicular to the light).
    Vec3 origin, axisU, axisV;
    // World position (w = 1) -> (u, v, depth): DnsrClassifyDispatch::cascadeWorldToShadow.
    Mat4 worldToShadow;
};

struct CascadeSet {
    uint32_t count = 0;
    Cascade cascades[kMaxCascades];
    // World distance along the light that depth 0..1 spans: every cascade starts at the scene's bounding sphere on
    // the light's side and ends past it, so every possible blocker is in every cascade's depth range.
    float depthRange = 1;
};

// `count` cascades (1..kMaxCascades) of size x size texels for a directional light towards `toLight`, fitted to
// slices of the view frustum (finest first; the last slice ends behind the scene), each the square around its
// slice's bounding sphere (never wider than the scene's), its centre snapped to whole texels so that the shadow
// maps do not crawl as the camera moves.
CascadeSet fitCascades(const Mat4 &invViewProj, Vec3 eye, Vec3 toLight, Vec3 sceneCenter, float sceneRadius,
                       uint32_t count, uint32_t size);
