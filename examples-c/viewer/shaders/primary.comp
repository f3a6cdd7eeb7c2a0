#version 450
// primary.comp: one camera ray per pixel through the BVH; writes the G-buffer dnsr reads (depth, world normal,
// motion vectors) plus what the later passes need (shadow-ray origin, albedo).
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

#ifdef PACKED_GBUFFER
// --gbuffer packed: the G-buffer an engine might keep instead (examples-c/custom_gbuffer): linear view depth and
// octahedral normals, read by dnsr through that example's callbacks.
layout(set = 0, binding = 14, r32f) uniform image2D linearDepthImage;   // distance along the view axis, 0 for sky
layout(set = 0, binding = 15, rg16_snorm) uniform image2D octNormalImage;

vec2 octEncode(vec3 n) {
    n /= abs(n.x) + abs(n.y) + abs(n.z);
    return n.z >= 0.0 ? n.xy : (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
}
#endif

void main()
{
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(pixel), frame.size.xy))) return;

    // The ray through the pixel centre, from the near plane to the far plane.
    vec2 uv = (vec2(pixel) + 0.5) / vec2(frame.size.xy);
    vec2 ndc = uv * 2.0 - 1.0;
    vec4 nearH = frame.invViewProj * vec4(ndc, 0.0, 1.0);
    vec4 farH = frame.invViewProj * vec4(ndc, 1.0, 1.0);
    vec3 nearP = nearH.xyz / nearH.w, farP = farH.xyz / farH.w;
    float tMax = length(farP - nearP);
    vec3 dir = (farP - nearP) / tMax;

    uint tri;
    float t;
    vec2 bary;
    bool hit = traceRay(nearP, dir, tMax, false, tri, t, bary);

    // Sky: depth 1 (dnsr's "no receiver"), no normal; its motion is that of the far point along the ray.
    vec3 p = hit ? nearP + dir * t : farP;
    float depth = 1.0;
    vec3 normal = vec3(0.0);
    vec3 bumped = vec3(0.0);
    vec4 albedo = vec4(0.0);
    vec4 rayOrigin = vec4(0.0);
    if (hit) {
        vec4 clip = frame.viewProj * vec4(p, 1.0);
        // Receivers must have 0 < depth < 1: keep a hit at the far plane from reading as sky.
        depth = clamp(clip.z / clip.w, 1e-7, 0.99999994);

        vec3 e1 = triGeometry[3 * tri + 1].xyz, e2 = triGeometry[3 * tri + 2].xyz;
        vec3 geometric = normalize(cross(e1, e2));
        if (dot(geometric, dir) > 0.0) geometric = -geometric;  // double-sided: face the camera
        vec4 n0 = triShading[3 * tri], n1 = triShading[3 * tri + 1], n2 = triShading[3 * tri + 2];
        normal = normalize(n0.xyz * (1.0 - bary.x - bary.y) + n1.xyz * bary.x + n2.xyz * bary.y);
        if (dot(normal, geometric) < 0.0) normal = -normal;
        // --normal-detail: what a normal map does to an engine's G-buffer, bumps of a world-space pattern that
        // tilt the shading normal (up to 60 degrees at detail 1); the geometry, and so the shadows cast, stay.
        // With --normal-detail-for dnsr only dnsr's packed normals get them (below).
        bumped = normal;
        if (frame.surfaceDetail.x > 0.0) {
            vec3 q = p * (6.2831853 / frame.surfaceDetail.y);
            vec3 bump = vec3(sin(q.y + 1.7 * sin(q.z)), sin(q.z + 1.3 * sin(q.x)), sin(q.x + 1.1 * sin(q.y)));
            bump -= normal * dot(normal, bump);
            bumped = normalize(normal + 1.7 * frame.surfaceDetail.x * bump);
            if (frame.surfaceDetail.z == 0.0) normal = bumped;
        }
        albedo = unpackUnorm4x8(floatBitsToUint(n0.w));

        // The shadow ray starts slightly off the surface (along the geometric normal, on the camera's side) so
        // that it cannot hit the triangle it leaves; the offset scales with the scene and with distance.
        float offset = frame.lightParams.z * (1.0 + t / max(frame.lightParams.w, 1e-6));
        rayOrigin = vec4(p + geometric * offset, 1.0);
    }

    // Motion vector, analytically: where this point was on screen last frame (the scene itself is static).
    // dnsr's convention: prev_uv = uv + velocity * motionVectorScale, with the scale (1, 1).
    vec4 prevClip = frame.prevViewProj * vec4(p, 1.0);
    vec2 velocity = vec2(2.0);  // behind last frame's camera: far off screen, so dnsr drops the history
    if (prevClip.w > 1e-6) velocity = (prevClip.xy / prevClip.w * 0.5 + 0.5) - uv;

    imageStore(depthImage, pixel, vec4(depth));
    imageStore(normalImage, pixel, vec4(normal, 0.0));
    imageStore(velocityImage, pixel, vec4(velocity, 0.0, 0.0));
    imageStore(albedoImage, pixel, albedo);
    imageStore(rayOriginImage, pixel, rayOrigin);
#ifdef PACKED_GBUFFER
    // The view axis: from the eye through the centre of the screen.
    vec4 centreH = frame.invViewProj * vec4(0.0, 0.0, 1.0, 1.0);
    vec3 forward = normalize(centreH.xyz / centreH.w - frame.eye.xyz);
    imageStore(linearDepthImage, pixel, vec4(hit ? dot(p - frame.eye.xyz, forward) : 0.0));
    imageStore(octNormalImage, pixel, vec4(hit ? octEncode(bumped) : vec2(0.0), 0.0, 0.0));
#endif
}
