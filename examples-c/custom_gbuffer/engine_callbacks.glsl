// An engine's callbacks file (docs/callbacks.md): its G-buffer holds linear view depth (R32_SFLOAT: distance
// along the view axis, 0 for sky) and octahedral world normals (RG16_SNORM), which dnsr reads as they are instead
// of through conversion passes. It replaces dnsr_callbacks_default.glsl in a copy of dnsr's shader sources
// (build_shaders.sh); everything else is dnsr's standard callbacks.
#define DNSR_ENGINE_DEPTH_NORMALS
#include "dnsr_callbacks_standard.glsl"

#if defined(DNSR_PASS_TILE_CLASSIFICATION) || defined(DNSR_PASS_FILTER) || defined(DNSR_PASS_CLASSIFY)
// dnsr binds the host's depth and normals at 4 and 6, whatever their formats (the hybrid-shadows classifier too).
layout(set = 0, binding = 4) uniform texture2D dnsr_depth;
layout(set = 0, binding = 6) uniform texture2D dnsr_normals;

// dnsr's passes reason in hardware depth. projectionInverse maps (ndc, d) to a view point whose distance along
// the view axis is z(d) = -(A + B d) / (C + E d) (rows 2 and 3 of the matrix); this inverts it for the pixel.
float dnsr_read_depth(ivec2 p) {
    float z = texelFetch(dnsr_depth, p + dnsr_get_offset(), 0).r;
    bool inverted = dnsr_get_is_depth_inverted();
    if (!(z > 0.0)) return inverted ? 0.0 : 1.0;
    vec2 ndc = (vec2(p) + 0.5) * dnsr_get_inv_extent() * 2.0 - 1.0;
    mat4 m = dnsr_get_projection_inverse();
    float a = m[0][2] * ndc.x + m[1][2] * ndc.y + m[3][2], b = m[2][2];
    float c = m[0][3] * ndc.x + m[1][3] * ndc.y + m[3][3], e = m[2][3];
    return -(a + z * c) / (z * e + b);
}

// Octahedral decode; a zero-length result would be a broken texel: dnsr's convention for those is vec3(0).
vec3 dnsr_read_normal(ivec2 p) {
    vec2 f = texelFetch(dnsr_normals, p + dnsr_get_offset(), 0).xy;
    vec3 n = vec3(f, 1.0 - abs(f.x) - abs(f.y));
    float t = max(-n.z, 0.0);
    n.xy += vec2(n.x >= 0.0 ? -t : t, n.y >= 0.0 ? -t : t);
    float len2 = dot(n, n);
    return (len2 > 1e-12 && len2 < 1e30) ? n * inversesqrt(len2) : vec3(0.0);
}
#endif
