"""Decision B133's measurement: the foot's rest |acc| warning (:func:`rest_scale_warning`, the candidate; not
adopted) on fresh simulated users 580-599 (scenario D, 100 Hz) unscaled and with the foot accelerometer x1.03
and x0.97, and on the real gaitmap foot recordings. Run: ``PYTHONPATH=. python
experiments/foot_rest_scale_b133.py``; writes experiments/results/foot_rest_scale_b133.md."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from pdrlearn.io import read_session
from pdrlearn.sim import simulate
from pdrlearn.track.foot_rest import foot_rest_stats

#: decision B133 (rule): the candidate's largest |rest |acc| / g - 1| before a warning
REST_SCALE_TOL = 0.02
USERS = range(580, 600)
SCALES = (1.0, 1.03, 0.97)
REAL = sorted({*Path("datasets/external").glob("gaitmap_*"), *Path("/work/shared/data").glob("gaitmap_*")})


def scaled(session, k: float):
    """The session with its foot accelerometer multiplied by ``k``."""
    st = session.streams["fAccelerometer"]
    st.values = np.asarray(st.values, dtype=float) * k
    return session


def rest_scale_warning(stats: dict | None, where: str) -> str | None:
    """Decision B133's candidate: one line when the foot's rest |acc| is more than :data:`REST_SCALE_TOL` off 1 g."""
    g = (stats or {}).get("rest_acc_g")
    if g is None or abs(g - 1.0) <= REST_SCALE_TOL:
        return None
    return (f"{where}: the foot accelerometer reads {g:.3f} g at its foot-flat rests (gravity alone: 1 g; more "
            f"than {100 * REST_SCALE_TOL:.0f} % off): its scale looks {100 * abs(g - 1):.1f} % too "
            f"{'large' if g > 1 else 'small'}, which changes the distance about as much; recalibrate the sensor's "
            f"scale, or divide fAccelerometer.csv by {g:.3f} (decision B133)")


def main() -> None:
    rows, warned = [], {k: 0 for k in SCALES}
    for u in USERS:
        for k in SCALES:
            stats = foot_rest_stats(scaled(simulate("D", user_seed=u, rate_hz=100.0), k))
            w = rest_scale_warning(stats, f"u{u}")
            warned[k] += w is not None
            rows.append(f"| sim u{u} | x{k:g} | {stats['rest_acc_g']:.4f} | {'yes' if w else 'no'} |")
    real_warned = 0
    for d in REAL:
        stats = foot_rest_stats(read_session(d))
        w = rest_scale_warning(stats, d.name)
        real_warned += w is not None
        rows.append(f"| real {d} | x1 | {stats['rest_acc_g']:.4f} | {'yes' if w else 'no'} |")
    n = len(USERS)
    head = [f"sim unscaled warned {warned[1.0]}/{n}; x1.03 {warned[1.03]}/{n}; x0.97 {warned[0.97]}/{n}; "
            f"real warned {real_warned}/{len(REAL)}", "", "| session | scale | rest acc g | warned |",
            "|---|---|---|---|"]
    text = "\n".join(head + rows) + "\n"
    print(text)
    Path("experiments/results/foot_rest_scale_b133.md").write_text(text)


if __name__ == "__main__":
    main()
