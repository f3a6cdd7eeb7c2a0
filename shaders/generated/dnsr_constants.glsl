// Generated from src/constants.rs by `DNSR_BLESS=1 cargo test generated_glsl`. Do not edit.
#ifndef DNSR_CONSTANTS_GLSL
#define DNSR_CONSTANTS_GLSL

struct DnsrFrameConstants {
    mat4 projection_inverse;
    mat4 reprojection;
    mat4 view_projection_inverse;
    vec4 eye_depth_sigma;
    vec4 motion_normals;
    uvec4 rect;
    uvec4 flags;
    vec4 inv_extent;
    vec4 disocclusion;
    vec4 rejection;
    vec4 temporal;
    vec4 filtering;
    vec4 runs;
    vec4 penumbra;
};

struct DnsrFilterPush {
    uvec4 pass;
    uvec4 lights;
    vec4 light_tan_half_angle;
};

#define DNSR_FLAG_RESET 1u
#define DNSR_FLAG_DEPTH_INVERTED 2u
#define DNSR_FLAG_LIT_BIT_MASK 4u
#define DNSR_FLAG_CHECKERBOARD 8u
#define DNSR_PASS_WRITE_INTERNAL 1u
#define DNSR_PASS_SKIP_CLEARED 2u
#define DNSR_PASS_WRITE_GUIDE 4u
#define DNSR_TILE_CLEARED 1u
#define DNSR_TILE_LIT 2u
#define DNSR_DEBUG_VIEW_NONE 0u
#define DNSR_DEBUG_VIEW_TILE_CLASSIFICATION 1u
#define DNSR_DEBUG_VIEW_SAMPLE_COUNT 2u
#define DNSR_DEBUG_VIEW_VARIANCE 3u
#define DNSR_DEBUG_VIEW_DISOCCLUSION 4u

#define DNSR_TILE_WIDTH 8
#define DNSR_TILE_HEIGHT 4
#define DNSR_GROUP_WIDTH 8
#define DNSR_GROUP_HEIGHT 8
#define DNSR_WIDE_GROUP_WIDTH 16
#define DNSR_WIDE_GROUP_HEIGHT 16
#define DNSR_MOMENT_RADIUS 8
#define DNSR_MAX_SAMPLE_RUN 4096
#define DNSR_RUN_CLAMP_SAMPLES 3
#define DNSR_SPEC_ID_PENUMBRA_GUIDED 0
#define DNSR_SPEC_ID_STABLE_HISTORY 1
#define DNSR_LIGHT_SLOTS 4

#endif
