// common.glsl: the resources every viewer pass shares (one descriptor set layout for all of them), the BVH
// traversal and the shadow-ray sampling. Included by every .comp file.

const uint kMaxLights = 2u;  // = kMaxLights in renderer.h
const uint kMaxCascades = 4u;  // = kMaxCascades in cascades.h

// ---- Per-frame constants (host struct FrameConstants in renderer.cpp; std140) ----
layout(set = 0, binding = 0, std140) uniform FrameConstants {
    mat4 viewProj;      // world -> clip (Vulkan: uv (0,0) top-left = NDC (-1,-1), depth 0..1)
    mat4 invViewProj;   // clip -> world
    mat4 prevViewProj;  // last frame's world -> clip, for the motion vectors
    vec4 eye;           // xyz: camera position
    vec4 lights[kMaxLights];  // xyz: direction towards light i (directional) or its position (point); w: 1 = point
    vec4 lightParams;   // x: tan(angular radius) (directional) or light radius (point), every light's; y: ambient;
                        // z: shadow-ray offset at the camera; w: scene radius (the offset grows with distance)
    uvec4 size;         // x, y: render size; z, w: hit-mask size in tiles
    uvec4 info;         // x: frame index; y: reference samples accumulated so far; z: number of lights;
                        // w: the hit-mask bits this frame traces (see tracedThisFrame)
    vec4 skyColor;
    // Hybrid mode's cascades (cascades.h): the world position of each one's texel corner (0, 0) on the plane its
    // rays start from, and its world extent along u and v.
    vec4 cascadeOrigin[kMaxCascades];
    vec4 cascadeAxisU[kMaxCascades];
    vec4 cascadeAxisV[kMaxCascades];
    vec4 cascadeParams;  // x: world distance along the light that depth 0..1 spans; y: texels per side
    vec4 surfaceDetail;  // x: normal detail (--normal-detail, 0: none); y: its world period; z: 1: in dnsr's
                         // packed normals alone (--normal-detail-for dnsr)
} frame;

// ---- Scene: the BVH and its triangles (storage buffers; host structs in bvh.h / renderer.cpp) ----
layout(set = 0, binding = 1, std430) readonly buffer BvhNodes { vec4 bvhNodes[]; };  // 2 per node
layout(set = 0, binding = 2, std430) readonly buffer TriGeometry { vec4 triGeometry[]; };  // v0, e1, e2
layout(set = 0, binding = 3, std430) readonly buffer TriShading { vec4 triShading[]; };  // n0 (w: albedo), n1, n2

// ---- Images (all in layout GENERAL) ----
layout(set = 0, binding = 4, rgba32f) uniform image2D rayOriginImage;  // xyz: shadow-ray origin; w: 1 = surface
layout(set = 0, binding = 5, r32f) uniform image2D depthImage;         // NDC depth, sky = 1
layout(set = 0, binding = 6, rgba16f) uniform image2D normalImage;     // world normal (xyz), 0 for sky
layout(set = 0, binding = 7, rgba16f) uniform image2D velocityImage;   // prev_uv - uv (xy)
layout(set = 0, binding = 8, rgba8) uniform image2D albedoImage;       // base colour
layout(set = 0, binding = 12, rgba8) uniform image2D displayImage;     // what the window or a PNG shows
// Per 8x4 tile, the pixels whose shadow ray this frame traced (hit-mask bits): hybrid mode's listed ones, or all.
layout(set = 0, binding = 27, r32ui) uniform uimage2D tracedImage;

// Each light's own images: light 0's at bindings 9..11, light 1's at 17..19 (bound to light 0's images when there
// is one light). Separate bindings rather than arrays of images: indexing those by a light number that is not a
// compile-time constant needs the device feature shaderStorageImageArrayDynamicIndexing.
layout(set = 0, binding = 9, r32ui) uniform uimage2D hitMaskImage;     // one bit per pixel, 1 = occluded
layout(set = 0, binding = 10, r32f) uniform image2D denoisedImage;     // dnsr's output, 1 = lit
layout(set = 0, binding = 11, r32f) uniform image2D referenceImage;    // sum of reference visibility samples
layout(set = 0, binding = 17, r32ui) uniform uimage2D hitMaskImage1;
layout(set = 0, binding = 18, r32f) uniform image2D denoisedImage1;
layout(set = 0, binding = 19, r32f) uniform image2D referenceImage1;

uint loadHitMask(uint light, ivec2 tile)
{
    return light == 0u ? imageLoad(hitMaskImage, tile).r : imageLoad(hitMaskImage1, tile).r;
}
void storeHitMask(uint light, ivec2 tile, uint mask)
{
    if (light == 0u) imageStore(hitMaskImage, tile, uvec4(mask));
    else imageStore(hitMaskImage1, tile, uvec4(mask));
}
float loadDenoised(uint light, ivec2 pixel)
{
    return light == 0u ? imageLoad(denoisedImage, pixel).r : imageLoad(denoisedImage1, pixel).r;
}
float loadReference(uint light, ivec2 pixel)
{
    return light == 0u ? imageLoad(referenceImage, pixel).r : imageLoad(referenceImage1, pixel).r;
}
void storeReference(uint light, ivec2 pixel, float sum)
{
    if (light == 0u) imageStore(referenceImage, pixel, vec4(sum));
    else imageStore(referenceImage1, pixel, vec4(sum));
}

// Bit (y % 4) * 8 + (x % 8) of an 8x4 tile's hit-mask word holds pixel (x, y).
uint tileBit(uvec2 pixel) { return (pixel.y % 4u) * 8u + pixel.x % 8u; }

// Whether this frame traces the pixel's shadow rays: every pixel, or with --checkerboard the pixels with
// (x + y) % 2 == this frame's phase. Tiles start at even x and y, so the traced bits form the same word in every
// tile, frame.info.w (Renderer::tracedBits()).
bool tracedThisFrame(uvec2 pixel) { return ((frame.info.w >> tileBit(pixel)) & 1u) != 0u; }

layout(push_constant) uniform PushConstants {
    uint mode;         // composite.comp: what to display; shadow.comp: 1 = also write the hit distance
    uint sampleBase;   // reference.comp: first sample index of this dispatch
    uint sampleCount;  // reference.comp: samples per pixel in this dispatch
    uint light;        // shadow.comp, reference.comp: the light traced; composite.comp: the light the views show
} pc;

const float kInfinity = 1e30;
const uint kStackSize = 48;  // = kBvhMaxDepth in bvh.h: the builder never goes deeper

// ---- Ray / BVH traversal ----

// Distance to an AABB along the ray, or kInfinity when missed or farther than tMax.
float rayBox(vec3 origin, vec3 invDir, vec3 bmin, vec3 bmax, float tMax)
{
    vec3 t0 = (bmin - origin) * invDir;
    vec3 t1 = (bmax - origin) * invDir;
    vec3 tSmall = min(t0, t1), tLarge = max(t0, t1);
    float tNear = max(max(tSmall.x, tSmall.y), max(tSmall.z, 0.0));
    float tFar = min(min(tLarge.x, tLarge.y), min(tLarge.z, tMax));
    return tNear <= tFar ? tNear : kInfinity;
}

// Moller-Trumbore, double-sided. Returns the distance, or kInfinity.
float rayTriangle(uint tri, vec3 origin, vec3 dir, float tMax, out vec2 bary)
{
    vec3 v0 = triGeometry[3 * tri].xyz, e1 = triGeometry[3 * tri + 1].xyz, e2 = triGeometry[3 * tri + 2].xyz;
    vec3 p = cross(dir, e2);
    float det = dot(e1, p);
    bary = vec2(0.0);
    if (abs(det) < 1e-12) return kInfinity;
    float invDet = 1.0 / det;
    vec3 s = origin - v0;
    float u = dot(s, p) * invDet;
    if (u < 0.0 || u > 1.0) return kInfinity;
    vec3 q = cross(s, e1);
    float v = dot(dir, q) * invDet;
    if (v < 0.0 || u + v > 1.0) return kInfinity;
    float t = dot(e2, q) * invDet;
    bary = vec2(u, v);
    return (t > 0.0 && t < tMax) ? t : kInfinity;
}

// Closest hit (anyHit = false) or any hit (anyHit = true, for shadow rays) along origin + t * dir, t < tMax.
// Returns whether something was hit; hitTri / hitT / hitBary describe the closest hit found.
bool traceRay(vec3 origin, vec3 dir, float tMax, bool anyHit, out uint hitTri, out float hitT, out vec2 hitBary)
{
    // A zero direction component would give 0 * inf = NaN in rayBox; nudge it instead.
    vec3 safeDir = mix(dir, vec3(1e-20), lessThan(abs(dir), vec3(1e-20)));
    vec3 invDir = 1.0 / safeDir;
    hitTri = 0u;
    hitT = tMax;
    hitBary = vec2(0.0);
    bool hit = false;
    if (rayBox(origin, invDir, bvhNodes[0].xyz, bvhNodes[1].xyz, tMax) == kInfinity) return false;

    uint stack[kStackSize];
    uint stackSize = 0u;
    uint node = 0u;
    while (true) {
        vec4 a = bvhNodes[2u * node], b = bvhNodes[2u * node + 1u];
        uint first = floatBitsToUint(a.w), count = floatBitsToUint(b.w);
        if (count > 0u) {  // leaf
            for (uint i = first; i < first + count; i++) {
                vec2 bary;
                float t = rayTriangle(i, origin, dir, hitT, bary);
                if (t < hitT) {
                    hit = true;
                    hitT = t;
                    hitTri = i;
                    hitBary = bary;
                    if (anyHit) return true;
                }
            }
        } else {  // interior: visit the nearer child first, keep the other for later
            uint left = first, right = first + 1u;
            float tLeft = rayBox(origin, invDir, bvhNodes[2u * left].xyz, bvhNodes[2u * left + 1u].xyz, hitT);
            float tRight = rayBox(origin, invDir, bvhNodes[2u * right].xyz, bvhNodes[2u * right + 1u].xyz, hitT);
            if (tRight < tLeft) {
                uint n = left; left = right; right = n;
                float t = tLeft; tLeft = tRight; tRight = t;
            }
            if (tLeft != kInfinity) {
                if (tRight != kInfinity && stackSize < kStackSize) stack[stackSize++] = right;
                node = left;
                continue;
            }
        }
        if (stackSize == 0u) break;
        node = stack[--stackSize];
    }
    return hit;
}

// ---- Sampling ----

// R2 low-discrepancy sequence (Roberts 2018) in 0.32 fixed point: exact for any index, no float drift.
uvec2 r2Fixed(uint index)
{
    return uvec2(3242174889u, 2447445413u) * index + uvec2(2147483648u);  // (1/g, 1/g^2) * 2^32, g = 1.3247...
}

// A per-pixel hash (pcg2d, Jarzynski & Olano 2020) decorrelating the pixels' sequences.
uvec2 pcg2d(uvec2 v)
{
    v = v * 1664525u + 1013904223u;
    v.x += v.y * 1664525u;
    v.y += v.x * 1664525u;
    v ^= v >> 16u;
    v.x += v.y * 1664525u;
    v.y += v.x * 1664525u;
    v ^= v >> 16u;
    return v;
}

// Sample `index` of pixel `pixel`'s sequence in [0,1)^2: the R2 sequence shifted by a random per-pixel offset
// (Cranley-Patterson rotation), so each pixel's samples stay well spread over frames.
vec2 sample2D(uvec2 pixel, uint index, uint seed)
{
    uvec2 u = r2Fixed(index) + pcg2d(pixel ^ uvec2(seed, seed * 7919u));  // wraps mod 2^32 = fract()
    return vec2(u >> 8u) * (1.0 / 16777216.0);
}

// Uniform point on the unit disk (Shirley-Chiu concentric map: keeps the sequence's stratification).
vec2 concentricDisk(vec2 u)
{
    vec2 o = 2.0 * u - 1.0;
    if (o.x == 0.0 && o.y == 0.0) return vec2(0.0);
    float r, phi;
    if (abs(o.x) > abs(o.y)) {
        r = o.x;
        phi = 0.78539816 * (o.y / o.x);
    } else {
        r = o.y;
        phi = 1.57079633 - 0.78539816 * (o.x / o.y);
    }
    return r * vec2(cos(phi), sin(phi));
}

// The seeds of a light's per-pixel sequences (sample2D) for its shadow rays and its reference: each light's own,
// so that light 1's noise is independent of light 0's, and the reference independent of the noisy input. Light 0
// keeps the seeds of the single-light viewer, so its rays do not depend on how many lights there are.
uint shadowSeed(uint light) { return 0x9e3779b9u + light * 0x6a09e667u; }
uint referenceSeed(uint light) { return 0x85ebca6bu + light * 0x6a09e667u; }

// Direction towards the light's centre from p, and the distance to it (kInfinity for a directional light).
vec3 lightDirection(uint light, vec3 p, out float dist)
{
    vec4 l = frame.lights[light];
    if (l.w == 0.0) {
        dist = kInfinity;
        return l.xyz;
    }
    vec3 d = l.xyz - p;
    dist = length(d);
    return d / dist;
}

// The direction of the shadow ray for sample u from `origin` to light `light` (l: the direction to its centre), and
// how far it goes: within a cone of the light's angular radius for a directional light, to a point of the disk of
// the light sphere facing `origin` for a point light.
vec3 shadowRayDirection(uint light, vec3 origin, vec3 l, vec2 u, out float tMax)
{
    vec3 t = normalize(abs(l.x) > 0.9 ? cross(l, vec3(0, 1, 0)) : cross(l, vec3(1, 0, 0)));
    vec3 b = cross(l, t);
    vec2 d = concentricDisk(u);
    if (frame.lights[light].w == 0.0) {
        tMax = kInfinity;
        return normalize(l + (d.x * t + d.y * b) * frame.lightParams.x);
    }
    vec3 target = frame.lights[light].xyz + (d.x * t + d.y * b) * frame.lightParams.x;
    vec3 dir = target - origin;
    tMax = length(dir);
    return dir / tMax;
}

// One shadow ray from `origin` (a surface point already nudged off its surface) with shading normal n, towards
// the point of light `light` sample u picks (shadowRayDirection), over the stretch [tMin, tMax] of the direction to
// the light (it leans off that direction by the light's angular radius at most, so its own length grows by 1 / cos
// of the lean; a point light also ends it). Hybrid mode traces the stretch dnsr's classifier bounded with the
// blockers the cascades show, forward from the surface or reversed from the far end towards it (a blocker nearest
// the light is met first). Returns true when occluded. A surface facing away from the light counts as occluded, as a
// ray through the object would find. With `closest`, a forward ray finds the nearest occluder and hitDistance is
// its distance from `origin` (the penumbra guidance dnsr reads); otherwise the first occluder found ends the
// traversal (cheaper) and hitDistance is only some occluder's distance. It is 0 when the ray is not occluded, and
// for a surface facing away from the light (no ray: distance unknown).
bool shadowRayInterval(uint light, vec3 origin, vec3 n, vec2 u, float tMin, float tMax, bool reversed, bool closest,
                       out float hitDistance)
{
    hitDistance = 0.0;
    float dist;
    vec3 l = lightDirection(light, origin, dist);
    if (dot(n, l) <= 0.0) return true;
    float rayMax;
    vec3 dir = shadowRayDirection(light, origin, l, u, rayMax);
    float lean = 1.0 / max(dot(dir, l), 1e-3);
    float start = tMin * lean, end = min(tMax * lean, rayMax);
    uint tri;
    float hitT;
    vec2 bary;
    if (reversed && end < kInfinity)  // stops just short of the surface point it would end at
        return traceRay(origin + dir * end, -dir, (end - start) * 0.9999, true, tri, hitT, bary);
    if (!traceRay(origin + dir * start, dir, end - start, !closest, tri, hitT, bary)) return false;
    hitDistance = start + hitT;
    return true;
}

// The whole ray: from the surface to the light.
bool shadowRay(uint light, vec3 origin, vec3 n, vec2 u, bool closest, out float hitDistance)
{
    return shadowRayInterval(light, origin, n, u, 0.0, kInfinity, false, closest, hitDistance);
}

// shadowRay as visibility: 1 when lit, 0 when occluded.
float shadowSample(uint light, vec3 origin, vec3 n, vec2 u)
{
    float unused;
    return shadowRay(light, origin, n, u, false, unused) ? 0.0 : 1.0;
}
