#version 450
// shadow.comp: one jittered shadow ray per pixel towards light pc.light (one dispatch per light), packed into that
// light's hit mask (or, with --rays k, k rays per pixel whose lit fraction goes to the visibility image dnsr reads
// with DNSR_SHADOW_INPUT_VISIBILITY; the mask then holds each pixel's first ray, for the noisy view). One
// invocation per 8x4 tile traces the tile's 32 rays and writes the tile's word once: no atomics and no subgroup
// operations, so the result does not depend on the device's subgroup size. Bit (y % 4) * 8 + (x % 8) is set when
// the ray hit an occluder (the FidelityFX convention, DNSR_HIT_MASK_OCCLUDED_BITS); sky pixels stay 0 (not
// occluded). With --checkerboard only the pixels of this frame's phase get a ray (DNSR_SHADOW_INPUT_CHECKERBOARD:
// dnsr ignores the others' bits); the others keep bit 0 and hit distance 0 (unknown).
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "shadow_outputs.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

void main()
{
    uvec2 tile = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(tile, frame.size.zw))) return;
    uint light = pc.light;
    bool writeDistance = pc.mode == 1u;
    uint rays = max(pc.sampleCount, 1u);  // rays per pixel: more than 1 writes the visibility image
    uint mask = 0u;
    for (uint bit = 0u; bit < 32u; bit++) {
        uvec2 pixel = tile * uvec2(8u, 4u) + uvec2(bit % 8u, bit / 8u);
        if (any(greaterThanEqual(pixel, frame.size.xy))) continue;  // partial tile at the right/bottom edge
        vec4 origin = imageLoad(rayOriginImage, ivec2(pixel));
        float hitDistance = 0.0, lit = float(rays);
        if (origin.w != 0.0 && tracedThisFrame(pixel)) {  // not sky, and not left to the other checkerboard phase
            vec3 n = imageLoad(normalImage, ivec2(pixel)).xyz;
            // This frame's samples of the pixel's sequence: successive frames walk the R2 sequence, so the
            // denoiser's temporal accumulation sees well-spread samples rather than white noise. The first ray's
            // distance is the guidance (dnsr reads it where the pixel is not fully lit).
            for (uint r = 0u; r < rays; r++) {
                vec2 u = sample2D(pixel, frame.info.x * rays + r, shadowSeed(light));
                float d = 0.0;
                if (shadowRay(light, origin.xyz, n, u, writeDistance, d)) {
                    lit -= 1.0;
                    if (r == 0u) mask |= 1u << bit;
                    if (hitDistance == 0.0) hitDistance = d;
                }
            }
        }
        if (writeDistance) storeHitDistance(light, ivec2(pixel), hitDistance);
        if (rays > 1u) storeVisibility(light, ivec2(pixel), lit / float(rays));
    }
    storeHitMask(light, ivec2(tile), mask);
}
