// shadow_outputs.glsl: the per-pixel images the shadow passes write besides the hit mask (bindings 13, 16, 20, 21),
// in R16F or, built with HIT_DISTANCE_R32F, R32F. Included after common.glsl.
// The penumbra guidance dnsr reads with DNSR_DISPATCH_USE_HIT_DISTANCE: per pixel, the distance along the shadow
// ray to the nearest occluder (0 where the ray was not occluded: dnsr reads it only where the mask says it was).
// Not in common.glsl: R16F storage needs the device feature shaderStorageImageExtendedFormats, so the shadow passes
// that write these (shadow.comp, shadow_listed.comp) are also built with HIT_DISTANCE_R32F for devices without it.
// The visibility image (binding 16) likewise. Light 1's are at bindings 20 and 21.
#ifdef HIT_DISTANCE_R32F
#define LIGHT_IMAGE_FORMAT r32f
#else
#define LIGHT_IMAGE_FORMAT r16f
#endif
layout(set = 0, binding = 13, LIGHT_IMAGE_FORMAT) uniform writeonly image2D hitDistanceImage;
layout(set = 0, binding = 16, LIGHT_IMAGE_FORMAT) uniform writeonly image2D visibilityImage;
layout(set = 0, binding = 20, LIGHT_IMAGE_FORMAT) uniform writeonly image2D hitDistanceImage1;
layout(set = 0, binding = 21, LIGHT_IMAGE_FORMAT) uniform writeonly image2D visibilityImage1;

void storeHitDistance(uint light, ivec2 pixel, float d)
{
    if (light == 0u) imageStore(hitDistanceImage, pixel, vec4(d));
    else imageStore(hitDistanceImage1, pixel, vec4(d));
}
void storeVisibility(uint light, ivec2 pixel, float v)
{
    if (light == 0u) imageStore(visibilityImage, pixel, vec4(v));
    else imageStore(visibilityImage1, pixel, vec4(v));
}
