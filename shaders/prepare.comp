#version 450
#define DNSR_PASS_PREPARE
#include "dnsr_callbacks_default.glsl"
#include "dnsr_common.glsl"
#include "prepare.glsl"

#ifdef DNSR_CHECKERBOARD_INPUT
layout(local_size_x = DNSR_WIDE_GROUP_WIDTH, local_size_y = DNSR_WIDE_GROUP_HEIGHT) in;
void main() { dnsr_prepare_checkerboard(ivec2(gl_GlobalInvocationID.xy), ivec2(gl_LocalInvocationID.xy)); }
#else
layout(local_size_x = DNSR_GROUP_WIDTH, local_size_y = DNSR_GROUP_HEIGHT) in;
void main() { dnsr_prepare(ivec2(gl_GlobalInvocationID.xy)); }
#endif
