// A free object's rigid start for the methods that start adaptively (VBD, the implicit
// method): the rigid move that fits the particles' guessed displacements best in least
// squares, linearised (sim::cpu::integrators::RigidMove), from sums over the object that
// rigid_start.comp (per stage) and the fused kernel take in their own ways. Include after
// predict_body.glsl.
#ifndef MSD_RIGID_START_GLSL
#define MSD_RIGID_START_GLSL

// Must equal sim::integrator::RIGID_REGULARISER.
const float RIGID_REGULARISER = 1e-5;

// What a particle adds to the sums, at q = x - origin (any point of the object, the same for
// all: the first particle's, where the substep or per stage the frame starts) with guessed
// displacement d = guess - x, in four vec4s:
// (sum q, sum d.x), (sum d.yz, sum (q x d).xy), (sum (q x d).z, sum q q^T's diagonal),
// (its xy, xz and yz, the count).
mat4 rigid_terms(vec3 q, vec3 d) {
    vec3 m = cross(q, d);
    return mat4(vec4(q, d.x), vec4(d.yz, m.xy), vec4(m.z, q * q), vec4(q.x * q.y, q.x * q.z, q.y * q.z, 1.0));
}

// The fitted move from the sums: the centre c (from the origin), the translation t and the
// linearised turn w, which move the particle at q by t and turn it about c by asin |w| about w
// (`rigid_move`).
struct RigidMove {
    vec3 centre;
    vec3 t;
    vec3 w;
};

RigidMove rigid_fit(mat4 s) {
    float n = max(s[3].w, 1.0);
    vec3 c = s[0].xyz / n;
    vec3 t = vec3(s[0].w, s[1].xy) / n;
    vec3 moment = vec3(s[1].zw, s[2].x) - n * cross(c, t);
    vec3 off = s[3].xyz;
    mat3 spread = mat3(s[2].y, off.x, off.y, off.x, s[2].z, off.z, off.y, off.z, s[2].w) - n * outerProduct(c, c);
    float trace = spread[0][0] + spread[1][1] + spread[2][2];
    // I = tr(S) E - S for S = sum r r^T, regularised (RIGID_REGULARISER)
    mat3 inertia = mat3(trace * (1.0 + RIGID_REGULARISER)) - spread;
    vec3 w = trace > 0.0 ? inverse(inertia) * moment : vec3(0.0);
    return RigidMove(c, t, w);
}

// The fitted move's displacement of the particle at q: t plus the exact turn by asin |w|,
// w x r + w x (w x r) / (1 + cos), r = q - c; a turn past a quarter is a quarter
// (sim::cpu::integrators::RigidMove says why).
vec3 rigid_move(RigidMove m, vec3 q) {
    vec3 w = m.w / max(length(m.w), 1.0);
    vec3 across = cross(w, q - m.centre);
    float cosine = sqrt(max(1.0 - dot(w, w), 0.0));
    return m.t + across + cross(w, across) / (1.0 + cosine);
}

// Where the particle at q = x - origin starts as a displacement from x: its guessed one `d`
// moved towards the fitted move's (predict_body.glsl's toward_rest).
vec3 rigid_start(RigidMove m, uvec2 cell, vec3 q, vec3 d) {
    return toward_rest(cell, rigid_move(m, q), d);
}

#endif
