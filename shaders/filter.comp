#version 450
#define DNSR_PASS_FILTER
#include "dnsr_callbacks_default.glsl"
#include "dnsr_common.glsl"
#include "filter.glsl"

#ifdef DNSR_LATER_PASS
// A later pass shares nothing between invocations, so its groups hold several 8x8 blocks: fewer groups to launch
// where most blocks return at once (cleared tiles).
const ivec2 DNSR_LATER_GROUP_SIZE = ivec2(DNSR_LATER_FILTER_GROUP_WIDTH, DNSR_LATER_FILTER_GROUP_HEIGHT);
layout(local_size_x = DNSR_LATER_FILTER_GROUP_WIDTH, local_size_y = DNSR_LATER_FILTER_GROUP_HEIGHT) in;
void main() {
    ivec2 lid = ivec2(gl_LocalInvocationID.xy);
    ivec2 block = ivec2(gl_WorkGroupID.xy) * (DNSR_LATER_GROUP_SIZE / DNSR_GROUP_SIZE) + lid / DNSR_GROUP_SIZE;
    if (any(greaterThanEqual(block * DNSR_GROUP_SIZE, dnsr_get_extent()))) return;
    dnsr_filter(block, lid % DNSR_GROUP_SIZE);
}
#else
layout(local_size_x = DNSR_GROUP_WIDTH, local_size_y = DNSR_GROUP_HEIGHT) in;
void main() { dnsr_filter(ivec2(gl_WorkGroupID.xy), ivec2(gl_LocalInvocationID.xy)); }
#endif
