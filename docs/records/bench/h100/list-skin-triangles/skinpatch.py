import sys,re
d=sys.argv[1]; val=sys.argv[2]
p=d+'/include/lists.glsl'; s=open(p).read()
s=s.replace("const float LIST_SKIN = 1.0;\n", "const float LIST_SKIN = 1.0;\nconst float TRIANGLE_LIST_SKIN = %s;\n"%val,1)
# list_skin() after has_triangles definition
s=s.replace("bool has_triangles() { return has(F_TRIANGLES) && (obj.flags & OBJ_SELF_TRIANGLES) != 0u; }\n",
 "bool has_triangles() { return has(F_TRIANGLES) && (obj.flags & OBJ_SELF_TRIANGLES) != 0u; }\nfloat list_skin() { return has_triangles() ? TRIANGLE_LIST_SKIN : LIST_SKIN; }\n",1)
s=s.replace("float list_reach() { return vertex_reach((1.0 + LIST_SKIN) * obj.self_distance); }","float list_reach() { return vertex_reach((1.0 + list_skin()) * obj.self_distance); }")
s=s.replace("float list_half_skin() { return 0.49 * LIST_SKIN * obj.self_distance; }","float list_half_skin() { return 0.49 * list_skin() * obj.self_distance; }")
assert s.count("list_skin()")==3, s.count("list_skin()")
open(p,'w').write(s)
p=d+'/include/constraints_body.glsl'; s=open(p).read()
assert s.count("(1.0 + LIST_SKIN)")==2
s=s.replace("(1.0 + LIST_SKIN)","(1.0 + list_skin())"); open(p,'w').write(s)
p=d+'/include/hash_count.glsl'; s=open(p).read()
assert "(1.0 / (1.0 + LIST_SKIN))" in s
open(p,'w').write(s)
