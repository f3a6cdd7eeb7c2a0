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
    vec4 moving;
    vec4 penumbra;
    vec4 light_position;
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
#define DNSR_FLAG_LIGHT_POSITION 16u
#define DNSR_PASS_WRITE_INTERNAL 1u
#define DNSR_PASS_SKIP_CLEARED 2u
#define DNSR_TILE_CLEARED 1u
#define DNSR_TILE_LIT 2u
#define DNSR_DEBUG_VIEW_NONE 0u
#define DNSR_DEBUG_VIEW_TILE_CLASSIFICATION 1u
#define DNSR_DEBUG_VIEW_SAMPLE_COUNT 2u
#define DNSR_DEBUG_VIEW_VARIANCE 3u
#define DNSR_DEBUG_VIEW_DISOCCLUSION 4u
#define DNSR_DEBUG_VIEW_SAMPLE_RUN 5u
#define DNSR_CLASSIFY_REJECT_LIT 1u
#define DNSR_CLASSIFY_BOUND_INTERVAL 2u
#define DNSR_CLASSIFY_CASCADES_INVERTED 4u

#define DNSR_TILE_WIDTH 8
#define DNSR_TILE_HEIGHT 4
#define DNSR_GROUP_WIDTH 8
#define DNSR_GROUP_HEIGHT 8
#define DNSR_WIDE_GROUP_WIDTH 16
#define DNSR_WIDE_GROUP_HEIGHT 16
#define DNSR_CLASSIFY_TILES_PER_GROUP 4
#define DNSR_MOMENT_RADIUS 8
#define DNSR_SURFACE_NORMAL_SCALE 511
#define DNSR_SURFACE_DOT_MIN 208897
#define DNSR_SURFACE_SUM_SCALE 2048
#define DNSR_MAX_SAMPLE_RUN 127
#define DNSR_RUN_CLAMP_SAMPLES 3
#define DNSR_UNCONVERGED_VARIANCE_INV 1000000
#define DNSR_UNCONVERGED_VARIANCE_INV_FP16 16384
#define DNSR_SIGNAL_MAX_DEVIATION_CODE 65000
#define DNSR_SIGNAL_SKY_CODE_ABOVE 65500
#define DNSR_DEPTH_CODE_BITS 16
#define DNSR_DEPTH_CODE_MANTISSA_BITS 10
#define DNSR_DEPTH_CODE_SHIFT 13
#define DNSR_DEPTH_CODE_OFFSET 113664
#define DNSR_DEPTH_COPY_NORMAL_BITS 8
#define DNSR_TURNED_NORMAL_COS_PERCENT 80
#define DNSR_PLANE_LINE_COS2_PERCENT 98
#define DNSR_FOOTPRINT_SLOPE_PERCENT 50
#define DNSR_FOOTPRINT_MAX_SLOPE 16
#define DNSR_MOMENTS_MEAN_BITS 14
#define DNSR_MOMENTS_COUNT_BITS 9
#define DNSR_MOMENTS_MEAN_MAX 16383
#define DNSR_COUNT_MANTISSA_BITS 5
#define DNSR_COUNT_SUBNORMAL_SCALE 4096
#define DNSR_COUNT_CODE_OFFSET 3808
#define DNSR_COUNT_MAX 252
#define DNSR_HARD_PENUMBRA_MIN_BLOCKER_PIXELS 2
#define DNSR_SPEC_ID_PENUMBRA_GUIDED 0
#define DNSR_SPEC_ID_STABLE_HISTORY 1
#define DNSR_SPEC_ID_MOVING_SHADOWS 3
#define DNSR_MOVING_SAMPLE_UNIT 1024
#define DNSR_MOVING_MARGIN_SAMPLES 2
#define DNSR_STILL_MOTION_INV_PIXELS 100
#define DNSR_MAX_QUIET_FRAMES 255
#define DNSR_MIXED_TEXEL_SAMPLES 8
#define DNSR_MIXED_TEXEL_SPREAD_PERCENT 25
#define DNSR_SPEC_ID_HARD_LIGHT 2
#define DNSR_LIGHT_SLOTS 4
#define DNSR_MAX_CASCADES 4
#define DNSR_MAX_CLASSIFY_TAPS 32

#define DNSR_CLASSIFY_MAX_SLOPE 4.0
const vec2 DNSR_CLASSIFY_DISC[DNSR_MAX_CLASSIFY_TAPS] = vec2[](
    vec2(0.0, 0.0),
    vec2(-0.80352205, -0.32264578),
    vec2(0.1899787, 0.75445276),
    vec2(0.66958874, -0.33623844),
    vec2(-0.6061607, 0.39278564),
    vec2(0.045295916, -0.88552225),
    vec2(0.68173, 0.16866235),
    vec2(-0.24923642, -0.46602866),
    vec2(-0.2440143, 0.7435986),
    vec2(-0.21781887, 0.046659984),
    vec2(0.15844338, -0.2305185),
    vec2(0.11214537, 0.17575073),
    vec2(0.59951264, 0.64105415),
    vec2(-0.712019, 0.06347498),
    vec2(0.53382665, -0.72580075),
    vec2(-0.074292034, 0.18129689),
    vec2(0.31526312, -0.053268433),
    vec2(-0.672386, -0.6307698),
    vec2(-0.07248488, -0.11212872),
    vec2(0.013155183, -0.38255104),
    vec2(0.98434, -0.14768286),
    vec2(-0.33690998, -0.20026568),
    vec2(0.28896633, 0.10944872),
    vec2(-0.5150281, 0.6525388),
    vec2(0.07316293, -0.040920716),
    vec2(0.032734636, 0.3986818),
    vec2(0.3237559, -0.9264969),
    vec2(-0.26177245, 0.28654727),
    vec2(0.8089674, 0.4750947),
    vec2(-0.25521973, -0.90316457),
    vec2(-0.04897184, 0.9788837),
    vec2(-0.9284752, 0.33165452)
);

#endif
