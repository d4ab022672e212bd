#!/usr/bin/env python3
"""Fuzzes `msdsim simulate` with mutated presets and random `--set` overrides.

Each case takes a shipped preset, applies one to three mutations (a value swapped for one of
another type, an extreme value, a deleted key, a duplicated table or array entry, a random
`--set`, or the text cut or garbled), runs `msdsim --validation simulate --frames 2 --quiet`,
and sorts the outcome:

  refused   exit 2, one line `msdsim: error: ...` on standard error
  ran       exit 0
  unstable  exit 3, one line `msdsim: error: ...` (the runtime guard)
  other     anything else: another exit code, a signal, a panic or internal error, more than
            one line on standard error (besides the log's warnings), a validation message, or
            no end within the timeout

Every `other` case is kept in OUT/other/ with the command and its output. Ends with the table
of outcomes (markdown) and exit code 1 when any case is `other`.

  scripts/fuzz-presets.py [--binary target/release/msdsim] [--cases 3000] [--jobs 2]
                          [--seed 1] [--out fuzz-out] [--timeout 120]
"""

import argparse
import concurrent.futures
import copy
import math
import os
import random
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

EXTREMES = [
    0, -1, 1, 2, 3, 7, 64, 1000, 4096, 4097, 65536, 2**31 - 1, 2**31, 2**32, 2**63 - 1, -2**63,
    0.0, -0.0, 1e-300, -1e-300, 1e-45, 1e-30, 1e-7, 0.5, 1e7, 1e30, 1e39, 1e300, -1e300,
    float("nan"), float("inf"), float("-inf"),
    "", "x", "nope", "top_row", "corners", "vertical", "horizontal", "triangles", "auto", "vbd",
    "a\u00e9\u4e2d", "x" * 5000, "1", "-", "\\u0007",
    True, False, [], [0], [1, 2], [1, 2, 3], [1.0, 2.0, 3.0, 4.0], [[1, 2]], ["a", 1], [1e300, 1e300],
    {}, {"x": 1}, {"structural": -1.0}, {"structural": 1e300, "shear": 0.0, "bending": float("nan")},
]


def toml_key(k):
    ok = k and all(c.isalnum() or c in "_-" for c in k)
    return k if ok else '"' + k.replace("\\", "\\\\").replace('"', '\\"') + '"'


def toml_value(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        out = v.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n")
        return '"' + "".join(c if c.isprintable() else "\\u%04x" % ord(c) for c in out) + '"'
    if isinstance(v, list):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{toml_key(k)} = {toml_value(x)}" for k, x in v.items()) + " }"
    raise TypeError(type(v))


def to_toml(doc):
    """TOML text of a parsed preset: scalars first, then tables, then arrays of tables."""
    lines = []
    for k, v in doc.items():
        if not isinstance(v, dict) and not (isinstance(v, list) and v and all(isinstance(x, dict) for x in v)):
            lines.append(f"{toml_key(k)} = {toml_value(v)}")
    for k, v in doc.items():
        if isinstance(v, dict):
            lines.append(f"\n[{toml_key(k)}]")
            lines.extend(f"{toml_key(a)} = {toml_value(b)}" for a, b in v.items())
    for k, v in doc.items():
        if isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
            for entry in v:
                lines.append(f"\n[[{toml_key(k)}]]")
                lines.extend(f"{toml_key(a)} = {toml_value(b)}" for a, b in entry.items())
    return "\n".join(lines) + "\n"


def paths(doc, prefix=()):
    """Every (path, value) in a document, tables and arrays of tables descended."""
    for k, v in doc.items():
        p = prefix + (k,)
        yield p, v
        if isinstance(v, dict):
            yield from paths(v, p)
        elif isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
            for i, entry in enumerate(v):
                yield from paths(entry, p + (i,))


def container(doc, path):
    node = doc
    for step in path[:-1]:
        node = node[step]
    return node


def extreme(rng):
    """A fresh copy of an extreme value (never shared, so no list can come to hold itself)."""
    return copy.deepcopy(rng.choice(EXTREMES))


def mutate(rng, doc, sets):
    """Applies one mutation to the parsed document (or adds a --set); returns its name."""
    all_paths = list(paths(doc))
    kind = rng.choice(["swap", "extreme", "delete", "duplicate", "set", "nudge", "nudge", "nudge"])
    if not all_paths:
        kind = "set"
    if kind in ("swap", "extreme", "nudge", "delete"):
        path, value = rng.choice(all_paths)
        parent = container(doc, path)
        if kind == "delete":
            del parent[path[-1]]
        elif kind == "nudge" and isinstance(value, (int, float)) and not isinstance(value, bool):
            parent[path[-1]] = type(value)(value * rng.choice([-1, 0, 0.5, 2, 10, 1000]))
        elif kind == "nudge" and isinstance(value, list) and value:
            i = rng.randrange(len(value))
            value[i] = extreme(rng)
        else:
            parent[path[-1]] = extreme(rng)
        return kind
    if kind == "duplicate":
        arrays = [(p, v) for p, v in all_paths if isinstance(v, list) and v]
        if not arrays:
            return "duplicate (none)"
        path, value = rng.choice(arrays)
        value.append(copy.deepcopy(value[rng.randrange(len(value))]))
        return kind
    # A --set of a known key (or a made-up one) to a random value.
    path, _ = rng.choice(all_paths)
    key = ".".join(str(p) for p in path)
    if rng.random() < 0.2:
        key = rng.choice([key + ".x", "nope." + key, key.replace(".", "..", 1), "cloth.99.mass", "sim"])
    v = extreme(rng)
    text = toml_value(v) if not isinstance(v, str) or rng.random() < 0.7 else v
    sets.append(f"{key}={text}")
    return "set"


def make_case(rng, presets):
    name, text = rng.choice(presets)
    doc = tomllib.loads(text)
    sets = []
    names = [mutate(rng, doc, sets) for _ in range(rng.randint(1, 3))]
    out = to_toml(doc)
    r = rng.random()
    if r < 0.05:
        out = out[: rng.randrange(len(out))]
        names.append("truncate")
    elif r < 0.10:
        i = rng.randrange(len(out))
        junk = rng.choice(["\x00", "\r", "[[", "]", "=", "\"", "\ufeff", "[sim]\n", "\xff"])
        out = out[:i] + junk + out[i:]
        names.append("garble")
    elif r < 0.13:
        header = rng.choice(["[sim]", "[ground]", "[wind]"])
        out = out + f"\n{header}\n"
        names.append("duplicate table")
    return name, out, sets, names


def classify(code, stderr, timed_out):
    # The log's warnings (a contact faster than exact, say) may come before the outcome.
    lines = [l for l in stderr.splitlines() if l.strip() and not l.startswith("[WARN ")]
    bad = timed_out or "panicked" in stderr or "internal error" in stderr or "alidation" in stderr
    if bad:
        return "other"
    one_error = len(lines) == 1 and lines[0].startswith("msdsim: error: ")
    if code == 0 and not lines:
        return "ran"
    if code == 2 and one_error:
        return "refused"
    if code == 3 and one_error:
        return "unstable"
    return "other"


def run_case(args, index, seed):
    rng = random.Random(seed * 1_000_003 + index)
    presets = [(p.name, p.read_text()) for p in sorted((ROOT / "presets").glob("*.toml"))]
    name, text, sets, names = make_case(rng, presets)
    work = Path(args.out) / "work" / str(index)
    work.mkdir(parents=True, exist_ok=True)
    preset = work / "case.toml"
    preset.write_bytes(text.encode("utf-8", "surrogatepass"))
    cmd = [args.binary, "--validation", "simulate", "--preset", str(preset), "--frames", "2", "--quiet"]
    for s in sets:
        cmd += ["--set", s]
    timed_out = False
    try:
        p = subprocess.run(cmd, capture_output=True, timeout=args.timeout, cwd=work)
        code, stderr = p.returncode, p.stderr.decode("utf-8", "replace")
    except subprocess.TimeoutExpired as e:
        code, stderr, timed_out = None, (e.stderr or b"").decode("utf-8", "replace"), True
    outcome = classify(code, stderr, timed_out)
    if outcome == "other":
        keep = Path(args.out) / "other" / str(index)
        keep.mkdir(parents=True, exist_ok=True)
        shutil.copy(preset, keep / "case.toml")
        (keep / "report.txt").write_text(
            f"from {name}, mutations {names}\ncommand: {cmd}\nexit: {code} timed out: {timed_out}\n{stderr}"
        )
    shutil.rmtree(work, ignore_errors=True)
    return outcome, code, names


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--binary", default=str(ROOT / "target/release/msdsim"))
    ap.add_argument("--cases", type=int, default=3000)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--out", default="fuzz-out")
    ap.add_argument("--timeout", type=float, default=120.0)
    args = ap.parse_args()
    if not os.access(args.binary, os.X_OK):
        sys.exit(f"fuzz-presets: {args.binary} is not an executable (cargo build --release first)")
    counts = {"refused": 0, "ran": 0, "unstable": 0, "other": 0}
    by_code = {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        futures = [pool.submit(run_case, args, i, args.seed) for i in range(args.cases)]
        for done, f in enumerate(concurrent.futures.as_completed(futures), 1):
            outcome, code, _ = f.result()
            counts[outcome] += 1
            by_code[code] = by_code.get(code, 0) + 1
            if done % 250 == 0:
                print(f"{done} cases: {counts}", file=sys.stderr, flush=True)
    print(f"| outcome (seed {args.seed}, {args.cases} cases) | cases |")
    print("|---|---:|")
    for k, v in counts.items():
        print(f"| {k} | {v} |")
    print(f"\nexit codes: {dict(sorted(by_code.items(), key=lambda kv: str(kv[0])))}")
    if counts["other"]:
        print(f"\n{counts['other']} case(s) in {args.out}/other/")
    sys.exit(1 if counts["other"] else 0)


if __name__ == "__main__":
    main()
