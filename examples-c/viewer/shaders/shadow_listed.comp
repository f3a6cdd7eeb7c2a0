#version 450
// shadow_listed.comp: hybrid mode's shadow rays: only the pixels dnsr's classifier listed, one workgroup per listed
// 8x4 tile (vkCmdDispatchIndirect on the classifier's counts), one invocation per pixel. The classifier prefilled
// the hit mask (the listed pixels with 0); an occluded ray ORs its bit in (DNSR_HIT_MASK_OCCLUDED_BITS), so the
// tile's other pixels keep the cascades' verdicts. The same per-pixel sample as shadow.comp's first ray, within the
// classifier's interval (pc.mode bit 0: reversed). With penumbra guidance (bit 1) the rays go forward to the nearest
// occluder and write its distance; the renderer cleared the other pixels' to 0, dnsr's "unknown". Also records the
// tile's traced pixels for the views and statistics.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "shadow_outputs.glsl"

// DNSR_CLASSIFY_TILE_BYTES per listed tile: x | y << 16 (in tiles), the pixels to trace, min t, max t (float bits).
layout(set = 0, binding = 26, std430) readonly buffer TileList { uvec4 tileList[]; };

layout(local_size_x = 8, local_size_y = 4) in;

void main()
{
    uvec4 record = tileList[gl_WorkGroupID.x];
    uvec2 tile = uvec2(record.x & 0xffffu, record.x >> 16u);
    uvec2 pixel = tile * uvec2(8u, 4u) + gl_LocalInvocationID.xy;
    uint bit = tileBit(pixel);
    if (bit == 0u) imageStore(tracedImage, ivec2(tile), uvec4(record.y));
    if (((record.y >> bit) & 1u) == 0u) return;
    vec4 origin = imageLoad(rayOriginImage, ivec2(pixel));
    if (origin.w == 0.0) return;  // sky: the classifier lists receivers only
    vec3 n = imageLoad(normalImage, ivec2(pixel)).xyz;
    vec2 u = sample2D(pixel, frame.info.x, shadowSeed(0u));
    bool guidance = (pc.mode & 2u) != 0u;
    float hitDistance;
    if (shadowRayInterval(0u, origin.xyz, n, u, uintBitsToFloat(record.z), uintBitsToFloat(record.w),
                          !guidance && (pc.mode & 1u) != 0u, guidance, hitDistance))
        imageAtomicOr(hitMaskImage, ivec2(tile), 1u << bit);
    if (guidance) storeHitDistance(0u, ivec2(pixel), hitDistance);
}
