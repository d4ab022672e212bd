#!/usr/bin/env python3
"""The table of scripts/stiff-cloth.sh's runs: per stiffness and method, the settled sag's error
against the static equilibrium (Newton's method on the total energy, tests/suite/large_steps.rs:
7.568 mm at 1e4 N/m, 3.510 mm at 1e5), the fastest particle after 4 s, and the GPU time a
frame; then each method's cheapest setting (substeps x iterations: GPU time a frame) within 5%
and 1%, and within them at rest (every particle under 1 mm/s).
Usage: scripts/stiff-cloth.py DIR > table.md (DIR: the runs' NAME.json and NAME.log)."""
import json
import math
import pathlib
import re
import sys

EQUILIBRIUM = {"1e4": 7.568e-3, "1e5": 3.510e-3}


def main(folder):
    rows = []
    for log in sorted(pathlib.Path(folder).glob("*.log")):
        k, method, substeps, iterations = log.stem.split("-", 3)
        text = log.read_text()
        time = re.search(r"GPU frame time: mean ([0-9.]+) ms", text)
        state = log.with_suffix(".json")
        if time is None or not state.exists():
            # (a run the runtime guard stopped, exit 3, has no final state: "stopped" below)
            rows.append((k, method, int(substeps), int(iterations), math.nan, math.nan, math.nan))
            continue
        o = json.loads(state.read_text())["objects"][0]
        sag = 1.0 - sum(p[1] for p in o["positions"]) / len(o["positions"])
        fastest = max(math.sqrt(sum(c * c for c in v)) for v in o["velocities"])
        error = sag / EQUILIBRIUM[k[1:]] - 1.0
        rows.append((k, method, int(substeps), int(iterations), error, fastest, float(time.group(1))))
    print("| k [N/m] | method | substeps | iterations | sag error | fastest [m/s] | GPU ms/frame |")
    print("|---|---|---:|---:|---:|---:|---:|")
    for k, method, s, it, error, fastest, time in sorted(rows, key=lambda r: (r[0], r[1], r[2], r[3])):
        if math.isnan(error):
            print(f"| {k[1:]} | {method} | {s} | {it} | stopped (guard) | | |")
            continue
        print(f"| {k[1:]} | {method} | {s} | {it} | {100 * error:+.1f}% | {fastest:.1e} | {time:.3f} |")
    print()
    print("| k [N/m] | method | cheapest sag within 5% | within 1% | within 5% and at rest | within 1% and at rest |")
    print("|---|---|---|---|---|---|")
    for k in sorted({r[0] for r in rows}):
        for method in sorted({r[1] for r in rows if r[0] == k}):
            cells = []
            for bound, rest in ((0.05, math.inf), (0.01, math.inf), (0.05, 1e-3), (0.01, 1e-3)):
                ok = [r for r in rows if r[0] == k and r[1] == method and abs(r[4]) <= bound and r[5] < rest]
                best = min(ok, key=lambda r: r[6], default=None)
                cells.append("none" if best is None else f"{best[2]} x {best[3]}: {best[6]:.3f} ms")
            print(f"| {k[1:]} | {method} | {' | '.join(cells)} |")


if __name__ == "__main__":
    main(sys.argv[1])
