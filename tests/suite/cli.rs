//! The binary on good and bad input: bad input exits with code 2 and one line that names the
//! problem, never a panic or a validation message. Runs with --validation.

use crate::common;

use std::path::Path;
use std::process::{Command, Output};

use common::GOOD;

fn msdsim(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_msdsim"))
        .arg("--validation")
        .args(args)
        .output()
        .expect("running the msdsim binary")
}

fn write(dir: &Path, name: &str, text: &str) -> String {
    let path = dir.join(name);
    std::fs::write(&path, text).expect("writing a test preset");
    path.display().to_string()
}

/// Runs `args` and checks: exit code 2, one stderr line containing every `needle`, no panic.
fn rejects(args: &[&str], needles: &[&str]) {
    let out = msdsim(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: expected exit code 2; stderr:\n{stderr}");
    assert!(
        !stderr.contains("panicked") && !stderr.contains("internal error"),
        "{args:?} panicked:\n{stderr}"
    );
    assert!(!stderr.to_lowercase().contains("validation"), "{args:?}: validation message:\n{stderr}");
    let lines: Vec<&str> = stderr.lines().filter(|l| !l.trim().is_empty()).collect();
    assert_eq!(lines.len(), 1, "{args:?}: expected one line, got:\n{stderr}");
    for needle in needles {
        assert!(stderr.contains(needle), "{args:?}: {needle:?} not in: {stderr}");
    }
}

#[test]
fn good_preset_runs_and_writes_the_state() {
    let dir = tempfile::tempdir().unwrap();
    let preset = write(dir.path(), "good.toml", GOOD);
    let out_path = dir.path().join("state.json");
    let out = msdsim(&[
        "simulate",
        "--preset",
        &preset,
        "--frames",
        "3",
        "--set",
        "sim.substeps=8",
        "--out",
        out_path.to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "exit {:?}\n{}", out.status, String::from_utf8_lossy(&out.stderr));
    assert!(stdout.contains("frame      3  gpu"), "per-frame GPU time missing:\n{stdout}");
    assert!(stdout.contains("GPU frame time: mean"), "summary missing:\n{stdout}");
    let state: serde_json::Value = serde_json::from_slice(&std::fs::read(&out_path).unwrap()).unwrap();
    assert_eq!(state["substeps"], 24, "3 frames of the overridden 8 substeps");
    assert!((state["time"].as_f64().unwrap() - 3.0 / 60.0).abs() < 1e-9);
    let objects = state["objects"].as_array().unwrap();
    assert_eq!(objects.len(), 2);
    assert_eq!(objects[0]["kind"], "cloth");
    assert_eq!(objects[0]["dims"], serde_json::json!([5, 4]));
    assert_eq!(objects[0]["positions"].as_array().unwrap().len(), 20);
    assert_eq!(objects[1]["kind"], "rope");
    assert_eq!(objects[1]["velocities"].as_array().unwrap().len(), 6);
}

#[test]
fn malformed_toml() {
    let dir = tempfile::tempdir().unwrap();
    let p = write(dir.path(), "bad.toml", "[sim\nsubsteps = 4\n");
    rejects(&["simulate", "--preset", &p], &["bad.toml", "line 1"]);
}

#[test]
fn unknown_key() {
    let dir = tempfile::tempdir().unwrap();
    let p = write(
        dir.path(),
        "k.toml",
        &GOOD.replace("mass = 0.01\nstiffness = {", "mass = 0.01\nmas = 1\nstiffness = {"),
    );
    rejects(&["simulate", "--preset", &p], &["k.toml", "cloth[0]", "unknown field `mas`"]);
}

#[test]
fn negative_mass() {
    let dir = tempfile::tempdir().unwrap();
    let p = write(dir.path(), "m.toml", &GOOD.replacen("mass = 0.01", "mass = -1.0", 1));
    rejects(&["simulate", "--preset", &p], &["m.toml", "cloth[0].mass = -1", "must be between 1e-9 and 1e9"]);
}

/// `sim.tolerance = 0` is outside the open interval, and the message says so.
#[test]
fn zero_tolerance_says_greater_than_zero() {
    let dir = tempfile::tempdir().unwrap();
    let p = write(dir.path(), "t.toml", &GOOD.replacen("substeps = 4", "substeps = 4\ntolerance = 0.0", 1));
    rejects(&["simulate", "--preset", &p], &["sim.tolerance = 0", "greater than 0 and less than 1"]);
}

/// Values that pass as f64 but mean nothing in the GPU's f32 (overflow, underflow to zero, or
/// infinity) are refused before the run, naming the key and the range allowed.
#[test]
fn values_beyond_what_f32_can_carry_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        ("radius = 0.2", "radius = 1e300", "sphere[0].radius = 1e300"),
        ("mass = 0.01", "mass = 1e-50", "cloth[0].mass = 1e-50"),
        ("mass = 0.01", "mass = inf", "cloth[0].mass = inf: must be a finite number > 0"),
        ("structural = 100.0", "structural = 1e40", "cloth[0].stiffness.structural = 1e40"),
        ("origin = [-0.2, 0.5, 0.0]", "origin = [-0.2, 1e30, 0.0]", "cloth[0].origin = [-0.2, 1e30, 0]"),
        ("substeps = 4", "substeps = 4\ngravity = [0.0, -1e20, 0.0]", "sim.gravity = [0, -1e20, 0]"),
    ];
    for (i, (from, to, needle)) in cases.into_iter().enumerate() {
        let p = write(dir.path(), &format!("f{i}.toml"), &GOOD.replacen(from, to, 1));
        rejects(&["simulate", "--preset", &p], &[needle, "must be"]);
    }
}

#[test]
fn zero_resolution() {
    let dir = tempfile::tempdir().unwrap();
    let p = write(dir.path(), "z.toml", &GOOD.replace("resolution = [5, 4]", "resolution = [0, 4]"));
    rejects(&["simulate", "--preset", &p], &["z.toml", "cloth[0].resolution"]);
}

#[test]
fn grid_too_large_for_device_memory() {
    let dir = tempfile::tempdir().unwrap();
    let p =
        write(dir.path(), "big.toml", &GOOD.replace("resolution = [5, 4]", "resolution = [16384, 16384]"));
    rejects(&["simulate", "--preset", &p], &["too large for the device"]);
}

#[test]
fn missing_file() {
    rejects(
        &["simulate", "--preset", "/nonexistent/preset.toml"],
        &["/nonexistent/preset.toml", "cannot read"],
    );
}

/// A FIFO with no writer as the preset reads as empty at once (it was waited on forever):
/// `simulate` refuses the empty scene with exit code 2; a preset through a pipe with a writer
/// (`--preset <(cat preset)`) runs; a folder is named as one. Each run must end within 30 s.
#[test]
fn a_pipe_or_a_folder_as_the_preset_is_refused_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("p.toml");
    assert!(Command::new("mkfifo").arg(&fifo).status().unwrap().success());
    let mut child = Command::new(env!("CARGO_BIN_EXE_msdsim"))
        .args(["simulate", "--preset", fifo.to_str().unwrap(), "--frames", "1"])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let start = std::time::Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed().as_secs() > 30 {
            child.kill().unwrap();
            panic!("simulate waited on a FIFO as its preset");
        }
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("nothing to simulate") && err.contains("p.toml"), "{err}");
    let piped = format!(
        "{} simulate --preset <(cat {}/presets/rope.toml) --frames 1 --quiet",
        env!("CARGO_BIN_EXE_msdsim"),
        env!("CARGO_MANIFEST_DIR")
    );
    let out = Command::new("bash").args(["-c", &piped]).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    rejects(&["simulate", "--preset", dir.path().to_str().unwrap()], &["a folder, not a preset"]);
}

#[test]
fn bad_override() {
    let dir = tempfile::tempdir().unwrap();
    let p = write(dir.path(), "o.toml", GOOD);
    rejects(&["simulate", "--preset", &p, "--set", "sim.substeps=zero"], &["sim.substeps", "invalid type"]);
    rejects(&["simulate", "--preset", &p, "--set", "cloth.nosuch.mass=1"], &["cloth", "nosuch"]);
    rejects(&["simulate", "--preset", &p, "--set", "sim.substeps"], &["KEY=VALUE"]);
    rejects(&["simulate", "--preset", &p, "--set", "sim.substeps=0"], &["sim.substeps = 0"]);
}

#[test]
fn bad_arguments() {
    let dir = tempfile::tempdir().unwrap();
    let p = write(dir.path(), "a.toml", GOOD);
    let out = msdsim(&["simulate", "--preset", &p, "--frames", "-3"]);
    assert_eq!(out.status.code(), Some(2), "clap rejects a negative frame count with code 2");
    rejects(&["simulate", "--preset", &p, "--device", "no-such-gpu"], &["no-such-gpu"]);
    rejects(
        &["simulate", "--preset", &p, "--out", "/nonexistent/dir/state.json"],
        &["--out", "cannot write"],
    );
}

/// Without any Vulkan driver the binary fails with a clear message (exit 1), and the test
/// harness, which uses the same context creation, fails loudly rather than skipping.
#[test]
fn no_vulkan_device_is_a_clear_failure() {
    let out = Command::new(env!("CARGO_BIN_EXE_msdsim"))
        .arg("devices")
        .env("VK_DRIVER_FILES", "/nonexistent/icd.json")
        .env("VK_ICD_FILENAMES", "/nonexistent/icd.json")
        .output()
        .expect("running the msdsim binary");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "stderr: {stderr}");
    assert!(stderr.contains("no usable Vulkan device"), "unclear message: {stderr}");
    assert!(!stderr.contains("panicked"), "panicked: {stderr}");
}

/// An unstable preset (springs far too stiff for the substep) is stopped by the runtime guard:
/// exit code 3 and one line that says what happened and what to change.
#[test]
fn an_unstable_scene_exits_3_with_advice() {
    let dir = tempfile::tempdir().unwrap();
    let unstable = GOOD
        .replace(
            "stiffness = { structural = 100.0, shear = 20.0, bending = 5.0 }",
            "stiffness = { structural = 50000.0, shear = 20.0, bending = 5.0 }",
        )
        .replace("mass = 0.01\nstiffness = {", "mass = 0.0001\nstiffness = {");
    let p = write(dir.path(), "unstable.toml", &unstable);
    let out = msdsim(&["simulate", "--preset", &p, "--frames", "60", "--quiet"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(3), "stderr: {stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("cloth 'c'") && stderr.contains("substeps"), "{stderr}");
    assert!(!stderr.to_lowercase().contains("validation") && !stderr.contains("panicked"), "{stderr}");
    assert!(stdout.contains("PAST IT"), "the prediction is printed before the run:\n{stdout}");
}

/// A blow-up is stopped by the guard at the end of its frame, not by the GPU timeout (issue
/// 69, item 6): the towel with edge contact and particles a thousand times too light blows up
/// in its first frame; its particles' non-finite positions used to share one cell of the
/// self-contact hash, so each search walked all of them and the frame took 5 to 8 s on
/// lavapipe alone; each now has a cell of its own and the run ends with the guard's exit 3 in
/// about a second a frame alone (3 to 3.6 s for its 3 frames). With another test running
/// beside it on 2 cores a frame took over 4 s and, once, over 6 s: the timeout of
/// 10 s leaves that margin and still stops the old behaviour under the same load. It runs the
/// two frames the guard needs: a third, submitted before the second's guard is read (frames
/// in flight), runs on the blown-up state, and on some runs took 30 to 40 s on lavapipe (not
/// yet explained: docs/guide/limits.md). Edge contact holds each move to half the contact
/// distance a substep (but not one past sim.max_speed), so the guard may see the blow-up
/// first as a spring stretched past twice its length; its message names the stability limit
/// either way. A run of the same scene at its own mass comes first: lavapipe compiles the
/// pipelines in the first frame (20 s and more with no shader cache yet, as on a fresh
/// machine), and Mesa's shader cache then has them for the timed run.
#[test]
#[ignore = "exhaustive tier: kept out of the default tier's 10-minute budget"]
fn a_blow_up_with_edge_contact_ends_within_its_frame() {
    let scene = [
        "simulate",
        "--preset",
        "presets/towel.toml",
        "--set",
        "cloth.0.self_contact=\"triangles_and_edges\"",
        "--set",
        "sim.integrator=\"symplectic_euler\"",
        "--quiet",
    ];
    // (its outcome is the timed run's to check)
    msdsim(&[&scene[..], &["--frames", "1"]].concat());
    let out = msdsim(
        &[&["--gpu-timeout", "10"], &scene[..], &["--set", "cloth.0.mass=1e-7", "--frames", "2"]].concat(),
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(3), "stderr: {stderr}");
    assert!(stderr.contains("blew up") || stderr.contains("over-stretched"), "{stderr}");
    assert!(stderr.contains("stability limit"), "{stderr}");
}

/// `stability` sweeps stiffness x substeps per method and writes the CSV and an SVG map each;
/// for symplectic Euler the stiffest, coarsest cell is unstable and predicted so, the softest,
/// finest one stable; the implicit method is stable in every cell, four decades of stiffness
/// at 1 to 64 substeps.
#[test]
#[ignore = "exhaustive tier: kept out of the default tier's 10-minute budget"]
fn stability_map_writes_csv_and_svg() {
    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().join("map");
    let out = msdsim(&[
        "stability",
        "--methods",
        "symplectic_euler,implicit",
        "--points",
        "3",
        "--frames",
        "10",
        "--out",
        out_dir.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(!stdout.contains("METHOD"), "names the files it wrote: {stdout}");
    let csv = std::fs::read_to_string(out_dir.join("stability.csv")).unwrap();
    let rows: Vec<&str> = csv.lines().filter(|l| !l.starts_with('#')).skip(1).collect();
    assert_eq!(rows.len(), 18, "{csv}");
    let euler = |prefix: &str| {
        let key = format!("symplectic_euler,{prefix}");
        *rows.iter().find(|r| r.starts_with(&key)).unwrap_or_else(|| panic!("no row {key}"))
    };
    let stiffest_coarsest = euler("100,1,");
    assert!(
        stiffest_coarsest.contains(",false,") && !stiffest_coarsest.ends_with("stable"),
        "{stiffest_coarsest}"
    );
    assert!(euler("0.01,64,").ends_with(",true,stable"), "{}", euler("0.01,64,"));
    let implicit: Vec<&&str> = rows.iter().filter(|r| r.starts_with("implicit,")).collect();
    assert_eq!(implicit.len(), 9);
    assert!(implicit.iter().all(|r| r.ends_with(",true,stable")), "{implicit:#?}");
    for method in ["symplectic_euler", "implicit"] {
        let svg = std::fs::read_to_string(out_dir.join(format!("stability-{method}.svg"))).unwrap();
        assert!(svg.starts_with("<svg") && svg.contains("predicted unstable"));
    }
}

/// `chart` on a tiny sweep: one row per setting with finite errors and costs for the stable
/// ones, a Pareto front, and an SVG with a curve per method. (The default tier's chart is
/// `chart_contact_scene_converges_with_substeps`.)
#[test]
#[ignore = "exhaustive tier: kept out of the default tier's 10-minute budget"]
fn chart_writes_csv_and_svg() {
    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().join("chart");
    let out = msdsim(&[
        "chart",
        "--scenes",
        "rope",
        "--substeps",
        "2,8",
        "--iterations",
        "3",
        "--reference-substeps",
        "64",
        "--out",
        out_dir.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let csv = std::fs::read_to_string(out_dir.join("chart.csv")).unwrap();
    let rows: Vec<Vec<&str>> =
        csv.lines().filter(|l| !l.starts_with('#')).skip(1).map(|l| l.split(',').collect()).collect();
    let methods = msdsim::sim::model::Integrator::ALL.len();
    assert_eq!(rows.len(), 2 * methods, "{methods} methods x 2 substep counts:\n{csv}");
    for r in &rows {
        let cost: f64 = r[5].parse().unwrap();
        assert!(cost > 0.0, "GPU time per simulated second: {r:?}");
        if r[r.len() - 1].is_empty() {
            let rms: f64 = r[6].parse().unwrap();
            assert!(rms.is_finite() && rms > 0.0, "{r:?}");
        }
    }
    assert!(rows.iter().any(|r| r[r.len() - 2] == "true"), "a Pareto front:\n{csv}");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains("chart-rope.svg") && !stdout.contains("SCENE"),
        "names the files it wrote: {stdout}"
    );
    let svg = std::fs::read_to_string(out_dir.join("chart-rope.svg")).unwrap();
    for label in ["symplectic_euler", "verlet", "xpbd (3 it.)", "implicit (3 it.)", "Pareto front"] {
        assert!(svg.contains(label), "{label} in the chart");
    }
}

/// Runs `chart` on built-in scene `scene` with `args`; returns its chart.csv and checks that
/// chart-SCENE.svg was written.
fn chart_scene(scene: &str, args: &[&str]) -> String {
    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().join("chart");
    let mut all = vec!["chart", "--scenes", scene, "--out", out_dir.to_str().unwrap()];
    all.extend_from_slice(args);
    let out = msdsim(&all);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(out_dir.join(format!("chart-{scene}.svg")).exists());
    std::fs::read_to_string(out_dir.join("chart.csv")).unwrap()
}

/// The RMS error at 0.5 s of a chart.csv's row for `method` at `substeps`.
fn chart_error(csv: &str, method: &str, substeps: &str) -> f64 {
    let row = csv
        .lines()
        .filter(|l| !l.starts_with('#'))
        .map(|l| l.split(',').collect::<Vec<_>>())
        .find(|r| r[1] == method && r[2] == substeps)
        .unwrap_or_else(|| panic!("no {method} row at {substeps} substeps:\n{csv}"));
    row[6].parse().unwrap()
}

/// `chart`'s stiff scene shows what docs/ACCURACY.md's "Large steps" measures: at one 1/60 s
/// substep and 10 iterations VBD and the implicit method follow the settling stiff cloth (they
/// converge to its sag) and XPBD, whose Gauss-Seidel sweeps resolve only part of the cloth's
/// stretch at that step, hangs several times too low: its error at least 5x each of theirs
/// (measured on lavapipe: see the assertion message).
#[test]
#[ignore = "exhaustive tier: kept out of the default tier's 10-minute budget"]
fn chart_stiff_scene_separates_the_large_step_methods() {
    let args = [
        "--methods",
        "vbd,implicit,xpbd",
        "--substeps",
        "1",
        "--iterations",
        "10",
        "--reference-substeps",
        "128",
    ];
    let csv = chart_scene("stiff", &args);
    let [vbd, implicit, xpbd] = ["vbd", "implicit", "xpbd"].map(|m| chart_error(&csv, m, "1"));
    assert!(
        xpbd > 5.0 * vbd.max(implicit),
        "VBD's error {vbd:.2e}, the implicit method's {implicit:.2e}, XPBD's {xpbd:.2e}:\n{csv}"
    );
}

/// `chart`'s contact scene (the curtain preset draped over its sphere, with Coulomb friction
/// and the ground): Verlet's error at 0.5 s falls at least 2x from 4 to 16 substeps, half of
/// first order's 4x, since contact and the stick-slip decisions of friction make a method at
/// best first order (measured on lavapipe: 3.4e-3 to 4.5e-4, 7.5x; at 2 s the decisions have
/// parted, 3.0e-3 to 2.0e-3, which the chart shows).
#[test]
fn chart_contact_scene_converges_with_substeps() {
    let csv =
        chart_scene("contact", &["--methods", "verlet", "--substeps", "4,16", "--reference-substeps", "128"]);
    let (coarse, fine) = (chart_error(&csv, "verlet", "4"), chart_error(&csv, "verlet", "16"));
    assert!(coarse > 2.0 * fine, "at 0.5 s: {coarse:.2e} at 4 substeps, {fine:.2e} at 16:\n{csv}");
}

/// `integrator = "auto"` calibrates, says what it picked (a method whose measured error meets
/// the tolerance) and simulates with it; a tolerance finer than its reference can certify is
/// refused with exit code 2 and the reason, before any simulation.
#[test]
#[ignore = "exhaustive tier: kept out of the default tier's 10-minute budget"]
fn auto_integrator_picks_a_method_within_the_tolerance() {
    let args = |tol: &str| {
        msdsim(&[
            "simulate",
            "--preset",
            "presets/curtain.toml",
            "--frames",
            "5",
            "--quiet",
            "--set",
            "cloth.0.resolution=[10, 10]",
            "--set",
            "sim.integrator=\"auto\"",
            "--set",
            &format!("sim.tolerance={tol}"),
        ])
    };
    let out = args("0.01");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let line = stdout.lines().find(|l| l.contains("picked")).unwrap_or_else(|| panic!("no pick:\n{stdout}"));
    let error: f64 = line.split("error ").nth(1).and_then(|s| s.split(' ').next()).unwrap().parse().unwrap();
    assert!(error <= 0.01, "{line}");
    let out = args("1e-9");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("sim.tolerance") && !stderr.contains("panicked"), "{stderr}");
}

/// A scene so stiff that Verlet blows up at 64 substeps a frame (its predicted limit is 92)
/// still calibrates: the reference then starts at 128 against 256 (the cheaper 64 against 128
/// pair, tried first, used to end the calibration with the guard's report).
#[test]
#[ignore = "exhaustive tier: kept out of the default tier's 10-minute budget"]
fn auto_calibrates_a_scene_too_stiff_for_the_cheaper_reference() {
    let out = msdsim(&[
        "simulate",
        "--preset",
        "presets/rope.toml",
        "--frames",
        "1",
        "--quiet",
        "--set",
        "rope.0.stiffness=300000",
        "--set",
        "sim.integrator=\"auto\"",
    ]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(stdout.contains("integrator = \"auto\" picked"), "{stdout}");
}

/// Runs `args`, expecting exit code 2 from clap's own checks, in one line like every other
/// error (clap's own message spans 3 to 6): the argument is named and it is not taken for an
/// unknown flag.
fn clap_rejects(args: &[&str], needle: &str) {
    let out = msdsim(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
    assert!(stderr.contains(needle) && !stderr.contains("unexpected argument"), "{args:?}: {stderr}");
    assert!(
        stderr.starts_with("msdsim: error: ") && stderr.trim_end().lines().count() == 1,
        "{args:?}: {stderr}"
    );
}

/// Negative and non-finite numbers are refused by the argument they were given to.
#[test]
fn negative_and_nan_arguments_name_their_option() {
    clap_rejects(&["simulate", "--preset", "presets/rope.toml", "--frames", "-5"], "'--frames");
    clap_rejects(&["stability", "--decades", "nan"], "'--decades");
    clap_rejects(&["stability", "--max-strain", "nan"], "'--max-strain");
    clap_rejects(&["simulate"], "--preset <FILE>");
}

/// What would run and report success for nothing is refused: a preset without objects (an
/// empty file, /dev/null), a file that is not a preset (/dev/urandom: capped, not read for
/// ever), a benchmark filter that matches no case, a chart against a reference that diverged.
#[test]
fn runs_that_would_mean_nothing_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let empty = write(dir.path(), "empty.toml", "[sim]\nsubsteps = 4\n");
    rejects(&["simulate", "--preset", &empty], &["empty.toml", "no cloth or rope"]);
    rejects(&["simulate", "--preset", "/dev/null"], &["/dev/null", "no cloth or rope"]);
    rejects(&["chart", "--preset", "/dev/null"], &["no cloth or rope"]);
    rejects(&["stability", "--preset", "/dev/null"], &["no cloth or rope"]);
    rejects(&["simulate", "--preset", "/dev/urandom"], &["/dev/urandom", "not a preset"]);
    let big = write(dir.path(), "big.toml", &format!("{GOOD}\n#{}\n", "x".repeat(2 << 20)));
    rejects(&["simulate", "--preset", &big], &["big.toml", "larger than 2 MiB"]);
    let out = dir.path().join("bench");
    let out_arg = out.to_str().unwrap();
    let bench = msdsim(&["bench", "--filter", "no such case", "--out", out_arg]);
    assert_eq!(bench.status.code(), Some(2), "{}", String::from_utf8_lossy(&bench.stderr));
    assert!(String::from_utf8_lossy(&bench.stderr).contains("matches no case"));
    assert!(!out.exists(), "the report's folder was made for nothing");
    let chart_out = dir.path().join("chart");
    let chart_args =
        ["chart", "--scenes", "rope", "--methods", "verlet", "--substeps", "2", "--reference-substeps", "2"];
    let chart = msdsim(&[&chart_args[..], &["--out", chart_out.to_str().unwrap()]].concat());
    assert_eq!(chart.status.code(), Some(2), "{}", String::from_utf8_lossy(&chart.stderr));
    assert!(String::from_utf8_lossy(&chart.stderr).contains("is not converged"));
}

/// Springs so stiff that no substep count within the limit of 4096 keeps symplectic Euler
/// stable: the prediction says so and names the integrators that are stable (instead of
/// asking for 4294967295 substeps), and the guard's advice too (exit 3).
#[test]
fn advice_past_the_largest_substep_count_names_the_stable_integrators() {
    let dir = tempfile::tempdir().unwrap();
    let p = write(dir.path(), "stiff.toml", &GOOD.replacen("structural = 100.0", "structural = 1e9", 1));
    let out = msdsim(&["simulate", "--preset", &p, "--frames", "30"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(3), "{stdout}\n{stderr}");
    for text in [&stdout, &stderr] {
        assert!(text.contains("no substep count up to 4096"), "{text}");
        assert!(text.contains("\"vbd\"") && !text.contains("4294967295"), "{text}");
    }
}

/// The same advice for a mesh cloth (a sliver triangle makes one vertex light, its springs
/// stiff against it) names the methods for large steps it runs with: every iterative one,
/// XPBD by spring classes too (`sim::cloth_mesh::METHODS`).
#[test]
fn advice_for_a_mesh_cloth_names_the_methods_it_runs_with() {
    let dir = tempfile::tempdir().unwrap();
    write(
        dir.path(),
        "s.obj",
        "v 0 1 0\nv 1 1 0\nv 1 0 0\nv 0 0 0\nv 1.000001 0.5 0\nf 1 4 3\nf 1 3 2\nf 2 3 5\n",
    );
    let text = "[sim]\nintegrator = \"symplectic_euler\"\n[[mesh_cloth]]\nname = \"s\"\nfile = \"s.obj\"\n\
                density = 0.2\nstiffness = { structural = 100.0, shear = 10.0, bending = 1.0 }\npinned = [0]\n";
    let p = write(dir.path(), "s.toml", text);
    let out = msdsim(&["simulate", "--preset", &p, "--frames", "30", "--quiet"]);
    let text = String::from_utf8_lossy(&out.stdout) + String::from_utf8_lossy(&out.stderr);
    let advice = "sim.integrator = \"xpbd\", \"implicit\", \"vbd\" or \"xpbd_jacobi\" (the methods";
    assert!(text.contains("PAST IT") && text.contains(advice), "{text}");
}

/// `integrator = "auto"` works on every shipped preset: where the scene is chaotic over the
/// 0.5 s calibration (the flag in the wind, the towel folding onto itself), it calibrates over a
/// shorter time the reference certifies and says so. (It used to refuse the flag and the towel
/// with the default tolerance.) Each cloth runs at most 20 particles a side, the same size, so
/// that lavapipe calibrates every preset in about 10 minutes of one core (the towel with
/// triangle self-contact alone took 257 s at its 40 x 40). So no cloth here has two
/// particles a thread in the fused kernel, as the shipped towel has. One test a preset, so that
/// the test threads share them (a calibration keeps about one core busy on lavapipe);
/// `auto_tests_name_every_shipped_preset` keeps the list whole.
fn auto_picks_a_method_on(name: &str) {
    let p = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("presets").join(format!("{name}.toml"));
    let scene = msdsim::scene::load(&p, &[]).unwrap();
    let coarse: Vec<String> = (scene.cloths.iter().enumerate())
        .map(|(i, c)| {
            format!("cloth.{i}.resolution=[{}, {}]", c.resolution[0].min(20), c.resolution[1].min(20))
        })
        .collect();
    let mut args = vec!["simulate", "--preset", p.to_str().unwrap(), "--frames", "1", "--quiet"];
    args.extend(["--set", "sim.integrator=\"auto\""]);
    args.extend(coarse.iter().flat_map(|c| ["--set", c.as_str()]));
    let out = msdsim(&args);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}: {}", p.display(), String::from_utf8_lossy(&out.stderr));
    assert!(stdout.contains("integrator = \"auto\" picked"), "{}: {stdout}", p.display());
}

/// One test a preset, named so that the longest calibrations start first (the test harness
/// starts tests in the order of their names; on lavapipe the towel takes about 220 s, the
/// playground 180, the rope on cloth 105, the others 10 to 40).
macro_rules! auto_preset_tests {
    ($($(#[$meta:meta])* $test:ident: $preset:literal),*) => {
        $(
            #[test]
            $(#[$meta])*
            fn $test() {
                auto_picks_a_method_on($preset);
            }
        )*
        #[test]
        fn auto_tests_name_every_shipped_preset() {
            let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("presets");
            let mut shipped: Vec<String> = (std::fs::read_dir(&dir).unwrap())
                .map(|e| e.unwrap().path())
                .filter(|p| p.extension().is_some_and(|x| x == "toml"))
                .map(|p| p.file_stem().unwrap().to_string_lossy().into_owned())
                .collect();
            shipped.sort();
            let mut tested = vec![$($preset),*];
            tested.sort();
            assert_eq!(shipped, tested, "add an auto_preset test for each new preset");
        }
    };
}

// The default tier calibrates the quickest preset (the curtain, about 5 s); the others repeat
// the same calibration on other scenes (towel 43 s, playground 128, rope on cloth 55 with
// nextest on 2 cores) and are the exhaustive tier's.
auto_preset_tests!(
    #[ignore = "exhaustive tier: the calibration again on another preset"]
    auto_preset_1_towel: "towel",
    #[ignore = "exhaustive tier: the calibration again on another preset"]
    auto_preset_2_playground: "playground",
    #[ignore = "exhaustive tier: the calibration again on another preset"]
    auto_preset_3_rope_on_cloth: "rope_on_cloth",
    #[ignore = "exhaustive tier: the calibration again on another preset"]
    auto_preset_4_flag: "flag",
    #[ignore = "exhaustive tier: the calibration again on another preset"]
    auto_preset_5_tablecloth: "tablecloth",
    #[ignore = "exhaustive tier: the calibration again on another preset"]
    auto_preset_6_rope: "rope",
    #[ignore = "exhaustive tier: the calibration again on another preset"]
    auto_preset_7_twist: "twist",
    #[ignore = "exhaustive tier: the calibration again on another preset"]
    auto_preset_9_turntable: "turntable",
    #[ignore = "exhaustive tier: the calibration again on another preset"]
    auto_preset_10_drape: "drape",
    #[ignore = "exhaustive tier: the calibration again on another preset"]
    auto_preset_11_holed_flag: "holed_flag",
    #[ignore = "exhaustive tier: the calibration again on another preset"]
    auto_preset_12_skirt: "skirt",
    auto_preset_8_curtain: "curtain"
);

/// `bench --end-to-end` runs a case as the app does (simulation and drawing offscreen, frames
/// in flight) and writes its report with the wall clock next to the GPU-only figure; a bad
/// --resolution is refused before any work.
#[test]
fn bench_end_to_end_writes_its_report() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("e2e");
    let out_arg = out.to_str().unwrap();
    let args = ["bench", "--end-to-end", "--filter", "rope 256, all features + 10", "--resolution", "64x48"];
    let run = msdsim(&[&args[..], &["--frames", "100", "--warmup", "2", "--out", out_arg]].concat());
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let md = std::fs::read_to_string(out.join("end-to-end.md")).unwrap();
    assert!(md.contains("64 x 48") && md.contains("| rope 256, all features + 10 spheres | 256 |"), "{md}");
    let csv = std::fs::read_to_string(out.join("end-to-end.csv")).unwrap();
    assert_eq!(csv.lines().filter(|l| !l.starts_with('#')).count(), 2, "{csv}");
    clap_rejects(&["bench", "--end-to-end", "--resolution", "8x8"], "'--resolution");
    clap_rejects(&["bench", "--end-to-end", "--resolution", "1920"], "'--resolution");
    clap_rejects(&["bench", "--resolution", "640x480"], "--end-to-end");
}

/// `simulate --shaders DIR` runs the GLSL of DIR: an unchanged copy of glsl/ gives the built-in
/// shaders' result bit for bit; a copy with a syntax error in a header stops the run with exit
/// code 2 and the compiler's file and line (it must not quietly run the built-in shaders); a
/// missing folder is named.
#[test]
fn simulate_runs_the_shaders_of_a_folder() {
    let dir = tempfile::tempdir().unwrap();
    let preset = write(dir.path(), "good.toml", GOOD);
    let copy = dir.path().join("glsl");
    std::fs::create_dir_all(copy.join("include")).unwrap();
    let source = Path::new(env!("CARGO_MANIFEST_DIR")).join("glsl");
    for sub in ["", "include"] {
        for entry in std::fs::read_dir(source.join(sub)).unwrap() {
            let path = entry.unwrap().path();
            if path.is_file() {
                std::fs::copy(&path, copy.join(sub).join(path.file_name().unwrap())).unwrap();
            }
        }
    }
    let run = |shaders: Option<&Path>, out: &str| {
        let out = dir.path().join(out);
        let mut args = vec!["simulate", "--preset", &preset, "--frames", "3", "--quiet"];
        let out_arg = out.display().to_string();
        args.extend(["--out", &out_arg]);
        let shaders_arg = shaders.map(|p| p.display().to_string());
        if let Some(s) = &shaders_arg {
            args.extend(["--shaders", s]);
        }
        (msdsim(&args), out)
    };
    let (built_in, built_in_out) = run(None, "built_in.json");
    assert!(built_in.status.success(), "{}", String::from_utf8_lossy(&built_in.stderr));
    let (copied, copied_out) = run(Some(&copy), "copied.json");
    assert!(copied.status.success(), "{}", String::from_utf8_lossy(&copied.stderr));
    let state = |p: &Path| {
        let v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(p).unwrap()).unwrap();
        v["objects"].clone()
    };
    assert_eq!(state(&built_in_out), state(&copied_out), "the copied shaders must compute the same");

    let header = copy.join("include").join("springs.glsl");
    let text = std::fs::read_to_string(&header).unwrap();
    std::fs::write(&header, format!("{text}\nnot glsl at all\n")).unwrap();
    let (broken, broken_out) = run(Some(&copy), "broken.json");
    let stderr = String::from_utf8_lossy(&broken.stderr);
    assert_eq!(broken.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("springs.glsl:") && stderr.contains("error"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(stderr.matches("syntax error").count(), 1, "said once: {stderr}");
    assert!(!broken_out.exists(), "no state written from a run that did not happen");
    // An include cycle (a header including itself, no guard) and an include from outside the
    // folders: clear compile errors, not an endless expansion (3 GB in 25 s) or an unwatched file.
    std::fs::write(&header, text).unwrap();
    std::fs::write(dir.path().join("outside.glsl"), "// a file beside the shader folder\n").unwrap();
    let looped = copy.join("include").join("loop.glsl");
    std::fs::write(&looped, "#include \"loop.glsl\"\n").unwrap();
    let normals = copy.join("cloth_normals.comp");
    let source = std::fs::read_to_string(&normals).unwrap();
    std::fs::write(
        &normals,
        source.replacen(
            "#include \"bindings.glsl\"",
            "#include \"bindings.glsl\"\n#include \"loop.glsl\"",
            1,
        ),
    )
    .unwrap();
    for (content, needle) in [
        ("#include \"loop.glsl\"\n", "an #include cycle"),
        ("#include \"../../outside.glsl\"\n", "outside the shader folder"),
    ] {
        std::fs::write(&looped, content).unwrap();
        let (out, _) = run(Some(&copy), "looped.json");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{stderr}");
        assert!(stderr.contains(needle) && stderr.contains("loop.glsl"), "{stderr}");
    }
    rejects(
        &["simulate", "--preset", &preset, "--shaders", "/nonexistent/glsl"],
        &["--shaders /nonexistent/glsl"],
    );
    rejects(&["simulate", "--preset", &preset, "--shaders", "/"], &["--shaders /", "not a shader folder"]);
}

/// Scenes of more objects or colliders than can run are refused before the run, with the
/// counts (12,000 two-node ropes did not finish 2 frames in 120 s; 20,000 spheres took 134 s):
/// 1,025 ropes and 1,025 spheres each get one line and exit 2; 1,024 ropes load.
#[test]
fn too_many_objects_or_colliders_are_refused_before_the_run() {
    let dir = tempfile::tempdir().unwrap();
    let ropes = |n: usize| {
        let rope = |i| {
            format!(
                "[[rope]]\nname = \"r{i}\"\nnodes = 2\nstart = [{i}, 1, 0]\nend = [{i}, 1, 0.1]\nmass = 0.01\n\
                 stiffness = 100.0\nbending_stiffness = 0.0\ndamping = 0.0\ndrag = 0.0\nfriction = 0.5\n\
                 radius = 0.01\nself_collision = false\npin = \"none\"\n"
            )
        };
        (0..n).map(rope).collect::<String>()
    };
    let spheres =
        (0..1025).map(|i| format!("[[sphere]]\ncenter = [{i}, 0, 0]\nradius = 0.1\n")).collect::<String>();
    let many_ropes = write(dir.path(), "ropes.toml", &ropes(1025));
    rejects(&["simulate", "--preset", &many_ropes, "--frames", "1"], &["1025 objects", "at most 1024"]);
    let many_spheres = write(dir.path(), "spheres.toml", &format!("{spheres}{}", ropes(1)));
    rejects(&["simulate", "--preset", &many_spheres, "--frames", "1"], &["1025 colliders", "at most 1024"]);
    let loaded = msdsim::scene::load(Path::new(&write(dir.path(), "most.toml", &ropes(1024))), &[]);
    assert!(loaded.is_ok(), "{:?}", loaded.err());
}

/// Hostile inputs that used to crash, be refused wrongly or pass as valid: a `--set` key of
/// 40,000 segments (a stack overflow, exit 134), `MSDSIM_VALIDATION=1` (refused as not a
/// boolean), a frame of 1e-44 s (a zero substep in f32, run anyway), an object name holding a
/// terminal escape sequence (printed raw), outputs naming an input or each other, ring weights
/// that overflow f32. Each is one line with exit 2, or runs.
#[test]
fn hostile_keys_values_and_names_get_one_clear_line() {
    let deep = format!("{}a=1", "a.".repeat(40_000));
    rejects(&["simulate", "--preset", "presets/flag.toml", "--set", &deep], &["--set", "at most 16"]);
    rejects(
        &["simulate", "--preset", "presets/flag.toml", "--set", "sim.frame_dt=1e-44"],
        &["sim.frame_dt", "between 1e-5 and 1"],
    );
    let out = msdsim(&["simulate", "--preset", "presets/flag.toml", "--set", "cloth.0.name=\"a\u{1b}[2Kb\""]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("control characters") && !stderr.contains('\u{1b}'), "{stderr}");
    // Outputs that would destroy an input or each other (exit 0 before: the preset replaced by
    // JSON, the recording by the state); the preset must be unchanged.
    let dir = tempfile::tempdir().unwrap();
    let preset = write(dir.path(), "p.toml", GOOD);
    let both = dir.path().join("x.usda").display().to_string();
    rejects(&["simulate", "--preset", &preset, "--out", &preset], &["--out", "the same file as the preset"]);
    rejects(
        &["simulate", "--preset", &preset, "--record", &both, "--out", &both],
        &["--out", "the same file as --record"],
    );
    // ... or a file the recording writes: an OBJ frame, a point cache's mesh.
    let (obj, frame) = (dir.path().join("x.obj"), dir.path().join("x_00002.obj"));
    rejects(
        &[
            "simulate",
            "--preset",
            &preset,
            "--record",
            obj.to_str().unwrap(),
            "--out",
            frame.to_str().unwrap(),
        ],
        &["--out", "the same file as a file --record writes"],
    );
    let cache = dir.path().join("x.pc2");
    rejects(
        &[
            "simulate",
            "--preset",
            &preset,
            "--record",
            cache.to_str().unwrap(),
            "--out",
            obj.to_str().unwrap(),
        ],
        &["--out", "the same file as a file --record writes"],
    );
    assert_eq!(std::fs::read_to_string(&preset).unwrap(), GOOD);
    // A recording that would replace or remove the preset (exit 0 before, the preset lost): a
    // frame it writes, an earlier frame it cleans up, a point cache's mesh or cache. Nothing is
    // written or removed.
    for (preset_name, record_name) in
        [("r_00001.obj", "r.obj"), ("r_00007.obj", "r.obj"), ("r.obj", "r.pc2"), ("r_flag.pc2", "r.pc2")]
    {
        let dir = tempfile::tempdir().unwrap();
        let preset = write(dir.path(), preset_name, GOOD);
        let record = dir.path().join(record_name);
        let record = record.to_str().unwrap();
        let args = ["simulate", "--preset", &preset, "--frames", "2", "--record", record];
        rejects(&args, &["--record", "would replace or remove the preset", preset_name]);
        assert_eq!(std::fs::read_to_string(&preset).unwrap(), GOOD, "{preset_name}");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1, "{preset_name}: a file was written");
        // ... also through a link to the folder.
        let link = dir.path().join("link");
        std::os::unix::fs::symlink(dir.path(), &link).unwrap();
        let through = link.join(record_name);
        let args = ["simulate", "--preset", &preset, "--frames", "2", "--record", through.to_str().unwrap()];
        rejects(&args, &["--record", "would replace or remove the preset"]);
        assert_eq!(std::fs::read_to_string(&preset).unwrap(), GOOD, "{preset_name}");
    }
    // --out naming a shader source of --shaders would replace the edited shader.
    let shaders = tempfile::tempdir().unwrap();
    let source = write(shaders.path(), "physics.comp", "#version 460\n");
    let args = [
        "simulate",
        "--preset",
        "presets/flag.toml",
        "--shaders",
        shaders.path().to_str().unwrap(),
        "--out",
        &source,
    ];
    rejects(&args, &["--out", "a shader source of --shaders"]);
    assert_eq!(std::fs::read_to_string(&source).unwrap(), "#version 460\n");
    rejects(
        &[
            "simulate",
            "--preset",
            "presets/rope.toml",
            "--set",
            "rope.0.ring_weights=[[1e300,0],[1,0],[1,0],[1,0],[1,0],[1,0],[1,0],[1,0]]",
        ],
        &["ring_weights", "between -100 and 100"],
    );
    // Messages stay short and name what is wrong: a tiny number in exponent form (it was 401
    // characters), an entry of an array the preset lacks (it was serde's "invalid type: map").
    let tiny = msdsim(&["simulate", "--preset", "presets/flag.toml", "--set", "sim.frame_dt=1e-300"]);
    let said = String::from_utf8_lossy(&tiny.stderr);
    assert!(said.contains("sim.frame_dt = 1e-300") && said.len() < 200, "{said}");
    rejects(
        &["simulate", "--preset", "presets/flag.toml", "--set", "box.0.center=[0,1,0]"],
        &["the preset has no box entries, so no box.0", "[[box]]"],
    );
    // A results folder that is a file, and an empty device name.
    let file = write(dir.path(), "results", "kept");
    for command in [&["bench", "--frames", "100", "--out", &file][..], &["chart", "--out", &file][..]] {
        rejects(command, &["--out", "a file, not a folder"]);
    }
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "kept");
    let empty = msdsim(&["--device", "", "devices"]);
    assert_eq!(empty.status.code(), Some(2), "an empty --device is refused");
    assert!(String::from_utf8_lossy(&empty.stderr).contains("--device"));
    rejects(
        &["simulate", "--preset", "presets/flag.toml", "--set", "cloth.0.name=\"1\""],
        &["must not be a number"],
    );
    rejects(
        &["simulate", "--preset", "presets/flag.toml", "--set", "wind.speed=0"],
        &["wind.speed = 0", "air speed", "model = \"paper\""],
    );
    // A preset written for the paper's wind (a force, no model) would otherwise blow the
    // default aerodynamic air and drop its force without a word.
    rejects(
        &["simulate", "--preset", "presets/flag.toml", "--set", "wind.force=0.05"],
        &["wind.force = 0.05", "no force", "model = \"paper\""],
    );
    for on in ["1", "true", "yes"] {
        let run = Command::new(env!("CARGO_BIN_EXE_msdsim"))
            .env("MSDSIM_VALIDATION", on)
            .args(["simulate", "--preset", "presets/rope.toml", "--frames", "1", "--quiet"])
            .output()
            .expect("running the msdsim binary");
        assert!(run.status.success(), "MSDSIM_VALIDATION={on}: {}", String::from_utf8_lossy(&run.stderr));
    }
}

/// A submission that outlives `--gpu-timeout` (a shader that never ends, here a frame far
/// slower than the 0.1 s allowed: 160,000 particles at 64 substeps on lavapipe) stops the run
/// with exit code 1 and one line saying what to do; the process ends without waiting for the
/// work (before, fences waited for ever). A timeout outside 0.1 to 86400 s is refused.
#[test]
fn gpu_work_past_the_timeout_stops_with_exit_1() {
    let dir = tempfile::tempdir().unwrap();
    let p = write(dir.path(), "p.toml", GOOD);
    let start = std::time::Instant::now();
    let args = [
        "--gpu-timeout",
        "0.1",
        "simulate",
        "--preset",
        &p,
        "--set",
        "cloth.0.resolution=[400,400]",
        "--set",
        "sim.substeps=64",
        "--frames",
        "20",
        "--quiet",
    ];
    let out = msdsim(&args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    let lines: Vec<&str> = stderr.lines().filter(|l| !l.trim().is_empty()).collect();
    assert_eq!(lines.len(), 1, "{stderr}");
    assert!(
        lines[0].contains("did not finish its work within 0.1 s") && lines[0].contains("--gpu-timeout"),
        "{stderr}"
    );
    assert!(start.elapsed().as_secs() < 60, "the run waited for the work: {:?}", start.elapsed());
    rejects(&["--gpu-timeout", "0", "devices"], &["--gpu-timeout", "0.1 to 86400"]);
}

/// A contact reach of many grid spacings is refused before the run, saying how far it may go
/// (a fuzzed rope of 21,000 nodes on 0.5 m with a 2 cm radius took over a minute a frame on
/// lavapipe: each node touched 1,680 others along the rope): the most nodes, or the largest
/// radius, that works.
#[test]
fn contact_reach_of_many_spacings_is_refused() {
    let root = env!("CARGO_MANIFEST_DIR");
    let rope = format!("{root}/presets/rope_on_cloth.toml");
    rejects(
        &["simulate", "--preset", &rope, "--set", "rope.0.nodes=21000"],
        &["rope[0].nodes = 21000", "at most 801 nodes", "or a radius of at most"],
    );
    // A rope whose reach no node count fixes (a radius of 10 m on 2 nodes 10 cm apart, with
    // self-collision; it ran into the GPU timeout before): the largest radius that works.
    let alone = format!("{root}/presets/rope.toml");
    let set =
        ["--set", "rope.0.nodes=2", "--set", "rope.0.radius=10", "--set", "rope.0.end=[-1.1, 1.1, 0.05]"];
    rejects(
        &[&["simulate", "--preset", &alone][..], &set[..]].concat(),
        &["rope[0].nodes = 2", "use a radius of at most 3.200e0 m"],
    );
    // Without contacts (no self-collision, no other object) a rope's nodes may be that dense.
    let set = ["--set", "rope.0.nodes=5000", "--set", "rope.0.self_collision=false"];
    let out = msdsim(&[&["simulate", "--preset", &alone, "--frames", "1", "--quiet"][..], &set[..]].concat());
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let curtain = format!("{root}/presets/curtain.toml");
    rejects(
        &["simulate", "--preset", &curtain, "--set", "cloth.0.self_collision_distance=1"],
        &["self_collision_distance = 1 m", "at most 16 spacings"],
    );
}

/// A mesh collider's file that is missing, of an unknown format, not a mesh or a bad one (a
/// triangle of no area, a vertex that is not a number, an index past the vertices) stops a
/// run with exit code 2 and one line naming the file and what is wrong; a good one runs, read
/// from beside the preset.
#[test]
fn bad_mesh_files_are_refused_in_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let preset = |file: &str| {
        let text = format!(
            "[[mesh]]\nfile = \"{file}\"\n[[rope]]\nname = \"r\"\nnodes = 4\nstart = [0.0, 2.0, 0.0]\nend = [0.3, 2.0, 0.0]\nmass = 0.01\nstiffness = 100.0\nradius = 0.01\n"
        );
        write(d, "scene.toml", &text)
    };
    let run = |file: &str, needles: &[&str]| {
        let p = preset(file);
        rejects(&["simulate", "--preset", &p, "--frames", "1"], needles);
    };
    run("missing.obj", &["mesh[0].file", "missing.obj", "cannot read"]);
    write(d, "shape.stl", "solid x\n");
    run("shape.stl", &["shape.stl", ".obj, .gltf or .glb"]);
    write(d, "flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
    run("flat.obj", &["flat.obj", "triangle 0", "no area"]);
    write(d, "nan.obj", "v 0 0 nan\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    run("nan.obj", &["nan.obj", "vertex 0"]);
    write(d, "past.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n");
    run("past.obj", &["past.obj"]);
    write(d, "broken.gltf", "{ not json");
    run("broken.gltf", &["broken.gltf", "glTF"]);
    write(d, "good.obj", "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nf 1 4 3 2\n");
    let good = msdsim(&["simulate", "--preset", &preset("good.obj"), "--frames", "2", "--quiet"]);
    assert!(good.status.success(), "{}", String::from_utf8_lossy(&good.stderr));
}

/// A mesh cloth's file that is missing or bad (a face of no area, a vertex that is not a
/// number, a face naming a vertex twice), a pin past its vertices, a `sew` that reaches along
/// its own border, or a self-collision thickness its rest shape does not leave room for stops a run with
/// exit code 2 and one line naming the object and what is wrong; a good one runs, and a
/// non-manifold one runs and says where no bending spring crosses.
#[test]
fn bad_mesh_cloths_are_refused_in_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let preset = |file: &str, more: &str| {
        let text = format!(
            "{more}[[mesh_cloth]]\nname = \"m\"\nfile = \"{file}\"\ndensity = 0.1\n\
             stiffness = {{ structural = 100.0, shear = 10.0, bending = 1.0 }}\npinned = [0]\n"
        );
        write(d, "scene.toml", &text)
    };
    let run = |file: &str, more: &str, needles: &[&str]| {
        let p = preset(file, more);
        rejects(&["simulate", "--preset", &p, "--frames", "1"], needles);
    };
    run("missing.obj", "", &["mesh_cloth[0].file", "missing.obj", "cannot read"]);
    write(d, "flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
    run("flat.obj", "", &["mesh_cloth[0]", "flat.obj", "face 0", "no area"]);
    write(d, "nan.obj", "v 0 0 nan\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    run("nan.obj", "", &["mesh_cloth[0]", "vertex 0", "finite"]);
    write(d, "twice.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 1 0\nf 1 2 3 4\n");
    run("twice.obj", "", &["mesh_cloth[0]", "face 0", "twice"]);
    write(
        d,
        "good.obj",
        "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 4/4 3/3 2/2\n",
    );
    let sewn =
        std::fs::read_to_string(preset("good.obj", "")).unwrap() + "sew = 3.0\nseam_stiffness = 10.0\n";
    let sewn = write(d, "sewn.toml", &sewn);
    rejects(
        &["simulate", "--preset", &sewn, "--frames", "1"],
        &["mesh_cloth[0]", "sew = 3", "its own border"],
    );
    let limited = std::fs::read_to_string(preset("good.obj", "")).unwrap() + "stretch_limit = -0.1\n";
    let limited = write(d, "limited.toml", &limited);
    rejects(&["simulate", "--preset", &limited, "--frames", "1"], &["mesh_cloth[0].stretch_limit = -0.1"]);
    // Two squares 1 cm apart: half the mean edge, the default thickness, would push them apart.
    write(
        d,
        "two.obj",
        "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv -1 0.01 -1\nv 1 0.01 -1\nv 1 0.01 1\nv -1 0.01 1\n\
         f 1 4 3 2\nf 5 8 7 6\n",
    );
    let thick = std::fs::read_to_string(preset("two.obj", "")).unwrap() + "self_collision = true\n";
    let thick = write(d, "thick.toml", &thick);
    rejects(
        &["simulate", "--preset", &thick, "--frames", "1"],
        &[
            "mesh_cloth[0]",
            "self-collision distance 1 m",
            "vertex 0",
            "1.000e-2 m",
            "self_collision_distance",
        ],
    );
    let past =
        std::fs::read_to_string(preset("good.obj", "")).unwrap().replace("pinned = [0]", "pinned = [9]");
    let past = write(d, "past.toml", &past);
    rejects(&["simulate", "--preset", &past, "--frames", "1"], &["pinned[0] = 9", "4 vertices"]);
    let good = msdsim(&["simulate", "--preset", &preset("good.obj", ""), "--frames", "2", "--quiet"]);
    assert!(good.status.success(), "{}", String::from_utf8_lossy(&good.stderr));
    // Three triangles on one edge: allowed, and said.
    write(d, "fan.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 0 -1 0\nf 1 2 3\nf 1 2 4\nf 1 2 5\n");
    let fan = msdsim(&["simulate", "--preset", &preset("fan.obj", ""), "--frames", "1"]);
    let said = String::from_utf8_lossy(&fan.stdout);
    assert!(fan.status.success(), "{}", String::from_utf8_lossy(&fan.stderr));
    assert!(said.contains("1 edge is shared by three or more faces (non-manifold)"), "{said}");
}
