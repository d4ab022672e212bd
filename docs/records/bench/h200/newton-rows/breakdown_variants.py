# Makes breakdown.sh's GLSL variants: copies of glsl/ under .gl/v_NAME/glsl, one change each.
# Run from the repository root before carrying .gl to the device, on 3312ceb's glsl/ (the
# measured tree): the edits name its text, which the branch-free spring loops (fa8be63) changed.
import os
import shutil


def variant(name, edits):
    d = f".gl/v_{name}/glsl"
    shutil.rmtree(d, ignore_errors=True)
    shutil.copytree("glsl", d)
    for f, old, new in edits:
        p = os.path.join(d, f)
        s = open(p).read()
        assert s.count(old) == 1, (name, f, old)
        open(p, "w").write(s.replace(old, new))


sb = "include/solver_bodies.glsl"
variant("nohess", [(sb, """        float c = k + damp - kt;
        iso += kt;
        diag += (c * n) * n;
        off += (c * n.xxy) * n.yzz;""", "        iso += k + damp;")])
variant("nodamp", [
    (sb, "        vec3 dj = SD(j);\n", "        vec3 dj = vec3(0.0);\n"),
    (sb, "force -= n * (k * (d - rest) + damp * dot(n, dx - dj));", "force -= n * (k * (d - rest));"),
])
variant("eight", [(sb, """    [[unroll]] for (int s = 0; s < 12; ++s) {
        ivec3 spring = SPRINGS[s];
        float k = obj.stiffness[spring.z];
        if (k == 0.0 && b == 0.0) continue;""", """    [[unroll]] for (int s = 0; s < 8; ++s) {
        ivec3 spring = SPRINGS[s];
        float k = obj.stiffness[spring.z];
        if (k == 0.0 && b == 0.0) continue;""")])
variant("floor", [("fused.comp", "if (k >= n || pinned[s] || colour[s] != c) continue;",
                   "if (k >= n || pinned[s] || colour[s] != c || k < CAP) continue;")])
# Both of nohess and nodamp: a visit that reads the neighbour's position and adds its spring's
# force alone.
variant("bare", [
    (sb, """        float c = k + damp - kt;
        iso += kt;
        diag += (c * n) * n;
        off += (c * n.xxy) * n.yzz;""", "        iso += k + damp;"),
    (sb, "        vec3 dj = SD(j);\n", "        vec3 dj = vec3(0.0);\n"),
    (sb, "force -= n * (k * (d - rest) + damp * dot(n, dx - dj));", "force -= n * (k * (d - rest));"),
])
# Triangle self-contact's floor (docs/records/bench/h100/triangle-floor): notest (no triangle or edge
# pair tested, the hash built and its candidates visited), nosearch (no candidate visited).
variant("notest", [("include/self_contact.glsl", "void self_triangles(uvec2 cell, vec3 x, uint j, float list_reach) {\n",
                    "void self_triangles(uvec2 cell, vec3 x, uint j, float list_reach) {\n    return;\n")])
variant("nosearch", [("fused.comp", "void listed_candidates(uvec2 cell, vec3 x, float reach, inout vec3 correction, inout uint n_active) {\n",
                      "void listed_candidates(uvec2 cell, vec3 x, float reach, inout vec3 correction, inout uint n_active) {\n    return;\n")])
