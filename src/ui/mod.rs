//! The ImGui scene editor and stats panel. The editor edits a copy of the scene; the app applies
//! the copy (see `app::sim_host`) and carries out the returned actions.

mod browse;
mod colliders;
mod editor;
mod help;
mod notices;
mod objects;
mod widgets;
mod wind;

pub use browse::resolve_preset;
pub use editor::{build, covered, unique_name, Action, EditorState, Selection, Stats};
pub use widgets::shown;
