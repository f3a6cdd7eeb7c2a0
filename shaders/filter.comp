#version 450
#define DNSR_PASS_FILTER
#include "dnsr_callbacks_default.glsl"
#include "dnsr_common.glsl"
#include "filter.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
void main() { dnsr_filter(ivec2(gl_WorkGroupID.xy), ivec2(gl_LocalInvocationID.xy)); }
