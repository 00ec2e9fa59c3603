"""Trunk posture of the lower-back unit: a contact made while the trunk is far from its walking upright is no step.

Decision W102 (docs/decisions/waist.md): rising from a chair or bending forward bounces the lower back like a step
and passes the motion gate (W4 / W76) and the IC rules; the trunk's tilt tells them apart. Not from the seeds: the
lower trunk leans about 10-20 deg from upright while walking, and 40 deg and more when rising from a chair or
bending (general gait physiology); :data:`MAX_TILT_DEG` is twice the walking range's upper end, chosen before
measuring.

Decision W104: :func:`transfer_veto` drops the contacts around a sit-to-stand (or bend) *event*, a run of samples whose
tilt from the walking upright exceeds :data:`TRANSFER_PEAK_DEG`: a brief transfer stays under W102's threshold in a
+-0.5 s mean but not at its peak.

Decision W109: ``keep_rhythm`` spares the contacts in that window that alternate left/right with a neighbour of their
walking sequence (W20's sides): a transfer or a bend is sagittal and shifts no weight sideways, a step does.

Decision W180: ``keep_between`` also spares an undecided contact (no W20 side) between two contacts of its walking
sequence on the same decided side: in ... L ? L ... the undecided one is the right foot of an alternating sequence.
Decision W184: ``keep_between="opposite"`` spares instead an undecided contact between two contacts of its sequence on
opposite decided sides (... L ? R ...: an extra contact inside a left/right pair; the veto cannot tell which of the
three is the step).

Decision W119: :func:`vault_veto` drops a contact whose step does not vault the pelvis (a weight shift while standing:
a pendulum step raises the pelvis, h ~ s^2 / (8 L), seed 003 eq. 1); not the trunk's posture, but the same
mechanism of dropping contacts. Decision W127: with ``spare_turns`` it keeps a contact whose step turns the pelvis
(a turn on the spot vaults little, like a weight shift).

Decision W189: :func:`stand_veto` drops a whole walking run whose median vertical bounce is under a third of the
recording's median contact bounce (standing sway chains contacts with the bounce of none of the wearer's steps).
Decision W191: with ``spare_turns`` a weak run holding a step that turns the pelvis (W127's test) is kept.
Decision W196: with ``spare_alternation`` a weak run whose decided sides (W20) alternate left/right is kept.
Decision W198: with ``spare_adjacent`` a weak run with walking strides within Mobilise-D's 3 s bout break before and
after it (inside one walking bout) is kept.
Decision W218: with ``walking_reference`` the reference is the bounce of the walking stretches (decided alternating
sides at a regular rhythm), which are never dropped.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.waist import _kernels as K
from pdrlearn.waist.ahrs import WaistIMU
from pdrlearn.waist.gait_rules import MAX_BREAK_S, MIN_BOUT_STRIDES, positional_strides
from pdrlearn.waist.plausibility import contact_lateral_velocity
from pdrlearn.waist.steplength import pendulum_h

#: A contact whose trunk direction is further than this from the session's walking upright is no step (deg; W102).
MAX_TILT_DEG = 40.0
#: Half-width of the window around a contact over which its trunk direction is averaged (s; one step, W102).
TILT_HALF_WINDOW_S = 0.5
#: A sample tilted more than this from the walking upright is part of a trunk-flexion event (deg; W104): above the
#: walking pelvis's few degrees, below the 30-45 deg of a chair transfer (simulator S36's ranges). Not from a seed.
TRANSFER_PEAK_DEG = 25.0
#: Contacts within this of a flexion event's peak are dropped (s; W104): half a 2 s sit-to-stand movement.
TRANSFER_HALF_S = 1.0


def window_directions(t: np.ndarray, up_body: np.ndarray, centre_s: np.ndarray, half_s: float) -> np.ndarray:
    """The AHRS's up direction in the body frame (``up_body``, one row per sample time ``t``) averaged over
    +-``half_s`` around each time of ``centre_s``, normalised (a pure kernel: W102's contact directions, W222's
    posture tilt). Decision W234: a non-finite up direction is left out of the windows (it would poison every later
    cumulative sum); a window with none finite gives a NaN direction."""
    # window means by cumulative sums: O(n) for any number of windows
    up = np.asarray(up_body, dtype=float)
    ok = np.isfinite(up).all(axis=1)
    csum = np.vstack([np.zeros((1, 3)), np.cumsum(np.where(ok[:, None], up, 0.0), axis=0)])
    cnt = np.r_[0, np.cumsum(ok)]
    lo = np.clip(np.searchsorted(t, centre_s - half_s), 0, len(t) - 1)
    hi = np.clip(np.searchsorted(t, centre_s + half_s, side="right"), lo + 1, len(t))
    n = (cnt[hi] - cnt[lo]).astype(float)
    with np.errstate(invalid="ignore", divide="ignore"):
        d = (csum[hi] - csum[lo]) / np.where(n > 0, n, np.nan)[:, None]
        return d / np.linalg.norm(d, axis=1, keepdims=True)


def contact_directions(t: np.ndarray, up_body: np.ndarray, event_s: np.ndarray) -> np.ndarray:
    """W102's direction of each contact: :func:`window_directions` over +-:data:`TILT_HALF_WINDOW_S` around it (a
    pure kernel, shared by the offline veto and W200's causal one)."""
    return window_directions(t, up_body, event_s, TILT_HALF_WINDOW_S)


def walking_upright(d: np.ndarray, walking: np.ndarray) -> np.ndarray:
    """W102's upright: the normalised median of the contact directions ``d`` over the ``walking`` contacts (all of
    them when none walks)."""
    walking = np.asarray(walking, dtype=bool)
    if not walking.any():
        walking = np.ones(len(d), dtype=bool)
    up = np.median(d[walking], axis=0)
    return up / np.linalg.norm(up)


def sample_tilt_deg(up_body: np.ndarray, upright: np.ndarray) -> np.ndarray:
    """Per sample: the angle (deg) between the AHRS's up direction ``up_body`` and ``upright`` (W104)."""
    u = up_body / np.linalg.norm(up_body, axis=1, keepdims=True)
    return np.degrees(np.arccos(np.clip(u @ upright, -1.0, 1.0)))


def flexion_runs(t: np.ndarray, tilt: np.ndarray) -> list[tuple[float, float, float]]:
    """W104's events: (start, peak, end) times (s) of each run of samples whose ``tilt`` exceeds
    :data:`TRANSFER_PEAK_DEG` (a run at an edge of ``t`` ends there)."""
    above = np.r_[False, np.asarray(tilt) > TRANSFER_PEAK_DEG, False]
    edges = np.flatnonzero(np.diff(above.astype(int)))
    return [(float(t[a]), float(t[a + int(np.argmax(tilt[a:b]))]), float(t[b - 1]))
            for a, b in zip(edges[::2], edges[1::2], strict=True)]


def near_flexion(event_s: np.ndarray, runs: list[tuple[float, float, float]]) -> np.ndarray:
    """W104's window test: per contact, inside a run of ``runs`` or within :data:`TRANSFER_HALF_S` of its peak."""
    e = np.asarray(event_s, dtype=float)
    veto = np.zeros(e.size, dtype=bool)
    for a, peak, b in runs:
        veto |= ((e >= a) & (e <= b)) | (np.abs(e - peak) <= TRANSFER_HALF_S)
    return veto


def spared(side: np.ndarray, has_next: np.ndarray, keep_rhythm: bool, keep_between: bool | str) -> np.ndarray:
    """Per contact: kept by the sit veto's sparing (W109's left/right pairs with ``keep_rhythm``; W180's undecided
    contact between same-side neighbours with ``keep_between``, W184's between opposite-side ones with
    ``keep_between="opposite"``), from W20's ``side`` and ``has_next``."""
    keep = np.zeros(len(side), dtype=bool)
    if keep_rhythm:
        keep |= alternating_pairs(side, has_next)
    if keep_between:
        keep |= undecided_between(side, has_next, opposite=keep_between == "opposite")
    return keep


def _contact_directions(imu: WaistIMU, event_s: np.ndarray, walking: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The AHRS's up direction in the body frame averaged over +-:data:`TILT_HALF_WINDOW_S` around each contact, and
    the session's upright: the normalised median of those directions over the ``walking`` contacts (W102)."""
    d = contact_directions(imu.t, imu.up_body, event_s)
    return d, walking_upright(d, walking)


def contact_tilt_deg(imu: WaistIMU, event_s: np.ndarray, walking: np.ndarray) -> np.ndarray:
    """Tilt (deg) of the trunk at each contact: the angle between the AHRS's up direction in the body frame
    (``imu.up_body``) averaged over +-:data:`TILT_HALF_WINDOW_S` around the contact, and the session's upright,
    the normalised median of those directions over the ``walking`` contacts (those that start a step). The
    upright is the session's own, so any mounting of the unit and a walker's constant stoop read 0 (W102)."""
    event_s = np.asarray(event_s, dtype=float)
    if imu.up_body is None or event_s.size == 0:
        return np.zeros(event_s.size)
    d, up = _contact_directions(imu, event_s, walking)
    return np.degrees(np.arccos(np.clip(d @ up, -1.0, 1.0)))


def flexion_events(imu: WaistIMU, event_s: np.ndarray, walking: np.ndarray, upright: np.ndarray | None = None
                   ) -> list[tuple[float, float, float]]:
    """Trunk-flexion events (W104): (start, peak, end) times (s) of each run of samples whose up direction is
    more than :data:`TRANSFER_PEAK_DEG` from the session's walking upright (:func:`contact_tilt_deg`'s), or from
    ``upright`` when given (decision W277: the still standing upright of a session without walking)."""
    event_s = np.asarray(event_s, dtype=float)
    if imu.up_body is None or (event_s.size == 0 and upright is None):
        return []
    up = upright if upright is not None else _contact_directions(imu, event_s, walking)[1]
    return flexion_runs(imu.t, sample_tilt_deg(imu.up_body, up))


def transfer_windows(imu: WaistIMU, event_s: np.ndarray, walking: np.ndarray, pad_s: float = 0.0,
                     upright: np.ndarray | None = None) -> list[tuple[float, float]]:
    """Decision W174: the time span (s) of each trunk-flexion event (:func:`flexion_events`): from
    :data:`TRANSFER_HALF_S` before its peak (or its start, if earlier) to :data:`TRANSFER_HALF_S` after it (or its
    end, if later), each edge widened by ``pad_s``: the sit-to-stand's (stand-to-sit's) movement, whose change of
    height is the transfer's, not a climb. ``upright``: W277's, as :func:`flexion_events` takes it."""
    return [(min(a, peak - TRANSFER_HALF_S) - pad_s, max(b, peak + TRANSFER_HALF_S) + pad_s)
            for a, peak, b in flexion_events(imu, event_s, walking, upright)]


def drop_contacts(steps: pd.DataFrame, keep: np.ndarray, count: str) -> pd.DataFrame:
    """``steps`` without the contacts not in ``keep``; a kept step whose next contact is dropped ends its walking
    sequence (``end_s`` = its start, no ``has_next``, confidence 0.5, as :func:`pdrlearn.kernels.waist.contact_rows`
    closes a sequence). ``attrs[count]`` counts the dropped."""
    has_next = steps["has_next"].to_numpy(bool)
    before_dropped = has_next & np.append(~keep[1:], False)  # the step that ended on a dropped contact
    out = steps.copy()
    out.loc[before_dropped, "end_s"] = out.loc[before_dropped, "start_s"]
    out.loc[before_dropped, "has_next"] = False
    if "confidence" in out:
        out.loc[before_dropped, "confidence"] = 0.5
    out = out[keep].reset_index(drop=True)
    out.attrs.update(steps.attrs)
    out.attrs[count] = int((~keep).sum())
    return out


def alternating_pairs(side: np.ndarray, has_next: np.ndarray) -> np.ndarray:
    """Per contact: True when it and a neighbour are consecutive contacts of one walking sequence (``has_next`` of
    the earlier) on decided, opposite sides (``side`` from :func:`pdrlearn.waist._kernels.step_sides`: +1 / -1,
    0 undecided) - a left/right step pair (decision W109)."""
    side = np.asarray(side, dtype=np.int8)
    pair = np.asarray(has_next, dtype=bool)[:-1] & (side[:-1].astype(int) * side[1:] == -1)
    return np.append(pair, False) | np.insert(pair, 0, False)


def undecided_between(side: np.ndarray, has_next: np.ndarray, *, opposite: bool = False) -> np.ndarray:
    """Per contact: True when its side is undecided (0) and its two neighbours are consecutive contacts of its
    walking sequence (``has_next`` of the one before and of itself) on the same decided side: in ... L ? L ... the
    undecided contact is the other foot of an alternating sequence (decision W180). With ``opposite`` the two
    neighbours are on opposite decided sides instead: in ... L ? R ... it is an extra contact inside a left/right
    pair (decision W184)."""
    side = np.asarray(side, dtype=int)
    hn = np.asarray(has_next, dtype=bool)
    out = np.zeros(side.size, dtype=bool)
    if side.size >= 3:
        product = side[:-2] * side[2:]  # +1 same decided side, -1 opposite decided sides, 0 one undecided
        out[1:-1] = (side[1:-1] == 0) & hn[:-2] & hn[1:-1] & (product == (-1 if opposite else 1))
    return out


def sit_veto_keywords(mode) -> dict:
    """:func:`transfer_veto`'s keywords for a value of the lower-back option ``sit_veto`` (decisions W104, W109,
    W180, W184, W185): ``keep_rhythm`` for ``"rhythm"`` / ``"alternation"`` / ``"opposite"``, ``keep_between``
    True for ``"alternation"`` and ``"opposite"`` for ``"opposite"``. Shared by `track` and `steps`' note (W297)."""
    return {"keep_rhythm": mode in ("rhythm", "alternation", "opposite"),
            "keep_between": {"alternation": True, "opposite": "opposite"}.get(mode, False)}


def transfer_veto(steps: pd.DataFrame, imu: WaistIMU, *, keep_rhythm: bool = False,
                  keep_between: bool | str = False, upright: np.ndarray | None = None) -> pd.DataFrame:
    """``steps`` without the contacts inside a trunk-flexion event (:func:`flexion_events`) or within
    :data:`TRANSFER_HALF_S` of its peak (decision W104); with ``keep_rhythm`` (decision W109) the contacts of
    that window that form a left/right pair with a neighbour (:func:`alternating_pairs`, W20's sides of the pelvis's
    lateral velocity at the contacts) are kept; with ``keep_between`` as well (decision W180) so are the undecided
    contacts between two same-side neighbours of their sequence (:func:`undecided_between`); with
    ``keep_between="opposite"`` (decision W184) those between two opposite-side neighbours instead.
    ``upright``: W277's, as :func:`flexion_events` takes it. ``attrs["n_vetoed"]`` counts the dropped."""
    if steps.empty:
        out = steps.copy()
        out.attrs["n_vetoed"] = 0
        return out
    e = steps["event_s"].to_numpy(float)
    has_next = steps["has_next"].to_numpy(bool)
    veto = near_flexion(e, flexion_events(imu, e, has_next, upright))
    if (keep_rhythm or keep_between) and veto.any():
        side = K.step_sides(contact_lateral_velocity(imu.t, imu.acc_ml, imu.fs, e), has_next)
        veto &= ~spared(side, has_next, keep_rhythm, keep_between)
    return drop_contacts(steps, ~veto, "n_vetoed")


def sit_veto_hint(n_flexed: int, *, realtime: bool = False) -> list[str]:
    """Decision W146: one line when ``n_flexed`` contacts (those :func:`transfer_veto` would drop) lie at a
    trunk-flexion event while the veto is off (a chair rise reads as a 0 m step and splits a TUG into bouts with
    its seated time as pauses, W145); none without such contacts. Decision E126: the option it names is W185's
    offline default ``"opposite"``: an offline track has it unless ``sit_veto`` is false, so the line says to turn
    it back on; a ``realtime`` track applies a veto only when one is set (W185)."""
    if not n_flexed:
        return []
    fix = ("to drop them put \"options\": {\"sit_veto\": \"opposite\"} in the --params JSON (a realtime track "
           "applies no sit veto unless one is set)" if realtime else
           "to drop them turn the default sit veto back on: remove \"sit_veto\": false from the --params JSON's "
           "\"options\" (or put \"sit_veto\": \"opposite\" there)")
    return [f"{n_flexed} contact(s) lie at a trunk flexion over {TRANSFER_PEAK_DEG:g} deg (a sit-to-stand or a bend): "
            "a chair rise reads as a 0 m step and splits the walk into bouts with the seated time as pauses (a TUG); "
            f"{fix} (decisions W104, W146, W185)"]


def tilt_gate(steps: pd.DataFrame, imu: WaistIMU, max_tilt_deg: float = MAX_TILT_DEG) -> pd.DataFrame:
    """``steps`` (one row per contact, :func:`pdrlearn.waist.events.steps_from_events`' columns) without the
    contacts whose trunk tilt (:func:`contact_tilt_deg`) exceeds ``max_tilt_deg``; a kept step whose next contact
    is dropped ends its walking sequence (``end_s`` = its start, no ``has_next``, confidence 0.5, as
    :func:`pdrlearn.kernels.waist.contact_rows` closes a sequence). ``attrs["n_tilted"]`` counts the dropped."""
    if steps.empty:
        out = steps.copy()
        out.attrs["n_tilted"] = 0
        return out
    tilt = contact_tilt_deg(imu, steps["event_s"].to_numpy(float), steps["has_next"].to_numpy(bool))
    return drop_contacts(steps, tilt <= max_tilt_deg, "n_tilted")


def vault_veto(steps: pd.DataFrame, imu: WaistIMU, *, spare_turns: bool = False,
               gyro_bias_rps: float = 0.0) -> pd.DataFrame:
    """``steps`` without the contacts whose step (IC to next IC, :func:`~pdrlearn.waist.steplength.pendulum_h`, W10)
    vaults the pelvis by less than a quarter of its neighbours' (:func:`pdrlearn.kernels.waist.low_vault_mask`:
    under half their step length by the pendulum relation; decision W119). W27's fragments and their owners are not
    judged and not neighbours (their vault is a split step's); sequence-closing contacts are not judged. The step
    before a dropped contact ends its sequence (:func:`drop_contacts`). ``attrs["n_unvaulted"]`` counts the
    dropped.

    ``spare_turns`` (decision W127): a contact whose step turns the pelvis by more than
    :data:`~pdrlearn.kernels.waist.TURN_STEP_DEG` (the vertical rate less ``gyro_bias_rps``, integrated from the IC
    to the next: :func:`~pdrlearn.kernels.waist.turning_step_mask`) is kept: a turn on the spot vaults little."""
    if steps.empty:
        out = steps.copy()
        out.attrs["n_unvaulted"] = 0
        return out
    fs = imu.fs
    has_next = steps["has_next"].to_numpy(bool)
    start, end = steps["start_s"].to_numpy(float), steps["end_s"].to_numpy(float)
    split = np.zeros(len(steps), dtype=bool)
    for a, b in K.fragment_windows(start, end, has_next).values():
        split[a:b + 1] = True
    ev = steps["event_s"].to_numpy(float)
    idx = np.clip(np.round((ev - imu.t[0]) * fs).astype(int), 0, len(imu.t) - 1)
    fc = np.round((steps["fc_s"].fillna(-1).to_numpy(float) - imu.t[0]) * fs).astype(int)
    use = has_next & ~split
    h = np.zeros(len(steps))
    for i in np.flatnonzero(use):
        h[i] = pendulum_h(imu.acc_v, fs, idx[i], fc[i], idx[i + 1])
    drop = K.low_vault_mask(h, use, ~has_next)
    if spare_turns and drop.any():  # W127: the pelvis's turn over the step, IC to the next IC
        drop &= ~turning_steps(steps, imu, gyro_bias_rps)
    return drop_contacts(steps, ~drop, "n_unvaulted")


def turning_steps(steps: pd.DataFrame, imu: WaistIMU, gyro_bias_rps: float = 0.0) -> np.ndarray:
    """Per contact: whether its step (IC to the next IC; a sequence-closing contact has none) turns the pelvis by
    more than :data:`~pdrlearn.kernels.waist.TURN_STEP_DEG` (the vertical rate less ``gyro_bias_rps``, integrated:
    :func:`~pdrlearn.kernels.waist.turning_step_mask`; decisions W127, W191)."""
    ev = steps["event_s"].to_numpy(float)
    has_next = steps["has_next"].to_numpy(bool)
    nxt = np.append(ev[1:], ev[-1])
    return K.turning_step_mask(np.where(has_next, K.integrate_rate(imu.t, imu.w_z - gyro_bias_rps, ev, nxt), 0.0))


def stand_veto(steps: pd.DataFrame, imu: WaistIMU, *, spare_turns: bool = False,
               gyro_bias_rps: float = 0.0, spare_alternation: bool = False,
               spare_adjacent: bool = False, walking_reference: bool = False) -> pd.DataFrame:
    """``steps`` without the walking runs (contacts chained by ``has_next``) whose median bounce
    (:func:`~pdrlearn.kernels.waist.contact_bounce`) is under :data:`~pdrlearn.kernels.waist.WEAK_RUN_FRAC` of the
    median bounce of all the contacts (:func:`~pdrlearn.kernels.waist.weak_run_mask`; decision W189).
    ``attrs["n_weak_run"]`` counts the dropped.

    ``spare_turns`` (decision W191): a weak run holding a step that turns the pelvis (:func:`turning_steps`, W127's
    15 deg, the vertical rate less ``gyro_bias_rps``) is kept whole: a slow turn on the spot bounces little, and
    standing does not turn the pelvis.

    ``spare_alternation`` (decision W196): a weak run whose decided sides (W20's :func:`~pdrlearn.kernels.waist.
    step_sides` of the pelvis's lateral velocity at the contacts, decided as the sit veto's, W109) alternate left /
    right, at least two of them decided (:func:`~pdrlearn.kernels.waist.alternating_run_mask`), is kept whole: real
    steps alternate sides, standing sway and weight shifts do not or stay undecided.

    ``spare_adjacent`` (decision W198): a weak run with a walking contact (of a run that is not weak and that starts
    or ends a stride, W47's :func:`~pdrlearn.waist.gait_rules.positional_strides`) at most
    :data:`~pdrlearn.waist.gait_rules.MAX_BREAK_S` (Mobilise-D's walking-bout break, 3 s) before its first contact
    AND one at most that after its last (:func:`~pdrlearn.kernels.waist.adjacent_run_mask`) is kept whole: it lies
    inside one walking bout (a slow turn on the spot between two walks), while standing sway lies away from walking
    on at least one side.

    ``walking_reference`` (decision W218): the runs are judged against the median bounce of the contacts of the
    *walking stretches* (:func:`~pdrlearn.kernels.waist.walking_stretch_mask`: at least Mobilise-D's 4 strides of
    contacts on decided, alternating sides at a regular rhythm; W189's median of all the contacts when there is none)
    instead of all the contacts', and the walk of a walking stretch is never dropped: the stretch and, out from it
    along its run, the contacts at most :data:`~pdrlearn.waist.gait_rules.MAX_BREAK_S` (Mobilise-D's bout break, 3 s)
    from it or with a bounce of their own at least a third of the reference (:func:`~pdrlearn.kernels.waist.
    walk_extent_mask`); the rest of the run is judged as before: a freeze's trembling chained to the walk before it
    (S51, W217) or a long standing recording cannot take the walk."""
    if steps.empty:
        out = steps.copy()
        out.attrs["n_weak_run"] = 0
        return out
    ev = steps["event_s"].to_numpy(float)
    idx = np.clip(np.round((ev - imu.t[0]) * imu.fs).astype(int), 0, len(imu.t) - 1)
    has_next = steps["has_next"].to_numpy(bool)
    spare = turning_steps(steps, imu, gyro_bias_rps) if spare_turns else None
    if spare_alternation:  # W196: the run's decided sides alternate
        spare = K.alternating_run_mask(K.step_sides(contact_lateral_velocity(imu.t, imu.acc_ml, imu.fs, ev),
                                                    has_next), has_next)
    bounce = K.contact_bounce(imu.acc_v, imu.fs, idx)
    judge = {}
    if walking_reference:  # W218: the walking stretches' bounce is the reference, and they are never dropped
        side = K.step_sides(contact_lateral_velocity(imu.t, imu.acc_ml, imu.fs, ev), has_next)
        stretch = K.walking_stretch_mask(side, has_next, ev, MIN_BOUT_STRIDES)  # Mobilise-D's 4 strides (W47)
        ref = K.walking_reference(bounce, stretch)
        strong = bounce >= K.WEAK_RUN_FRAC * ref
        judge = {"reference": ref, "keep": K.walk_extent_mask(ev, has_next, stretch, strong, MAX_BREAK_S)}
    if spare_adjacent:  # W198: walking strides (not weak, W189's test read once) within 3 s before and after
        a, b = positional_strides(has_next)
        in_stride = np.zeros(ev.size, dtype=bool)
        in_stride[a], in_stride[b] = True, True
        walking = in_stride & ~K.weak_run_mask(bounce, has_next, **judge)
        spare = K.adjacent_run_mask(ev, has_next, walking, MAX_BREAK_S)
    drop = K.weak_run_mask(bounce, has_next, spare=spare, **judge)
    return drop_contacts(steps, ~drop, "n_weak_run")
