//! The view's draw list: the scene's items and the editor's marks on them.

use super::Viewer;
use crate::app::handles;
use crate::render::{view, DrawItem, Shape};
use glam::{Mat4, Quat, Vec3};

impl Viewer {
    /// What the view draws: the scene (the selected object tinted, markers on the pinned
    /// particles), the selection's arrows and the grabbed particle's target.
    pub(super) fn draw_items(&self) -> Vec<DrawItem> {
        let host = self.host();
        let tinted = handles::collider_index(host.scene(), self.editor.selected);
        let mut items = view::scene_items(host.scene(), host.sim().time(), tinted);
        if let Some(object) = self.editor.selected.object(host.scene()) {
            view::mark_selected(&mut items, object);
        }
        items.extend(view::pin_items(&host.pin_markers(), host.model(), self.camera.eye()));
        if let Some(at) = handles::position(host.scene(), self.editor.selected) {
            items.extend(handles::items(&self.camera, at, self.handle.map(|h| h.axis)));
        }
        if let Some(g) = self.input.grab {
            let model = Mat4::from_scale_rotation_translation(Vec3::splat(0.015), Quat::IDENTITY, g.target);
            items.push(DrawItem::solid(Shape::Cube, model, [1.0, 0.85, 0.1], false));
        }
        items
    }
}
