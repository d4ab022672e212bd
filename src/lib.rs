//! msdsim: a GPU mass-spring-damper simulator for cloth and ropes on raw Vulkan compute.
//!
//! Layers, bottom up: `vk` (the only place with ash, and with `atomic_file`'s signal handler the
//! only `unsafe`), `shaders` (GLSL compile and SPIR-V layout reading), `sim` (model, GPU
//! simulation, CPU reference), `scene` (TOML presets), `render` (drawing), `ui` (the ImGui
//! editor), `app` (the windowed app), `cli` (the commands).

pub mod app;
pub mod atomic_file;
pub mod bench;
pub mod cli;
pub mod error;
pub mod export;
pub mod render;
pub mod scene;
pub mod shaders;
pub mod sim;
pub mod study;
pub mod ui;
pub mod vk;
