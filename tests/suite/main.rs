//! The integration tests, one binary (one link, not one a file): each module is a subject,
//! `common` their shared scenes, references and checks. The slow tier is `#[ignore]`d with a
//! reason; `scripts/test.sh --all` runs it too (docs/guide/testing.md).

mod common;

mod app;
mod cli;
mod closed_forms;
mod colliders;
mod frames_in_flight;
mod friction;
mod gpu_vs_cpu;
mod grab;
mod guard;
mod hot_reload;
mod integrators;
mod inter_object;
mod invariants;
mod large_steps;
mod layout;
mod mesh_cloth;
mod mesh_colliders;
mod output;
mod pins;
mod preset_roundtrip;
mod presets;
mod recording_memory;
mod self_contact;
mod stability;
mod wind;
