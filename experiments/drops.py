"""Decision B64: scattered dropped foot samples (``pdrlearn simulate --drop-rate``) and the read-time bridge.

Per user: a 20 m straight walk (``--scenario walk --length-m 20``) and a 20 m curved route, at 20 Hz (default)
and 100 Hz, copies with drop rate 0, 0.01, 0.03 (same walk and seed: only the drop mask differs). Each copy is
tracked with ``pdrlearn track`` (no model) offline with bridging off and on (:func:`bridging`) and
with ``--streaming`` (bridging on and off). The real recordings (datasets/real) are tracked with bridging off and on and
their steps.csv / trajectory.csv compared byte for byte, as are the 0 % copies.

Usage::

    OMP_NUM_THREADS=1 PYTHONPATH=. .venv/bin/python experiments/drops.py --users 31-36 --out /tmp/drops

Writes experiments/results/drops_<users>.md and .csv.
"""

# ruff: noqa: E501
from __future__ import annotations

import argparse
import contextlib
import json
import logging
import shutil
from pathlib import Path
from unittest import mock

import pandas as pd
from typer.testing import CliRunner

import pdrlearn.io.plasys as P  # noqa: E402
from _results import add_users, user_range, write_result, write_table  # noqa: E402
from pdrlearn.cli import app  # noqa: E402

ROUTES = {"straight": ["--scenario", "walk", "--length-m", "20"],
          "curved": ["--route", "straight:5, curve:90:3, straight:4, curve:-90:3, straight:2"]}
RATES = (20.0, 100.0)
DROPS = (0.0, 0.01, 0.03)
REAL = Path(__file__).resolve().parents[1] / "datasets" / "real"


def cli(args: list[str]) -> tuple[int, str]:
    r = CliRunner().invoke(app, [str(a) for a in args])
    return r.exit_code, r.output


def cli_json(args: list[str]) -> tuple[dict, str]:
    """Run a ``--json`` command: its JSON (parsed from stdout alone: a warning on stderr may hold braces, as
    B65's names ``{"timestamps": true}``) and the whole output (warnings included)."""
    r = CliRunner().invoke(app, [str(a) for a in args])
    if r.exit_code:
        raise SystemExit(f"{args[0]} {args[1]}: {r.output[-500:]}")
    return json.loads(r.stdout[r.stdout.index("{"):]), r.output


def bridging():
    """Every session read bridges its short dropped-sample intervals, as ``read_session(bridge_drops=True)`` (B64's
    option) does, also where the CLI reads with the default (decision E251: a stand-in, no module switch)."""
    real = P._bridge_drops

    def bridge(streams, folder, _bridge, streamed=False):
        return real(streams, folder, True, streamed=streamed)

    return mock.patch.object(P, "_bridge_drops", bridge)


def track(d: Path, out: Path, bridge: bool, streaming: bool = False) -> dict:
    shutil.rmtree(out, ignore_errors=True)
    with bridging() if bridge else contextlib.nullcontext():
        summary, text = cli_json(["track", d, "--out", out, "--json"] + (["--streaming"] if streaming else []))
    summary["warned"] = "B64" in text
    return summary


def same(a: Path, b: Path) -> bool:
    return all((a / f).read_bytes() == (b / f).read_bytes() for f in ("steps.csv", "trajectory.csv"))


def simulate_walk(root: Path, u: int, route: str, spec, rate: float, drop: float) -> tuple[Path, dict]:
    """Simulate one walk with dropped samples into ``root``; its folder and the row's truth columns."""
    d = root / f"u{u}_{route}_{rate:g}_{drop:g}"
    shutil.rmtree(d, ignore_errors=True)
    code, text = cli(["simulate", *spec, "--user-seed", u, "--rate", rate, "--drop-rate", drop, "--out", d, "--json"])
    if code:
        raise SystemExit(f"simulate {d}: {text[-500:]}")
    sim = json.loads(text[text.index("{"):])
    return d, {"user": u, "route": route, "rate_hz": rate, "drop_rate": drop,
               "dropped": sim.get("dropped_samples", 0), "truth_m": sim["distance_m"]}


def walks(users: range, root: Path):
    """(folder, row) of every simulated walk of ``users`` (``--users``' seeds): ROUTES x RATES x DROPS."""
    for u in users:
        for route, spec in ROUTES.items():
            for rate in RATES:
                for drop in DROPS:
                    yield simulate_walk(root, u, route, spec, rate, drop)


WALK = ["user", "route", "rate_hz"]  # a walk's copies differ by drop rate alone


def by_drop(df: pd.DataFrame, tags):
    """Per drop rate of ``df`` (one row a tracked copy, ``err_<tag>`` its distance error %): the rate, its copies
    indexed by walk, and per tag of ``tags`` the worst: max over the walks of (|error| - |error| of its 0 % copy)."""
    base = df[df.drop_rate == 0].set_index(WALK)
    for drop in DROPS:
        g = df[df.drop_rate == drop].set_index(WALK)
        yield drop, g, {t: (g[f"err_{t}"].abs() - base[f"err_{t}"].abs()).max() for t in tags}


def by_rate_route(df: pd.DataFrame, tags=()):
    """Per (drop rate, rate, route) of ``df``: those, the copies, and per tag of ``tags`` each copy's |error| -
    |error| of its walk's 0 % copy (indexed by walk)."""
    base = df[df.drop_rate == 0].set_index(WALK)
    for (drop, rate, route), g in df.groupby(["drop_rate", "rate_hz", "route"]):
        gi = g.set_index(WALK)
        yield drop, rate, route, g, {t: gi[f"err_{t}"].abs() - base.loc[gi.index, f"err_{t}"].abs() for t in tags}


def main() -> None:
    ap = argparse.ArgumentParser()
    add_users(ap, "31-36")
    ap.add_argument("--out", default="/tmp/drops")
    ap.add_argument("--no-real", action="store_true")
    a = ap.parse_args()
    root = Path(a.out)
    root.mkdir(parents=True, exist_ok=True)
    logging.disable(logging.INFO)
    rows = []
    for d, row in walks(user_range(a.users), root):
        for tag, bridge, streaming in (("off", False, False), ("on", True, False),
                                       ("stream_off", False, True), ("stream_on", True, True)):
            s = track(d, root / f"{d.name}_{tag}", bridge, streaming)
            row[f"err_{tag}"] = s.get("distance_error_pct")
            row[f"f1_{tag}"] = s.get("step_f1")
            row[f"mae_{tag}"] = s.get("stride_length_mae_pct")
            row[f"warned_{tag}"] = s["warned"]
        row["identical"] = same(root / f"{d.name}_off", root / f"{d.name}_on")
        rows.append(row)
        print(json.dumps(row), flush=True)
    df = pd.DataFrame(rows)
    real = []
    if not a.no_real:
        for d in sorted(p for p in REAL.iterdir() if p.is_dir()):
            track(d, root / f"real_{d.name}_off", False)
            track(d, root / f"real_{d.name}_on", True)
            real.append((d.name, same(root / f"real_{d.name}_off", root / f"real_{d.name}_on")))
            print(real[-1], flush=True)
    write_table(f"drops_{a.users}", df)
    lines = [f"# Dropped samples (decision B64), users {a.users}", "",
             "Distance error % of `pdrlearn track` (no model) vs the simulated truth; off/on = bridging off/on "
             "(offline), stream = `track --streaming`. Median |error| over the walks per drop rate.", "",
             "| drop | walks | median abs err off | median abs err on | worst (abs err - abs err of 0 % copy) off | worst on | stream off median | stream on median | F1 off min | F1 on min | F1 on < off | warned off | warned on | 0 % copies identical |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for drop, g, worse in by_drop(df, ("off", "on")):
        lines.append(f"| {drop:g} | {len(g)} | {g.err_off.abs().median():.3f} | {g.err_on.abs().median():.3f} | "
                     f"{worse['off']:+.3f} | {worse['on']:+.3f} | {g.err_stream_off.abs().median():.3f} | "
                     f"{g.err_stream_on.abs().median():.3f} | {g.f1_off.min():.3f} | {g.f1_on.min():.3f} | "
                     f"{int((g.f1_on < g.f1_off - 1e-12).sum())} | {int(g.warned_off.sum())} | {int(g.warned_on.sum())} | "
                     f"{bool(g.identical.all()) if drop == 0 else '-'} |")
    lines += ["", "Per rate and route (median distance error %, signed):", "",
              "| drop | rate | route | off | on | stream off | stream on |", "|---|---|---|---|---|---|---|"]
    for drop, rate, route, g, _ in by_rate_route(df):
        lines.append(f"| {drop:g} | {rate:g} | {route} | {g.err_off.median():+.3f} | {g.err_on.median():+.3f} | "
                     f"{g.err_stream_off.median():+.3f} | {g.err_stream_on.median():+.3f} |")
    if real:
        lines += ["", "Real recordings (datasets/real), steps.csv and trajectory.csv byte-identical off vs on: "
                  + ", ".join(f"{n} {ok}" for n, ok in real)]
    write_result(f"drops_{a.users}", lines)


if __name__ == "__main__":
    main()
