"""Decision C249: each recording is scored only for its own test. A visit's T25FW recording, its 6MWT recording and its
TUG each used to score every test the tool can find in a walk - a T25FW's two 10 m walks read as a 60 m "6MWT", a
6MWT's first 7.62 m as a T25FW - and C83's visit mean mixed them (trial s51t2 F1). Beside corridor.py's
:func:`pdrlearn.track.corridor.too_short_note` (a recording holding under half of a timed test's duration scores no
corridor walk test), :func:`own_test` reconciles a track's summary once the corridor test is scored."""

from __future__ import annotations

#: decision C249: the summary keys a scored corridor walk test adds (cleared on a TUG's recording)
CORRIDOR_SCORE_KEYS = ("n_laps", "walk_test_distance_m", "walk_test_distance_per_minute_m", "fatigue_index",
                       "walk_test_stopped_s", "walk_test_n_rests", "walk_test_rest_time_s", "walk_test_rests",
                       "walk_test_scale", "gait_speed_corridor_mps")


def clear_walkway_tests(out: dict, note: str, trials: bool = False) -> None:
    """In place: the walkway tests of a summary - the 10 m walk (L312) and the T25FW (L387), their time and speed -
    empty, each note ``note`` (decisions L445, C249); with ``trials`` also the 10 m walk's trial keys (L524) and
    the T25FW's (C251). Only the tests the summary has keys of."""
    from pdrlearn.track.walk_test import KEYS, T25FW_KEYS

    for time_key, speed_key, note_key in (KEYS, T25FW_KEYS):
        if note_key not in out and time_key not in out:
            continue
        out[time_key] = out[speed_key] = None
        out[note_key] = note
    if trials:
        for key, empty in (("n_ten_m_walk_trials", 0), ("ten_m_walk_max_speed_mps", None), ("n_t25fw_trials", 0),
                           ("t25fw_trial_times_s", [])):
            if key in out:
                out[key] = empty


def own_test(summary: dict, laps=None):
    """Decision C249, in place: ``summary`` (a track's, its corridor keys scored) reduced to its recording's own test,
    and ``laps`` as kept (None or emptied). (b) A recording where a TUG is timed (``tug_time_s``) scores no corridor
    walk test: :data:`CORRIDOR_SCORE_KEYS` empty, ``walk_test_note`` says why. (c) A recording scored as a timed
    corridor walk test (``walk_test_protocol_s`` and a distance) times no T25FW and no 10 m walk
    (:func:`clear_walkway_tests`; :func:`is_walk_test_recording`: ten_m_walk_trials.csv is not written). Returns
    ``(laps, lines)``: the warning lines (coded C249)."""
    from pdrlearn.track.corridor import walk_test_label
    from pdrlearn.warning_lines import coded

    if summary.get("walk_test_distance_m") is None:
        return laps, []
    label = walk_test_label(summary.get("walk_test_protocol_s"))
    if summary.get("tug_time_s") is not None:  # (b) a TUG's 3 m out and back is no corridor test
        for key in CORRIDOR_SCORE_KEYS:
            if key in summary:
                summary[key] = None
        summary["walk_test_note"] = (f"a TUG was timed in this recording ({summary['tug_time_s']:.1f} s): a TUG's "
                                     f"recording is no {label}; no walk test scored (decision C249)")
        return (laps.iloc[0:0] if laps is not None else None), [coded(f"corridor walk test: "
                                                                      f"{summary['walk_test_note']}", "C249")]
    if not is_walk_test_recording(summary):  # without a duration the recording's test is not known
        return laps, []
    timed = [k for k in ("t25fw_time_s", "ten_m_walk_time_s") if summary.get(k) is not None]
    clear_walkway_tests(summary, f"the recording is the {label} (scored on the corridor): its first metres are no "
                        "T25FW and its passes no 10 m walk; not timed (decision C249)", trials=True)
    if not timed:
        return laps, []
    return laps, [coded(f"{label} recording: {' and '.join(k.split('_time_s')[0] for k in timed)} not timed, the "
                        "recording is scored as the corridor walk test only (decision C249)", "C249")]


def is_walk_test_recording(summary: dict) -> bool:
    """Decision C249: whether a track's summary is scored as a timed corridor walk test (a duration asked and a
    distance scored): its recording times no walkway test."""
    return summary.get("walk_test_protocol_s") is not None and summary.get("walk_test_distance_m") is not None
