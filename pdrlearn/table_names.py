"""The names of the tables in the data dictionary (:data:`pdrlearn.columns.TABLES`'s keys, in its order), in a module
that imports nothing, so that the help of the columns command lists them without loading numpy (decisions C14, E152)."""

from __future__ import annotations

#: :data:`pdrlearn.columns.TABLES`'s keys in the order shown (built from this tuple: a table added there is added
#: here)
TABLE_NAMES: tuple[str, ...] = ("sessions.csv", "groups.csv", "subjects.csv",
                                "changes.csv",  # C81
                                "changes_summary.csv",  # C85
                                "subjects_pooled.csv", "groups_pooled.csv",  # C257, C258
                                "bouts.csv",
                                "strides.csv",  # E163
                                "turns.csv", "periods.csv",
                                "segments.csv",  # L619
                                "laps.csv",  # L383
                                "splits.csv",  # L411
                                "direction_changes.csv",  # L412
                                "transfers.csv", "tug_phases.csv",  # W293
                                "tug_trials.csv",  # W325
                                "ten_m_walk_trials.csv",  # L524
                                "freezes.csv",
                                "flights.csv",  # W417
                                "ramps.csv",  # L301
                                "ramp_runs.csv",  # L568
                                "stairs.csv",  # L432
                                "curbs.csv",  # L573
                                "rides.csv",  # L377
                                "wb_scores.csv",  # W493
                                "steps.csv", "steps.csv (foot)",  # E137
                                "trajectory.csv",  # B309
                                "at_times.csv",  # L638
                                "gait_steps.csv", "gait_cycles.csv", "gait_bouts.csv",  # L287
                                "gait_pairs.csv",  # C110
                                "gait_changes.csv", "gait_changes_summary.csv",  # cohort C242
                                "detections.csv", "events.csv", "steps.json",  # steps 59
                                "cohort_summary.csv",  # cohort C106
                                "cohort_methods.csv", "cohort_methods_summary.csv",  # cohort C92
                                "cv.csv", "louo.csv")  # classifiers C143
