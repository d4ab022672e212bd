//! The simulation: the model (`model`), the integrators (`integrator`), the GPU struct mirrors (`gpu_types`), the Vulkan compute
//! simulation (`gpu`) and the f64 CPU reference (`cpu`).

pub mod cloth_mesh;
pub mod collider;
pub mod collider_mesh;
pub mod colouring;
pub mod cpu;
pub mod gpu;
pub mod gpu_types;
pub mod integrator;
pub mod model;
pub mod pins;
pub mod stability;
pub mod turbulence;
pub mod turn;
