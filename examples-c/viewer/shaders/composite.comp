#version 450
// composite.comp: the final image, color = albedo * (ambient + sum over the lights of N.L * shadow), or one of the
// debug views of light pc.light, into displayImage (RGBA8, gamma-encoded for the composite). pc.mode: 0 noisy 1-spp
// shadow, 1 denoised shadow, 2 reference shadow, 3 composite, 4 hit-mask density per tile (of the traced pixels),
// 9 what decided each pixel in hybrid mode, 10 the fraction of each tile's pixels traced.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

float maskShadow(uint light, ivec2 pixel)
{
    return ((loadHitMask(light, pixel / ivec2(8, 4)) >> tileBit(uvec2(pixel))) & 1u) != 0u ? 0.0 : 1.0;
}

// The pixel's ray, or for a pixel --checkerboard did not trace this frame the mean of its traced neighbours in the
// image (all four are traced), as dnsr reconstructs it: the shadow dnsr starts from.
float noisyShadow(uint light, ivec2 pixel)
{
    if (tracedThisFrame(uvec2(pixel))) return maskShadow(light, pixel);
    const ivec2 neighbours[4] = ivec2[4](ivec2(-1, 0), ivec2(1, 0), ivec2(0, -1), ivec2(0, 1));
    float sum = 0.0, count = 0.0;
    for (int k = 0; k < 4; k++) {
        ivec2 q = pixel + neighbours[k];
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(uvec2(q), frame.size.xy))) continue;
        sum += maskShadow(light, q);
        count += 1.0;
    }
    return sum / count;  // count >= 2: the image is at least 8x8
}

void main()
{
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(pixel), frame.size.xy))) return;
    float depth = imageLoad(depthImage, pixel).r;
    vec3 n = imageLoad(normalImage, pixel).xyz;
    vec3 albedo = imageLoad(albedoImage, pixel).rgb;
    vec3 origin = imageLoad(rayOriginImage, pixel).xyz;
    uint light = pc.light;
    float dist;
    float nDotL = max(dot(n, lightDirection(light, origin, dist)), 0.0);
    float ambient = frame.lightParams.y;

    vec3 color;
    if (pc.mode == 0u) {
        color = vec3(noisyShadow(light, pixel));
    } else if (pc.mode == 1u) {
        color = vec3(loadDenoised(light, pixel));
    } else if (pc.mode == 2u) {
        float count = float(max(frame.info.y, 1u));
        color = vec3(frame.info.y == 0u ? noisyShadow(light, pixel) : loadReference(light, pixel) / count);
    } else if (pc.mode == 3u) {
        // Each light brings at most (1 - ambient) / lights, so that no surface is lit beyond its albedo however
        // many lights there are.
        float direct = 0.0;
        for (uint i = 0u; i < frame.info.z; i++)
            direct += max(dot(n, lightDirection(i, origin, dist)), 0.0) * clamp(loadDenoised(i, pixel), 0.0, 1.0);
        color = depth >= 1.0 ? frame.skyColor.rgb
                             : albedo * (ambient + (1.0 - ambient) * direct / float(frame.info.z));
        color = pow(color, vec3(1.0 / 2.2));
    } else if (pc.mode == 9u) {
        // Hybrid mode: pale = lit and dark blue = shadowed by the cascades' verdict; orange = lit and dark red =
        // occluded by a ray. The tiles dnsr's classifier listed have their grid drawn.
        uint traced = imageLoad(tracedImage, pixel / ivec2(8, 4)).r;
        bool ray = ((traced >> tileBit(uvec2(pixel))) & 1u) != 0u;
        bool lit = maskShadow(light, pixel) > 0.5;
        vec3 tint = ray ? (lit ? vec3(1.0, 0.6, 0.15) : vec3(0.55, 0.1, 0.08))
                        : (lit ? vec3(0.85, 0.85, 0.8) : vec3(0.15, 0.2, 0.45));
        bool edge = traced != 0u && (pixel.x % 8 == 0 || pixel.y % 4 == 0);
        color = depth >= 1.0 ? frame.skyColor.rgb * 0.7 : tint * (0.6 + 0.4 * nDotL) * (edge ? 0.7 : 1.0);
    } else if (pc.mode == 10u) {
        // Pixels traced per tile: grey none, dark red a few, through to yellow all 32.
        uint traced = bitCount(imageLoad(tracedImage, pixel / ivec2(8, 4)).r);
        vec3 heat = traced == 0u ? vec3(0.3) : mix(vec3(0.45, 0.05, 0.05), vec3(1.0, 0.95, 0.3), float(traced) / 32.0);
        bool edge = pixel.x % 8 == 0 || pixel.y % 4 == 0;
        color = heat * (depth >= 1.0 ? 0.6 : 1.0) * (edge ? 0.8 : 1.0);
    } else {
        // Occluded rays per tile: all lit (green) and all occluded (blue) tiles are the ones dnsr's tile
        // classification can skip; the mixed ones (orange, brighter = more occluded) go through the filter. Out of
        // the rays traced: with --checkerboard, half the tile's pixels.
        uint word = loadHitMask(light, pixel / ivec2(8, 4));
        uint occluded = bitCount(word), traced = bitCount(frame.info.w);
        vec3 tint = occluded == 0u ? vec3(0.2, 0.7, 0.3)
                  : occluded == traced ? vec3(0.2, 0.3, 0.8)
                  : mix(vec3(1.0, 0.8, 0.3), vec3(0.8, 0.3, 0.1), float(occluded) / float(traced));
        float shade = depth >= 1.0 ? 0.6 : 0.5 + 0.5 * nDotL;
        bool edge = pixel.x % 8 == 0 || pixel.y % 4 == 0;
        color = tint * shade * (edge ? 0.75 : 1.0);
    }
    imageStore(displayImage, pixel, vec4(clamp(color, 0.0, 1.0), 1.0));
}
