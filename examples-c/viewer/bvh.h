// bvh.h: a bounding volume hierarchy over the scene's triangles, built on the CPU and traversed by the compute
// shaders (the viewer needs no ray-tracing extension).
#pragma once

#include <cstdint>
#include <vector>

#include "vec_math.h"

// 32 bytes, laid out as the shaders read it (two vec4 per node; see shaders/common.glsl).
struct BvhNode {
    float boundsMin[3];
    uint32_t leftOrFirst;  // interior: index of the left child (the right one follows it); leaf: first triangle
    float boundsMax[3];
    uint32_t triangleCount;  // 0 for an interior node
};
static_assert(sizeof(BvhNode) == 32, "BvhNode is read as two vec4 by the shaders");

struct Bvh {
    std::vector<BvhNode> nodes;          // nodes[0] is the root
    std::vector<uint32_t> triangleOrder;  // leaf triangle i is scene triangle triangleOrder[i]
    uint32_t depth = 0;
};

// The shaders' traversal stack holds this many entries; the builder never goes deeper (it makes a leaf of what
// is left instead), so traversal can never overflow its stack.
constexpr uint32_t kBvhMaxDepth = 48;

// Binned SAH build (16 bins per axis, leaves of at most 4 triangles where a split helps). `positions` holds
// three vertices per triangle.
Bvh buildBvh(const std::vector<Vec3> &positions);
