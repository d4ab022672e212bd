// The constraint stage for one particle (shared by constraints.comp and fused.comp), Jacobi:
// every correction is computed from IN, the physics output: the stretch limit on structural and
// shear springs, self-collision (spatial hash or brute force), then sphere colliders with
// friction, and the velocity update. Writes OUT(i). The corrections of all active constraints of
// a particle are averaged (Jacobi averaging): summing them, as sequential Gauss-Seidel would,
// overshoots when several act at once and diverges.
// Include after bindings.glsl and springs.glsl, with IN and OUT defined.
#ifndef MSD_CONSTRAINTS_BODY_GLSL
#define MSD_CONSTRAINTS_BODY_GLSL

bool pinned_in(uint j) { return IN(j).pos.w > 0.5; }

// Adds the push from particle j when it is within `reach` of x (and not a rest-state neighbour).
void self_contact(uvec2 cell, vec3 x, uint j, float reach, inout vec3 correction, inout uint n_active) {
    ivec2 other = ivec2(int(j % obj.dims.x), int(j / obj.dims.x));
    vec2 rest = vec2(other - ivec2(cell)) * obj.spacing;
    if (dot(rest, rest) < reach * reach) return;  // includes j == this particle
    vec3 to_j = IN(j).pos.xyz - x;
    float d = length(to_j);
    if (d < reach && d > 0.0) {
        correction += (to_j / d) * ((d - reach) * (pinned_in(j) ? 1.0 : 0.5));
        n_active += 1u;
    }
}

void constraints_particle(uvec2 cell) {
    uint i = cell.x + cell.y * obj.dims.x;
    Particle p = IN(i);
    if (p.pos.w > 0.5) {
        OUT(i) = Particle(p.pos, vec4(0.0));
        return;
    }
    vec3 x = p.pos.xyz;
    vec3 v = p.vel.xyz;
    vec3 correction = vec3(0.0);
    uint n_active = 0u;

    // Springs may not stretch past (1 + stretch_limit) * rest: each end moves half the excess
    // (all of it when the other end is pinned).
    if ((obj.flags & OBJ_STRETCH_LIMIT) != 0u) {
        for (int s = 0; s < 8; ++s) {
            ivec3 spring = SPRINGS[s];
            int j = neighbour(ivec2(cell), spring.xy, obj.dims);
            if (j < 0 || obj.stiffness[spring.z] == 0.0) continue;
            vec3 to_j = IN(j).pos.xyz - x;
            float d = length(to_j);
            float excess = d - rest_length(spring, obj.spacing, obj.rest_scale) * (1.0 + obj.stretch_limit);
            if (excess > 0.0) {
                correction += (to_j / d) * (excess * (pinned_in(uint(j)) ? 1.0 : 0.5));
                n_active += 1u;
            }
        }
    }

    // Self-collision: particles closer than self_distance push apart, except pairs that are
    // closer than that in the rest state (grid neighbours), which the springs already keep.
    // Candidates come from the spatial hash (the 27 cells around this one) or, as the reference,
    // from every particle.
    if ((obj.flags & OBJ_SELF_COLLISION) != 0u) {
        float reach = obj.self_distance;
        if ((obj.flags & OBJ_SELF_HASH) != 0u) {
            // Cells are 2 * reach wide, so every particle within reach lies in the 2 x 2 x 2
            // block of cells nearest to x. Buckets two cells share are visited once.
            ivec3 base = ivec3(floor(x * obj.cell_inv - 0.5));
            uint seen[8];
            for (int c = 0; c < 8; ++c) {
                uint h = cell_hash(base + ivec3(c & 1, (c >> 1) & 1, c >> 2), obj.hash_mask);
                seen[c] = h;
                bool again = false;
                for (int k = 0; k < c; ++k) again = again || seen[k] == h;
                if (again) continue;
                uint end = starts[h + 1u];
                for (uint at = starts[h]; at < end; ++at) {
                    vec4 e = sorted[at];
                    if (distance(e.xyz, x) < reach) {
                        self_contact(cell, x, floatBitsToUint(e.w), reach, correction, n_active);
                    }
                }
            }
        } else {
            uint n = particle_count();
            for (uint j = 0u; j < n; ++j) self_contact(cell, x, j, reach, correction, n_active);
        }
    }

    if (n_active > 1u) correction /= float(n_active);
    x += correction;
    v += correction / g.dt;  // velocity follows the position correction

    // Sphere colliders: project out to radius + margin, remove the approaching normal velocity,
    // scale the tangential velocity by (1 - friction).
    for (uint s = 0u; s < g.sphere_count; ++s) {
        vec3 c = spheres[s].xyz;
        float reach = spheres[s].w + obj.margin;
        vec3 from_c = x - c;
        float d = length(from_c);
        if (d < reach) {
            vec3 n = d > 0.0 ? from_c / d : vec3(0.0, 1.0, 0.0);
            x = c + n * reach;
            float vn = dot(v, n);
            vec3 vt = v - vn * n;
            v = vt * (1.0 - obj.friction) + max(vn, 0.0) * n;
        }
    }

    OUT(i) = Particle(vec4(x, 0.0), vec4(v, 0.0));
}

#endif
