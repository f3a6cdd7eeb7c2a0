#version 450
#define DNSR_PASS_TILE_CLASSIFICATION
#include "dnsr_callbacks_default.glsl"
#include "dnsr_common.glsl"
#include "tile_classification.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
void main() { dnsr_tile_classification(ivec2(gl_WorkGroupID.xy), ivec2(gl_LocalInvocationID.xy)); }
