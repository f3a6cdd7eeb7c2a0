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

struct DnsrClassifyConstants {
    mat4 cascade0;
    mat4 cascade1;
    mat4 cascade2;
    mat4 cascade3;
    mat4 cascade_units;
    mat4 cascade_axes_u;
    mat4 cascade_axes_v;
    vec4 light;
    uvec4 settings;
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
#define DNSR_CLASSIFY_REJECT_LIT 1u
#define DNSR_CLASSIFY_BOUND_INTERVAL 2u
#define DNSR_CLASSIFY_CASCADES_INVERTED 4u

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
#define DNSR_MAX_CASCADES 4
#define DNSR_MAX_CLASSIFY_TAPS 32

#define DNSR_CLASSIFY_MAX_SLOPE 4.0
const vec2 DNSR_CLASSIFY_DISC[DNSR_MAX_CLASSIFY_TAPS] = vec2[](
    vec2(0.0, 0.0),
    vec2(-0.8635132, -0.34673458),
    vec2(0.21538423, 0.8553444),
    vec2(0.7735511, -0.3884438),
    vec2(-0.71323097, 0.46216604),
    vec2(0.048103385, -0.94040734),
    vec2(0.8134971, 0.201262),
    vec2(-0.34284136, -0.64105356),
    vec2(-0.2758303, 0.8405533),
    vec2(-0.46150506, 0.09886113),
    vec2(0.29957983, -0.4358573),
    vec2(0.24561036, 0.3849129),
    vec2(0.6399176, 0.68425894),
    vec2(-0.84214395, 0.07507535),
    vec2(0.56239784, -0.7646467),
    vec2(-0.16783935, 0.4095829),
    vec2(0.55754554, -0.09420567),
    vec2(-0.7002729, -0.6569307),
    vec2(-0.19837111, -0.30686536),
    vec2(0.021262968, -0.6183244),
    vec2(0.9866332, -0.1480269),
    vec2(-0.53815293, -0.3198883),
    vec2(0.5198386, 0.19689377),
    vec2(-0.5648744, 0.7156938),
    vec2(0.25269327, -0.14133373),
    vec2(0.051756494, 0.6303528),
    vec2(0.32680365, -0.9352188),
    vec2(-0.42018747, 0.45995507),
    vec2(0.83520424, 0.4905032),
    vec2(-0.26344475, -0.93227106),
    vec2(-0.049466304, 0.9887674),
    vec2(-0.93507606, 0.33401236)
);

#endif
