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
    vec2(-0.73016983, 0.57152957),
    vec2(0.45812374, -0.628413),
    vec2(0.41222113, 0.88432443),
    vec2(-0.78962976, -0.50811446),
    vec2(0.08782339, 0.09335377),
    vec2(0.8671938, 0.040793907),
    vec2(-0.24288976, -0.92215854),
    vec2(-0.4676214, -0.038302336),
    vec2(-0.13383324, 0.7124924),
    vec2(0.600811, 0.43806517),
    vec2(0.022760047, -0.55609477),
    vec2(-0.98746794, -0.025856623),
    vec2(0.46048433, -0.15663359),
    vec2(0.8635472, -0.46826202),
    vec2(0.17558524, 0.47771978),
    vec2(-0.309704, 0.39144704),
    vec2(0.22114787, -0.974006),
    vec2(-0.29191628, -0.41571334),
    vec2(-0.55148834, -0.7660873),
    vec2(-0.49315706, 0.8129603),
    vec2(-0.76662606, 0.23082921),
    vec2(0.05022362, -0.23162988),
    vec2(0.41821447, 0.15686578),
    vec2(0.014310075, 0.97448695),
    vec2(-0.5801198, -0.31073552),
    vec2(-0.1763088, 0.011374758),
    vec2(0.90992755, 0.33054549),
    vec2(0.31374842, -0.3823459),
    vec2(0.66072, 0.73414373),
    vec2(-0.5764465, 0.38075656),
    vec2(-0.9225912, -0.273681),
    vec2(0.75318277, -0.2202439)
);

#endif
