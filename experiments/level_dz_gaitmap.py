"""gaitmap's own per-stride height change on the gaitmap foot recordings (decision L68), for comparison with
experiments/level_dz.py: BarthDtw + RamppEventDetection + StrideLevelTrajectory as experiments/peers.py, with
its ForwardBackwardIntegration's ``level_assumption`` off (on, its default, it forces every stride to end at the
height it started: dz = 0 by construction).

Usage (the peer tools' venv, ``make peers``)::

    PYTHONPATH=.:experiments .venv-peers/bin/python experiments/level_dz_gaitmap.py
"""

from __future__ import annotations

import logging
import warnings

import numpy as np
import pandas as pd

from level_dz import CHOOSE, LEVEL, STAIRS, folder  # experiments/ on the path (see Usage)
from pdrlearn.io import read_session


def main() -> None:
    from gaitmap.event_detection import RamppEventDetection
    from gaitmap.preprocessing import sensor_alignment
    from gaitmap.stride_segmentation import BarthDtw
    from gaitmap.trajectory_reconstruction import ForwardBackwardIntegration, StrideLevelTrajectory
    from gaitmap.utils.coordinate_conversion import convert_left_foot_to_fbf, convert_right_foot_to_fbf

    logging.disable(logging.WARNING)
    warnings.simplefilter("ignore")
    for name in CHOOSE + LEVEL + STAIRS:
        d = folder(name)
        if d is None:
            continue
        s = read_session(d)
        side = s.meta.get("foot") if s.meta.get("foot") in ("left", "right") else "left"
        acc, gyr = s["fAccelerometer"], s["fGyroscope"]
        fs = float(s.meta.get("rate_hz"))
        sf = pd.DataFrame(np.column_stack([acc.values, np.degrees(gyr.values)]),
                          columns=["acc_x", "acc_y", "acc_z", "gyr_x", "gyr_y", "gyr_z"])
        try:
            data = sensor_alignment.align_dataset_to_gravity(sf, fs)
        except ValueError:  # no static window (the MS recordings): as experiments/peers.py
            data = sf
        bf = (convert_left_foot_to_fbf if side == "left" else convert_right_foot_to_fbf)(data)
        dtw = BarthDtw().segment(data=bf, sampling_rate_hz=fs)
        ed = RamppEventDetection().detect(data=bf, stride_list=dtw.stride_list_, sampling_rate_hz=fs)
        mv = ed.min_vel_event_list_
        if len(mv) == 0:
            print(f"{name:26s} gaitmap found no strides")
            continue
        tr = StrideLevelTrajectory(pos_method=ForwardBackwardIntegration(level_assumption=False)).estimate(
            data=sf, stride_event_list=mv, sampling_rate_hz=fs)
        g = tr.position_.groupby(level=0)
        dz = (g["pos_z"].last() - g["pos_z"].first()).to_numpy()
        L = np.hypot(g["pos_x"].last() - g["pos_x"].first(), g["pos_y"].last() - g["pos_y"].first()).to_numpy()
        a = np.abs(dz)
        print(f"{name:26s} strides {len(dz):3d} distance {L.sum():7.2f} m altitude {dz.sum():+6.2f} m "
              f"median|dz| {np.median(a):.3f} p90 {np.percentile(a, 90):.3f} max {a.max():.3f} "
              f">=0.10: {int((a >= 0.10).sum())}")


if __name__ == "__main__":
    main()
