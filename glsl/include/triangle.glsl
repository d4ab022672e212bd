// A cloth grid's triangles around a vertex, the point of a triangle or a segment nearest to a
// point, the nearest points of two segments and how much an edge pair takes part, and a
// contact's Coulomb friction: shared by a cloth's contact with itself (self_contact.glsl) and
// contact between objects (contact.comp). CPU twin: sim::cpu::self_contact (cloth_triangles,
// triangle_nearest, point_segment_nearest, segment_nearest, edge_fade, friction_correction).
#ifndef MSD_TRIANGLE_GLSL
#define MSD_TRIANGLE_GLSL

// The six triangles around a vertex at grid (c, r): the cell (c + x, r + y) and its triangle z.
const ivec3 VERTEX_TRIANGLES[6] = ivec3[6](ivec3(0, 0, 0), ivec3(-1, 0, 1), ivec3(-1, 0, 0),
                                           ivec3(-1, -1, 1), ivec3(0, -1, 0), ivec3(0, -1, 1));

// The one-ring of a vertex in order around it: its triangle k of VERTEX_TRIANGLES has the
// vertex and ring vertices k and k + 1 (mod 6).
const ivec2 VERTEX_RING[6] = ivec2[6](ivec2(1, 0), ivec2(0, 1), ivec2(-1, 1), ivec2(-1, 0), ivec2(0, -1), ivec2(1, -1));

// Whether a vertex at squared distance da (index ia) is nearer than one at db (index ib).
bool nearer(float da, uint ia, float db, uint ib) { return da < db || (da == db && ia < ib); }

// The barycentric weights of the point of triangle (a, b, c) nearest to p (Ericson,
// Real-Time Collision Detection, 5.1.5).
vec3 triangle_nearest(vec3 p, vec3 a, vec3 b, vec3 c) {
    vec3 ab = b - a;
    vec3 ac = c - a;
    vec3 ap = p - a;
    float d1 = dot(ab, ap);
    float d2 = dot(ac, ap);
    if (d1 <= 0.0 && d2 <= 0.0) return vec3(1.0, 0.0, 0.0);
    vec3 bp = p - b;
    float d3 = dot(ab, bp);
    float d4 = dot(ac, bp);
    if (d3 >= 0.0 && d4 <= d3) return vec3(0.0, 1.0, 0.0);
    float vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
        float t = d1 / (d1 - d3);
        return vec3(1.0 - t, t, 0.0);
    }
    vec3 cp = p - c;
    float d5 = dot(ab, cp);
    float d6 = dot(ac, cp);
    if (d6 >= 0.0 && d5 <= d6) return vec3(0.0, 0.0, 1.0);
    float vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
        float t = d2 / (d2 - d6);
        return vec3(1.0 - t, 0.0, t);
    }
    float va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {
        float t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return vec3(0.0, 1.0 - t, t);
    }
    float sum = va + vb + vc;
    if (!(sum > 0.0)) return vec3(1.0, 0.0, 0.0);  // a degenerate triangle: its first vertex
    return vec3(va, vb, vc) / sum;
}

// The parameter t of the point a + t (b - a) of segment (a, b) nearest to p (a segment shrunk
// to a point: its first end). Twin: sim::cpu::self_contact::point_segment_nearest.
float point_segment_nearest(vec3 p, vec3 a, vec3 b) {
    vec3 ab = b - a;
    float len2 = dot(ab, ab);
    return len2 > 0.0 ? clamp(dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
}

// The parameters (s, t) of the nearest points p1 + s (q1 - p1) and p2 + t (q2 - p2) of two
// segments (Ericson, Real-Time Collision Detection, 5.1.9). Segments nearer parallel than a
// relative 1e-5 (where f32 cannot place the nearest points along them) take s = 0: an end, so
// an edge-edge contact leaves them to the vertex-triangle contacts. Twin:
// sim::cpu::self_contact::segment_nearest.
vec2 segment_nearest(vec3 p1, vec3 q1, vec3 p2, vec3 q2) {
    vec3 d1 = q1 - p1;
    vec3 d2 = q2 - p2;
    vec3 r = p1 - p2;
    float a = dot(d1, d1);
    float e = dot(d2, d2);
    float f = dot(d2, r);
    if (!(a > 0.0) || !(e > 0.0)) return vec2(0.0);  // (grid edges never shrink to a point)
    float c = dot(d1, r);
    float b = dot(d1, d2);
    float denom = a * e - b * b;
    float s = denom > 1e-5 * a * e ? clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
    float t = (b * s + f) / e;
    if (t < 0.0) {
        t = 0.0;
        s = clamp(-c / a, 0.0, 1.0);
    } else if (t > 1.0) {
        t = 1.0;
        s = clamp((b - c) / a, 0.0, 1.0);
    }
    return vec2(s, t);
}

// How much a pair of a cloth's edges whose nearest points lie at st along them takes part (in
// self-contact and between cloths): fully where both lie inside their edges by EDGE_FADE of
// them or more, fading to 0 as one reaches an end (where the vertex-triangle contacts of that
// end hold it). An edge pair that stopped at an end would move its particles by its whole
// overlap there or not at all, and a deep pile of layers turned such jumps (where f32 and the
// CPU twin's f64 rounded either way) into centimetres a frame. Twin:
// sim::cpu::self_contact::edge_fade.
const float EDGE_FADE = 0.05;
float edge_fade(vec2 st) {
    float inside = min(min(st.x, 1.0 - st.x), min(st.y, 1.0 - st.y));
    return clamp(inside * (1.0 / EDGE_FADE), 0.0, 1.0);
}

// Whether a pair of ends keyed ka (their indices, in the caller's order) at squared distance da
// comes before one keyed kb at db: nearer, the distances compared in steps of 1 / `step`, ties
// by the keys (a total order). Compared in steps because a regular grid has many pairs of ends
// equally far apart, whose rounding (which kernels and the CPU twin do differently) would
// otherwise pick which pair comes first. Used to find each edge pair once, from its nearest
// ends (self_contact.glsl's ends_before, contact.comp).
bool ends_in_order(float da, uvec2 ka, float db, uvec2 kb, float step) {
    float qa = floor(da * step);
    float qb = floor(db * step);
    if (qa != qb) return qa < qb;
    return ka.x < kb.x || (ka.x == kb.x && ka.y < kb.y);
}

// The parameters (s, t) of the nearest points of two capsules' axes, segments p1 q1 and p2 q2
// (a rope's segments; either may be a point, a lone node). Nearly parallel axes meet along
// an interval: the middle of the part of p1 q1 that q2 p2 overlaps, so that two ropes lying
// side by side press at the middle of their overlap. Twin: sim::cpu::self_contact::capsule_nearest.
vec2 capsule_nearest(vec3 p1, vec3 q1, vec3 p2, vec3 q2) {
    vec3 d1 = q1 - p1;
    vec3 d2 = q2 - p2;
    float a = dot(d1, d1);
    float e = dot(d2, d2);
    if (!(a > 0.0)) return vec2(0.0, point_segment_nearest(p1, p2, q2));
    if (!(e > 0.0)) return vec2(point_segment_nearest(p2, p1, q1), 0.0);
    float b = dot(d1, d2);
    if (a * e - b * b > 1e-5 * a * e) return segment_nearest(p1, q1, p2, q2);
    float s0 = dot(p2 - p1, d1) / a;
    float s1 = dot(q2 - p1, d1) / a;
    float s = 0.5 * (clamp(min(s0, s1), 0.0, 1.0) + clamp(max(s0, s1), 0.0, 1.0));
    return vec2(s, point_segment_nearest(p1 + s * d1, p2, q2));
}

// How much of the relative motion `moved` over the substep friction undoes in a contact of
// normal n whose normal correction is `normal`: all of its tangential part within the cone
// (static), else mu times the normal correction of it (kinetic: Coulomb's bound on the
// tangential impulse). Twin: sim::cpu::self_contact::friction_correction.
vec3 friction_correction(vec3 moved, vec3 n, float normal, float mu) {
    vec3 slip = moved - dot(moved, n) * n;
    float len = length(slip);
    float most = mu * normal;
    return len <= most ? slip : slip * (most / len);
}

#endif
