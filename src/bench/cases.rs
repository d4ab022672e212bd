//! The benchmark matrix: cloths of 50^2 to 1024^2 particles and ropes of 256 to 65,536 nodes,
//! each plain and with wind, 10 spheres, self-collision, and all of them; plus the paper's own
//! cases (section V). Every scene keeps the curtain preset's per-particle parameters (mass
//! 10 g, springs of 400/100/40 N/m, 2 cm spacing), so it is stable at 16 substeps per 1/60 s
//! whatever its size: larger scenes are larger cloths, not finer ones.

use crate::scene::{
    self, BoxCollider, Capsule, Cloth, ClothPins, Ground, Orientation, PerSpring, Rope, RopePins, Scene,
    SelfContact, Sphere, Wind,
};

/// One benchmark scene.
#[derive(Debug, Clone)]
pub struct Case {
    pub group: &'static str,
    pub name: String,
    pub scene: Scene,
}

const SPACING: f64 = 0.02;

#[derive(Clone, Copy)]
struct Features {
    wind: bool,
    spheres: usize,
    /// A ground, a box and a capsule (the other collider types, against the 10 spheres).
    shapes: bool,
    self_collision: bool,
    /// What a cloth's self-collision keeps apart (`self_contact`).
    contact: SelfContact,
}

const NONE: Features = Features {
    wind: false,
    spheres: 0,
    shapes: false,
    self_collision: false,
    contact: SelfContact::Particles,
};

const VARIANTS: [(&str, Features); 8] = [
    ("springs only", NONE),
    ("+ wind", Features { wind: true, ..NONE }),
    ("+ 10 spheres", Features { spheres: 10, ..NONE }),
    ("+ ground, box, capsule", Features { shapes: true, ..NONE }),
    ("+ self-collision", Features { self_collision: true, ..NONE }),
    ("+ triangle self-contact", Features { self_collision: true, contact: SelfContact::Triangles, ..NONE }),
    (
        "+ triangle and edge self-contact",
        Features { self_collision: true, contact: SelfContact::TrianglesAndEdges, ..NONE },
    ),
    ("all features", Features { wind: true, spheres: 10, self_collision: true, ..NONE }),
];

fn base_scene() -> Scene {
    Scene::default()
}

fn cloth(res: u32) -> Cloth {
    let size = SPACING * (res - 1) as f64;
    Cloth {
        name: format!("cloth{res}"),
        resolution: [res, res],
        size: [size, size],
        origin: [-size / 2.0, size + 0.5, 0.0],
        orientation: Orientation::Vertical,
        mass: 0.01,
        stiffness: PerSpring { structural: 400.0, shear: 100.0, bending: 40.0 },
        rest_scale: PerSpring { structural: 1.0, shear: 1.0, bending: 1.0 },
        damping: 0.005,
        drag: 0.002,
        stretch_limit: Some(0.1),
        friction: 0.3,
        collision_margin: 0.005,
        self_collision: false,
        self_collision_distance: Some(SPACING / 2.0),
        self_contact: SelfContact::Particles,
        pin: ClothPins::TopRow,
        pinned: Vec::new(),
        pin_box: None,
        pin_motion: None,
        pin_groups: Vec::new(),
        color: [0.7, 0.2, 0.2],
        back_color: [0.8, 0.7, 0.5],
    }
}

fn rope(nodes: u32) -> Rope {
    let length = SPACING * (nodes - 1) as f64;
    Rope {
        name: format!("rope{nodes}"),
        nodes,
        start: [-length / 2.0, 1.0, 0.0],
        end: [length / 2.0, 1.0, 0.0],
        mass: 0.01,
        stiffness: 800.0,
        bending_stiffness: 5.0,
        rest_scale: 1.0,
        damping: 0.01,
        drag: 0.005,
        stretch_limit: Some(0.05),
        friction: 0.5,
        radius: 0.008,
        ring_weights: None,
        self_collision: false,
        self_collision_distance: None,
        pin: RopePins::First,
        pinned: Vec::new(),
        pin_box: None,
        pin_motion: None,
        pin_groups: Vec::new(),
        color: [0.7, 0.6, 0.4],
    }
}

/// Ten spheres spread along x over `span` metres at height `y`, in front (z > 0) of x-y objects.
fn spheres(span: f64, y: f64) -> Vec<Sphere> {
    (0..10)
        .map(|k| Sphere {
            center: [(k as f64 / 9.0 - 0.5) * span * 0.8, y, 0.12 * span.min(4.0)],
            radius: 0.1 * span.min(4.0),
            motion: None,
        })
        .collect()
}

/// A ground below an object of `span` metres centred at height `y`, and a box and a capsule in
/// front of it where `spheres` puts its spheres.
fn shapes(span: f64, y: f64) -> (Ground, BoxCollider, Capsule) {
    let (z, r) = (0.12 * span.min(4.0), 0.1 * span.min(4.0));
    let ground = Ground { height: (y - span / 2.0 - 0.2).min(0.0), friction: None };
    let block = BoxCollider {
        center: [-0.2 * span, y, z],
        half_extents: [0.15 * span, r, r],
        rotation: [0.0, 0.0, 20.0],
        motion: None,
    };
    let capsule = Capsule { start: [0.1 * span, y, z], end: [0.4 * span, y - r, z], radius: r, motion: None };
    (ground, block, capsule)
}

/// The paper's wind cone (a force on every particle) aimed at the centre of an object of `span`
/// metres at height `y`.
fn wind(span: f64, y: f64) -> Wind {
    Wind {
        enabled: true,
        model: crate::scene::WindKind::Paper,
        origin: [0.0, y, span],
        direction: [0.0, 0.0, -1.0],
        force: 0.02,
        full_force_radius: span * 0.3,
        attenuation_radius: span * 0.3,
        reference_distance: span,
        ..Default::default()
    }
}

fn with_features(mut scene: Scene, f: Features, span: f64, y: f64) -> Scene {
    if f.wind {
        scene.wind = wind(span, y);
    }
    scene.spheres = spheres(span, y).into_iter().take(f.spheres).collect();
    if f.shapes {
        let (ground, block, capsule) = shapes(span, y);
        scene.ground = Some(ground);
        scene.boxes = vec![block];
        scene.capsules = vec![capsule];
    }
    scene.cloths.iter_mut().for_each(|c| {
        c.self_collision = f.self_collision;
        c.self_contact = f.contact;
    });
    scene.ropes.iter_mut().for_each(|r| r.self_collision = f.self_collision);
    scene
}

/// The paper's cases (section V): curtain 50x50 with all features (wind, self-collision), with
/// one sphere, with ten, and without self-collision; rope of 256 nodes, and with ten spheres.
fn paper_cases() -> Vec<Case> {
    let curtain = || {
        let mut s = scene::parse(include_str!("../../presets/curtain.toml"), "presets/curtain.toml", &[])
            .expect("the curtain preset is valid");
        s.clear_colliders(); // the paper's curtain has no floor
        s.wind = wind(2.0, 1.0);
        s
    };
    let mut cases = Vec::new();
    let all = curtain();
    let mut one = curtain();
    one.spheres = spheres(2.0, 1.0).into_iter().take(1).collect();
    let mut ten = curtain();
    ten.spheres = spheres(2.0, 1.0);
    let mut shaped = curtain();
    let (ground, block, capsule) = shapes(2.0, 1.0);
    (shaped.ground, shaped.boxes, shaped.capsules) = (Some(ground), vec![block], vec![capsule]);
    let mut no_self = curtain();
    no_self.cloths[0].self_collision = false;
    let mut triangles = curtain();
    triangles.cloths[0].self_contact = SelfContact::Triangles;
    let mut edges = curtain();
    edges.cloths[0].self_contact = SelfContact::TrianglesAndEdges;
    for (name, scene) in [
        ("curtain 50x50, all features", all),
        ("curtain 50x50, all features, triangle self-contact", triangles),
        ("curtain 50x50, all features, triangle and edge self-contact", edges),
        ("curtain 50x50, all features + 1 sphere", one),
        ("curtain 50x50, all features + 10 spheres", ten),
        ("curtain 50x50, all features + ground, box, capsule", shaped),
        ("curtain 50x50, without self-collision", no_self),
    ] {
        cases.push(Case { group: "paper", name: name.into(), scene });
    }
    let rope_scene = |spheres_n: usize| {
        let mut s = base_scene();
        let mut r = rope(256);
        r.self_collision = true;
        s.ropes.push(r);
        with_features(s, Features { wind: true, spheres: spheres_n, self_collision: true, ..NONE }, 5.1, 1.0)
    };
    cases.push(Case { group: "paper", name: "rope 256, all features".into(), scene: rope_scene(0) });
    cases.push(Case {
        group: "paper",
        name: "rope 256, all features + 10 spheres".into(),
        scene: rope_scene(10),
    });
    cases
}

/// Eight 32 x 32 cloths lying flat 3 cm apart over a ground, falling onto it and onto each
/// other: with inter-object contact (every object per stage), also keeping their edges from
/// each other's (`self_contact = "triangles_and_edges"`, no self-collision), and without (each
/// fused).
fn stacked_cases() -> Vec<Case> {
    let stack = |contact: bool, edges: bool| {
        let mut s = base_scene();
        s.sim.inter_object = contact;
        s.ground = Some(Ground { height: 0.0, friction: None });
        for k in 0..8 {
            let mut c = cloth(32);
            c.name = format!("cloth{k}");
            c.orientation = Orientation::Horizontal;
            let size = c.size[0];
            c.origin = [-size / 2.0 + 0.01 * k as f64, 0.1 + 0.03 * k as f64, -size / 2.0];
            c.pin = ClothPins::None;
            c.stretch_limit = None;
            if edges {
                c.self_contact = SelfContact::TrianglesAndEdges;
            }
            s.cloths.push(c);
        }
        s
    };
    vec![
        Case {
            group: "contact",
            name: "8 cloths 32x32, inter-object contact".into(),
            scene: stack(true, false),
        },
        Case {
            group: "contact",
            name: "8 cloths 32x32, inter-object contact, edges".into(),
            scene: stack(true, true),
        },
        Case { group: "contact", name: "8 cloths 32x32, no contact".into(), scene: stack(false, false) },
    ]
}

/// Cloth resolutions (particles per side) and rope lengths (nodes) of the full matrix.
pub const CLOTH_SIZES: [u32; 5] = [50, 128, 256, 512, 1024];
pub const ROPE_SIZES: [u32; 5] = [256, 1024, 4096, 16384, 65536];

/// The paper's cases, then every variant of cloths of `cloth_sizes` particles per side and of
/// ropes of `rope_sizes` nodes.
pub fn matrix(cloth_sizes: &[u32], rope_sizes: &[u32]) -> Vec<Case> {
    let mut cases = paper_cases();
    cases.extend(stacked_cases());
    for &res in cloth_sizes {
        let span = SPACING * (res - 1) as f64;
        for (variant, f) in VARIANTS {
            let mut s = base_scene();
            s.cloths.push(cloth(res));
            let scene = with_features(s, f, span, span / 2.0 + 0.5);
            cases.push(Case { group: "cloth", name: format!("cloth {res}x{res}, {variant}"), scene });
        }
    }
    for &nodes in rope_sizes {
        let span = SPACING * (nodes - 1) as f64;
        for (variant, f) in VARIANTS {
            let mut s = base_scene();
            s.ropes.push(rope(nodes));
            let scene = with_features(s, f, span, 0.6);
            cases.push(Case { group: "rope", name: format!("rope {nodes}, {variant}"), scene });
        }
    }
    cases
}

#[cfg(test)]
mod tests {
    #[test]
    fn every_case_is_a_valid_scene() {
        for case in super::matrix(&super::CLOTH_SIZES, &super::ROPE_SIZES) {
            crate::scene::validate(&case.scene).unwrap_or_else(|e| panic!("{}: {e}", case.name));
        }
    }
}
