#version 460
#extension GL_GOOGLE_include_directive : require
// Scene meshes: simulation surfaces (SurfaceVertex straight from the compute buffers) and
// primitive meshes share one vertex layout: vec4 position, vec4 normal.
#include "render.glsl"

layout(location = 0) in vec4 in_pos;
layout(location = 1) in vec4 in_normal;
layout(location = 0) out vec3 world_pos;
layout(location = 1) out vec3 world_normal;

void main() {
    vec4 w = draw.model * vec4(in_pos.xyz, 1.0);
    world_pos = w.xyz;
    world_normal = mat3(draw.model) * in_normal.xyz;
    gl_Position = cam.view_proj * w;
}
