// bvh.cpp: binned surface-area-heuristic BVH build. Each split evaluates 16 bins along each axis of the
// centroid bounds and takes the cheapest; when no split beats a leaf (or the centroids coincide) the node
// becomes a leaf. Children are stored next to each other so a node needs one child index.
#include "bvh.h"

#include <algorithm>
#include <cfloat>

namespace {

struct Aabb {
    Vec3 min{FLT_MAX, FLT_MAX, FLT_MAX};
    Vec3 max{-FLT_MAX, -FLT_MAX, -FLT_MAX};
    void grow(Vec3 p) { min = vmin(min, p), max = vmax(max, p); }
    void grow(const Aabb &b) { min = vmin(min, b.min), max = vmax(max, b.max); }
    float area() const
    {
        Vec3 e = max - min;
        if (e.x < 0) return 0;  // empty
        return 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
    }
};

constexpr int kBins = 16;
constexpr uint32_t kMaxLeafSize = 4;
constexpr float kTraversalCost = 1.0f;  // relative to one triangle test

struct Builder {
    const std::vector<Vec3> &positions;
    std::vector<Aabb> triBounds;
    std::vector<Vec3> centroids;
    Bvh bvh;

    void setBounds(BvhNode &node, const Aabb &b)
    {
        node.boundsMin[0] = b.min.x, node.boundsMin[1] = b.min.y, node.boundsMin[2] = b.min.z;
        node.boundsMax[0] = b.max.x, node.boundsMax[1] = b.max.y, node.boundsMax[2] = b.max.z;
    }

    // Finds the best binned split of triangles [first, first + count); returns false if a leaf is better.
    bool findSplit(uint32_t first, uint32_t count, const Aabb &bounds, int &bestAxis, float &bestPlane)
    {
        Aabb centroidBounds;
        for (uint32_t i = first; i < first + count; i++) centroidBounds.grow(centroids[bvh.triangleOrder[i]]);
        float bestCost = FLT_MAX;
        for (int axis = 0; axis < 3; axis++) {
            float lo = component(centroidBounds.min, axis), hi = component(centroidBounds.max, axis);
            if (!(hi > lo)) continue;  // all centroids on one plane along this axis
            Aabb binBounds[kBins];
            uint32_t binCount[kBins] = {};
            float scale = kBins / (hi - lo);
            for (uint32_t i = first; i < first + count; i++) {
                uint32_t t = bvh.triangleOrder[i];
                int b = std::min(kBins - 1, static_cast<int>((component(centroids[t], axis) - lo) * scale));
                binCount[b]++;
                binBounds[b].grow(triBounds[t]);
            }
            // Sweep from the right to get the right-hand side of every plane, then from the left.
            float rightArea[kBins - 1];
            uint32_t rightCount[kBins - 1];
            Aabb acc;
            uint32_t n = 0;
            for (int b = kBins - 1; b > 0; b--) {
                acc.grow(binBounds[b]);
                n += binCount[b];
                rightArea[b - 1] = acc.area();
                rightCount[b - 1] = n;
            }
            acc = Aabb{};
            n = 0;
            for (int b = 0; b < kBins - 1; b++) {
                acc.grow(binBounds[b]);
                n += binCount[b];
                if (n == 0 || rightCount[b] == 0) continue;
                float cost = acc.area() * n + rightArea[b] * rightCount[b];
                if (cost < bestCost) {
                    bestCost = cost;
                    bestAxis = axis;
                    bestPlane = lo + (b + 1) / scale;
                }
            }
        }
        if (bestCost == FLT_MAX) return false;
        float leafCost = static_cast<float>(count);
        float splitCost = kTraversalCost + bestCost / std::max(bounds.area(), FLT_MIN);
        return count > kMaxLeafSize * 4 || splitCost < leafCost;  // large nodes always split
    }

    void build()
    {
        size_t triangles = positions.size() / 3;
        triBounds.resize(triangles);
        centroids.resize(triangles);
        bvh.triangleOrder.resize(triangles);
        for (size_t t = 0; t < triangles; t++) {
            for (int k = 0; k < 3; k++) triBounds[t].grow(positions[3 * t + k]);
            centroids[t] = (triBounds[t].min + triBounds[t].max) * 0.5f;
            bvh.triangleOrder[t] = static_cast<uint32_t>(t);
        }
        bvh.nodes.reserve(2 * triangles);
        bvh.nodes.push_back({});
        bvh.nodes[0].leftOrFirst = 0;
        bvh.nodes[0].triangleCount = static_cast<uint32_t>(triangles);

        // Explicit stack of (node, depth): no recursion, so a huge scene cannot overflow the C++ stack.
        std::vector<std::pair<uint32_t, uint32_t>> stack{{0u, 1u}};
        while (!stack.empty()) {
            auto [index, depth] = stack.back();
            stack.pop_back();
            bvh.depth = std::max(bvh.depth, depth);
            uint32_t first = bvh.nodes[index].leftOrFirst, count = bvh.nodes[index].triangleCount;
            Aabb bounds;
            for (uint32_t i = first; i < first + count; i++) bounds.grow(triBounds[bvh.triangleOrder[i]]);
            setBounds(bvh.nodes[index], bounds);

            int axis = 0;
            float plane = 0;
            if (count <= 1 || depth >= kBvhMaxDepth || !findSplit(first, count, bounds, axis, plane)) continue;
            auto middle = std::partition(bvh.triangleOrder.begin() + first, bvh.triangleOrder.begin() + first + count,
                                         [&](uint32_t t) { return component(centroids[t], axis) < plane; });
            uint32_t leftCount = static_cast<uint32_t>(middle - (bvh.triangleOrder.begin() + first));
            if (leftCount == 0 || leftCount == count) {
                // Rounding put everything on one side: fall back to a median split on the same axis.
                leftCount = count / 2;
                std::nth_element(bvh.triangleOrder.begin() + first, bvh.triangleOrder.begin() + first + leftCount,
                                 bvh.triangleOrder.begin() + first + count, [&](uint32_t a, uint32_t b) {
                                     return component(centroids[a], axis) < component(centroids[b], axis);
                                 });
            }
            uint32_t left = static_cast<uint32_t>(bvh.nodes.size());
            bvh.nodes.push_back({});
            bvh.nodes.push_back({});
            bvh.nodes[left].leftOrFirst = first;
            bvh.nodes[left].triangleCount = leftCount;
            bvh.nodes[left + 1].leftOrFirst = first + leftCount;
            bvh.nodes[left + 1].triangleCount = count - leftCount;
            bvh.nodes[index].leftOrFirst = left;
            bvh.nodes[index].triangleCount = 0;
            stack.push_back({left, depth + 1});
            stack.push_back({left + 1, depth + 1});
        }
    }
};

}  // namespace

Bvh buildBvh(const std::vector<Vec3> &positions)
{
    Builder builder{positions, {}, {}, {}};
    builder.build();
    return std::move(builder.bvh);
}
