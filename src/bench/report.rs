//! The benchmark reports: a Markdown table (with a roofline column per stage) and a CSV, both
//! headed by the device, driver, date and command line. Frame totals come from frames with
//! only a start and an end timestamp; stage times from frames with timestamps between stages.
//!
//! Roofline: the fewest bytes a stage must move per particle and substep, over the measured
//! copy bandwidth. Physics reads and writes each particle once (32 + 32 bytes); so does the
//! constraint stage, plus the spatial hash when self-collision is on (count: read 32, write 8;
//! scatter: read 8 + 4, write 4; the query reads its bucket range, about 16 more); the surface
//! stage reads each particle and writes each surface vertex (32 bytes).

use super::{EndToEnd, Measurement, Spread};
use std::fmt::Write as _;

pub struct Header {
    pub device: String,
    pub driver: String,
    pub command: String,
    pub date: String,
    /// Measured copy bandwidth [bytes/s] and the buffer size it was measured with.
    pub bandwidth: Option<(f64, u64)>,
}

/// Ideal bytes per substep of the physics and constraint stages.
pub fn ideal_bytes(m: &Measurement, hashed: bool) -> (f64, f64) {
    let n = m.particles as f64;
    let physics = 64.0 * n;
    let constraints = 64.0 * n + if hashed { 72.0 * n } else { 0.0 };
    (physics, constraints)
}

fn us(ms: f64) -> String {
    format!("{:.1}", ms * 1e3)
}

pub fn markdown(header: &Header, rows: &[(Measurement, bool)]) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "Device: {} ({}); {}", header.device, header.driver, header.date);
    let _ = writeln!(out, "Command: `{}`", header.command);
    if let Some((bw, bytes)) = header.bandwidth {
        let _ = writeln!(
            out,
            "Measured copy bandwidth: {:.0} GB/s ({} MiB buffer, read + write)",
            bw * 1e-9,
            bytes >> 20
        );
    }
    let _ = writeln!(out);
    let _ = writeln!(
        out,
        "| case | particles | path | ms/frame (median) | p10 - p90 | frames/s | physics ms | constraints ms | surface ms | physics us/substep (roofline) | constraints us/substep (roofline) |"
    );
    let _ = writeln!(out, "|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|");
    for (m, hashed) in rows {
        let sub = m.substeps as f64;
        let roof =
            |bytes: f64| header.bandwidth.map(|(bw, _)| us(bytes / bw * 1e3)).unwrap_or_else(|| "-".into());
        let (pb, cb) = ideal_bytes(m, *hashed);
        let _ = writeln!(
            out,
            "| {} | {} | {} | {:.3} | {:.3} - {:.3} | {:.0} | {:.3} | {:.3} | {:.3} | {} ({}) | {} ({}) |",
            m.case,
            m.particles,
            m.path,
            m.total.median,
            m.total.p10,
            m.total.p90,
            1e3 / m.total.median.max(1e-9),
            m.physics.median,
            m.constraints.median,
            m.surface.median,
            us(m.physics.median / sub),
            roof(pb),
            us(m.constraints.median / sub),
            roof(cb),
        );
    }
    out
}

pub fn csv(header: &Header, rows: &[(Measurement, bool)]) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "# device: {}", header.device);
    let _ = writeln!(out, "# driver: {}", header.driver);
    let _ = writeln!(out, "# date: {}", header.date);
    let _ = writeln!(out, "# command: {}", header.command);
    if let Some((bw, _)) = header.bandwidth {
        let _ = writeln!(out, "# copy_bandwidth_bytes_per_s: {bw:.0}");
    }
    let _ = writeln!(
        out,
        "group,case,particles,substeps,path,frames,total_median_ms,total_p10_ms,total_p90_ms,physics_median_ms,physics_p10_ms,physics_p90_ms,constraints_median_ms,constraints_p10_ms,constraints_p90_ms,surface_median_ms,surface_p10_ms,surface_p90_ms"
    );
    for (m, _) in rows {
        let s = |x: &super::Spread| format!("{:.6},{:.6},{:.6}", x.median, x.p10, x.p90);
        let _ = writeln!(
            out,
            "{},\"{}\",{},{},{},{},{},{},{},{}",
            m.group,
            m.case,
            m.particles,
            m.substeps,
            m.path,
            m.frames,
            s(&m.total),
            s(&m.physics),
            s(&m.constraints),
            s(&m.surface)
        );
    }
    out
}

/// The end-to-end table: each case as the app runs it (simulation and drawing into an offscreen
/// target, frames in flight) by the wall clock, next to its GPU time, and the GPU-only figure
/// of the same case from `measure` (a frame at a time, timestamps only).
pub fn end_to_end_markdown(header: &Header, extent: [u32; 2], rows: &[(EndToEnd, Measurement)]) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "Device: {} ({}); {}", header.device, header.driver, header.date);
    let _ = writeln!(out, "Command: `{}`", header.command);
    let _ = writeln!(out, "Offscreen target: {} x {} RGBA8 + D32", extent[0], extent[1]);
    let _ = writeln!(out);
    let _ = writeln!(
        out,
        "| case | particles | path | end to end frames/s | wall ms/frame | interval p10 - p90 | GPU sim ms | GPU render ms | host record ms | GPU-only ms/frame (frames/s) |"
    );
    let _ = writeln!(out, "|---|---:|---|---:|---:|---:|---:|---:|---:|---:|");
    let ms = |s: Option<Spread>| s.map(|s| format!("{:.3}", s.median)).unwrap_or_else(|| "-".into());
    for (e, m) in rows {
        let _ = writeln!(
            out,
            "| {} | {} | {} | {:.0} | {:.3} | {:.3} - {:.3} | {} | {} | {:.3} | {:.3} ({:.0}) |",
            e.case,
            e.particles,
            e.path,
            e.frames_per_second(),
            e.wall_ms,
            e.interval.p10,
            e.interval.p90,
            ms(e.sim_gpu),
            ms(e.render_gpu),
            e.record.median,
            m.total.median,
            1e3 / m.total.median.max(1e-9),
        );
    }
    out
}

pub fn end_to_end_csv(header: &Header, extent: [u32; 2], rows: &[(EndToEnd, Measurement)]) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "# device: {}", header.device);
    let _ = writeln!(out, "# driver: {}", header.driver);
    let _ = writeln!(out, "# date: {}", header.date);
    let _ = writeln!(out, "# command: {}", header.command);
    let _ = writeln!(out, "# target: {}x{}", extent[0], extent[1]);
    let _ = writeln!(
        out,
        "case,particles,path,frames,end_to_end_fps,wall_ms,interval_median_ms,interval_p10_ms,interval_p90_ms,sim_gpu_median_ms,render_gpu_median_ms,record_median_ms,gpu_only_median_ms"
    );
    let ms = |s: Option<Spread>| s.map(|s| format!("{:.4}", s.median)).unwrap_or_default();
    for (e, m) in rows {
        let _ = writeln!(
            out,
            "\"{}\",{},{},{},{:.1},{:.4},{:.4},{:.4},{:.4},{},{},{:.4},{:.4}",
            e.case,
            e.particles,
            e.path,
            e.frames,
            e.frames_per_second(),
            e.wall_ms,
            e.interval.median,
            e.interval.p10,
            e.interval.p90,
            ms(e.sim_gpu),
            ms(e.render_gpu),
            e.record.median,
            m.total.median,
        );
    }
    out
}
