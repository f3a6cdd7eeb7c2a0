#version 450
#define DNSR_PASS_CLASSIFY
#include "dnsr_callbacks_default.glsl"
#include "dnsr_common.glsl"
#include "classify.glsl"

layout(local_size_x = DNSR_TILE_WIDTH, local_size_y = DNSR_TILE_HEIGHT * DNSR_CLASSIFY_TILES_PER_GROUP) in;
void main() { dnsr_classify(ivec2(gl_WorkGroupID.xy), ivec2(gl_LocalInvocationID.xy)); }
