#version 460
#extension GL_GOOGLE_include_directive : require
// Double-sided Blinn-Phong: the side facing along the normal gets `front`, the other `back`,
// each lit with the normal turned towards the viewer. Output is gamma-encoded (UNORM target).
#include "render.glsl"

layout(location = 0) in vec3 world_pos;
layout(location = 1) in vec3 world_normal;
layout(location = 0) out vec4 out_color;

void main() {
    if (draw.params.y > 0.5) {  // a ground shadow: the floor's colour (draw.front) darkened,
        // blended by keeping the darker (overlapping layers darken once)
        out_color = vec4(pow(clamp(draw.front.rgb, 0.0, 1.0), vec3(1.0 / 2.2)) * 0.65, 1.0);
        return;
    }
    vec3 to_eye = normalize(cam.eye.xyz - world_pos);
    float len = length(world_normal);
    vec3 n = len > 1e-8 ? world_normal / len : to_eye;
    bool front = dot(n, to_eye) >= 0.0;
    vec3 base = front ? draw.front.rgb : draw.back.rgb;
    vec3 c = base;
    if (draw.params.x > 0.5) {
        if (!front) n = -n;
        vec3 l = normalize(cam.light_pos.xyz - world_pos);
        vec3 h = normalize(l + to_eye);
        float diffuse = max(dot(n, l), 0.0);
        float specular = diffuse > 0.0 ? 0.35 * pow(max(dot(n, h), 0.0), 48.0) : 0.0;
        c = base * (cam.light_color.w + diffuse * cam.light_color.rgb) + specular * cam.light_color.rgb;
    }
    out_color = vec4(pow(clamp(c, 0.0, 1.0), vec3(1.0 / 2.2)), 1.0);
}
