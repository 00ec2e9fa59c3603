"""Live waist tracking (decisions W64-W66): WaistTracker against the realtime replay, its cost and its state.

    PYTHONPATH=$PWD .venv/bin/python experiments/waist_live.py [--external datasets/external] [--hours 1]

Prints, per mobgap session (HA001/HA002/MS001 Test11 and Test5 Trial1), the live and replay
(``track_waist(session, pipeline="waist-pendulum", realtime=True)``) distances, the step F1 of the live contacts
against the replay's (exact match), the W27 merges of each and how far apart the final positions are; then the CPU
time per push (1 sample, 1 s of samples), per second of data, how long after its end a step is reported, the import
time, and (``--hours``) the state size over a looped simulated stream.
"""

from __future__ import annotations

import argparse
import logging
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
SESSIONS = [f"mobgap_{s}_{t}_Trial1" for s in ("HA001", "HA002", "MS001") for t in ("Test11", "Test5")]


def compare(folder: Path) -> str:
    from pdrlearn.io import read_session
    from pdrlearn.track.waist import track_waist
    from pdrlearn.waist import WaistTracker

    s = read_session(folder)
    a, g = s["wAccelerometer"], s["wGyroscope"]
    tr = WaistTracker(a.rate_hz, meta=s.meta)
    out = tr.push(a.t, a.values, g.values) + tr.flush()
    ref = track_waist(s, pipeline="waist-pendulum", realtime=True)
    st, trj = ref.steps, ref.trajectory
    live_ev, ref_ev = {o.t for o in out}, set(st["event_s"])
    tp = len(live_ev & ref_ev)
    f1 = 2 * tp / (len(live_ev) + len(ref_ev)) if live_ev or ref_ev else 1.0
    dl, dr = sum(o.length_m for o in out), float(st["length_m"].sum())
    apart = float(np.hypot(tr.position[0] - trj["x"].iloc[-1], tr.position[1] - trj["y"].iloc[-1]))
    where = []
    if len(out) == len(st):  # the rows whose length differs: where in their sequence, their W27 inputs
        from pdrlearn.track.waist import _sequences

        diff = np.flatnonzero(np.abs(np.array([o.length_m for o in out]) - st["length_m"].to_numpy()) > 1e-9)
        dur = (st["end_s"] - st["start_s"]).to_numpy()
        for seq in _sequences(st):
            for i in diff[np.isin(diff, seq)]:
                where.append(f"row {i}: step {i - seq[0] + 1} of {len(seq) - 1}, {dur[i]:.2f} s, sequence median "
                             f"{np.median(dur[seq[:-1]]):.2f} s")
    return (f"| {folder.name.removeprefix('mobgap_').removesuffix('_Trial1')} | {len(out)} | {dl:.2f} / {dr:.2f} | "
            f"{100 * (dl - dr) / dr:+.2f} % (step F1 {f1:.3f}) | {sum(o.merged for o in out)} / "
            f"{int(st['merged'].sum())} | {apart:.3f} m | {'; '.join(where)} |")


def latency(folder: Path) -> list[str]:
    from pdrlearn.io import read_session
    from pdrlearn.waist import WaistTracker

    s = read_session(folder)
    a, g = s["wAccelerometer"], s["wGyroscope"]
    dur = a.t[-1] - a.t[0]
    lines = []
    for chunk in (1, int(round(a.rate_hz))):
        tr = WaistTracker(a.rate_hz, meta=s.meta)
        tr.push(a.t[:1], a.values[:1], g.values[:1])  # the lazy imports outside the timing
        cpu, late = [], []
        c0 = time.process_time()
        for i in range(1, len(a.t), chunk):
            t0 = time.process_time_ns()
            new = tr.push(a.t[i:i + chunk], a.values[i:i + chunk], g.values[i:i + chunk])
            cpu.append((time.process_time_ns() - t0) / 1e6)
            late += [a.t[min(i + chunk, len(a.t)) - 1] - st.end_s for st in new if st.has_next]
        total = time.process_time() - c0
        cpu = np.array(cpu)
        p50, p99 = np.percentile(cpu, 50), np.percentile(cpu, 99)
        lines.append(f"push of {chunk} sample(s): p50 {p50:.3f} ms, p99 {p99:.2f} ms, max {cpu.max():.1f} ms CPU "
                     f"({cpu.size} pushes); {total / dur:.3f} s CPU per s of data; a step reported "
                     f"{np.median(late):.2f} s (median), {np.max(late):.2f} s (max) after its end")
    return lines


def import_time() -> str:
    code = ("import time; c=time.process_time(); w=time.perf_counter(); import pdrlearn.waist; "
            "print(f'{time.process_time()-c:.2f} s CPU ({time.perf_counter()-w:.2f} s wall)')")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.strip()
    return f"import pdrlearn.waist: {out}"


def _rss_kib() -> int:
    """Resident memory of this process (KiB; Linux /proc, else 0)."""
    try:
        return int(Path("/proc/self/statm").read_text().split()[1]) * 4
    except (OSError, IndexError, ValueError):
        return 0


def long_stream(hours: float, fs: float = 20.0) -> list[str]:
    from pdrlearn.sim import simulate
    from pdrlearn.waist import WaistTracker

    s = simulate("B", 1, speed="slow", rate_hz=fs)
    a, g = s["wAccelerometer"], s["wGyroscope"]
    t1 = a.t - a.t[0]
    period = t1[-1] + 1.0 / fs
    tr = WaistTracker(fs, meta=s.meta, frame=s.require_frame("waist"), keep_steps=1000)
    k, c0, rows, m, n = 0, time.process_time(), [], int(fs), 0
    while k * period < hours * 3600:
        for i in range(0, len(t1), m):
            n += len(tr.push(t1[i:i + m] + k * period, a.values[i:i + m], g.values[i:i + m]))
        k += 1
        rows.append((k * period / 60, tr.state_size(), len(tr._rows), _rss_kib()))
    n += len(tr.flush())
    out = [f"{k} loops of a {period:.0f} s simulated walk = {k * period / 3600:.2f} h at {fs:g} Hz in 1 s pushes: "
           f"{n} steps, {time.process_time() - c0:.0f} s CPU"]
    for mnt, size, nrows, kib in rows[:: max(1, len(rows) // 6)] + rows[-1:]:
        out.append(f"  minute {mnt:5.1f}: state_size {size} numbers ({nrows} contact rows), process RSS {kib} KiB")
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    ap.add_argument("--hours", type=float, default=0.0, help="also stream this many hours of a looped simulation")
    args = ap.parse_args()
    logging.disable(logging.WARNING)
    print("| session | steps | live / replay distance (m) | difference | W27 merges live / replay "
          "| final position apart | rows of another length |")
    print("|---|---|---|---|---|---|---|")
    for name in SESSIONS:
        folder = args.external / name
        if not folder.is_dir():
            folder = ROOT / "datasets" / "real" / name
        if folder.is_dir():
            print(compare(folder))
        else:
            print(f"| {name} | (not found under {args.external}) |")
    for line in latency(ROOT / "datasets" / "real" / "mobgap_HA001_Test11_Trial1"):
        print(line)
    print(import_time())
    if args.hours > 0:
        for line in long_stream(args.hours):
            print(line)


if __name__ == "__main__":
    main()
