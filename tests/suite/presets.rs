//! Every shipped preset loads, builds and runs on the GPU with validation and synchronization
//! validation (two substeps per frame, to keep lavapipe quick).

use crate::common;

use msdsim::scene;
use msdsim::sim::gpu::GpuSim;

/// The presets whose first frame compiles the contact pipelines (8 to 40 s each on lavapipe
/// with no shader cache yet, as on a fresh machine): the exhaustive tier's, where each also
/// runs in cli's `auto_preset_*`.
const HEAVY: [&str; 6] = ["drape", "playground", "skirt", "towel", "turntable", "twist"];

#[test]
fn every_preset_loads_and_runs() {
    presets_load_and_run(|name| !HEAVY.contains(&name));
}

#[test]
#[ignore = "exhaustive tier: kept out of the default tier's 10-minute budget"]
fn every_preset_with_contact_pipelines_loads_and_runs() {
    presets_load_and_run(|name| HEAVY.contains(&name));
}

fn presets_load_and_run(which: impl Fn(&str) -> bool) {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("presets");
    // (the presets, not the meshes some of them read)
    let mut names: Vec<_> = (std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    names.sort();
    let ctx = common::gpu();
    for path in names.iter().filter(|p| which(&p.file_stem().unwrap().to_string_lossy())) {
        let scene = scene::load(path, &["sim.substeps=2".to_string()])
            .unwrap_or_else(|e| panic!("{} does not load: {e}", path.display()));
        let objects = scene.cloths.len() + scene.ropes.len() + scene.mesh_cloths.len();
        assert!(objects > 0, "{} is empty", path.display());
        let model = scene::to_model(&scene);
        let mut sim = GpuSim::new(&ctx, &model).unwrap();
        sim.step_frame(&ctx).unwrap();
        let states = sim.read_states(&ctx).unwrap();
        for (o, s) in model.objects.iter().zip(&states) {
            assert!(
                s.particles.iter().all(|p| p.pos.iter().all(|x| x.is_finite())),
                "{}: {} has non-finite positions",
                path.display(),
                o.name
            );
        }
        sim.destroy(&ctx);
    }
    // (the heavy ones too, so that a renamed one is not left out of both tiers)
    for required in ["curtain", "flag", "towel", "rope", "playground"].into_iter().chain(HEAVY) {
        assert!(
            names.iter().any(|p| p.file_stem().unwrap() == required),
            "presets/{required}.toml is missing"
        );
    }
    common::assert_clean(&ctx);
}

/// The sections of a reference page (`## ` and `### ` headings) with the first backticked
/// token of each table row, up to its first space (`--frames N` gives `--frames`).
fn reference_rows(page: &str) -> Vec<(String, Vec<String>)> {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/reference").join(page);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut sections: Vec<(String, Vec<String>)> = Vec::new();
    for line in text.lines() {
        if let Some(heading) = line.strip_prefix("### ").or_else(|| line.strip_prefix("## ")) {
            sections.push((heading.trim().to_string(), Vec::new()));
        } else if let (Some(row), Some(section)) = (line.strip_prefix("| `"), sections.last_mut()) {
            let token = row.split('`').next().unwrap_or("");
            section.1.push(token.split(' ').next().unwrap_or("").trim_end_matches(',').to_string());
        }
    }
    sections
}

/// The names serde expects where `toml` puts an unknown key (its "unknown field" message).
fn expected_keys(toml: &str) -> std::collections::BTreeSet<String> {
    let message = match toml::from_str::<scene::Scene>(toml) {
        Ok(_) => panic!("an unknown key was accepted in:\n{toml}"),
        Err(e) => e.to_string(),
    };
    let expected = message.split("expected").nth(1).unwrap_or_else(|| panic!("no field list in: {message}"));
    expected.split('`').skip(1).step_by(2).map(str::to_string).collect()
}

/// docs/reference/presets.md lists exactly the keys each table of a preset accepts: every
/// table's row keys against the list serde gives when it refuses an unknown key.
#[test]
fn the_preset_reference_lists_every_key_of_every_table() {
    let probes = [
        ("`[sim]`", "[sim]\nzz_unknown = 0\n"),
        ("`[wind]`", "[wind]\nzz_unknown = 0\n"),
        ("`[light]`", "[light]\nzz_unknown = 0\n"),
        ("`[ground]`", "[ground]\nzz_unknown = 0\n"),
        ("`[[sphere]]`", "[[sphere]]\nzz_unknown = 0\n"),
        ("`[[box]]`", "[[box]]\nzz_unknown = 0\n"),
        ("`[[capsule]]`", "[[capsule]]\nzz_unknown = 0\n"),
        ("`[[mesh]]`", "[[mesh]]\nzz_unknown = 0\n"),
        ("motion", "[[sphere]]\ncenter = [0.0, 0.0, 0.0]\nradius = 1.0\nmotion = { zz_unknown = 0 }\n"),
        ("`[[cloth]]`", "[[cloth]]\nzz_unknown = 0\n"),
        ("`[[rope]]`", "[[rope]]\nzz_unknown = 0\n"),
        ("`[[mesh_cloth]]`", "[[mesh_cloth]]\nzz_unknown = 0\n"),
        ("seams", "[[mesh_cloth]]\n[[mesh_cloth.seam]]\nzz_unknown = 0\n"),
        ("pin groups", "[[cloth]]\n[[cloth.pin_group]]\nzz_unknown = 0\n"),
    ];
    let sections = reference_rows("presets.md");
    for (heading, probe) in probes {
        let (_, rows) = sections
            .iter()
            .find(|(h, _)| h == heading)
            .unwrap_or_else(|| panic!("docs/reference/presets.md has no section {heading}"));
        let documented: std::collections::BTreeSet<String> = rows.iter().cloned().collect();
        assert_eq!(
            documented,
            expected_keys(probe),
            "docs/reference/presets.md, {heading}: documented vs accepted"
        );
    }
}

/// docs/reference/cli.md lists exactly the flags of every command (and the global ones), as
/// the clap definitions make them.
#[test]
fn the_cli_reference_lists_every_flag_of_every_command() {
    use clap::CommandFactory;
    let cli = msdsim::cli::Cli::command();
    let longs = |c: &clap::Command| -> std::collections::BTreeSet<String> {
        c.get_arguments().filter_map(|a| a.get_long()).map(|l| format!("--{l}")).collect()
    };
    let sections = reference_rows("cli.md");
    let documented = |heading: &str| -> std::collections::BTreeSet<String> {
        let (_, rows) = sections
            .iter()
            .find(|(h, _)| h == heading)
            .unwrap_or_else(|| panic!("docs/reference/cli.md has no section {heading}"));
        rows.iter().filter(|r| r.starts_with("--") && *r != "--help" && *r != "--version").cloned().collect()
    };
    assert_eq!(documented("Global options"), longs(&cli), "docs/reference/cli.md, global options");
    let commands: Vec<&clap::Command> = cli.get_subcommands().collect();
    assert!(!commands.is_empty());
    for c in commands {
        let heading = format!("msdsim {}", c.get_name());
        assert_eq!(documented(&heading), longs(c), "docs/reference/cli.md, {heading}");
    }
}
