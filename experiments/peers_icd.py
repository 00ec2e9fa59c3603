"""mobgap's own IC detectors on the INDIP reference walking bouts, scored as `pdrlearn steps` (decision 26 of
docs/decisions/steps.md; peers, measured, no pdrlearn default changes).

mobgap 1.2.0's `IcdIonescu` (the detector of both its Mobilise-D pipelines), `IcdShinImproved` and
`IcdHKLeeImproved`, defaults, each run on every reference walking bout (`reference_parameters_.wb_list`) of
the mobgap recordings, on mobgap's body-frame data (`to_body_frame`, as its pipelines), one bout at a time
(start..end sample, as its `GsIterator` slices a gait sequence; and, added after the first run, with 1 s
of data on either side); the contacts of all bouts of a recording
together, scored with `pdrlearn.steps.evaluate.score_steps` (inside the bouts, untimed and same-foot-gap
detections unscored, 0.25 s), beside `pdrlearn steps --detector waist-ic` on the whole recording.

Needs mobgap (not a pdrlearn dependency): `make peers` builds `.venv-peers`; then
    PYTHONPATH=$PWD .venv-peers/bin/python experiments/peers_icd.py [--external datasets/external]
Writes experiments/results/peers_icd.md.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import itertools
import logging
import sys
import warnings
from pathlib import Path

import numpy as np
import pandas as pd

ROOT = Path(__file__).resolve().parents[1]
PAD_S = 1.0  # the padded variant (added after the first run): data on either side of a bout
RECORDINGS = ("HA001_Test11_Trial1", "HA002_Test11_Trial1", "MS001_Test11_Trial1", "HA001_Test5_Trial1",
              "HA001_Test5_Trial2", "MS001_Test5_Trial1", "MS001_Test5_Trial2")  # INDIP bouts (HA002 Test5: none)


def counts(ev_s: np.ndarray, session) -> tuple[int, int, int]:
    from pdrlearn.steps.evaluate import score_steps

    s = score_steps(pd.DataFrame({"event_s": np.sort(ev_s), "unit": "waist"}), session)
    return s["true_positives"], s["scored_count"], s["reference_count"]


def f1(c) -> float:
    tp, det, ref = (sum(x) for x in zip(*c, strict=True))
    return 2 * tp / (det + ref) if det + ref else float("nan")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    args = ap.parse_args()
    warnings.filterwarnings("ignore")
    logging.basicConfig(level=logging.ERROR)
    from peers import _mobgap_data_dir

    _mobgap_data_dir()  # before mobgap is imported: it reads MOBGAP_DATA_DIR at import
    try:
        from mobgap.data import LabExampleDataset
        from mobgap.initial_contacts import IcdHKLeeImproved, IcdIonescu, IcdShinImproved
        from mobgap.utils.conversions import to_body_frame
    except ImportError:
        sys.exit("experiments/peers_icd.py needs mobgap 1.2.0: run make peers first (builds .venv-peers)")

    from pdrlearn.io import read_session
    from pdrlearn.steps.detectors import get_detector

    ds = LabExampleDataset(reference_system="INDIP")
    dets = {"IcdIonescu": IcdIonescu, "IcdShinImproved": IcdShinImproved, "IcdHKLeeImproved": IcdHKLeeImproved}
    res = {k: {} for k in ("waist-ic", *dets, *(f"{d} padded 1 s" for d in dets))}
    for name in RECORDINGS:
        s = read_session(args.external / f"mobgap_{name}")
        subj, test, trial = name.split("_")
        dp = ds.get_subset(cohort=subj[:2], participant_id=subj[2:], test=test, trial=trial)
        fs = float(dp.sampling_rate_hz)
        if len(dp.data_ss) != len(s["wAccelerometer"].t):
            print(f"{name}: mobgap has {len(dp.data_ss)} samples, our session {len(s['wAccelerometer'].t)}: skipped")
            continue
        data = to_body_frame(dp.data_ss)
        wbs = dp.reference_parameters_.wb_list
        res["waist-ic"][name] = counts(get_detector("waist-ic").detect(s)["event_s"].to_numpy(float), s)
        for (k, cls), pad in itertools.product(dets.items(), (0, PAD_S)):
            ics = []
            for wb in wbs.itertuples():
                lo = max(0, int(wb.start) - int(round(pad * fs)))
                hi = min(len(data), int(wb.end) + int(round(pad * fs)))
                d = cls().detect(data.iloc[lo:hi], sampling_rate_hz=fs)
                ics.append(d.ic_list_["ic"].to_numpy(float) + lo)
            ev = np.concatenate(ics) / fs if ics else np.zeros(0)
            res[k if not pad else f"{k} padded 1 s"][name] = counts(ev, s)
    print("| detector | " + " | ".join(RECORDINGS) + " | Test11 pooled | Test5 pooled |")
    print("|---|" + "---|" * (len(RECORDINGS) + 2))
    for k, r in res.items():
        cells = [f"{f1([r[n]]):.3f} ({r[n][0]}/{r[n][1]}/{r[n][2]})" if n in r else "-" for n in RECORDINGS]
        t11 = [r[n] for n in r if "Test11" in n]
        t5 = [r[n] for n in r if "Test5" in n]
        print(f"| {k} | " + " | ".join(cells) + f" | {f1(t11):.3f} | {f1(t5):.3f} |")
    print("\nCells: F1 (TP / scored detections / reference contacts). mobgap's detectors were given the reference "
          "bouts; waist-ic ran on the whole recording. A reference bout starts and ends at a contact, so on the bout "
          "alone its first and last contacts lie at the data's edges; 'padded 1 s' (added after the first run) gives "
          "each bout 1 s of data on either side (detections outside the bouts are not scored).")


if __name__ == "__main__":
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        main()
    (ROOT / "experiments" / "results" / "peers_icd.md").write_text(buf.getvalue())
    print(buf.getvalue(), end="")
