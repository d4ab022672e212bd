// The collider types (sim::collider: one row of KINDS and one Shape variant each, whose
// `distance` is the CPU twin of collider_distance here) and the contact response they share.
// A type the scene does not use is compiled out by its feature bit (features.glsl).
// Include after bindings.glsl.
#ifndef MSD_COLLIDERS_GLSL
#define MSD_COLLIDERS_GLSL
#include "features.glsl"
#include "triangle.glsl"

// Type ids (ColliderKind's glsl_id; checked by tests/suite/layout.rs).
#define COLLIDER_SPHERE 0u
#define COLLIDER_GROUND 1u
#define COLLIDER_BOX 2u
#define COLLIDER_CAPSULE 3u
#define COLLIDER_MESH 4u

// Rotates v by the unit quaternion q (xyz vector part, w scalar).
vec3 rotate(vec4 q, vec3 v) {
    vec3 t = 2.0 * cross(q.xyz, v);
    return v + q.w * t + cross(q.xyz, t);
}

float sign_of(float x) { return x >= 0.0 ? 1.0 : -1.0; }

float position_slack(vec3 x);

// Unsigned word k of the collider buffer's vec4s from vec4 `at` on.
uint collider_word(uint at, uint k) { return floatBitsToUint(collider_words[at + (k >> 2u)][k & 3u]); }

// Signed distance from x to mesh collider c's triangles and the outward normal, less its
// thickness (sim::collider_mesh::ColliderMesh::distance, which says how): c.a xyz its centre,
// c.rotation its turn, c.b x its first vec4 (a header: the grid's origin and cell; its dims
// and reach), y and z where its items and triangles start from there (these offsets and the
// dims as float values), w its thickness. Only triangles within the reach count; where none
// is, a lower bound of at least the reach.
float mesh_distance(Collider c, vec3 x, out vec3 n) {
    vec3 p = rotate(vec4(-c.rotation.xyz, c.rotation.w), x - c.a.xyz);
    uint base = uint(c.b.x);
    vec4 h0 = collider_words[base];
    vec4 h1 = collider_words[base + 1u];
    uvec3 dims = uvec3(h1.xyz);
    float reach = h1.w;
    vec3 q = (p - h0.xyz) / h0.w;
    n = rotate(c.rotation, vec3(0.0, 1.0, 0.0));
    // (written so that a NaN position is outside: its cell would be any)
    if (!(all(greaterThanEqual(q, vec3(0.0))) && all(lessThan(q, vec3(dims))))) {
        vec3 out_of = max(max(h0.xyz - p, p - (h0.xyz + vec3(dims) * h0.w)), vec3(0.0));
        return max(length(out_of), reach) - c.b.w;
    }
    uvec3 cq = uvec3(q);
    uint cell = cq.x + dims.x * (cq.y + dims.y * cq.z);
    uint items = base + uint(c.b.y);
    uint triangles = base + uint(c.b.z);
    uint last = collider_word(base + 2u, cell + 1u);
    float best = reach;
    float best_d = 1e30;
    float best_square = 0.0;
    vec3 best_n = vec3(0.0, 1.0, 0.0);
    // Distances within a few f32 steps count as equal (the CPU twin's `tie`).
    float tie = position_slack(p) + position_slack(c.a.xyz);
    for (uint k = collider_word(base + 2u, cell); k < last; ++k) {
        uint t = triangles + 3u * collider_word(items, k);
        vec3 ta = collider_words[t].xyz;
        vec3 tb = collider_words[t + 1u].xyz;
        vec3 tc = collider_words[t + 2u].xyz;
        vec3 w = triangle_nearest(p, ta, tb, tc);
        vec3 off = p - (w.x * ta + w.y * tb + w.z * tc);
        float d = length(off);
        if (d > reach) continue;
        vec3 face = normalize(cross(tb - ta, tc - ta));
        // How squarely in front of (or behind) the triangle p is decides a tie.
        float square = d > 0.0 ? abs(dot(off, face)) / d : 1.0;
        if (d < best_d - tie || (d <= best_d + tie && square > best_square)) {
            float side = dot(off, face) >= 0.0 ? 1.0 : -1.0;
            best = side * d;
            best_n = d > 1e-12 ? off * (side / d) : face;
            best_d = d;
            best_square = square;
        }
    }
    n = rotate(c.rotation, best_n);
    return best - c.b.w;
}

// Signed distance from x to collider c's surface (negative inside) and the outward normal.
float collider_distance(Collider c, vec3 x, out vec3 n) {
    uint kind = floatBitsToUint(c.a.w);
    n = vec3(0.0, 1.0, 0.0);
    if (has(F_SPHERES) && kind == COLLIDER_SPHERE) {
        vec3 from_c = x - c.a.xyz;
        float d = length(from_c);
        if (d > 0.0) n = from_c / d;
        return d - c.b.w;
    }
    if (has(F_GROUND) && kind == COLLIDER_GROUND) {
        return x.y - c.a.y;
    }
    if (has(F_BOX) && kind == COLLIDER_BOX) {
        vec4 inv = vec4(-c.rotation.xyz, c.rotation.w);
        vec3 local = rotate(inv, x - c.a.xyz);
        vec3 q = abs(local) - c.b.xyz;
        vec3 outside = max(q, vec3(0.0));
        vec3 s = vec3(sign_of(local.x), sign_of(local.y), sign_of(local.z));
        float out_d = length(outside);
        if (out_d > 0.0) {
            n = rotate(c.rotation, s * outside / out_d);
            return out_d;
        }
        // Inside: out through the nearest face.
        vec3 axis = q.x >= q.y && q.x >= q.z ? vec3(1.0, 0.0, 0.0) : (q.y >= q.z ? vec3(0.0, 1.0, 0.0) : vec3(0.0, 0.0, 1.0));
        n = rotate(c.rotation, axis * s);
        return dot(q, axis);
    }
    if (has(F_CAPSULE) && kind == COLLIDER_CAPSULE) {
        vec3 ab = c.b.xyz - c.a.xyz;
        float len2 = dot(ab, ab);
        float t = len2 > 0.0 ? clamp(dot(x - c.a.xyz, ab) / len2, 0.0, 1.0) : 0.0;
        vec3 from_p = x - (c.a.xyz + ab * t);
        float d = length(from_p);
        if (d > 0.0) {
            n = from_p / d;
        } else {
            // On the axis: any direction across it.
            vec3 other = abs(ab.x) < 0.9 * sqrt(len2) ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
            n = normalize(cross(ab, other));
        }
        return d - c.b.w;
    }
    if (has(F_MESH) && kind == COLLIDER_MESH) return mesh_distance(c, x, n);
    return 1e30;  // a type compiled out
}

// The point collider c turns about, where it is at the frame's start: its centre, a
// capsule's midpoint (sim::collider::Shape::reference_point).
vec3 collider_centre(Collider c) {
    return floatBitsToUint(c.a.w) == COLLIDER_CAPSULE ? 0.5 * (c.a.xyz + c.b.xyz) : c.a.xyz;
}

// Where collider c is `since` after the frame's start (sim::collider::Pose): moved by its
// velocity (`shift`) and turned by its spin about its centre (`centre`: where it is at the
// frame's start), the turn kept as the rotation `back` that takes a point back into the
// frame's start, where the record places the collider. Taken once a collider and substep;
// the turn is compiled in only where some collider turns (F_TURNING), and there one that does
// not pays one compare a test.
struct ColliderPose {
    vec3 velocity;
    vec3 shift;
    vec3 spin;
    vec3 centre;
    vec4 back;
};

ColliderPose collider_pose(Collider c, float since) {
    ColliderPose p;
    p.velocity = c.extra.yzw;
    p.shift = p.velocity * since;
    p.spin = has(F_TURNING) ? c.spin.xyz : vec3(0.0);
    p.centre = vec3(0.0);
    p.back = vec4(0.0, 0.0, 0.0, 1.0);
    if (p.spin != vec3(0.0)) {
        p.centre = collider_centre(c);
        vec3 turn = p.spin * since;
        float angle = length(turn);
        if (angle > 0.0) p.back = vec4(turn * (-sin(0.5 * angle) / angle), cos(0.5 * angle));
    }
    return p;
}

// The signed distance from x to collider c's surface at pose `p` and the outward normal `n`
// (sim::collider::ColliderModel::distance_at): the point taken back into the frame's start,
// the normal forward.
float collider_distance_at(Collider c, ColliderPose p, vec3 x, out vec3 n) {
    if (p.spin == vec3(0.0)) return collider_distance(c, x - p.shift, n);
    vec3 r = x - p.shift - p.centre;
    float d = collider_distance(c, p.centre + rotate(p.back, r), n);
    n = rotate(vec4(-p.back.xyz, p.back.w), n);
    return d;
}

// The velocity of collider c's surface at x at pose `p`: its own plus its spin's about its
// centre (sim::collider::ColliderModel::surface_velocity).
vec3 collider_surface_velocity(ColliderPose p, vec3 x) {
    return p.spin == vec3(0.0) ? p.velocity : p.velocity + cross(p.spin, x - p.shift - p.centre);
}

// A few f32 steps of a position near x [m]: 5e-7 (1 + its largest coordinate).
float position_slack(vec3 x) {
    vec3 a = abs(x);
    return 5e-7 * (1.0 + max(a.x, max(a.y, a.z)));
}

// The response to a collider moving at `velocity` that a particle at x is `depth` inside of
// the object's margin along the surface normal n: projected out to the margin and its
// approaching normal velocity removed, both relative to the collider; then Coulomb friction
// with coefficient mu: the contact's normal impulse per unit mass this substep is jn =
// max(approaching speed, depth / dt) (what the projection removed: the speed, or for an
// overlap the approach does not explain, a squeeze, the depth over the substep), and the
// tangential impulse is at most mu jn. Static when the particle's tangential speed relative
// to the collider is within mu jn: it is put back, tangentially, where it began the substep
// and moves with the collider. Kinetic otherwise: its tangential speed loses mu jn and its
// slip over the substep mu jn dt. So the friction force is mu times the normal force whatever
// the substep, and a particle on a slope sticks below the friction angle (tan a < mu).
// `substep_start()` (defined by the includer) is where the particle began the substep; it is
// asked for only in a contact (per stage it is a read of the state buffer the stage writes).
vec3 substep_start();
void contact_response(inout vec3 x, inout vec3 v, vec3 n, float depth, float mu, vec3 velocity) {
    x += n * depth;
    vec3 relative = v - velocity;
    float vn = dot(relative, n);
    // (The depth counts past a few f32 steps of the position only: at rest it equals the
    // approach over the substep, and its rounding, 5 to 15% of it at 64 substeps, would
    // otherwise add friction through the max. A particle leaving with its overlap within
    // that slack has no normal impulse, so no friction: jn is never negative, which would
    // push it along its slip and speed it up.)
    float jn = max(0.0, max(-vn, (depth - position_slack(x)) / g.dt));
    vec3 vt = relative - vn * n;
    vec3 moved = x - substep_start() - velocity * g.dt;  // over the substep, relative
    vec3 slip = moved - dot(moved, n) * n;
    float vt_len = length(vt);
    if (vt_len <= mu * jn) {
        x -= slip;
        vt = vec3(0.0);
    } else {
        float slip_len = length(slip);
        x -= slip * min(mu * jn * g.dt / max(slip_len, 1e-30), 1.0);
        vt *= 1.0 - mu * jn / vt_len;
    }
    v = velocity + vt + max(vn, 0.0) * n;
}

// Collider k's friction coefficient: its own, else the object's.
float collider_friction(Collider c) { return c.extra.x >= 0.0 ? c.extra.x : obj.friction; }

// Colliders against the particle: each moves it out to the object's margin from its surface
// (contact_response, against the surface's velocity there). A record holds where the collider
// is at the frame's start, its velocity over the frame (extra.yzw) and its spin: `since` is
// the time from the frame's start to the end of this substep (collider_pose).
// `touch`: how far past the margin a particle still counts as touching (its velocity answers
// the collider, its position is not moved): 0 but for vbd_iterate.comp's last iteration, whose
// particles the iterations before held at the margin exactly.
void collide_within(inout vec3 x, inout vec3 v, float since, float touch) {
    if (!has(F_COLLIDERS)) return;
    for (uint k = 0u; k < g.collider_count; ++k) {
        Collider c = colliders[k];
        ColliderPose pose = collider_pose(c, since);
        vec3 n;
        float d = collider_distance_at(c, pose, x, n);
        if (d < obj.margin + touch) {
            vec3 surface = collider_surface_velocity(pose, x);
            contact_response(x, v, n, max(obj.margin - d, 0.0), collider_friction(c), surface);
        }
    }
}

void collide(inout vec3 x, inout vec3 v, float since) { collide_within(x, v, since, 0.0); }

#endif
