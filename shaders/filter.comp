#version 450
#define DNSR_PASS_FILTER
#include "dnsr_callbacks_default.glsl"
#include "dnsr_common.glsl"
#include "filter.glsl"

layout(local_size_x = DNSR_WIDE_GROUP_WIDTH, local_size_y = DNSR_WIDE_GROUP_HEIGHT) in;
#if defined(DNSR_LIGHT_SLOTS_VARIANT) && defined(DNSR_LATER_PASS)
void main() { dnsr_filter_lights(ivec2(gl_WorkGroupID.xy), ivec2(gl_LocalInvocationID.xy)); }
#else
void main() { dnsr_filter(ivec2(gl_WorkGroupID.xy), ivec2(gl_LocalInvocationID.xy)); }
#endif
