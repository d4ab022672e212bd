#version 460
#extension GL_GOOGLE_include_directive : require
// Scene meshes: simulation surfaces (SurfaceVertex straight from the compute buffers) and
// primitive meshes share one vertex layout: vec4 position, vec4 normal.
#include "render.glsl"

layout(location = 0) in vec4 in_pos;
layout(location = 1) in vec4 in_normal;
layout(location = 0) out vec3 world_pos;
layout(location = 1) out vec3 world_normal;

// The ground shadow (draw.params.y = 1): the point flattened onto the ground plane y =
// draw.params.z along the ray from the light, lifted 2 mm so it lies over the grid. The host
// draws shadows only with the light above the ground; points near or above the light's height
// go at most 20 times their distance from the light (they cast no shadow in truth).
vec4 on_ground(vec4 w) {
    vec3 light = cam.light_pos.xyz;
    float t = min((light.y - draw.params.z) / max(light.y - w.y, 1e-3), 20.0);
    vec3 s = light + (w.xyz - light) * t;
    return vec4(s.x, draw.params.z + 0.002, s.z, 1.0);
}

void main() {
    vec4 w = draw.model * vec4(in_pos.xyz, 1.0);
    if (draw.params.y > 0.5) w = on_ground(w);
    world_pos = w.xyz;
    world_normal = mat3(draw.model) * in_normal.xyz;
    gl_Position = cam.view_proj * w;
}
