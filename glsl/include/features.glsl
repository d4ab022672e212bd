// What a scene uses, compiled in or out: a specialization constant (id 3) that the host sets
// per object from its model (src/sim/gpu/pipelines.rs, `features`). A feature the scene does
// not use is removed from the pipeline, not skipped at run time. The runtime flags (wind on,
// collider count, ObjectParams.flags) still apply inside a compiled-in feature. Shaders created
// without the constant (default: everything but F_SEGMENT_PAIRS, which marks a rope) behave as
// before.
// The bits are mirrored in src/sim/gpu_types.rs (FEATURE_*).
#ifndef MSD_FEATURES_GLSL
#define MSD_FEATURES_GLSL

#define F_STRUCTURAL 1u   // structural springs (stiffness or damping along them)
#define F_SHEAR      2u   // shear springs
#define F_BENDING    4u   // bending springs
#define F_DAMPING    8u   // spring dashpots (read the neighbours' velocities)
#define F_WIND       16u  // the wind cone
#define F_SPHERES    32u  // sphere colliders
#define F_STRETCH    64u  // the stretch limit
#define F_SELF       128u // self-collision (ObjectParams.flags: through the hash or every pair)
#define F_GROUND     256u // the ground plane
#define F_BOX        512u // box colliders
#define F_CAPSULE    1024u // capsule colliders
#define F_MESH       131072u // mesh colliders (colliders.glsl, mesh_distance)
#define F_COLLIDERS  (F_SPHERES | F_GROUND | F_BOX | F_CAPSULE | F_MESH)
#define F_CONTACT    2048u // inter-object contact (the contact buffer, filled by contact.comp)
#define F_EDGES      4096u // colliders against edges and faces too (constraints_body.glsl)
#define F_TRIANGLES  8192u // a cloth's self-contact against its triangles (self_contact.glsl)
#define F_EDGE_PAIRS 16384u // ... and of its edges against its edges (self_contact.glsl)
#define F_SEGMENT_PAIRS 32768u // ... a rope's: its segments against its segments, no triangles
#define F_TURNING    65536u // colliders that turn (colliders.glsl, collider_pose)
#define F_CLOTH_MESH 262144u // a cloth made from a mesh: its lists, not a grid (mesh_springs.glsl)

layout(constant_id = 3) const uint FEATURES = 0x37FFFu;

bool has(uint feature) { return (FEATURES & feature) != 0u; }

#endif
