"""Why mobgap's bout distance on daily activities beats our pendulum on the bouts it tracks (decision W56): the
per-bout error vs the bouts' own strides (W25) split into a step-count part and a per-step-length part,
``(1 + err_strides) = (1 + count_err)(1 + step_err)`` (as experiments/waist.py's decomposition), for mobgap's
``MobilisedPipelineHealthy`` on every subject (W50's 4.63 % row) and our ``waist-pendulum`` (calibrated and
uncalibrated) on the Test11 bouts where that mobgap pipeline has steps. mobgap is run exactly as
experiments/peers.py does (its own LabExampleDataset, defaults), our pendulum exactly as experiments/waist.py.

Run: make peers && PYTHONPATH=. .venv-peers/bin/python experiments/peers_bout_parts.py [--external datasets/external]
"""

from __future__ import annotations

import numpy as np
import pandas as pd

import peers as P  # noqa: E402
import waist as W  # noqa: E402


def parts(b: pd.DataFrame) -> pd.DataFrame:
    """Per bout: count_err = detected / reference steps - 1, step_err = mean tracked / mean reference step - 1 (%)."""
    n, nr = b["n_steps"].to_numpy(float), b["n_reference_steps"].to_numpy(float)
    ref_step = b["reference_strides_m"].to_numpy(float) / nr
    per = (b["tracked_m"].to_numpy(float) / np.where(n > 0, n, np.nan)) / ref_step
    return b.assign(count_err_pct=100 * (n / nr - 1), step_err_pct=100 * (per - 1))


def main() -> None:
    external, runs = W.test11_cli()
    P._mobgap_data_dir()
    _, mob_b, _ = P.run_mobgap(external, sorted({t for _, t in runs}))
    ours_b: list = []
    W.real(external, runs, configs=[("waist-pendulum", "waist-pendulum", {})], bouts=ours_b)
    mob = pd.DataFrame(mob_b)
    mob = mob[mob.pipeline == "mobgap Healthy"].assign(params="all subjects")
    b = parts(pd.concat([mob, pd.DataFrame(ours_b)], ignore_index=True))
    tracked = b[(b.pipeline == "mobgap Healthy") & (b.n_steps > 0)][["subject", "start_s"]]
    k = b.merge(tracked, on=["subject", "start_s"])
    cols = ["pipeline", "params", "subject", "start_s", "n_steps", "n_reference_steps", "error_strides_pct",
            "count_err_pct", "step_err_pct"]
    print("per bout (Test11, the bouts mobgap Healthy tracks):")
    print(k[cols].round(2).to_string(index=False))
    print("\nmedians over those bouts:")
    for (p, q), g in k.groupby(["pipeline", "params"], sort=False):
        print(f"{p} ({q}): {len(g)} bouts, |err vs strides| {g.error_strides_pct.abs().median():.2f} %, "
              f"|count part| {g.count_err_pct.abs().median():.2f} % (signed {g.count_err_pct.median():+.2f} %), "
              f"|per-step part| {g.step_err_pct.abs().median():.2f} % (signed {g.step_err_pct.median():+.2f} %)")


if __name__ == "__main__":
    main()
