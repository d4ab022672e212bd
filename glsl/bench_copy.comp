#version 460
// Bandwidth probe for `msdsim bench`: copies one buffer of vec4 into another. Its measured
// bytes per second are the roofline the simulation stages are compared with.

layout(local_size_x = 256) in;
layout(std430, set = 0, binding = 0) readonly buffer Src { vec4 src[]; };
layout(std430, set = 0, binding = 1) writeonly buffer Dst { vec4 dst[]; };

void main() {
    uint i = gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * 256u;
    if (i < uint(src.length())) dst[i] = src[i];
}
