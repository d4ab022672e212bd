//! Drawing the scene: primitive meshes generated in code (`mesh`), the orbit camera (`camera`)
//! and the renderer that records the draws (`scene_renderer`). The simulation's surface buffers
//! are drawn directly as vertex buffers; nothing goes through the CPU.

pub mod camera;
pub mod mesh;
mod scene_renderer;
pub mod view;

pub use scene_renderer::{DrawItem, SceneRenderer, Shape};
