"""Where the daily-activity bout distance error of ``waist-pendulum`` comes from (issue 8, decision W111).

Per Test11 reference bout of the mobgap subjects (calibrated on the subject's Test5 walks, as
experiments/waist.py), the error against INDIP's bout ``Length`` is split multiplicatively,
``1 + err_L = (1 + ref)(1 + count)(1 + step)`` (W25, W56):
- ``ref``: the bout's own strides (W25) / ``Length`` - 1 -- INDIP leaves its untimed steps out of ``Length`` (X2b);
- ``count``: detected / reference steps - 1, with the contacts behind it: ``missed`` (reference contacts no
  detection matches within the tolerance) and ``extra`` (detections matching none);
- ``step``: mean tracked step / mean reference step - 1.
Two more views of the same bout: ``turn`` = (tracked - reference) distance of the steps whose midpoint lies in
one of INDIP's turns (turns.csv; reference = its steps there x the bout's mean reference step), in % of the
bout's strides length, ``straight`` the rest; ``edge`` = the midpoint rule (W21) minus each step weighted by its
time overlap with the bout, in %: our steps that straddle the bout's ends.
Then the pooled median with each part removed (the counterfactual medians), and HA001 calibrated on Test5
Trial1 only: the demo's number (total tracked / total ``Length`` - 1 over the bouts, not a median).

Run: PYTHONPATH=. .venv/bin/python experiments/waist_bout_parts.py [--external datasets/external]
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

import waist as W  # noqa: E402
from pdrlearn.io import read_session  # noqa: E402
from pdrlearn.steps.evaluate import DEFAULT_TOLERANCE_S, match_events  # noqa: E402
from pdrlearn.track import get_pipeline  # noqa: E402
from pdrlearn.waist.calibration import calibrate  # noqa: E402
from pdrlearn.waist.evaluate import bout_stride_length, distance_metrics, reference_bouts, steps_in_interval  # noqa: E402
from pdrlearn.waist.params import resolve_params  # noqa: E402


def track(ext: Path, cal_names: list[str], test_name: str, options: dict | None = None):
    """The calibrated ``waist-pendulum`` steps of one test recording (experiments/waist.py's protocol)."""
    cal = [read_session(ext / n) for n in cal_names]
    test = read_session(ext / test_name)
    base, _ = resolve_params(cal[0], None)
    base.options = dict(options or {})
    params = calibrate(cal, "waist-pendulum", params=base)
    return get_pipeline("waist-pendulum")(test, params=params, **(options or {})).steps, test


def _in_any(t: np.ndarray, iv: np.ndarray) -> np.ndarray:
    return np.zeros(len(t), bool) if not len(iv) else ((t[:, None] >= iv[:, 0]) & (t[:, None] <= iv[:, 1])).any(1)


def bout_parts(steps: pd.DataFrame, session, subject: str) -> pd.DataFrame:
    """One row per reference bout: the parts of its error (module docstring)."""
    bouts = reference_bouts(session)
    lengths = steps["length_m"].abs().to_numpy(float)
    mid = 0.5 * (steps["start_s"].to_numpy(float) + steps["end_s"].to_numpy(float))
    has_next = steps["has_next"].to_numpy(bool)
    ev = steps["event_s"].to_numpy(float)
    ref_ic = np.sort(session.extras["ics"]["ic_s"].dropna().to_numpy(float))
    tr = session.extras.get("turns")
    turns = np.c_[tr["start_s"], tr["end_s"]] if tr is not None else np.zeros((0, 2))
    angle = np.abs(tr["angle_deg"].to_numpy(float)) if tr is not None else np.zeros(0)
    rows = []
    for b in bouts.itertuples():
        m = steps_in_interval(steps, b.start_s, b.end_s)
        est = float(lengths[m].sum())
        ref_s, n_ref = bout_stride_length(session, b.start_s, b.end_s)
        n = int((m & has_next).sum())
        d = np.sort(ev[(ev >= b.start_s - DEFAULT_TOLERANCE_S) & (ev <= b.end_s + DEFAULT_TOLERANCE_S)])
        r = ref_ic[(ref_ic >= b.start_s - 1e-6) & (ref_ic <= b.end_s + 1e-6)]
        i_d, _ = match_events(d, r, DEFAULT_TOLERANCE_S)
        # reference steps (IC to next timed IC) and ours whose midpoint lies in an INDIP turn of the bout
        sel = (turns[:, 0] < b.end_s) & (turns[:, 1] > b.start_s)
        bt = turns[sel]
        ref_step = ref_s / n_ref
        n_ref_turn = int(_in_any(0.5 * (r[1:] + r[:-1]), bt).sum()) if len(r) > 1 else 0
        ref_turn = ref_step * n_ref_turn
        in_turn = m & _in_any(mid, bt)
        overlap = np.clip(np.minimum(steps["end_s"], b.end_s) - np.maximum(steps["start_s"], b.start_s), 0, None)
        dur = (steps["end_s"] - steps["start_s"]).to_numpy(float)
        w = np.where(dur > 0, overlap.to_numpy(float) / np.where(dur > 0, dur, 1), 0.0)
        rows.append({
            "subject": subject, "start_s": b.start_s, "dur_s": b.end_s - b.start_s,
            "turn_deg": float(angle[sel].sum()),
            "L_m": b.length_m, "L_strides_m": ref_s, "tracked_m": est,
            "err_L": 100 * (est / b.length_m - 1), "err_str": 100 * (est / ref_s - 1),
            "ref": 100 * (ref_s / b.length_m - 1), "count": 100 * (n / n_ref - 1),
            "step": 100 * ((est / n) / ref_step - 1) if n else np.nan,
            "missed": int(len(r) - i_d.size), "extra": int(len(d) - i_d.size),
            "turn": 100 * (lengths[in_turn].sum() - ref_turn) / ref_s,
            "turn_n": f"{int((in_turn & has_next).sum())}/{n_ref_turn}",
            "straight": 100 * (lengths[m & ~in_turn].sum() - (ref_s - ref_turn)) / ref_s,
            "edge": 100 * (est - float((lengths * w).sum())) / ref_s})
    return pd.DataFrame(rows)


def counterfactual_medians(t: pd.DataFrame) -> dict[str, float]:
    """Pooled median |error vs Length| with one part of each bout's error removed."""
    g = 1 + t.err_L / 100
    return {"as is": t.err_L.abs().median(),
            "ref part removed (= vs strides)": t.err_str.abs().median(),
            "count part removed": (100 * (g / (1 + t["count"] / 100) - 1)).abs().median(),
            "per-step part removed": (100 * (g / (1 + t.step / 100) - 1)).abs().median(),
            "turn steps as the reference": (100 * ((t.tracked_m - t.turn / 100 * t.L_strides_m) / t.L_m - 1)
                                            ).abs().median(),
            "edges overlap-weighted": (100 * ((t.tracked_m - t.edge / 100 * t.L_strides_m) / t.L_m - 1)
                                       ).abs().median(),
            "ref and count removed": (100 * (g / (1 + t.ref / 100) / (1 + t["count"] / 100) - 1)).abs().median()}


def main() -> None:
    external, runs = W.test11_cli()
    t = pd.concat([bout_parts(*track(external, c, n), n.split("_")[1]) for c, n in runs], ignore_index=True)
    print("per bout (%; 1 + err_L = (1 + ref)(1 + count)(1 + step); turn + straight = err_str):")
    print(t.round(1).to_string(index=False))
    print("\npooled median |bout error| with one part removed, vs Length / vs the bouts' strides:")
    strides = counterfactual_medians(t.assign(err_L=t.err_str, L_m=t.L_strides_m, ref=0.0))
    for k, v in counterfactual_medians(t).items():
        print(f"  {k}: {v:.2f} / {strides[k]:.2f} %")
    ha = [r for r in runs if r[1].split("_")[1] == "HA001"][0][1]
    steps, s = track(external, [ha.replace("Test11", "Test5")], ha)
    d = distance_metrics(steps, s)
    dp = bout_parts(steps, s, "HA001")
    excess = dp.tracked_m.sum() - dp.L_m.sum()
    print(f"\ndemo (HA001 Test11, calibrated on Test5 Trial1 only): total error {d['distance_error_pct']:.2f} % "
          f"(sum tracked / sum Length - 1), median per bout {d['bout_distance_error_median_pct']:.2f} %; "
          f"excess {excess:.2f} m, of it in INDIP turns {(dp.turn / 100 * dp.L_strides_m).sum():.2f} m, "
          f"straight {(dp.straight / 100 * dp.L_strides_m).sum():.2f} m, "
          f"ref gap {(dp.L_strides_m - dp.L_m).sum():.2f} m")


if __name__ == "__main__":
    main()
