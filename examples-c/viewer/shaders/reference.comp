#version 450
// reference.comp: the ground truth the viewer measures against. Adds pc.sampleCount shadow samples per pixel
// (sample indices pc.sampleBase...) towards light pc.light to the running sum in that light's reference image; the
// display divides by the total. Its sequence uses a different per-pixel seed than shadow.comp, so it is
// independent of the noisy input.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

void main()
{
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(pixel), frame.size.xy))) return;
    vec4 origin = imageLoad(rayOriginImage, pixel);
    float sum = 0.0;
    if (origin.w == 0.0) {
        sum = float(pc.sampleCount);  // sky is lit
    } else {
        vec3 n = imageLoad(normalImage, pixel).xyz;
        for (uint i = 0u; i < pc.sampleCount; i++)
            sum += shadowSample(pc.light, origin.xyz, n, sample2D(uvec2(pixel), pc.sampleBase + i,
                                                                 referenceSeed(pc.light)));
    }
    if (pc.sampleBase != 0u) sum += loadReference(pc.light, pixel);
    storeReference(pc.light, pixel, sum);
}
