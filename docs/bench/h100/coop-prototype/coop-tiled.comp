#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
// EXPERIMENT: every substep of a frame for one cloth in one dispatch of one workgroup per
// 16 x 16 tile, which meet at a grid barrier between the physics and the constraints. Each
// phase first copies its tile and a border of 2 into shared memory (coherent loads, one or two
// a thread), and the springs read their other ends there. Explicit methods, no self-collision.
#define STATE_COOP
#include "bindings.glsl"
#define SPRING_NEIGHBOUR(cell, s) tile_neighbour(cell, s)
#include "springs.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

const int REACH = 2;
const int TW = 20;
shared vec4 tile_x[TW * TW];
shared vec4 tile_v[TW * TW];
int tile_neighbour(uvec2 cell, int s) {
    if (neighbour(ivec2(cell), SPRINGS[s].xy, obj.dims) < 0) return -1;
    ivec2 t = ivec2(gl_LocalInvocationID.xy) + REACH + SPRINGS[s].xy;
    return t.x + t.y * TW;
}

#define NPOS(j) tile_x[j].xyz
#define NVEL(j) tile_v[j].xyz
#define CPOS(j) tile_x[j].xyz
#define CPINNED(j) (tile_x[j].w > 0.5)
#define IN(i) p_in[i]
#define OUT(i) p_out[i]
#include "physics_body.glsl"
#undef IN
#undef OUT
#define IN(i) p_out[i]
#define OUT(i) p_in[i]
#include "constraints_body.glsl"

uint sync_phase = 0u;
void grid_sync() {
    sync_phase += 1u;
    memoryBarrierBuffer();
    barrier();
    if (gl_LocalInvocationIndex == 0u) {
        atomicAdd(self_list[0], 1u);
        uint want = sync_phase * gl_NumWorkGroups.x * gl_NumWorkGroups.y;
        while (atomicAdd(self_list[0], 0u) < want) {}
    }
    barrier();
    memoryBarrierBuffer();
}

// The tile and its border from `from_b` (else p_in): positions (drifted by `drift` times the
// velocity, w the pinned flag) and velocities.
void load_tile(bool from_b, float drift) {
    ivec2 origin = ivec2(gl_WorkGroupID.xy * gl_WorkGroupSize.xy) - REACH;
    for (uint t = gl_LocalInvocationIndex; t < uint(TW * TW); t += 256u) {
        ivec2 c = origin + ivec2(int(t) % TW, int(t) / TW);
        if (c.x >= 0 && c.y >= 0 && c.x < int(obj.dims.x) && c.y < int(obj.dims.y)) {
            uint i = uint(c.x + c.y * int(obj.dims.x));
            vec4 pos = from_b ? p_out[i].pos : p_in[i].pos;
            vec4 vel = from_b ? p_out[i].vel : p_in[i].vel;
            tile_x[t] = vec4(pos.xyz + drift * vel.xyz, pos.w);
            tile_v[t] = vel;
        }
    }
    barrier();
}

void main() {
    uvec2 cell = gl_GlobalInvocationID.xy;
    bool inside = cell.x < obj.dims.x && cell.y < obj.dims.y;
    for (uint s = 0u; s < g.substeps; ++s) {
        load_tile(false, physics_drift());
        if (inside) physics_particle(cell, s, false);
        grid_sync();
        load_tile(true, 0.0);
        if (inside) constraints_particle(cell, s, false);
        grid_sync();
    }
}
