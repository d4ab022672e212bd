//! Where the editor puts a new object: centred where the camera looks, its bottom above the
//! ground, and raised above every object or collider its box would meet, so that it does not
//! start inside anything.

use super::{Cloth, MeshCloth, Rope, Scene};
use glam::DVec3;

/// Space kept between a new object's box and the ground or another box [m].
const GAP: f64 = 0.05;

/// The boxes of the scene's objects (their initial particles, a rope's tube included) and of
/// its bounded colliders.
fn boxes(scene: &Scene) -> Vec<(DVec3, DVec3)> {
    let model = super::to_model(scene);
    let objects = model.objects.iter().filter_map(|o| {
        let first = *o.positions.first()?;
        let (lo, hi) = o.positions.iter().fold((first, first), |(lo, hi), p| (lo.min(*p), hi.max(*p)));
        Some((lo - o.rope_radius, hi + o.rope_radius))
    });
    let colliders = model.colliders.iter().filter_map(|c| c.shape.bounds());
    objects.chain(colliders).collect()
}

/// The offset that moves a box [min, max] so that it sits centred on `look_at` (its centre's
/// height kept at least half its height plus GAP above the ground), then raised above every
/// box of `scene` it would meet.
pub fn offset(scene: &Scene, (min, max): (DVec3, DVec3), look_at: DVec3) -> DVec3 {
    let half = (max - min) * 0.5;
    let mut centre = look_at;
    if let Some(g) = &scene.ground {
        centre.y = centre.y.max(g.height + half.y + GAP);
    }
    let others = boxes(scene);
    // Each raise clears one box and can only meet boxes higher up: at most one pass a box.
    for _ in 0..=others.len() {
        let (lo, hi) = (centre - half, centre + half);
        let meets = |(a, b): &&(DVec3, DVec3)| (lo - GAP).cmplt(*b).all() && (hi + GAP).cmpgt(*a).all();
        match others.iter().filter(meets).map(|(_, b)| b.y).reduce(f64::max) {
            Some(top) => centre.y = top + GAP + half.y,
            None => break,
        }
    }
    centre - (min + max) * 0.5
}

/// Places a new cloth (not yet in `scene`) by `offset`.
pub fn place_cloth(scene: &Scene, cloth: &mut Cloth, look_at: DVec3) {
    let alone = Scene { cloths: vec![cloth.clone()], ..Scene::default() };
    let d = offset(scene, boxes(&alone)[0], look_at);
    cloth.origin = (DVec3::from_array(cloth.origin) + d).to_array();
}

/// Places a new mesh cloth (not yet in `scene`; its file read) by `offset`.
pub fn place_mesh_cloth(scene: &Scene, cloth: &mut MeshCloth, look_at: DVec3) {
    let alone = Scene { mesh_cloths: vec![cloth.clone()], ..Scene::default() };
    if let Some(&b) = boxes(&alone).first() {
        let d = offset(scene, b, look_at);
        cloth.center = (DVec3::from_array(cloth.center) + d).to_array();
    }
}

/// Places a new rope (not yet in `scene`) by `offset`.
pub fn place_rope(scene: &Scene, rope: &mut Rope, look_at: DVec3) {
    let alone = Scene { ropes: vec![rope.clone()], ..Scene::default() };
    let d = offset(scene, boxes(&alone)[0], look_at);
    rope.start = (DVec3::from_array(rope.start) + d).to_array();
    rope.end = (DVec3::from_array(rope.end) + d).to_array();
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A new object lands where the camera looks, above the ground, and clear of what is
    /// there (issue 28, item 8: new objects appeared at the origin, inside the curtain).
    #[test]
    fn new_objects_are_placed_clear_of_the_scene() {
        let text =
            std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/presets/tablecloth.toml")).unwrap();
        let mut scene = super::super::parse(&text, "tablecloth.toml", &[]).unwrap();
        let before = boxes(&scene);
        let mut cloth = scene.cloths[0].clone();
        cloth.name = "another".into();
        let look_at = DVec3::new(0.3, 0.2, -0.1);
        place_cloth(&scene, &mut cloth, look_at);
        let alone = Scene { cloths: vec![cloth.clone()], ..Scene::default() };
        let (lo, hi) = boxes(&alone)[0];
        let centre = (lo + hi) * 0.5;
        assert!((centre.x - look_at.x).abs() < 1e-9 && (centre.z - look_at.z).abs() < 1e-9, "{centre}");
        assert!(lo.y >= scene.ground.as_ref().unwrap().height + GAP - 1e-9, "above the ground: {lo}");
        for (a, b) in &before {
            let apart = (0..3).any(|k| lo[k] >= b[k] + GAP - 1e-9 || hi[k] <= a[k] - GAP + 1e-9);
            assert!(apart, "the new cloth [{lo}, {hi}] meets [{a}, {b}]");
        }
        scene.cloths.push(cloth);
        let mut rope = super::super::parse(
            &std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/presets/rope.toml")).unwrap(),
            "rope.toml",
            &[],
        )
        .unwrap()
        .ropes[0]
            .clone();
        place_rope(&scene, &mut rope, look_at);
        let alone = Scene { ropes: vec![rope], ..Scene::default() };
        let (lo, hi) = boxes(&alone)[0];
        for (a, b) in &boxes(&scene) {
            let apart = (0..3).any(|k| lo[k] >= b[k] + GAP - 1e-9 || hi[k] <= a[k] - GAP + 1e-9);
            assert!(apart, "the new rope [{lo}, {hi}] meets [{a}, {b}]");
        }
    }
}
