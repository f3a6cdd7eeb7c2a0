#version 450
// cascade.comp: one of hybrid mode's cascaded shadow maps (cascades.h says where each lies; pc.light is the
// cascade): per texel, a ray from the plane past the scene on the light's side straight down the light direction;
// the distance to the first surface it meets, over the depth range, is the texel's depth (1 where it meets
// nothing). An engine rasterises its shadow maps instead; dnsr's classifier reads them the same way.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

layout(set = 0, binding = 22, r32f) uniform writeonly image2D cascadeImage0;
layout(set = 0, binding = 23, r32f) uniform writeonly image2D cascadeImage1;
layout(set = 0, binding = 24, r32f) uniform writeonly image2D cascadeImage2;
layout(set = 0, binding = 25, r32f) uniform writeonly image2D cascadeImage3;

layout(local_size_x = 8, local_size_y = 8) in;

void main()
{
    uint c = pc.light;
    uint size = uint(frame.cascadeParams.y);
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(texel), uvec2(size)))) return;
    vec2 uv = (vec2(texel) + 0.5) / float(size);
    vec3 origin = frame.cascadeOrigin[c].xyz + frame.cascadeAxisU[c].xyz * uv.x + frame.cascadeAxisV[c].xyz * uv.y;
    float range = frame.cascadeParams.x;
    uint tri;
    float t;
    vec2 bary;
    float depth = traceRay(origin, -frame.lights[0].xyz, range, false, tri, t, bary) ? t / range : 1.0;
    if (c == 0u) imageStore(cascadeImage0, texel, vec4(depth));
    else if (c == 1u) imageStore(cascadeImage1, texel, vec4(depth));
    else if (c == 2u) imageStore(cascadeImage2, texel, vec4(depth));
    else imageStore(cascadeImage3, texel, vec4(depth));
}
