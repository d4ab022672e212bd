// The physics stage for one particle (shared by physics.comp and fused.comp): forces
// (gravity, springs with damping, wind cone, Stokes drag) and symplectic Euler. Reads IN(i),
// writes OUT(i): the including shader defines both. For objects whose self-collision uses the
// spatial hash it also counts the new position into its bucket (counts[] were zeroed by the
// previous substep's scan) and records its rank there.
// Include after bindings.glsl and springs.glsl, with IN and OUT defined.
#ifndef MSD_PHYSICS_BODY_GLSL
#define MSD_PHYSICS_BODY_GLSL

// Scales gravity for every object (1 = as the scene says). A knob to try hot reload with:
// edit it while the app runs and the cloth falls faster or slower at once.
const float GRAVITY_SCALE = 1.0;

// The paper's wind: a cone from wind_origin along wind_dir, full force inside the full-force
// half-angle, falling linearly (in the cosine) to zero at the attenuation half-angle.
vec3 wind_force(vec3 x) {
    vec3 to_x = x - g.wind_origin;
    float d = length(to_x);
    if (g.wind_enabled == 0u || d <= 0.0) return vec3(0.0);
    float c = dot(g.wind_dir, to_x / d);
    float ratio;
    if (g.wind_cos_full > g.wind_cos_att) {
        ratio = clamp((c - g.wind_cos_att) / (g.wind_cos_full - g.wind_cos_att), 0.0, 1.0);
    } else {
        ratio = c >= g.wind_cos_full ? 1.0 : 0.0;
    }
    return g.wind_dir * (g.wind_force * ratio);
}

// The first pass of the spatial hash: take a rank in the bucket of the new position.
void count_into_bucket(uint i, vec3 x_new) {
    if ((obj.flags & OBJ_SELF_HASH) == 0u) return;
    uint h = cell_hash(ivec3(floor(x_new * obj.cell_inv)), obj.hash_mask);
    cell_rank[i] = uvec2(h, atomicAdd(counts[h], 1u));
}

void physics_particle(uvec2 cell) {
    uint i = cell.x + cell.y * obj.dims.x;
    Particle p = IN(i);
    if (p.pos.w > 0.5) {  // pinned: keep the position, no velocity
        OUT(i) = Particle(p.pos, vec4(0.0));
        count_into_bucket(i, p.pos.xyz);
        return;
    }
    vec3 x = p.pos.xyz;
    vec3 v = p.vel.xyz;

    vec3 force = obj.mass * GRAVITY_SCALE * g.gravity + wind_force(x) - obj.drag * v;
    for (int s = 0; s < 12; ++s) {
        ivec3 spring = SPRINGS[s];
        float k = obj.stiffness[spring.z];
        if (k == 0.0 && obj.stiffness.w == 0.0) continue;
        int j = neighbour(ivec2(cell), spring.xy, obj.dims);
        if (j < 0) continue;
        vec3 to_j = IN(j).pos.xyz - x;
        float d = length(to_j);
        if (d <= 0.0) continue;
        vec3 dir = to_j / d;
        float rest = rest_length(spring, obj.spacing, obj.rest_scale);
        float damping = obj.stiffness.w * dot(IN(j).vel.xyz - v, dir);
        force += (k * (d - rest) + damping) * dir;  // Hooke's law plus a dashpot along the spring
    }

    vec3 v_new = v + force * (g.dt / obj.mass);
    vec3 x_new = x + v_new * g.dt;
    OUT(i) = Particle(vec4(x_new, 0.0), vec4(v_new, 0.0));
    count_into_bucket(i, x_new);
}

#endif
