"""A length model without the user's length-class bounds, tracked offline, streamed and as a bundle (decisions
L50, L59, L60 in docs/decisions/localization.md).

L50's case, by the CLI: simulated user 1 (`pdrlearn simulate -s A -u 1`, `-s length -u 1`, normal speed) with
meta.json's `length_class_bounds_m` removed from both, and `length_m` removed from the length exercise's
steps.csv (classes kept: the model has no bounds); `pdrlearn train LEN --tasks length --methods heuristic
--units foot`; `pdrlearn export MODEL` (no bounds), the same bundle rewritten as an export before L59 wrote it
(the thesis step bounds x 2 with `length_bounds_source` "thesis ch.6.3 step bounds x 2 (stride)"), and
`pdrlearn export MODEL --length-bounds 1.0241,1.5196`, the user's own edges (the simulator's). Then, for the bayes
(default) and thesis rules: `pdrlearn track A --method M3 --model MODEL [--streaming]` and `pdrlearn run BUNDLE
A`. Prints per run: distance, its error against the labelled strides, the final position error, whether the
length-bounds warning was printed, and the stride lengths (|steps.csv length_m|).

Run: PYTHONPATH=. .venv/bin/python experiments/no_bounds_bundle.py
"""

from __future__ import annotations

import contextlib
import io
import json
import sys
import tempfile
from pathlib import Path

import pandas as pd

FALLBACK_SOURCE = "thesis ch.6.3 step bounds x 2 (stride)"  # what an export before L59 wrote
FALLBACK = {"short": [0.0, 0.60], "normal": [0.60, 0.90], "long": [0.92, 20.0]}


def cli(args: list[str]) -> tuple[str, str]:
    """``pdrlearn ARGS`` in this process: (stdout, stderr); exit != 0 stops the script."""
    from pdrlearn.cli import main

    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        rc = main([str(a) for a in args])
    if rc != 0:
        raise SystemExit(f"pdrlearn {' '.join(map(str, args))} exited {rc}: {err.getvalue()}")
    return out.getvalue(), err.getvalue()


def drop_bounds(session: Path, drop_length: bool = False) -> list[float]:
    meta = json.loads((session / "meta.json").read_text())
    bounds = meta.pop("length_class_bounds_m")
    (session / "meta.json").write_text(json.dumps(meta, indent=1))
    if drop_length:
        steps = pd.read_csv(session / "steps.csv")
        steps.drop(columns=["length_m"]).to_csv(session / "steps.csv", index=False)
    return [float(b) for b in bounds]


def report(label: str, out: str, err: str, folder: Path) -> None:
    s = json.loads(out)
    lengths = pd.read_csv(folder / "steps.csv")["length_m"].abs()
    warn = [ln for ln in err.splitlines() if "length-class bounds" in ln]
    print(f"{label:58s} distance {s['distance_m']:.2f} m of {s['distance_ref_m']:.2f} m "
          f"({s['distance_error_pct']:+.2f} %), final position error {s['final_position_error_m']:.3f} m, "
          f"{len(lengths)} strides {lengths.min():.2f}-{lengths.max():.2f} m "
          f"(middle 14: {lengths.iloc[1:-1].min():.2f}-{lengths.iloc[1:-1].max():.2f} m)")
    print(f"{'':58s} bounds warning: {'yes' if warn else 'no'}; stride lengths "
          f"{' '.join(f'{v:.2f}' for v in lengths)} m")


def main(argv: list[str]) -> None:
    if argv:
        raise SystemExit(__doc__.strip().splitlines()[-1])
    with tempfile.TemporaryDirectory() as tmp:
        d = Path(tmp)
        cli(["simulate", "-s", "A", "-u", "1", "--out", d / "A"])
        cli(["simulate", "-s", "length", "-u", "1", "--out", d / "len"])
        user = drop_bounds(d / "A")
        drop_bounds(d / "len", drop_length=True)
        cli(["train", d / "len", "--tasks", "length", "--methods", "heuristic", "--units", "foot", "--out",
             d / "model"])
        _, err = cli(["export", d / "model", "--out", d / "b_none"])
        disp = json.loads((d / "b_none" / "manifest.json").read_text())["displacement"]
        print(f"export: length_bounds_m {disp['length_bounds_m']}, "
              f"length_bounds_source {disp['length_bounds_source']!r}")
        print(f"export stderr: {err.strip()}")
        cli(["export", d / "model", "--out", d / "b_user", "--length-bounds", f"{user[0]},{user[1]}"])
        from pdrlearn.runtime.bundle import MANIFEST_SHA, sha256_file

        old = d / "b_pre_l59"  # as an export before L59 wrote it
        cli(["export", d / "model", "--out", old])
        m = json.loads((old / "manifest.json").read_text())
        m["displacement"].update(length_bounds_m=FALLBACK, length_bounds_source=FALLBACK_SOURCE)
        (old / "manifest.json").write_text(json.dumps(m))
        (old / MANIFEST_SHA).write_text(f"{sha256_file(old / 'manifest.json')}  manifest.json\n")
        k = 0
        for rules in ("bayes", "thesis"):
            r = ["--rules", rules]
            for label, args in (("track --model", ["track", d / "A", "--method", "M3", "--model", d / "model"]),
                                ("track --model --streaming", ["track", d / "A", "--method", "M3", "--model",
                                                               d / "model", "--streaming"]),
                                ("run (bundle without bounds)", ["run", d / "b_none", d / "A"]),
                                ("run (bundle exported before L59)", ["run", old, d / "A"]),
                                (f"run (bundle --length-bounds {user[0]},{user[1]})", ["run", d / "b_user", d / "A"])):
                k += 1
                out_dir = d / f"out{k}"
                out, err = cli([*args, *r, "--out", out_dir, "--json"])
                report(f"{label} --rules {rules}", out, err, out_dir)


if __name__ == "__main__":
    main(sys.argv[1:])
