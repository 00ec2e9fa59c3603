"""Decision E311: ``pdrlearn run BUNDLE SESSION --gait OTHER_FOOT``: ``gait``'s tables of the two feet's streamed
strides. Each foot session is replayed through the runtime :class:`~pdrlearn.runtime.tracker.Tracker` foot-only
with contacts on (decisions E26, E49), each stride gets L73's toe-off by the kernel the offline track uses
(:func:`pdrlearn.track.toeoff.toe_off_times`), and :func:`pdrlearn.track.bilateral.pair_sessions` does the rest, as
for ``pdrlearn gait`` (its checks, :func:`~pdrlearn.track.bilateral.bilateral_gait`, the same files)."""

from __future__ import annotations

import logging
import math
from contextlib import contextmanager
from pathlib import Path

#: decision E311: the force files whose streaming makes the runtime's contact the force onset (E49)
FORCE_FILES = ("fForceA", "fForceB")


def streamed_foot_track(bundle, *, chunk_s: float = 1.0, **tracker_options):
    """Decision E311: a ``track_foot(session, ignore_force)`` for :func:`pdrlearn.track.bilateral.pair_sessions`
    that replays the session's foot unit through a foot-only, contacts-on ``Tracker`` of ``bundle``
    (``tracker_options``: run's classification options, e.g. ``rules``, ``methods``) in ``chunk_s`` pushes and gives
    the streamed steps as ``run`` writes them (:func:`pdrlearn.cli.export.streamed_result`) plus each stride's toe-off
    ``tc_s`` (L73's gyroscope kernel, as offline). ``ignore_force``: the force files are not streamed (the contact is
    the accelerometer impact, steps decision 72's one detector)."""

    def track(session, ignore_force: bool):
        from pdrlearn.cli.export import frames_of, streamed_result
        from pdrlearn.orient.filters import unit_data
        from pdrlearn.runtime.replay import replay_chunks
        from pdrlearn.runtime.tracker import Tracker
        from pdrlearn.track.gait import streamed_gait_columns
        from pdrlearn.track.gait_contacts import FORCE_STANCE
        from pdrlearn.track.toeoff import toe_off_times

        streams = {n: st for n, st in session.streams.items()
                   if n.startswith("f") and len(st) and not (ignore_force and n in FORCE_FILES)}
        rates = {n: st.rate_hz for n, st in streams.items()}
        bundle.check_streams({n: math.nan for n in rates}, where=f"session '{session.name}'", units=("foot",))
        tracker = Tracker(bundle, frames=frames_of(session, bundle, ("foot",)), clock_check=False,
                          stream_checks=False, input_rates_hz=rates, units=("foot",), sensors=list(streams),
                          start=(0.0, 0.0, 0.0), contacts=True,  # decision E49: each stride's initial contact
                          stream_ends_s={n: float(st.t[-1]) for n, st in streams.items()},
                          max_gap_s=math.inf,  # B141: a recording's gaps are its own, as run's replay
                          **tracker_options)
        steps = []
        for chunk in replay_chunks({n: (st.t, st.values) for n, st in streams.items()}, chunk_s):
            steps += tracker.push(chunk)
        steps += tracker.flush()
        result = streamed_result(steps)
        table = result.steps
        if len(table):  # decision L73, as offline --toe-off: the toe-off and the stance / swing columns
            foot = unit_data(session, "foot", purpose="the toe-off (decision L73)")
            result.steps = streamed_gait_columns(table, tc_s=toe_off_times(
                foot.t, foot.gyr, *(table[c].to_numpy(float) for c in ("start_s", "end_s", "event_s"))))
        # steps decision 72: the detector that timed the contacts (E49: the force onset when both insoles stream)
        result.info["stance_source"] = FORCE_STANCE if all(n in streams for n in FORCE_FILES) else "inertial"
        return result

    return track


def gait_pair(session_dir: Path, other_dir: Path) -> tuple[Path, Path, tuple]:
    """Decision E311: ``(left, right, read)`` of ``session_dir`` and the other foot's ``other_dir``: the sides from
    meta.json's foot (B321's check), ``session_dir`` the left with none recorded (``gait``'s side warning says so);
    ``read``: :func:`pdrlearn.track.bilateral.read_pair`'s sessions, read as ``run`` reads them and checked (one line
    each: the same recording twice, no foot unit, not one walk on one clock), before any replay."""
    from pdrlearn.runtime.replay import read_meta
    from pdrlearn.track.bilateral import read_pair, session_foot

    feet = [session_foot(read_meta(Path(d))) for d in (session_dir, other_dir)]
    left, right = (other_dir, session_dir) if feet[0] == "right" or feet[1] == "left" else (session_dir, other_dir)
    return left, right, read_pair(left, right, streamed=True)


@contextmanager
def said_once(said: list[str]):
    """Decision E311: inside the body, a WARNING of a ``pdrlearn`` logger whose message ``said`` holds (run's own
    replay said it: the bundle's rate line, ...) or that the body said already (each foot's replay says the bundle's
    lines again) is not logged; every other record passes."""
    seen: set[str] = set()

    def once(record: logging.LogRecord) -> bool:
        if record.levelno < logging.WARNING:
            return True
        msg = record.getMessage()
        if msg in seen or any(line.startswith(msg) for line in said):
            return False
        seen.add(msg)
        return True

    loggers = [logging.getLogger(n) for n in list(logging.Logger.manager.loggerDict)
               if n == "pdrlearn" or n.startswith("pdrlearn.")]
    for lg in loggers:
        lg.addFilter(once)
    try:
        yield
    finally:
        for lg in loggers:
            lg.removeFilter(once)


def run_gait(bundle, pair: tuple[Path, Path, tuple], *, chunk_s: float, said: list[str] = (),
             **tracker_options) -> dict:
    """Decision E311: ``gait``'s result (:func:`pdrlearn.track.bilateral.pair_sessions`) of :func:`gait_pair`'s
    ``pair``, both feet replayed by :func:`streamed_foot_track`; a warning ``said`` already (run's) or by the other
    foot's replay is not repeated (:func:`said_once`)."""
    from pdrlearn.track.bilateral import pair_sessions

    left, right, read = pair
    with said_once(list(said)):
        return pair_sessions(left, right, read=read, track_foot=streamed_foot_track(bundle, chunk_s=chunk_s,
                                                                                     **tracker_options))
