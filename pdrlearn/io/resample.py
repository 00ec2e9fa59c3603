"""A recorded session at another rate than a model's, for ``pdrlearn track --model`` and ``pdrlearn evaluate``
(decision B113 in docs/decisions/bad-input.md): tracked at its own rate with decision C18's warning (the
default, as ``pdrlearn run``, E22 amended), resampled to the model's rate (``--resample``) or refused
(``--no-resample``).

The resampling is the runtime's (:class:`pdrlearn.runtime.resample.StreamResampler`, decision E22): each
stream is pushed in one piece and flushed. Offline has the whole recording, but the same causal resampler is
used rather than an offline equivalent (``scipy.signal.resample_poly`` ...): its FIR delay is taken out of the
timestamps, so it has no phase shift, and one push gives, bit for bit, what ``pdrlearn run --resample`` feeds
the kernels in any chunking (E22's chunk invariance): the offline and the streamed tracks of a resampled
session see the same samples. Its edges (the first and last sample repeated over half the filter) and its
gaps (> 1 s, not bridged) are the runtime's too.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Mapping

import numpy as np

from pdrlearn.errors import DataError
from pdrlearn.io.session import Session, Stream

log = logging.getLogger(__name__)

#: the three choices, as ``Tracker(resample=...)``: the data's own rate (warned), resampled, refused
RESAMPLE_MODES = ("native", True, False)


def resample_mode(resample: bool, no_resample: bool) -> bool | str:
    """``--resample`` / ``--no-resample`` as :data:`RESAMPLE_MODES`; both together is a one-line error (as
    ``pdrlearn run``'s, E22 amended)."""
    if resample and no_resample:
        raise DataError("--resample and --no-resample contradict each other; give one of them (default: the "
                        "session is used at its own rate, with a warning when it is not the model's)")
    return True if resample else False if no_resample else "native"


def model_rates(model) -> dict[str, float]:
    """Sensor -> the rate (Hz) the model's training sessions had (``manifest.json`` ``sampling_rate_hz``);
    empty for oracle labels or a model without rates."""
    rates = getattr(model, "sampling_rate_hz", None) or {}
    return {n: float(r) for n, r in rates.items() if r and math.isfinite(float(r)) and float(r) > 0}


def off_rates(session: Session, rates: Mapping[str, float]) -> dict[str, tuple[float, float]]:
    """Sensor -> (session Hz, model Hz) for the streams of ``session`` whose rate differs from ``rates`` by more
    than the calibration's tolerance (decisions E14, C18: ``rate_differs``)."""
    from pdrlearn.kernels.distance import rate_differs

    out = {}
    for name, st in session.streams.items():
        if name in rates and len(st) > 1:
            fs = float(st.rate_hz)
            if math.isfinite(fs) and rate_differs(rates[name], fs):
                out[name] = (fs, rates[name])
    return out


def resample_stream(stream: Stream, rate_hz: float) -> Stream:
    """``stream`` on the grid ``k / rate_hz`` (s) by the runtime's causal resampler (decision E22): one push of
    the whole stream, then its flush."""
    from pdrlearn.runtime.resample import StreamResampler

    r = StreamResampler(stream.rate_hz, rate_hz)
    t1, v1 = r.push(stream.t, stream.values)
    t2, v2 = r.flush()
    return Stream(stream.name, np.concatenate([t1, t2]), np.concatenate([v1, v2]))


def resample_session(session: Session, rates: Mapping[str, float]) -> Session:
    """A copy of ``session`` whose streams named in ``rates`` (sensor -> Hz) are resampled to those rates (the
    others as they are). ``meta["resampled"]`` records sensor -> ``{"from_hz", "to_hz"}`` (the distance
    calibration is still judged at the recorded rate, E22); :meth:`Session.content_id` stays the
    recording's (decision B87: ``evaluate`` still knows a training session)."""
    streams = {n: resample_stream(s, rates[n]) if n in rates else s for n, s in session.streams.items()}
    done = {n: {"from_hz": float(session.streams[n].rate_hz), "to_hz": float(rates[n])}
            for n in rates if n in session.streams}
    out = Session(name=session.name, streams=streams, steps=session.steps, trajectory=session.trajectory,
                  extras=session.extras, meta={**session.meta, "resampled": done}, frames=session.frames,
                  folder=session.folder, infer_frames=session.infer_frames, check_units=session.check_units)
    out._t_start_uncut = session._t_start_uncut
    out._source_id = session.content_id()
    return out


def recorded_rate(session: Session, name: str) -> tuple[float, float | None]:
    """The rate (Hz) ``name`` was recorded at and the rate it was resampled to (None: not resampled)."""
    rec = (session.meta.get("resampled") or {}).get(name)
    if isinstance(rec, dict):
        return float(rec["from_hz"]), float(rec["to_hz"])
    return float(session.streams[name].rate_hz), None


def at_model_rate(session: Session, model, mode: bool | str, *, command: str) -> Session:
    """Decision B113: the session as ``command`` (``track``, ``evaluate``) uses it with ``model``: unchanged at
    the model's rate or with ``mode="native"`` (decision C18's warning, from the tracker / evaluation, names
    ``--resample``); resampled to the model's rates with ``mode=True`` (one warning line); with ``mode=False`` a
    stream at another rate is a one-line :class:`DataError` naming the rates and the fixes."""
    if mode not in RESAMPLE_MODES:
        raise ValueError(f"mode must be one of {RESAMPLE_MODES}, not {mode!r}")
    rates = model_rates(model)
    if mode != "native" and not rates:
        flag = "--resample" if mode is True else "--no-resample"
        raise DataError(f"{command}: {flag} compares the session's rate with the model's, but "
                        + ("--model oracle has no rate" if isinstance(model, str) else
                           "the model's manifest.json records no sampling_rate_hz (trained before it was stored)")
                        + f"; drop {flag}")
    off = off_rates(session, rates)
    if not off or mode == "native":
        return session
    what = ", ".join(f"{n} {fs:.4g} Hz" for n, (fs, _) in off.items())
    to = sorted({r for _, r in off.values()})
    model_hz = " / ".join(f"{r:g}" for r in to)
    if mode is False:
        raise DataError(f"{session.where}: {what}: not the model's {model_hz} Hz (--no-resample); record at "
                        f"{model_hz} Hz or train a model at this rate (`pdrlearn train`), or pass --resample to "
                        "resample the session to the model's rate, or leave both out to use it at its own rate "
                        "with a warning (decision B113)")
    from pdrlearn.runtime.resample import StreamResampler, resampled_text

    out = resample_session(session, {n: r for n, (_, r) in off.items()})
    done = {n: StreamResampler(fs, r) for n, (fs, r) in off.items()}
    log.warning("%s: %s: resampled to the model's %s Hz before %s (--resample, decision B113: the runtime's "
                "resampler, E22); the distance calibration is still judged at the recorded rate", session.where,
                resampled_text(done, latency=False), model_hz, "tracking" if command == "track" else "scoring")
    return out
