// Layouts shared by the scene-drawing shaders. Mirrored in src/sim/gpu_types.rs (Camera, Draw)
// and checked against the SPIR-V by tests/suite/layout.rs.
#ifndef MSD_RENDER_GLSL
#define MSD_RENDER_GLSL

struct Camera {
    mat4 view_proj;    // world -> clip (Vulkan: y down, depth 0..1)
    vec4 eye;          // xyz camera position [m]
    vec4 light_pos;    // xyz light position [m]
    vec4 light_color;  // rgb light colour; w ambient factor
};

layout(std140, set = 0, binding = 0) uniform CameraBuf { Camera cam; };

// Per draw (push constants, 112 bytes: lavapipe guarantees only 128).
layout(push_constant) uniform Draw {
    mat4 model;   // object -> world
    vec4 front;   // rgb colour of the side the normal points to
    vec4 back;    // rgb colour of the other side
    vec4 params;  // x: 1 lit (Blinn-Phong), 0 flat colour; y: 1 a ground shadow at height z
} draw;

#endif
