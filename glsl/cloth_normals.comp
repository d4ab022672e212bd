#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
// Surface stage for cloth, once per frame after the last substep: angle-weighted smoothed
// normals from the final positions, and the runtime guard. Reads p_in (the state buffer),
// writes surface[] and the guard (with the contact lists' counters, lists.glsl); with DRAWN
// off (nothing draws the cloth), only the guard.
#include "bindings.glsl"
#include "springs.glsl"
#include "lists.glsl"

layout(local_size_x = 16, local_size_y = 16, local_size_z = 1) in;
layout(constant_id = 0) const bool DRAWN = true;

void main() {
    uvec2 cell = gl_GlobalInvocationID.xy;
    if (cell.x >= obj.dims.x || cell.y >= obj.dims.y) return;
    uint i = cell.x + cell.y * obj.dims.x;
    guard_check(i, p_in[i]);
    guard_strain(cell);
    if (i == 0u) report_lists();
    if (!DRAWN) return;
    vec3 x = p_in[i].pos.xyz;
    if (is_mesh()) {
        // A mesh cloth's: its triangles' normals about it, weighted by their areas.
        vec3 sum = vec3(0.0);
        for (uint k = mesh_ring_first(i); k < mesh_ring_first(i + 1u); ++k) {
            uvec3 t = mesh_triangle(mesh_ring_triangle(k));
            vec3 a = p_in[t.x].pos.xyz;
            sum += cross(p_in[t.y].pos.xyz - a, p_in[t.z].pos.xyz - a);
        }
        float len = length(sum);
        surface[i] = SurfaceVertex(vec4(x, 1.0), vec4(len > 0.0 ? sum / len : vec3(0.0, 0.0, 1.0), 0.0));
        return;
    }

    // Edges to the structural neighbours in turning order (+column, -row, -column, +row); each
    // consecutive pair that exists contributes its unit cross product weighted by the angle
    // between the two edges. With this order the normal of a vertical cloth (rows going down)
    // points to +z and that of a horizontal one (rows along +z) points up.
    const ivec2 ring[4] = ivec2[4](ivec2(1, 0), ivec2(0, -1), ivec2(-1, 0), ivec2(0, 1));
    vec3 edge[4];
    bool has[4];
    for (int k = 0; k < 4; ++k) {
        int j = neighbour(ivec2(cell), ring[k], obj.dims);
        has[k] = j >= 0;
        edge[k] = has[k] ? p_in[j].pos.xyz - x : vec3(0.0);
        float len = length(edge[k]);
        has[k] = has[k] && len > 0.0;
        edge[k] = has[k] ? edge[k] / len : vec3(0.0);
    }
    vec3 sum = vec3(0.0);
    for (int k = 0; k < 4; ++k) {
        int l = (k + 1) % 4;
        if (!has[k] || !has[l]) continue;
        vec3 c = cross(edge[k], edge[l]);
        float len = length(c);
        if (len <= 0.0) continue;
        float angle = acos(clamp(dot(edge[k], edge[l]), -1.0, 1.0));
        sum += c / len * angle;
    }
    float len = length(sum);
    vec3 n = len > 0.0 ? sum / len : vec3(0.0, 0.0, 1.0);
    surface[i] = SurfaceVertex(vec4(x, 1.0), vec4(n, 0.0));
}
