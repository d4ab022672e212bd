//! Reading presets: TOML text -> `--set` overrides -> strict deserialisation -> range checks.
//! Every error is one line naming the file and the key.

use super::{validate, Scene};
use crate::error::UserError;
use std::path::Path;

/// The largest preset file read or saved [bytes]: a preset is a page of text; anything larger
/// (a device such as /dev/urandom, a wrong file) is refused instead of read without end. The
/// TOML parser keeps about 60 times the text in memory at its peak (a 16 MiB list of `pinned`
/// entries took 1.9 GB; 2 MiB takes 125 MB more than the run), and 2 MiB still holds 270,000
/// pinned particles.
pub const MAX_PRESET_BYTES: u64 = 2 << 20;

/// Loads a preset file and applies `KEY=VALUE` overrides.
pub fn load(path: &Path, overrides: &[String]) -> Result<Scene, UserError> {
    use std::io::Read as _;
    use std::os::unix::fs::OpenOptionsExt as _;
    const PIPE_WAIT: std::time::Duration = std::time::Duration::from_secs(10);
    const PIPE_POLL: std::time::Duration = std::time::Duration::from_millis(10);
    let refuse = |why: String| UserError(format!("{}: {why}", path.display()));
    // Opened and read without blocking: a FIFO with no writer reads as empty at once instead
    // of being waited on for ever; one whose writer is slow (`--preset <(...)`) is waited on
    // while data keeps coming, PIPE_WAIT at most between two reads. A regular file is read
    // as ever.
    let mut file = std::fs::OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NONBLOCK)
        .open(path)
        .map_err(|e| refuse(format!("cannot read the preset: {e}")))?;
    if file.metadata().is_ok_and(|m| m.is_dir()) {
        return Err(refuse("a folder, not a preset".into()));
    }
    let mut bytes = Vec::new();
    let mut chunk = vec![0u8; 1 << 16];
    let mut idle = std::time::Duration::ZERO;
    while bytes.len() as u64 <= MAX_PRESET_BYTES {
        match file.read(&mut chunk) {
            Ok(0) => break,
            Ok(n) => {
                bytes.extend_from_slice(&chunk[..n]);
                idle = std::time::Duration::ZERO;
            }
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(e) if e.kind() == std::io::ErrorKind::WouldBlock && idle < PIPE_WAIT => {
                std::thread::sleep(PIPE_POLL);
                idle += PIPE_POLL;
            }
            Err(e) if e.kind() == std::io::ErrorKind::WouldBlock => {
                return Err(refuse(format!("nothing came from the pipe in {} s", PIPE_WAIT.as_secs())));
            }
            Err(e) => return Err(refuse(format!("cannot read the preset: {e}"))),
        }
    }
    if bytes.len() as u64 > MAX_PRESET_BYTES {
        return Err(refuse(format!("larger than {} MiB: not a preset", MAX_PRESET_BYTES >> 20)));
    }
    let text =
        String::from_utf8(bytes).map_err(|_| refuse("not a text file (UTF-8): not a preset".into()))?;
    let folder = path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    parse_in(&text, &path.display().to_string(), overrides, folder)
}

/// `load` for the headless commands: a scene without a cloth or a rope is refused, since a run
/// of it would report success for nothing.
pub fn load_runnable(path: &Path, overrides: &[String]) -> Result<Scene, UserError> {
    let scene = load(path, overrides)?;
    if scene.cloths.is_empty() && scene.ropes.is_empty() && scene.mesh_cloths.is_empty() {
        return Err(UserError(format!(
            "{}: the scene has no cloth or rope: nothing to simulate",
            path.display()
        )));
    }
    Ok(scene)
}

/// Writes a scene as a preset (atomically: a temporary file, then a rename). What it writes
/// loads back to the identical scene; a scene too large to load back is refused.
pub fn save(scene: &Scene, path: &Path) -> anyhow::Result<()> {
    use anyhow::Context as _;
    let text = preset_text(scene).context("serialising the scene")?;
    let header = "# Saved by msdsim. Units: metres, seconds, kilograms, newtons.\n\n";
    let text = format!("{header}{text}");
    if text.len() as u64 > MAX_PRESET_BYTES {
        return Err(UserError(format!(
            "{}: the scene would take {:.1} MiB as a preset, more than the {} MiB a preset may have (a list of pinned particles that long: pin rows or corners instead)",
            path.display(),
            text.len() as f64 / (1 << 20) as f64,
            MAX_PRESET_BYTES >> 20
        ))
        .into());
    }
    crate::atomic_file::replace(path, text.as_bytes(), true)
        .map_err(|e| UserError(format!("{}: cannot write the preset: {e}", path.display())))?;
    Ok(())
}

/// The scene as preset text in the shipped presets' layout: a section for each part of the
/// scene (`[sim]`, `[[cloth]]`, ...) and the tables inside those inline (`stiffness = {
/// structural = 400.0, shear = 100.0, bending = 40.0 }`), not sections of their own.
fn preset_text(scene: &Scene) -> Result<String, toml_edit::ser::Error> {
    use toml_edit::Item;
    // The serialiser gives the root's parts as inline values: each becomes a section, or one
    // for each of its elements; what they hold stays inline.
    let mut doc = toml_edit::ser::to_document(scene)?;
    for (_, item) in doc.as_table_mut().iter_mut() {
        let value = std::mem::take(item);
        *item = match value.into_table() {
            Ok(table) => Item::Table(table),
            Err(value) => match value.into_array_of_tables() {
                Ok(tables) => Item::ArrayOfTables(tables),
                Err(value) => value,
            },
        };
    }
    Ok(doc.to_string())
}

/// The key of the line holding byte `at` of `text` when that line is `key =` with no value at
/// or after `at` (a comment may follow): a bare, quoted or dotted key, nothing else before it.
fn key_without_value(text: &str, at: usize) -> Option<&str> {
    let at = (0..=at.min(text.len())).rev().find(|&i| text.is_char_boundary(i))?;
    let start = text[..at].rfind('\n').map_or(0, |i| i + 1);
    let end = text[at..].find('\n').map_or(text.len(), |i| at + i);
    let (before, after) = (text[start..at].trim_end(), text[at..end].trim());
    let key = before.strip_suffix('=')?.trim();
    let rest_empty = after.is_empty() || after.starts_with('#');
    let key_chars = key.chars().all(|c| c.is_alphanumeric() || "_-.\"' ".contains(c));
    (rest_empty && !key.is_empty() && key_chars).then_some(key)
}

/// Parses preset text; `origin` names it in error messages. Mesh files named by a relative
/// path are the working folder's.
pub fn parse(text: &str, origin: &str, overrides: &[String]) -> Result<Scene, UserError> {
    parse_in(text, origin, overrides, Path::new("."))
}

/// Reads each mesh collider's and mesh cloth's file (a relative path is `folder`'s; it is made
/// absolute, so that the scene saved elsewhere still finds it).
pub fn load_meshes(scene: &mut Scene, origin: &str, folder: &Path) -> Result<(), UserError> {
    for (i, m) in scene.meshes.iter_mut().enumerate() {
        if m.loaded.is_some() {
            continue;
        }
        let path = beside(folder, &m.file);
        let file = super::mesh_file::read(&path)
            .map_err(|e| UserError(format!("{origin}: mesh[{i}].file {}: {e}", path.display())))?;
        m.file = path.display().to_string();
        m.loaded = Some(std::sync::Arc::new(file));
    }
    for (i, c) in scene.mesh_cloths.iter_mut().enumerate() {
        if c.loaded.is_some() {
            continue;
        }
        let path = beside(folder, &c.file);
        let file = super::mesh_file::read_faces(&path)
            .map_err(|e| UserError(format!("{origin}: mesh_cloth[{i}].file {}: {e}", path.display())))?;
        c.file = path.display().to_string();
        c.loaded = Some(std::sync::Arc::new(file));
    }
    Ok(())
}

/// A file named in a preset: as given where absolute, else `folder`'s; made absolute.
fn beside(folder: &Path, file: &str) -> std::path::PathBuf {
    let given = Path::new(file);
    let path = if given.is_absolute() { given.to_path_buf() } else { folder.join(given) };
    std::path::absolute(&path).unwrap_or(path)
}

fn parse_in(text: &str, origin: &str, overrides: &[String], folder: &Path) -> Result<Scene, UserError> {
    let mut table: toml::Table = text.parse().map_err(|e: toml::de::Error| {
        let at = e
            .span()
            .map(|s| {
                let before = &text[..s.start.min(text.len())];
                let line = before.matches('\n').count() + 1;
                let column = before.len() - before.rfind('\n').map(|i| i + 1).unwrap_or(0) + 1;
                format!("line {line}, column {column}: ")
            })
            .unwrap_or_default();
        // A carriage return without a line feed (old Mac line endings) reads as a bad character
        // in the middle of a line: say so.
        let bare_cr = text.match_indices('\r').any(|(i, _)| !text[i + 1..].starts_with('\n'));
        let why = if bare_cr {
            " (the file has a carriage return without a line feed: save it with Unix (LF) or Windows (CRLF) line endings)"
        } else {
            ""
        };
        // `key =` with nothing after it: the parser expects a value there and names only the
        // string's quotes, which misleads when the key wants a number.
        if let Some(key) = e.span().and_then(|s| key_without_value(text, s.start)) {
            return UserError(format!(
                "{origin}: {at}`{key} =` has no value on its line (write a number, \"text\", true or false, \
                 [a, list] or {{ a = table }} after the `=`){why}"
            ));
        }
        UserError(format!("{origin}: {at}{}{why}", one_line(e.message())))
    })?;
    for spec in overrides {
        apply_override(&mut table, spec).map_err(|e| UserError(format!("--set {}: {e}", shortened(spec))))?;
    }
    let origin = if overrides.is_empty() { origin.to_string() } else { format!("{origin} (with --set)") };
    let scene: Scene = serde_path_to_error::deserialize(toml::Value::Table(table)).map_err(|e| {
        let path = e.path().to_string();
        let message = plain_types(&one_line(e.inner().message()));
        if path == "." {
            UserError(format!("{origin}: {message}"))
        } else {
            UserError(format!("{origin}: {path}: {message}"))
        }
    })?;
    validate::check(&scene).map_err(|e| UserError(format!("{origin}: {e}")))?;
    let mut scene = scene;
    load_meshes(&mut scene, &origin, folder)?;
    // (again, with the meshes read: how far their vertices reach once scaled)
    validate::check(&scene).map_err(|e| UserError(format!("{origin}: {e}")))?;
    Ok(scene)
}

/// The most dotted segments a `--set` key may have (the deepest preset key has 4); deeper ones
/// are refused before the recursive walk.
const MAX_KEY_SEGMENTS: usize = 16;

/// Applies `KEY=VALUE` to a preset table. KEY is a dotted path (`sim.substeps`); array entries
/// are chosen by index or by name (`cloth.0.mass`, `cloth.curtain.mass`, `sphere[1].radius`).
/// VALUE is a TOML value (`32`, `[0, -9.81, 0]`, `true`, `"top_row"`), or a bare string.
pub fn apply_override(table: &mut toml::Table, spec: &str) -> Result<(), String> {
    let (key, raw) =
        spec.split_once('=').ok_or_else(|| "expected KEY=VALUE, for example sim.substeps=32".to_string())?;
    let key = key.trim().replace('[', ".").replace(']', "");
    let segments: Vec<&str> = key.split('.').map(str::trim).collect();
    if segments.len() > MAX_KEY_SEGMENTS {
        return Err(format!(
            "key of {} segments: a preset key has at most {MAX_KEY_SEGMENTS} (for example cloth.curtain.stiffness.shear)",
            segments.len()
        ));
    }
    if segments.iter().any(|s| s.is_empty()) {
        return Err(format!("malformed key \"{key}\""));
    }
    set_path(table, &segments, parse_value(raw.trim()), "")
}

fn set_path(table: &mut toml::Table, path: &[&str], value: toml::Value, walked: &str) -> Result<(), String> {
    let Some((head, rest)) = path.split_first() else {
        return Err("empty key".into());
    };
    let here = if walked.is_empty() { head.to_string() } else { format!("{walked}.{head}") };
    if rest.is_empty() {
        table.insert(head.to_string(), value);
        return Ok(());
    }
    // An index into an array the preset lacks (`box.0.center` without boxes) names what is
    // missing, rather than making a table that the preset's types then refuse.
    if !table.contains_key(*head) && rest.first().is_some_and(|s| s.parse::<usize>().is_ok()) {
        return Err(format!(
            "the preset has no {here} entries, so no {here}.{}: add one to the preset ([[{head}]])",
            rest[0]
        ));
    }
    let entry = table.entry(head.to_string()).or_insert_with(|| toml::Value::Table(toml::Table::new()));
    match entry {
        toml::Value::Table(t) => set_path(t, rest, value, &here),
        toml::Value::Array(items) => {
            // The segment after an array selects an entry by index or by name.
            let (selector, rest) = rest.split_first().expect("rest is not empty");
            let count = items.len();
            let item = select(items, selector).ok_or_else(|| {
                format!("{here} has no entry \"{selector}\" ({count} entries; use an index or a name)")
            })?;
            let here = format!("{here}.{selector}");
            match item {
                _ if rest.is_empty() => {
                    *item = value;
                    Ok(())
                }
                toml::Value::Table(t) => set_path(t, rest, value, &here),
                _ => Err(format!("{here} is a value, not a table")),
            }
        }
        _ => Err(format!("{here} is a value, not a table")),
    }
}

/// `text` as it is quoted in a message: at most 80 characters (then "..."), control characters
/// escaped.
fn shortened(text: &str) -> String {
    let cut: String = text.chars().take(80).collect();
    let more = if cut.len() < text.len() { "..." } else { "" };
    format!("{}{more}", cut.escape_debug())
}

/// serde's messages, which end with the type expected, with Rust's type names ("expected
/// u32") in words a preset's author reads.
fn plain_types(message: &str) -> String {
    const WORDS: [(&str, &str); 8] = [
        ("expected u8", "expected a whole number from 0 to 255"),
        ("expected u16", "expected a whole number from 0 to 65535"),
        ("expected u32", "expected a whole number from 0 to 4294967295"),
        ("expected u64", "expected a whole number of 0 or more"),
        ("expected usize", "expected a whole number of 0 or more"),
        ("expected i32", "expected a whole number"),
        ("expected f32", "expected a number"),
        ("expected f64", "expected a number"),
    ];
    (WORDS.iter())
        .find_map(|(rust, plain)| message.strip_suffix(rust).map(|head| format!("{head}{plain}")))
        .unwrap_or_else(|| message.to_string())
}

/// A message folded onto one line.
fn one_line(message: &str) -> String {
    let joined =
        message.trim().lines().map(str::trim).filter(|l| !l.is_empty()).collect::<Vec<_>>().join("; ");
    short_quotes(&joined)
}

/// The longest a value quoted in a message may run (in characters) before it is cut with "...".
const MOST_QUOTED: usize = 80;

/// `message` with every part quoted in "..." or `...` (serde quotes the value it refused,
/// however long) cut to MOST_QUOTED characters.
fn short_quotes(message: &str) -> String {
    let mut out = String::with_capacity(message.len().min(4 * MOST_QUOTED));
    let mut open: Option<char> = None;
    let mut run = 0;
    for c in message.chars() {
        match open {
            Some(q) if c == q => {
                if run > MOST_QUOTED {
                    out.push_str("...");
                }
                out.push(c);
                open = None;
            }
            Some(_) => {
                run += 1;
                if run <= MOST_QUOTED {
                    out.push(c);
                }
            }
            None => {
                if c == '"' || c == '`' {
                    open = Some(c);
                    run = 0;
                }
                out.push(c);
            }
        }
    }
    out
}

fn select<'a>(items: &'a mut [toml::Value], selector: &str) -> Option<&'a mut toml::Value> {
    if let Ok(i) = selector.parse::<usize>() {
        return items.get_mut(i);
    }
    items.iter_mut().find(|v| v.get("name").and_then(|n| n.as_str()) == Some(selector))
}

fn parse_value(raw: &str) -> toml::Value {
    format!("v = {raw}")
        .parse::<toml::Table>()
        .ok()
        .and_then(|mut t| t.remove("v"))
        .unwrap_or_else(|| toml::Value::String(raw.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A number of the wrong kind is named in words, not by Rust's type ("expected u32").
    #[test]
    fn wrong_numbers_are_named_in_words() {
        for set in ["sim.substeps=-1", "sim.substeps=1.5", "sim.substeps=\"many\""] {
            let err = parse(BASE, "p.toml", &[set.to_string()]).unwrap_err().0;
            assert!(
                err.contains("sim.substeps") && err.contains("whole number from 0 to 4294967295"),
                "{err}"
            );
            assert!(!err.contains("u32"), "{err}");
        }
        assert_eq!(plain_types("expected u32s"), "expected u32s");
        assert_eq!(plain_types("x, expected f64"), "x, expected a number");
    }

    /// A carriage return without a line feed is named as the reason (issue 30, item 12: the
    /// error gave none); Windows line endings parse as Unix ones.
    #[test]
    fn a_bare_carriage_return_is_named() {
        let err = parse("[sim]\rsubsteps = 8\n", "p.toml", &[]).unwrap_err().0;
        assert!(
            err.starts_with("p.toml: line 1") && err.contains("carriage return without a line feed"),
            "{err}"
        );
        let windows = parse("[sim]\r\nsubsteps = 8\r\n", "p.toml", &[]).unwrap();
        assert_eq!(windows.sim.substeps, 8);
        let other = parse("[sim\nsubsteps = 8\n", "p.toml", &[]).unwrap_err().0;
        assert!(!other.contains("carriage"), "{other}");
    }

    /// A scene whose preset would be larger than a preset may be is refused on save, not
    /// written to fail on load (issue 30, item 12: a 16 MiB list of pins took 2.4 GB to load).
    #[test]
    fn a_scene_too_large_to_load_back_is_not_saved() {
        let mut scene = parse(BASE, "t.toml", &[]).unwrap();
        scene.cloths[0].pinned = vec![[1, 1]; 300_000];
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("big.toml");
        let err = format!("{:#}", save(&scene, &path).unwrap_err());
        assert!(err.contains("more than the 2 MiB"), "{err}");
        assert!(!path.exists() && std::fs::read_dir(dir.path()).unwrap().next().is_none());
        scene.cloths[0].pinned.truncate(10);
        save(&scene, &path).unwrap();
        assert_eq!(load(&path, &[]).unwrap(), scene);
    }

    const BASE: &str = r#"
[sim]
substeps = 4
[[cloth]]
name = "a"
resolution = [3, 3]
size = [1.0, 1.0]
origin = [0.0, 0.0, 0.0]
mass = 0.1
stiffness = { structural = 1.0, shear = 1.0, bending = 1.0 }
[[cloth]]
name = "b"
resolution = [3, 3]
size = [1.0, 1.0]
origin = [0.0, 0.0, 0.0]
mass = 0.1
stiffness = { structural = 1.0, shear = 1.0, bending = 1.0 }
"#;

    fn with(overrides: &[&str]) -> Result<Scene, UserError> {
        parse(BASE, "t.toml", &overrides.iter().map(|s| s.to_string()).collect::<Vec<_>>())
    }

    #[test]
    fn overrides_reach_tables_array_entries_and_inline_tables() {
        let s = with(&[
            "sim.substeps=32",
            "cloth.1.mass=0.5",
            "cloth.a.stiffness.shear=7",
            "cloth[1].origin=[1, 2, 3]",
            "sim.gravity = [0, -1, 0]",
            "cloth.a.pin=top_row",
        ])
        .unwrap();
        assert_eq!(s.sim.substeps, 32);
        assert_eq!(s.cloths[1].mass, 0.5);
        assert_eq!(s.cloths[0].stiffness.shear, 7.0);
        assert_eq!(s.cloths[1].origin, [1.0, 2.0, 3.0]);
        assert_eq!(s.sim.gravity, [0.0, -1.0, 0.0]);
        assert_eq!(s.cloths[0].pin, super::super::ClothPins::TopRow);
    }

    #[test]
    fn long_quoted_values_are_cut() {
        let long = "9".repeat(5000);
        let cut = short_quotes(&format!("invalid type: string \"{long}\", expected u32; `{long}`"));
        assert!(cut.len() < 250 && cut.contains(&format!("\"{}...\"", "9".repeat(80))), "{cut}");
        assert_eq!(short_quotes("unknown field `x`, expected \"y\""), "unknown field `x`, expected \"y\"");
    }

    #[test]
    fn override_errors_name_the_key() {
        assert!(with(&["cloth.c.mass=1"]).unwrap_err().0.contains("cloth has no entry \"c\""));
        assert!(with(&["cloth.5.mass=1"]).unwrap_err().0.contains("no entry \"5\""));
        assert!(with(&["sim.substeps.x=1"]).unwrap_err().0.contains("sim.substeps is a value"));
        assert!(with(&["sim..x=1"]).unwrap_err().0.contains("malformed key"));
        let e = with(&["sim.substepz=1"]).unwrap_err().0;
        assert!(e.contains("t.toml (with --set): sim.substepz: unknown field"), "{e}");
    }

    #[test]
    fn a_key_without_a_value_is_named() {
        for text in
            ["[sim]\nsubsteps =\n", "[sim]\nsubsteps =   # per frame\nframe_dt = 0.01\n", "[sim]\nsubsteps ="]
        {
            let e = parse(text, "x.toml", &[]).unwrap_err().0;
            assert!(e.starts_with("x.toml: line 2, column"), "{e}");
            assert!(e.contains("`substeps =` has no value"), "{e}");
        }
        // Not a key on its own: the parser's own message.
        for text in ["[sim]\ngravity = [\n  { y =\n", "a = b =\n"] {
            let e = parse(text, "x.toml", &[]).unwrap_err().0;
            assert!(!e.contains("has no value"), "{e}");
        }
    }

    #[test]
    fn syntax_errors_give_line_and_column() {
        let e = parse("[sim]\nsubsteps = = 3\n", "x.toml", &[]).unwrap_err().0;
        assert!(e.starts_with("x.toml: line 2, column"), "{e}");
        assert!(!e.contains('\n'), "one line: {e}");
    }

    #[test]
    fn range_errors_name_key_value_and_unit() {
        let e = with(&["cloth.b.stiffness.bending=-2"]).unwrap_err().0;
        assert_eq!(
            e,
            "t.toml (with --set): cloth[1].stiffness.bending = -2: must be between 0 and 1e12 (N/m)"
        );
        let e = with(&["cloth.a.name=\"b\""]).unwrap_err().0;
        assert!(e.contains("another object has this name"), "{e}");
        let e = with(&["cloth.a.pinned=[[3, 0]]"]).unwrap_err().0;
        assert!(e.contains("cloth[0].pinned[0] = [3, 0]: outside the 3 x 3 grid"), "{e}");
        let e = with(&["cloth.a.mass=nan"]).unwrap_err().0;
        assert!(e.contains("cloth[0].mass = NaN"), "{e}");
    }

    /// Pin groups (`[[cloth.pin_group]]`): each must hold a particle, none that another group
    /// or the object's own pins hold, its list inside the grid, at most seven; a valid one
    /// pins its particles in a group of their own with its motion, and survives a save.
    #[test]
    fn pin_groups_are_checked_and_kept() {
        let group = |g: &str| format!("cloth.a.pin_group=[{g}]");
        let e = with(&[&group("{ pin_motion = { velocity = [0, 1, 0] } }")]).unwrap_err().0;
        assert!(e.contains("cloth[0].pin_group[0]: holds no particle"), "{e}");
        let e = with(&[&group("{ pinned = [[3, 0]] }")]).unwrap_err().0;
        assert!(e.contains("cloth[0].pin_group[0].pinned[0] = [3, 0]: outside the 3 x 3 grid"), "{e}");
        // (far outside, with a box of the object's own: it used to build the groups unchecked)
        let own_box = "cloth.a.pin_box={ min = [-0.1, -0.1, -1.0], max = [0.1, 0.1, 1.0] }";
        let e = with(&[own_box, &group("{ pinned = [[0, 4000000000]] }")]).unwrap_err().0;
        assert!(e.contains("cloth[0].pin_group[0].pinned[0] = [0, 4000000000]: outside"), "{e}");
        let e = with(&["cloth.a.pin=\"corners\"", &group("{ pinned = [[0, 0]] }")]).unwrap_err().0;
        assert!(
            e.contains("cloth[0].pin_group[0]: particle [0, 0] is pinned by its object's own pins"),
            "{e}"
        );
        let e = with(&[&group("{ pinned = [[1, 1]] }, { pinned = [[1, 1], [2, 2]] }")]).unwrap_err().0;
        assert!(
            e.contains("cloth[0].pin_group[1]: particle [1, 1] is pinned by pin_group[0] already"),
            "{e}"
        );
        let eight = ["{ pinned = [[0, 0]] }"; 8].join(", ");
        let e = with(&[&group(&eight)]).unwrap_err().0;
        assert!(e.contains("cloth[0].pin_group: 8 groups, at most 7"), "{e}");
        let e =
            with(&[&group("{ pinned = [[1, 1]], pin_motion = { velocity = [0, 500, 0] } }")]).unwrap_err().0;
        assert!(e.contains("cloth[0].pin_group[0].pin_motion: its pins would move at up to 500 m/s"), "{e}");
        let ok = group("{ pinned = [[1, 1]] }, { pin_box = { min = [0.9, -1.1, -1.0], max = [1.1, -0.4, 1.0] }, pin_motion = { angular_velocity = [0, 90, 0] } }");
        let s = with(&["cloth.a.pin=\"top_corners\"", &ok]).unwrap();
        let o = &crate::scene::build::to_model(&s).objects[0];
        let groups: Vec<(usize, usize)> =
            (0..9).filter(|&i| o.pinned[i]).map(|i| (i, o.group_of(i))).collect();
        assert_eq!(groups, [(0, 0), (2, 0), (4, 1), (5, 2), (8, 2)], "{:?}", o.positions);
        assert_eq!(o.pin_groups.len(), 2);
        assert!(!o.pin_groups[0].is_moving() && o.pin_groups[1].turns());
        let text = preset_text(&s).unwrap();
        assert_eq!(parse(&text, "groups.toml", &[]).unwrap(), s, "{text}");
    }

    /// A pin motion needs pins to move and exactly one way of moving, as a collider's; a valid
    /// one survives a save.
    #[test]
    fn a_pin_motion_is_checked_and_kept() {
        let e = with(&["cloth.a.pin_motion={ velocity = [0, 1, 0] }"]).unwrap_err().0;
        assert!(e.contains("cloth[0].pin_motion: no particle is pinned for it to move"), "{e}");
        let e = with(&[
            "cloth.a.pin=\"corners\"",
            "cloth.a.pin_motion={ velocity = [0, 1, 0], keyframes = [[0, 0, 0, 0]] }",
        ])
        .unwrap_err()
        .0;
        assert!(e.contains("cloth[0].pin_motion: give a velocity or keyframes, not both"), "{e}");
        let e = with(&[
            "cloth.a.pin=\"corners\"",
            "cloth.a.pin_motion={ keyframes = [[1, 0, 0, 0], [0.5, 0, 1, 0]] }",
        ])
        .unwrap_err()
        .0;
        assert!(e.contains("cloth[0].pin_motion.keyframes[1]: time 0.5 s is not after"), "{e}");
        let corners = "cloth.a.pin=\"corners\"";
        let e = with(&[corners, "cloth.a.pin_motion={ pivot = [0, 1, 0] }"]).unwrap_err().0;
        assert!(e.contains("cloth[0].pin_motion.pivot: there is no angular_velocity"), "{e}");
        let e = with(&[corners, "cloth.a.pin_motion={ angular_velocity = [0, nan, 0] }"]).unwrap_err().0;
        assert!(e.contains("cloth[0].pin_motion.angular_velocity"), "{e}");
        assert!(
            with(&[corners, "cloth.a.pin_motion={ angular_velocity = [0, 90, 0] }"]).is_ok(),
            "a turn alone"
        );
        // (the guard's 100 m/s: 150 m/s along, or 20 turns a second 1.4 m from the pivot)
        let e = with(&[corners, "cloth.a.pin_motion={ velocity = [150, 0, 0] }"]).unwrap_err().0;
        assert!(
            e.contains("cloth[0].pin_motion: its pins would move at up to 150 m/s, past sim.max_speed"),
            "{e}"
        );
        let e = with(&[corners, "cloth.a.pin_motion={ angular_velocity = [0, 7200, 0], pivot = [1, 0, 1] }"])
            .unwrap_err()
            .0;
        assert!(e.contains("past sim.max_speed"), "{e}");
        // (4 substeps of 1/60 s: 50,000 degrees/s is 208 degrees a substep)
        let e =
            with(&[corners, "cloth.a.pin_motion={ angular_velocity = [0, 50000, 0], pivot = [0, 0, 0] }"])
                .unwrap_err()
                .0;
        assert!(e.contains("degrees a substep, half a turn or more"), "{e}");
        let e = with(&[corners, "cloth.a.pin_motion={ velocity = [0, 1, 0], interpolation = \"smooth\" }"])
            .unwrap_err()
            .0;
        assert!(e.contains("cloth[0].pin_motion: interpolation joins keyframes"), "{e}");
        let e =
            with(&[corners, "cloth.a.pin_motion={ keyframes = [[0, 0, 0, 0]], interpolation = \"cubic\" }"])
                .unwrap_err()
                .0;
        assert!(e.contains("unknown variant `cubic`, expected `linear` or `smooth`"), "{e}");
        let e = with(&[
            corners,
            "cloth.a.pin_motion={ angular_velocity = [0, 90, 0], rotation_keyframes = [[0, 0, 0, 0]] }",
        ])
        .unwrap_err()
        .0;
        assert!(
            e.contains("cloth[0].pin_motion: give angular_velocity or rotation_keyframes, not both"),
            "{e}"
        );
        let e = with(&[corners, "cloth.a.pin_motion={ rotation_keyframes = [[0, 0, 0, 0], [0, 0, 90, 0]] }"])
            .unwrap_err()
            .0;
        assert!(e.contains("cloth[0].pin_motion.rotation_keyframes[1]: time 0 s is not after"), "{e}");
        assert!(
            with(&[
                corners,
                "cloth.a.pin_motion={ rotation_keyframes = [[0, 0, 0, 0], [1, 0, 90, 0]], pivot = [0, 1, 0], interpolation = \"smooth\" }"
            ])
            .is_ok(),
            "a keyed turn alone, smooth, about a pivot"
        );
        // (180 degrees in 0.01 s is 300 degrees a frame of 1/60 s: past half a turn)
        let e =
            with(&[corners, "cloth.a.pin_motion={ rotation_keyframes = [[0, 0, 0, 0], [0.01, 0, 180, 0]] }"])
                .unwrap_err()
                .0;
        assert!(e.contains("rotation_keyframes: up to 300 degrees a frame, half a turn or more"), "{e}");
        let text = format!("{BASE}[[sphere]]\ncenter = [0, 0, 0]\nradius = 1\nmotion = {{ rotation_keyframes = [[0, 0, 0, 0]], pivot = [0, 1, 0] }}\n");
        let e = parse(&text, "t.toml", &[]).unwrap_err().0;
        assert!(e.contains("sphere[0].motion.pivot: a collider turns about its centre"), "{e}");
        let text = format!("{BASE}[[box]]\ncenter = [0, 0, 0]\nhalf_extents = [1, 1, 1]\nmotion = {{ rotation_keyframes = [[0, 0, 0, 0], [1, 0, 90, 0]], interpolation = \"smooth\" }}\n");
        assert!(parse(&text, "t.toml", &[]).is_ok(), "a keyed turn alone");
        let text = format!("{BASE}[[box]]\ncenter = [0, 0, 0]\nhalf_extents = [1, 1, 1]\nmotion = {{ rotation_keyframes = [[0, 0, 0, 0], [0.01, 0, 180, 0]] }}\n");
        let e = parse(&text, "t.toml", &[]).unwrap_err().0;
        assert!(
            e.contains("box[0].motion.rotation_keyframes: up to 300 degrees a frame, half a turn or more"),
            "{e}"
        );
        let text = format!("{BASE}[[sphere]]\ncenter = [0, 0, 0]\nradius = 1\nmotion = {{ angular_velocity = [0, 90, 0] }}\n");
        assert!(parse(&text, "t.toml", &[]).is_ok(), "a turn alone");
        let text = format!("{BASE}[[box]]\ncenter = [0, 0, 0]\nhalf_extents = [1, 1, 1]\nmotion = {{ velocity = [1, 0, 0], angular_velocity = [0, 90, 0] }}\n");
        assert!(parse(&text, "t.toml", &[]).is_ok(), "a turn with a velocity");
        let text = format!("{BASE}[[box]]\ncenter = [0, 0, 0]\nhalf_extents = [1, 1, 1]\nmotion = {{ angular_velocity = [0, 1e5, 0] }}\n");
        let e = parse(&text, "t.toml", &[]).unwrap_err().0;
        assert!(e.contains("box[0].motion.angular_velocity:") && e.contains("half a turn or more"), "{e}");
        let s = with(&[
            "cloth.b.pinned=[[1, 1]]",
            "cloth.b.pin_motion={ keyframes = [[0, 0, 0, 0], [2, 0, 0.5, 0]], interpolation = \"smooth\", rotation_keyframes = [[0, 0, 0, 0], [2, 0, 45, 0]] }",
        ])
        .unwrap();
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("pins.toml");
        save(&s, &path).unwrap();
        assert!(std::fs::read_to_string(&path).unwrap().contains("interpolation = \"smooth\""));
        let back = crate::scene::load(&path, &[]).unwrap();
        assert_eq!(back.cloths[1].pin_motion, s.cloths[1].pin_motion);
        assert!(back.cloths[1].pin_motion.is_some());
        let model = crate::scene::build::to_model(&back);
        assert!(
            matches!(model.objects[1].pin_motion.translation, crate::sim::collider::Motion::Smooth(_)),
            "{:?}",
            model.objects[1].pin_motion.translation
        );
    }

    /// A pin box pins the particles placed inside it (its faces too), is checked, carries a
    /// pin motion on its own, and survives a save.
    #[test]
    fn a_pin_box_pins_what_it_holds() {
        // (cloth a: 3 x 3 particles 0.5 m apart from the origin, rows going down -y)
        let s = with(&["cloth.a.pin_box={ min = [-0.1, -0.5, -0.1], max = [1.1, 0.1, 0.1] }"]).unwrap();
        let model = crate::scene::build::to_model(&s);
        let pinned: Vec<usize> = (0..9).filter(|&i| model.objects[0].pinned[i]).collect();
        assert_eq!(pinned, vec![0, 1, 2, 3, 4, 5], "the top two rows");
        let listed = with(&[
            "cloth.a.pin_box={ min = [-0.1, -0.5, -0.1], max = [1.1, 0.1, 0.1] }",
            "cloth.a.pinned=[[1, 2]]",
        ])
        .unwrap();
        let by_rule: Vec<usize> = (0..9).filter(|&i| listed.cloths[0].pinned_by_rule()[i]).collect();
        assert_eq!(by_rule, pinned, "the box's, not the list's");
        let e = with(&["cloth.a.pin_box={ min = [0, 0, 0], max = [1, -1, 0] }"]).unwrap_err().0;
        assert!(e.contains("cloth[0].pin_box: min [0.0, 0.0, 0.0] is past max [1.0, -1.0, 0.0]"), "{e}");
        let e = with(&["cloth.a.pin_box={ min = [5, 5, 5], max = [6, 6, 6] }"]).unwrap_err().0;
        assert!(e.contains("cloth[0].pin_box: no particle is placed inside it"), "{e}");
        let e = with(&["cloth.a.pin_box={ min = [0, 0, 0], max = [nan, 1, 1] }"]).unwrap_err().0;
        assert!(e.contains("cloth[0].pin_box.max"), "{e}");
        let s = with(&[
            "cloth.b.pin_box={ min = [-0.1, -0.1, -0.1], max = [0.1, 0.1, 0.1] }",
            "cloth.b.pin_motion={ velocity = [0, 0.5, 0] }",
        ])
        .unwrap();
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("box.toml");
        save(&s, &path).unwrap();
        let back = crate::scene::load(&path, &[]).unwrap();
        assert_eq!(back.cloths[1].pin_box, s.cloths[1].pin_box);
        assert!(crate::scene::build::to_model(&back).objects[1].pinned[0]);
    }

    #[test]
    fn saved_presets_keep_their_tables_inline() {
        let mut s = with(&["cloth.a.stretch_limit=0.1", "cloth.b.pinned=[[1, 1]]"]).unwrap();
        s.spheres.push(crate::scene::Sphere {
            center: [0.0, 0.5, 0.0],
            radius: 0.2,
            motion: Some(crate::scene::Motion {
                keyframes: vec![[0.0, 0.0, 0.5, 0.0], [1.0, 0.2, 0.5, 0.0]],
                ..Default::default()
            }),
        });
        let text = preset_text(&s).unwrap();
        assert!(
            text.contains("[[cloth]]") && text.contains("[sim]") && text.contains("[[sphere]]"),
            "{text}"
        );
        assert!(
            !text.contains("[cloth.") && !text.contains("[sphere."),
            "nested tables as sections:\n{text}"
        );
        assert!(text.contains("stiffness = { structural = "), "{text}");
        assert!(text.contains("motion = { keyframes = ["), "{text}");
        assert_eq!(parse(&text, "inline.toml", &[]).unwrap(), s);
    }

    #[test]
    fn a_scene_survives_a_toml_round_trip() {
        let s = with(&["cloth.a.stretch_limit=0.1", "cloth.b.pinned=[[1, 1]]"]).unwrap();
        let text = toml::to_string(&s).unwrap();
        assert_eq!(parse(&text, "round.toml", &[]).unwrap(), s);
    }
}

#[cfg(test)]
mod pin_group_tests {
    use super::*;

    /// The editor's "add pin group" (`Cloth::add_pin_group`, `Rope::add_pin_group`) leaves a
    /// scene that validates on every shipped preset's objects, each new group holding one
    /// particle nothing else pins, until the object has its seven groups or no free particle.
    #[test]
    fn adding_pin_groups_keeps_every_preset_valid() {
        for entry in std::fs::read_dir("presets").unwrap() {
            let path = entry.unwrap().path();
            if path.extension().is_none_or(|x| x != "toml") {
                continue; // (the meshes some presets read)
            }
            let mut scene = load(&path, &[]).unwrap();
            for k in 0..scene.cloths.len() {
                let mut added = 0;
                while scene.cloths[k].add_pin_group() {
                    added += 1;
                    super::super::validate::check(&scene)
                        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
                }
                assert_eq!(
                    scene.cloths[k].pin_groups.len(),
                    7,
                    "{}: cloth {k} ({added} added)",
                    path.display()
                );
            }
            for k in 0..scene.ropes.len() {
                while scene.ropes[k].add_pin_group() {
                    super::super::validate::check(&scene)
                        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
                }
                let r = &scene.ropes[k];
                let free = r.pinned_by_rule().iter().filter(|p| !**p).count();
                assert!(
                    r.pin_groups.len() == 7 || r.pin_groups.len() >= free,
                    "{}: rope {k}",
                    path.display()
                );
            }
        }
    }
}
