//! What each editor field means, with its units: the tooltips. Every labelled widget of the
//! editor (`widgets`) looks its label up here, so a field is explained once; a test reads the
//! editor's sources and checks that every label it passes has an entry.
//!
//! A label's entry is found by the whole label (`"radius [m]##collider"`), else by its visible
//! part (before `##`).

const HELP: &[(&str, &str)] = &[
    // Simulation
    ("real time", "Simulate as many frames per drawn frame as the wall clock has run (up to 4), so motion plays at its real speed where the device keeps up; off, and while recording: one frame per drawn frame (slower than real time on a slow device, as the Stats say). The GPU times shown are then the last simulated frame's."),
    ("substeps", "Substeps per simulated frame: each advances frame dt / substeps. More substeps are more accurate and stable, and cost proportionally more."),
    ("frame dt [ms]", "Simulated time per frame [ms]; 16.667 is 60 frames a second."),
    ("gravity [m/s^2]", "Gravitational acceleration, x y z [m/s^2]; -9.81 in y is Earth's."),
    ("objects touch each other", "Contact between objects: every particle is kept the sum of the two objects' contact radii (a cloth's collision margin, a rope's radius) from another cloth's triangles, and a rope's nodes that far from another rope's; equal and opposite, with Coulomb friction (the mean of the two objects' friction). Scenes pay for it only with two or more objects."),
    ("cloths keep their edges apart", "Touching cloths also keep their edges (rows, columns, diagonals) apart, so no edge of one passes through another where no vertex touches (sim.inter_object_edges, on by default). Off: only where a cloth keeps its own edges apart (self contact triangles and edges)."),
    ("integrator", "How a substep advances the springs: symplectic Euler (the paper's) and Verlet are explicit (fast, limited by the stiffest spring); XPBD, implicit and VBD take large steps (a stiff cloth held at its corners settles at one 1/60 s substep; XPBD hangs it long at few iterations) and converge to BDF2, a second-order implicit method; auto picks the cheapest method within the tolerance."),
    ("iterations", "Solver iterations per substep of an iterative method (for the implicit method, conjugate-gradient iterations, linearised again every 5): more converge closer to the method's implicit (BDF2) solve and cost more. At one substep a stiff cloth needs about 10."),
    ("contact iterations", "Passes over a cloth's contacts with its own triangles each substep, each from where the passes before moved the particles: a layer landing on several others is stopped within the substep only with several (a strip piling on itself let 281 edges through with one pass, 6 with four). Each costs about as much as the first pass's application."),
    ("relaxation", "XPBD over-relaxation of each Gauss-Seidel correction (1: none; below 2)."),
    ("tolerance (of size)", "For integrator = auto: the largest position error allowed after 0.5 s, as a fraction of the scene's size."),
    // Wind
    ("enabled##wind", "Blow wind inside the cone."),
    ("origin [m]##wind", "The wind cone's apex [m]."),
    ("direction##wind", "The wind's direction (normalised)."),
    ("model##wind", "paper: the same force on every particle in the cone, whatever the cloth's orientation (the paper's figures); aerodynamic: drag from the air's velocity relative to the cloth, on its area facing the air (a flag flutters, an edge-on sheet barely moves)."),
    ("air speed [m/s]", "Aerodynamic wind: the air's speed in the cone's core [m/s]."),
    ("air density [kg/m^3]", "Aerodynamic wind: the air's density (1.2 at sea level) [kg/m^3]."),
    ("normal drag", "Aerodynamic wind: drag coefficient across the cloth (about 1.2 for a flat plate)."),
    ("tangential drag", "Aerodynamic wind: drag coefficient along the cloth (skin friction, a few hundredths)."),
    ("lift", "Aerodynamic wind: lift coefficient of a cloth at 45 degrees to the air, across the air (0: drag only); none face-on or edge-on."),
    ("turbulence [m/s]", "Aerodynamic wind: how strong its gusts are, the root-mean-square speed of the air's turbulence added to the steady wind [m/s] (0: a steady wind). A flag flutters in a little."),
    ("eddy size [m]", "Aerodynamic wind: the size of the turbulence's eddies (the field mixes sizes from half to twice this) [m]."),
    ("eddy frequency [Hz]", "Aerodynamic wind: how fast the eddies change as the wind carries them along [Hz]."),
    ("seed##wind", "Aerodynamic wind: picks the turbulence's eddies; the same seed blows the same gusts every run."),
    ("force [N]##wind", "The paper's wind: force on each particle at full strength [N]."),
    ("full-force radius [m]", "Radius of the cone's full-force core at the reference distance [m]."),
    ("attenuation radius [m]", "Radius at the reference distance where the force has faded to zero [m]."),
    ("reference distance [m]", "Distance from the apex at which the two radii are given [m]."),
    // Light
    ("position [m]##light", "The point light's position [m]."),
    ("colour##light", "The light's colour (linear RGB)."),
    ("ambient", "Light reaching every surface regardless of the lamp (0..1)."),
    // Cloth
    ("columns", "Particles along the cloth's width."),
    ("rows", "Particles along the cloth's height."),
    ("width [m]", "The cloth's width at rest [m]."),
    ("height [m]", "The cloth's height at rest [m]."),
    ("origin [m]", "Position of the particle at column 0, row 0 [m]."),
    ("orientation", "Vertical: rows run down from the origin; horizontal: rows run along +z."),
    ("pins", "Which particles are fixed in space (Ctrl + click pins or frees single particles)."),
    ("mass [kg/particle]", "Mass of each particle [kg]."),
    ("mass [kg/node]", "Mass of each rope node [kg]."),
    ("stiffness [N/m]", "Spring constant of the rope's segments [N/m]."),
    ("structural##stiffness [N/m]", "Spring constant of the springs to the 4 direct neighbours [N/m]: resists stretching."),
    ("shear##stiffness [N/m]", "Spring constant of the diagonal springs [N/m]: resists shearing."),
    ("bending##stiffness [N/m]", "Spring constant of the springs to the neighbours two apart [N/m]: resists bending."),
    ("structural##rest length scale", "Rest length of the structural springs as a multiple of the grid spacing (below 1: pre-tensioned)."),
    ("shear##rest length scale", "Rest length of the shear springs as a multiple of their grid length."),
    ("bending##rest length scale", "Rest length of the bending springs as a multiple of their grid length."),
    ("rest length scale", "Rest length of the rope's springs as a multiple of the node spacing."),
    ("bending stiffness [N/m]", "Spring constant of the springs between nodes two apart [N/m]: resists bending."),
    ("spring damping [N s/m]", "Dashpot along each spring [N s/m]: damps stretching and bending oscillations."),
    ("drag [N s/m]", "Air drag on each particle, force = -drag x velocity [N s/m]."),
    ("stretch limit", "Springs may not stretch more than this fraction of their rest length (ticked: enforced every substep)."),
    ("friction", "Coulomb friction coefficient mu against colliders (and, averaged with the other's, against other objects; with triangle self-contact, between its own layers): sticks on slopes flatter than atan(mu), slides on steeper ones (0: ice, 0.4: cloth on wood, 1: rubber)."),
    ("collision margin [m]", "Distance kept from colliders, and the cloth's contact radius against other objects [m]."),
    ("self-collision", "The object keeps apart from itself: a cloth's particles from its triangles (or, with self-contact particles, from each other), a rope's nodes from each other (grid neighbours excepted)."),
    ("self-contact", "What a cloth's self-collision keeps apart. triangles (the default): its particles from its triangles, the distance a thickness, every contact equal and opposite (no layer passes through another at normal speeds; several times the cost). particles: its particles, the self-collision distance apart (the paper's; fast, but layers can pass between particles)."),
    ("self-collision distance [m]", "With triangle self-contact the cloth's thickness: how far its particles keep from its triangles; else the distance below which two particles push apart (ticked: set here; else half the spacing, a mesh cloth's half its mean edge, or a rope's diameter) [m]."),
    ("front colour", "Colour of the cloth's front side (linear RGB)."),
    ("back colour", "Colour of the cloth's back side (linear RGB)."),
    // Rope
    ("nodes", "Number of rope nodes (particles)."),
    ("start [m]", "Position of the first node [m]."),
    ("end [m]", "Position of the last node at rest [m]."),
    ("radius [m]", "The rope's radius [m]: its tube, and its contact radius against colliders and other objects."),
    ("colour", "The object's colour (linear RGB)."),
    // Colliders
    ("height [m]##ground", "Height of the ground plane [m]: below it is solid."),
    ("friction (own)##ground", "Friction on the ground for every object (ticked); unticked, each object's own friction applies."),
    ("centre [m]", "The collider's centre [m]."),
    ("centre [m]##mesh cloth", "Where the mesh file's origin goes [m]."),
    ("scale##mesh cloth", "The mesh file's units in metres: 1 for a file in metres, 0.01 for centimetres, 0.001 for millimetres. Its origin stays at the centre."),
    ("weld [m]", "Vertices nearer than this are one particle [m] (0: those at the same place): a glTF file repeats its vertices along texture seams."),
    ("density [kg/m^2]", "Mass per area [kg/m^2], lumped at the vertices by area (each takes an equal part of each of its faces'): light cotton about 0.15, denim 0.4."),
    ("sew [m]", "Border vertices this near another part of the border are sewn to the nearest such by a seam spring [m] (0: none): panels laid round a body, their edges a little apart, close into a garment. Less than the border's edges."),
    ("seam stiffness [N/m]", "Stiffness of the seams' springs, of rest length zero [N/m]: how fast the sewn runs of vertices close."),
    ("radius [m]##collider", "The collider's radius [m]."),
    ("half extents [m]", "Half the box's size along its own x, y, z [m]."),
    ("scale##mesh", "The mesh file's units in metres: 1 for a file in metres, 0.01 for centimetres, 0.001 for millimetres. Its origin stays at the centre."),
    ("thickness [m]##mesh", "How far out from the mesh's triangles its surface is [m]: 0 keeps particles their margin from the triangles themselves."),
    ("reach [m]##mesh", "How far from its triangles particles are found [m], inside and out: a particle deeper than this inside a closed mesh is not pushed out. More than its thickness plus every object's margin; more costs more."),
    ("rotation x, y, z [deg]", "The box's, mesh's or mesh cloth's rotation about x, then y, then z [degrees] (a mesh's about its origin)."),
    ("start [m]##capsule", "Centre of the capsule's first end cap [m]."),
    ("end [m]##capsule", "Centre of the capsule's second end cap [m]."),
    ("moves", "Move the collider at a constant velocity (it drags what it touches through friction)."),
    ("velocity [m/s]", "The collider's velocity [m/s]."),
    ("turns", "Turn the collider steadily about its centre (a capsule's midpoint): what it touches is carried round by friction, as on a turntable."),
    ("angular velocity [degrees/s]", "The collider's turn: about this vector's direction, at its length in degrees a second (e.g. [0, 90, 0]: a quarter turn a second about the vertical, anticlockwise seen from above)."),
    ("pins move", "Move the pinned particles together at a constant velocity: they carry the object (keyframes: `pin_motion` in the preset)."),
    ("pin velocity [m/s]", "The pinned particles' velocity [m/s]."),
    ("box min [m]", "The lowest corner of the box whose particles are pinned (as placed at the start) [m]."),
    ("box max [m]", "The highest corner of the box whose particles are pinned (as placed at the start) [m]."),
    ("add pin group", "Add a pin group: a few pinned particles with a motion of their own (it starts as a small box about a free corner; move the box, or Ctrl+click particles into the preset's list)."),
    ("remove pin group", "Remove this pin group: its particles are free again (unless the object's own pins hold them)."),
    ("pins turn", "Turn the pinned particles together steadily about their centre (or the preset's `pivot`): they twist or swing the object."),
    ("pin angular velocity [degrees/s]", "The pins' turn: about this vector's direction, at its length in degrees a second."),
];

/// The tooltip of the widget labelled `label`.
pub fn help(label: &str) -> Option<&'static str> {
    let find = |key: &str| HELP.iter().find(|(k, _)| *k == key).map(|(_, t)| *t);
    find(label).or_else(|| find(label.split("##").next().unwrap_or(label)))
}

#[cfg(test)]
mod tests {
    use super::help;

    /// Every label the editor's sources pass to a widget helper (`drag(ui, "...", ...)` and the
    /// like, and the three spring types of `springs(ui, "...", ...)`) has a tooltip.
    #[test]
    fn every_editor_field_has_a_tooltip() {
        let sources = [include_str!("editor.rs"), include_str!("colliders.rs"), include_str!("objects.rs")];
        let helpers = ["drag(", "drag3(", "int(", "optional(", "choice(", "color(", "check(", " button("];
        let mut labels = Vec::new();
        for source in sources {
            for (i, _) in source.match_indices("(ui,") {
                let before = &source[..i + 1];
                let after = source[i + 4..].trim_start();
                let Some(rest) = after.strip_prefix('"') else { continue };
                let label = &rest[..rest.find('"').expect("a closed string")];
                if before.ends_with("springs(") {
                    labels.extend(["structural", "shear", "bending"].map(|s| format!("{s}##{label}")));
                } else if helpers.iter().any(|h| before.ends_with(h)) {
                    labels.push(label.to_string());
                }
            }
        }
        assert!(labels.len() > 40, "found {} labels: the scan is broken", labels.len());
        let missing: Vec<_> = labels.iter().filter(|l| help(l).is_none()).collect();
        assert!(missing.is_empty(), "no tooltip for {missing:?} (src/ui/help.rs)");
    }

    #[test]
    fn a_label_is_found_by_its_visible_part_when_its_context_has_no_entry() {
        assert!(help("radius [m]##collider").unwrap().contains("collider"));
        assert!(help("radius [m]##anything").unwrap().contains("rope"));
        assert!(help("no such field").is_none());
    }
}
