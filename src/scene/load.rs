//! Reading presets: TOML text -> `--set` overrides -> strict deserialisation -> range checks.
//! Every error is one line naming the file and the key.

use super::{validate, Scene};
use crate::error::UserError;
use std::path::Path;

/// Loads a preset file and applies `KEY=VALUE` overrides.
pub fn load(path: &Path, overrides: &[String]) -> Result<Scene, UserError> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| UserError(format!("{}: cannot read the preset: {e}", path.display())))?;
    parse(&text, &path.display().to_string(), overrides)
}

/// Parses preset text; `origin` names it in error messages.
pub fn parse(text: &str, origin: &str, overrides: &[String]) -> Result<Scene, UserError> {
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
        UserError(format!("{origin}: {at}{}", e.message().trim()))
    })?;
    for spec in overrides {
        apply_override(&mut table, spec).map_err(|e| UserError(format!("--set {spec}: {e}")))?;
    }
    let origin = if overrides.is_empty() { origin.to_string() } else { format!("{origin} (with --set)") };
    let scene: Scene = serde_path_to_error::deserialize(toml::Value::Table(table)).map_err(|e| {
        let path = e.path().to_string();
        let message = e.inner().message().trim().to_string();
        if path == "." {
            UserError(format!("{origin}: {message}"))
        } else {
            UserError(format!("{origin}: {path}: {message}"))
        }
    })?;
    validate::check(&scene).map_err(|e| UserError(format!("{origin}: {e}")))?;
    Ok(scene)
}

/// Applies `KEY=VALUE` to a preset table. KEY is a dotted path (`sim.substeps`); array entries
/// are chosen by index or by name (`cloth.0.mass`, `cloth.curtain.mass`, `sphere[1].radius`).
/// VALUE is a TOML value (`32`, `[0, -9.81, 0]`, `true`, `"top_row"`), or a bare string.
pub fn apply_override(table: &mut toml::Table, spec: &str) -> Result<(), String> {
    let (key, raw) =
        spec.split_once('=').ok_or_else(|| "expected KEY=VALUE, for example sim.substeps=32".to_string())?;
    let key = key.trim().replace('[', ".").replace(']', "");
    let segments: Vec<&str> = key.split('.').map(str::trim).collect();
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
