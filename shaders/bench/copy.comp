#version 450
// dnsr-bench's copy kernel: the device's copy roofline. Each invocation copies one 16-byte element from a
// storage buffer to another (coalesced, no reuse), over a 2D grid of 256-wide groups so that large copies stay
// within maxComputeWorkGroupCount. Bytes moved = read + write = 2 * 16 * count.
// Compiled by `make shaders` (DNSR_BLESS=1 cargo test bless_) to shaders/bench/copy.spv.

layout(local_size_x = 256) in;

layout(set = 0, binding = 0, std430) readonly buffer Source { uvec4 src[]; };
layout(set = 0, binding = 1, std430) writeonly buffer Destination { uvec4 dst[]; };
layout(push_constant) uniform Push { uint count; } push;

void main() {
    uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    uint i = group * 256u + gl_LocalInvocationID.x;
    if (i < push.count) dst[i] = src[i];
}
