//! `.usda`: USD (ASCII), every attribute's samples grouped, written when the recording ends.

use super::*;

impl Recording {
    /// Writes the USD ASCII text: time codes `first_code()..=last_code()` at the simulation's
    /// frame rate; the meshes' time samples from the spool, a frame at a time.
    pub(super) fn write_usda(&self, w: &mut dyn std::io::Write) -> std::io::Result<()> {
        let mut out = String::new();
        let _ = writeln!(
            out,
            "#usda 1.0\n(\n    defaultPrim = \"scene\"\n    metersPerUnit = 1\n    upAxis = \"Y\""
        );
        let _ = writeln!(
            out,
            "    startTimeCode = {}\n    endTimeCode = {}\n    timeCodesPerSecond = {}\n    framesPerSecond = {}\n)\n",
            self.first_code,
            self.last_code().max(self.first_code),
            self.fps,
            self.fps
        );
        let _ = writeln!(out, "def Xform \"scene\"\n{{");
        for t in &self.tracks {
            let _ = writeln!(
                out,
                "    def Mesh \"{}\" (\n        prepend apiSchemas = [\"MaterialBindingAPI\"]\n    )\n    {{",
                t.name
            );
            let _ = writeln!(out, "        rel material:binding = </scene/materials/{}>", t.name);
            let _ = writeln!(out, "        uniform token subdivisionScheme = \"none\"");
            let _ = writeln!(out, "        uniform bool doubleSided = 1");
            let _ = writeln!(out, "        int[] faceVertexCounts = [{}]", vec!["3"; t.counts].join(", "));
            let indices: Vec<String> = t.indices.iter().map(u32::to_string).collect();
            let _ = writeln!(out, "        int[] faceVertexIndices = [{}]", indices.join(", "));
            let [r, g, b] = t.color;
            let _ = writeln!(out, "        color3f[] primvars:displayColor = [({r}, {g}, {b})]");
            // UsdPreviewSurface has one colour for both sides: a cloth's back goes in a primvar.
            let [r, g, b] = t.back;
            let _ = writeln!(out, "        color3f primvars:msdsim:backColor = ({r}, {g}, {b}) (\n            interpolation = \"constant\"\n        )");
            let st: Vec<String> = t.st.iter().map(|[u, v]| format!("({u}, {v})")).collect();
            let _ = writeln!(
                out,
                "        texCoord2f[] primvars:st = [{}] (\n            interpolation = \"faceVarying\"\n        )",
                st.join(", ")
            );
            let st_indices: Vec<String> = t.st_indices.iter().map(u32::to_string).collect();
            let _ = writeln!(out, "        int[] primvars:st:indices = [{}]", st_indices.join(", "));
            w.write_all(out.as_bytes())?;
            out.clear();
            let spooled = |k: u64| move |f: u64, values: &mut Vec<[f32; 3]>| self.spooled(t, k, f, values);
            samples(w, self.first_code, self.frames, "point3f[] points", spooled(0))?;
            let _ = writeln!(
                out,
                "        normal3f[] normals (\n            interpolation = \"vertex\"\n        )"
            );
            w.write_all(out.as_bytes())?;
            out.clear();
            samples(w, self.first_code, self.frames, "normal3f[] normals", spooled(1))?;
            samples(w, self.first_code, self.frames, "vector3f[] velocities", spooled(2))?;
            let extents = |f: u64, values: &mut Vec<[f32; 3]>| {
                self.spooled(t, 0, f, values)?;
                *values = extent(values).to_vec();
                Ok(())
            };
            samples(w, self.first_code, self.frames, "float3[] extent", extents)?;
            let _ = writeln!(out, "    }}");
        }
        self.usda_colliders(&mut out);
        self.usda_materials(&mut out);
        let _ = writeln!(out, "}}");
        w.write_all(out.as_bytes())
    }

    /// Track `t`'s attribute k (0 points, 1 normals, 2 velocities) in frame f, from the spool.
    pub(super) fn spooled(
        &self,
        t: &Track,
        k: u64,
        f: u64,
        values: &mut Vec<[f32; 3]>,
    ) -> std::io::Result<()> {
        use std::os::unix::fs::FileExt as _;
        let spool =
            self.spool.as_ref().ok_or_else(|| std::io::Error::other("a USD recording has a spool"))?;
        let n = t.recorded_vertices() as u64;
        let mut bytes = vec![0u8; 12 * n as usize];
        spool.file.read_exact_at(&mut bytes, f * spool.frame_bytes + t.spooled_at + k * 12 * n)?;
        values.clear();
        values.extend(bytes.chunks_exact(12).map(|c| {
            std::array::from_fn(|i| f32::from_le_bytes([c[4 * i], c[4 * i + 1], c[4 * i + 2], c[4 * i + 3]]))
        }));
        Ok(())
    }

    /// The name of the colliders' material: `colliders`, made unique against the objects'.
    pub(super) fn collider_material(&self) -> String {
        let mut taken = self.tracks.iter().map(|t| t.name.clone()).collect();
        unique_name(&mut taken, "colliders".into())
    }

    /// A `UsdPreviewSurface` material for each object (its front colour) and one for the
    /// colliders (grey), in a scope `materials`; the meshes and shapes bind them.
    pub(super) fn usda_materials(&self, out: &mut String) {
        let _ = writeln!(out, "    def Scope \"materials\"\n    {{");
        let grey = [COLLIDER_GREY; 3];
        let shared = self.collider_material();
        let colliders = (!self.colliders.is_empty()).then_some((shared.as_str(), &grey));
        for (name, [r, g, b]) in self.tracks.iter().map(|t| (t.name.as_str(), &t.color)).chain(colliders) {
            let _ = writeln!(out, "        def Material \"{name}\"\n        {{");
            let _ = writeln!(
                out,
                "            token outputs:surface.connect = </scene/materials/{name}/surface.outputs:surface>"
            );
            let _ = writeln!(out, "            def Shader \"surface\"\n            {{");
            let _ = writeln!(out, "                uniform token info:id = \"UsdPreviewSurface\"");
            let _ = writeln!(out, "                color3f inputs:diffuseColor = ({r}, {g}, {b})");
            let _ = writeln!(out, "                float inputs:roughness = 0.8");
            let _ = writeln!(out, "                token outputs:surface");
            let _ = writeln!(out, "            }}\n        }}");
        }
        let _ = writeln!(out, "    }}");
    }

    /// The colliders as USD shapes in a scope `colliders` (grey): a sphere as a Sphere, a
    /// capsule as a Capsule along its local z, a box as a Cube of size 2 scaled by its half
    /// extents and turned by its rotation, the ground as a 40 m square Mesh facing up at its
    /// height. A moving collider's translation is time-sampled at every frame, a fixed one's
    /// constant; a turning one's orientation is time-sampled too (about its centre, where its
    /// translation places it).
    pub(super) fn usda_colliders(&self, out: &mut String) {
        if self.colliders.is_empty() {
            return;
        }
        let _ = writeln!(out, "    def Scope \"colliders\"\n    {{");
        let material = self.collider_material();
        for (i, c) in self.colliders.iter().enumerate() {
            let kind = c.shape.kind().label();
            let (prim, place, rotation): (&str, DVec3, Option<DQuat>) = match c.shape {
                Shape::Sphere { center, .. } => ("Sphere", center, None),
                Shape::Capsule { a, b, .. } => (
                    "Capsule",
                    (a + b) / 2.0,
                    Some(DQuat::from_rotation_arc(DVec3::Z, (b - a).normalize_or(DVec3::Z))),
                ),
                Shape::Box { center, rotation, .. } => ("Cube", center, Some(rotation)),
                Shape::Ground { height } => ("Mesh", DVec3::new(0.0, height, 0.0), None),
                Shape::Mesh { center, rotation, .. } => ("Mesh", center, Some(rotation)),
            };
            let _ = writeln!(out, "        def {prim} \"{kind}_{i}\" (\n            prepend apiSchemas = [\"MaterialBindingAPI\"]\n        )\n        {{");
            let _ = writeln!(out, "            rel material:binding = </scene/materials/{material}>");
            match c.shape {
                Shape::Sphere { radius, .. } => {
                    let _ = writeln!(out, "            double radius = {radius}");
                }
                Shape::Capsule { a, b, radius } => {
                    let _ = writeln!(out, "            uniform token axis = \"Z\"\n            double height = {}\n            double radius = {radius}", a.distance(b));
                }
                Shape::Box { .. } => {
                    let _ = writeln!(out, "            double size = 2");
                }
                Shape::Ground { .. } => {
                    let h = GROUND_HALF_SIZE;
                    // (a flat quad, not a subdivision cage: as the objects' meshes say)
                    let _ = writeln!(out, "            uniform token subdivisionScheme = \"none\"");
                    let _ = writeln!(out, "            int[] faceVertexCounts = [4]\n            int[] faceVertexIndices = [0, 1, 2, 3]");
                    let _ = writeln!(out, "            point3f[] points = [(-{h}, 0, -{h}), (-{h}, 0, {h}), ({h}, 0, {h}), ({h}, 0, -{h})]");
                    let _ = writeln!(
                        out,
                        "            normal3f[] normals = [(0, 1, 0), (0, 1, 0), (0, 1, 0), (0, 1, 0)]"
                    );
                    let _ = writeln!(out, "            float3[] extent = [(-{h}, 0, -{h}), ({h}, 0, {h})]");
                }
                Shape::Mesh { ref mesh, .. } => {
                    // Its triangles in its own frame (the transform below places it); the
                    // thickness is not drawn.
                    let list = |items: Vec<String>| items.join(", ");
                    let counts = list(vec!["3".to_string(); mesh.triangles.len()]);
                    let indices = list(mesh.triangles.iter().flatten().map(|k| k.to_string()).collect());
                    let points = list(
                        mesh.vertices
                            .iter()
                            .map(|p| format!("({}, {}, {})", p.x as f32, p.y as f32, p.z as f32))
                            .collect(),
                    );
                    let (lo, hi) = mesh.bounds();
                    let _ = writeln!(out, "            uniform token subdivisionScheme = \"none\"");
                    let _ = writeln!(out, "            int[] faceVertexCounts = [{counts}]\n            int[] faceVertexIndices = [{indices}]");
                    let _ = writeln!(out, "            point3f[] points = [{points}]");
                    let _ = writeln!(
                        out,
                        "            float3[] extent = [({}, {}, {}), ({}, {}, {})]",
                        lo.x as f32, lo.y as f32, lo.z as f32, hi.x as f32, hi.y as f32, hi.z as f32
                    );
                }
            }
            let _ = writeln!(out, "            color3f[] primvars:displayColor = [({COLLIDER_GREY}, {COLLIDER_GREY}, {COLLIDER_GREY})]");
            let mut order = vec!["\"xformOp:translate\""];
            if c.motion.is_moving() {
                let _ = writeln!(out, "            double3 xformOp:translate.timeSamples = {{");
                for (f, &t) in self.times.iter().enumerate() {
                    let p = place + c.motion.offset(t);
                    let _ = writeln!(
                        out,
                        "                {}: ({}, {}, {}),",
                        self.first_code + f as u64,
                        p.x,
                        p.y,
                        p.z
                    );
                }
                let _ = writeln!(out, "            }}");
            } else {
                let _ = writeln!(
                    out,
                    "            double3 xformOp:translate = ({}, {}, {})",
                    place.x, place.y, place.z
                );
            }
            if c.turns() {
                let _ = writeln!(out, "            quatd xformOp:orient.timeSamples = {{");
                for (f, &t) in self.times.iter().enumerate() {
                    let q = c.turn_at(t) * rotation.unwrap_or(DQuat::IDENTITY);
                    let code = self.first_code + f as u64;
                    let _ = writeln!(out, "                {code}: ({}, {}, {}, {}),", q.w, q.x, q.y, q.z);
                }
                let _ = writeln!(out, "            }}");
                order.push("\"xformOp:orient\"");
            } else if let Some(q) = rotation {
                let _ =
                    writeln!(out, "            quatd xformOp:orient = ({}, {}, {}, {})", q.w, q.x, q.y, q.z);
                order.push("\"xformOp:orient\"");
            }
            if let Shape::Box { half_extents: e, .. } = c.shape {
                let _ = writeln!(out, "            double3 xformOp:scale = ({}, {}, {})", e.x, e.y, e.z);
                order.push("\"xformOp:scale\"");
            }
            let _ = writeln!(out, "            uniform token[] xformOpOrder = [{}]", order.join(", "));
            let _ = writeln!(out, "        }}");
        }
        let _ = writeln!(out, "    }}");
    }
}

/// The bounding box of `points`: [min, max].
pub(super) fn extent(points: &[[f32; 3]]) -> [[f32; 3]; 2] {
    let lo = points.iter().fold([f32::MAX; 3], |m, p| std::array::from_fn(|i| m[i].min(p[i])));
    let hi = points.iter().fold([f32::MIN; 3], |m, p| std::array::from_fn(|i| m[i].max(p[i])));
    [lo, hi]
}

/// `name.timeSamples = { first: [(x, y, z), ...], ... }`, numbers in Rust's shortest exact
/// form, `frames` frames (each read by `frame`) at time codes from `first` on.
pub(super) fn samples(
    w: &mut dyn std::io::Write,
    first: u64,
    frames: u64,
    name: &str,
    mut frame: impl FnMut(u64, &mut Vec<[f32; 3]>) -> std::io::Result<()>,
) -> std::io::Result<()> {
    writeln!(w, "        {name}.timeSamples = {{")?;
    let mut values = Vec::new();
    for f in 0..frames {
        frame(f, &mut values)?;
        write!(w, "            {}: [", first + f)?;
        for (i, [x, y, z]) in values.iter().enumerate() {
            write!(w, "{}({x}, {y}, {z})", if i == 0 { "" } else { ", " })?;
        }
        writeln!(w, "],")?;
    }
    writeln!(w, "        }}")
}

/// A valid USD prim name: letters, digits and underscores, not starting with a digit.
pub(super) fn usd_name(name: &str) -> String {
    let mut s: String = name.chars().map(|c| if c.is_ascii_alphanumeric() { c } else { '_' }).collect();
    if s.is_empty() || s.starts_with(|c: char| c.is_ascii_digit()) {
        s.insert(0, '_');
    }
    s
}
