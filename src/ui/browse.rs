//! A preset browser beside a path field: the folders and `.toml` files of the field's folder
//! (from the folder the app was started in), to pick from instead of typing. No native dialog:
//! the file-dialog crates need a desktop portal or a GTK install on Linux.

use imgui::Ui;
use std::path::{Path, PathBuf};

/// An entry of a folder as the browser lists it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Entry {
    /// The folder above.
    Up,
    Folder(String),
    File(String),
}

/// The folder whose entries the browser lists for the path typed in a field: the path itself
/// when it is a folder, else the folder it would be in ("." for a bare name).
pub fn folder_of(typed: &str) -> PathBuf {
    let path = Path::new(typed);
    if typed.is_empty() || path.is_dir() {
        return if typed.is_empty() { PathBuf::from(".") } else { path.to_path_buf() };
    }
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// The preset file a path typed in a field names, to read: as typed (from the folder the app
/// was started in) when it exists or is absolute; else the preset of that file name in the
/// folder of `beside` (the scene's own preset file: where the shipped presets are when the app
/// was started with one of them); else the shipped preset of that name in the source tree's
/// `presets/` (so "presets/towel.toml" loads wherever the app was started); else as typed,
/// for the error to name.
pub fn resolve_preset(typed: &str, beside: &str) -> PathBuf {
    let path = PathBuf::from(typed);
    if path.exists() || path.is_absolute() {
        return path;
    }
    let Some(name) = path.file_name() else { return path };
    let own = Path::new(beside).parent().map(|dir| dir.join(name));
    let shipped = Path::new(env!("CARGO_MANIFEST_DIR")).join("presets").join(name);
    own.into_iter().chain([shipped]).find(|p| p.is_file()).unwrap_or(path)
}

/// The entries of `dir`: the folder above, then its folders and its files of extensions
/// `exts` (compared ignoring case), each by name; hidden ones (a leading dot) left out. An
/// unreadable folder lists only the way up.
pub fn entries_of(dir: &Path, exts: &[&str]) -> Vec<Entry> {
    let mut folders = Vec::new();
    let mut files = Vec::new();
    for e in std::fs::read_dir(dir).into_iter().flatten().flatten() {
        let name = e.file_name().to_string_lossy().into_owned();
        if name.starts_with('.') {
            continue;
        }
        let path = e.path();
        if path.is_dir() {
            folders.push(name);
        } else if path.extension().is_some_and(|x| exts.iter().any(|e| x.eq_ignore_ascii_case(e))) {
            files.push(name);
        }
    }
    folders.sort();
    files.sort();
    std::iter::once(Entry::Up)
        .chain(folders.into_iter().map(Entry::Folder))
        .chain(files.into_iter().map(Entry::File))
        .collect()
}

/// The path a field holds after picking `entry` in `dir`: a folder keeps the browser open on it
/// (the path ends with `/`), a file is the new path.
pub fn pick(dir: &Path, entry: &Entry) -> String {
    let joined = match entry {
        Entry::Up => {
            let parent = if dir == Path::new(".") || dir.as_os_str().is_empty() {
                PathBuf::from("..")
            } else if dir.components().next_back() == Some(std::path::Component::ParentDir) {
                dir.join("..")
            } else {
                dir.parent().map_or_else(
                    || dir.to_path_buf(),
                    |p| {
                        if p.as_os_str().is_empty() {
                            PathBuf::from(".")
                        } else {
                            p.to_path_buf()
                        }
                    },
                )
            };
            return format!("{}/", parent.display().to_string().trim_end_matches('/'));
        }
        Entry::Folder(name) => format!("{}/", dir.join(name).display()),
        Entry::File(name) => dir.join(name).display().to_string(),
    };
    joined.strip_prefix("./").map(str::to_string).unwrap_or(joined)
}

/// A "Browse" button for `path` (a field's text): a popup with the current folder (absolute,
/// so the user sees where a relative path goes) and its entries; clicking a folder opens it,
/// a file puts its path in the field. Returns true when the field changed.
pub fn browse_button(ui: &Ui, id: &str, path: &mut String) -> bool {
    browse_files(ui, id, path, &["toml"])
}

/// `browse_button` listing the files of extensions `exts`.
pub fn browse_files(ui: &Ui, id: &str, path: &mut String, exts: &[&str]) -> bool {
    let popup = format!("browse##{id}");
    if ui.button(format!("Browse##{id}")) {
        ui.open_popup(&popup);
    }
    let mut changed = false;
    ui.popup(&popup, || {
        let dir = folder_of(path);
        let shown = std::fs::canonicalize(&dir).unwrap_or_else(|_| dir.clone());
        ui.text_disabled(format!("in {}", shown.display()));
        ui.separator();
        for entry in entries_of(&dir, exts) {
            let label = match &entry {
                Entry::Up => "../".to_string(),
                Entry::Folder(name) => format!("{name}/"),
                Entry::File(name) => name.clone(),
            };
            let folder = !matches!(entry, Entry::File(_));
            if ui.selectable_config(&label).close_popups(!folder).build() {
                *path = pick(&dir, &entry);
                changed = true;
            }
        }
    });
    changed
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A shipped preset is found by its name from any folder; a path that exists, or is
    /// absolute, or names no shipped preset, is taken as typed.
    #[test]
    fn shipped_presets_are_found_wherever_the_app_started() {
        let shipped = Path::new(env!("CARGO_MANIFEST_DIR")).join("presets/towel.toml");
        for typed in ["presets/towel.toml", "elsewhere/towel.toml", "towel.toml"] {
            let found = resolve_preset(typed, "nowhere/scene.toml");
            assert!(found.is_file(), "{typed} -> {}", found.display());
            assert_eq!(std::fs::read(&found).unwrap(), std::fs::read(&shipped).unwrap(), "{typed}");
        }
        assert_eq!(resolve_preset("no/such.toml", ""), PathBuf::from("no/such.toml"));
        assert_eq!(resolve_preset("/no/towel.toml", ""), PathBuf::from("/no/towel.toml"));
        let dir = tempfile::tempdir().unwrap();
        let own = dir.path().join("towel.toml");
        std::fs::write(&own, "").unwrap();
        assert_eq!(resolve_preset(own.to_str().unwrap(), ""), own, "an existing file as typed");
        // Presets installed elsewhere: found beside the scene's own preset first.
        let scene = dir.path().join("curtain.toml");
        assert_eq!(resolve_preset("elsewhere/towel.toml", scene.to_str().unwrap()), own);
    }

    /// The browser lists the way up, folders, then `.toml` files, hidden and other files left
    /// out; picking walks down into a folder, up again, and returns a file's path.
    #[test]
    fn the_browser_lists_folders_and_presets_and_picks_paths() {
        let dir = tempfile::tempdir().unwrap();
        let root = dir.path();
        std::fs::create_dir(root.join("presets")).unwrap();
        std::fs::create_dir(root.join(".git")).unwrap();
        for f in ["presets/b.toml", "presets/a.TOML", "presets/notes.txt", "top.toml", ".hidden.toml"] {
            std::fs::write(root.join(f), "").unwrap();
        }
        let top = entries_of(root, &["toml"]);
        assert_eq!(top, vec![Entry::Up, Entry::Folder("presets".into()), Entry::File("top.toml".into())]);
        let presets = root.join("presets");
        assert_eq!(
            entries_of(&presets, &["toml"]),
            vec![Entry::Up, Entry::File("a.TOML".into()), Entry::File("b.toml".into())]
        );
        let root_text = root.display().to_string();
        let into = pick(root, &Entry::Folder("presets".into()));
        assert_eq!(into, format!("{root_text}/presets/"));
        assert_eq!(folder_of(&into), PathBuf::from(format!("{root_text}/presets/")));
        let file = pick(&folder_of(&into), &Entry::File("b.toml".into()));
        assert_eq!(file, format!("{root_text}/presets/b.toml"));
        assert_eq!(folder_of(&file), presets);
        assert_eq!(pick(&presets, &Entry::Up), format!("{root_text}/"));
        // Relative paths stay relative, from the folder the app was started in.
        assert_eq!(folder_of("presets/curtain.toml"), PathBuf::from("presets"));
        assert_eq!(folder_of("curtain.toml"), PathBuf::from("."));
        assert_eq!(pick(Path::new("."), &Entry::File("x.toml".into())), "x.toml");
        assert_eq!(pick(Path::new("."), &Entry::Folder("presets".into())), "presets/");
        assert_eq!(pick(Path::new("presets"), &Entry::Up), "./");
        assert_eq!(pick(Path::new("."), &Entry::Up), "../");
        assert_eq!(pick(Path::new(".."), &Entry::Up), "../../");
        assert!(
            entries_of(&root.join("missing"), &["toml"]) == vec![Entry::Up],
            "an unreadable folder lists the way up"
        );
    }
}
