#version 450
#define DNSR_PASS_TILE_CLASSIFICATION
#include "dnsr_callbacks_default.glsl"
#include "dnsr_common.glsl"
#include "tile_classification.glsl"

layout(local_size_x = DNSR_WIDE_GROUP_WIDTH, local_size_y = DNSR_WIDE_GROUP_HEIGHT) in;
void main() { dnsr_tile_classification(ivec2(gl_WorkGroupID.xy), ivec2(gl_LocalInvocationID.xy)); }
