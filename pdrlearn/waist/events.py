"""Initial / final contact detection from waist acceleration (seed 003 sec. 3.1)."""

from __future__ import annotations

import logging

import numpy as np
import pandas as pd

from pdrlearn.signal import lowpass
from pdrlearn.waist import _kernels as K
from pdrlearn.waist.ahrs import WaistIMU

log = logging.getLogger(__name__)

#: Vertical-acceleration std (m/s^2, 2 s window) above which the user is taken to be walking.
#: Seed 000 sec. II-B uses 1.5 m/s^2 for brisk walks with a phone in the pocket/belt; slow daily-life
#: gait at the lower back stays well below that (docs/decisions/waist.md W4), so the default is lower.
WALK_THRESHOLD_MPS2 = 0.5
PAPER_WALK_THRESHOLD_MPS2 = 1.5  # seed 000 sec. II-B
#: decision W255: the ``fast_fill`` value that adds W242's contacts only outside the freeze index's episodes (W213)
FAST_FILL_OUTSIDE_FREEZE = "outside_freeze"


def causal_lowpass_delay_s(cutoff_hz: float, fs: float, *, at_hz: float = 1.0) -> float:
    """Group delay (s) at ``at_hz`` of the causal Butterworth of :func:`pdrlearn.signal.lowpass`."""
    from scipy import signal as sg

    from pdrlearn.signal import butter_sos

    b, a = sg.sos2tf(butter_sos(cutoff_hz, fs))
    _, gd = sg.group_delay((b, a), w=[at_hz], fs=fs)
    return float(gd[0]) / fs


def gate_threshold(imu: WaistIMU, walk_threshold: float | None = None, *, relative: bool = True
                   ) -> tuple[float, np.ndarray, str]:
    """The offline motion gate's threshold (m/s^2) of a whole recording, the centred 2 s SD of its vertical
    acceleration it is judged on, and where the threshold comes from ("params", "relative", "fixed"): the given
    ``walk_threshold``, else :data:`WALK_THRESHOLD_MPS2` lowered to the session-relative gate of decision W76
    (:func:`~pdrlearn.waist._kernels.relative_walk_threshold`) when ``relative``. One rule for ``pdrlearn track``'s
    lower-back pipelines and the ``waist-ic`` step detector (decision steps 35)."""
    sigma = K.rolling_std(imu.acc_v, imu.fs, causal=False)
    if walk_threshold is not None:
        return float(walk_threshold), sigma, "params"
    thr = K.relative_walk_threshold(sigma, WALK_THRESHOLD_MPS2) if relative else WALK_THRESHOLD_MPS2
    return float(thr), sigma, "relative" if thr != WALK_THRESHOLD_MPS2 else "fixed"


def gate_contacts(table: pd.DataFrame, source, *, walk_threshold: float | None = None,
                  relative: bool = True) -> pd.DataFrame:
    """Decision W473: the rows of a lower-back steps table (``event_s``, s on the session's clock) whose contact the
    lower-back pipelines' walking gate (W4) lets through: the variance of the gravity-removed vertical acceleration
    over the gate's 2 s window centred on it reaches the gate's threshold squared (the threshold of
    :func:`gate_threshold`: ``walk_threshold`` m/s^2, else 0.5 m/s^2 lowered by W76's session-relative rule when
    ``relative``). ``source`` is the session (or its :class:`~pdrlearn.waist.ahrs.WaistIMU`). The gate is
    :func:`pdrlearn.kernels.step_events.motion_gate_kernel`, the one the pelvic-gyro detector applies (steps decision
    23); ``track --detector NAME --gate`` applies it to a detector's contacts. Rows keep their order and columns."""
    from pdrlearn.kernels.step_events import GateState, motion_gate_flush, motion_gate_kernel
    from pdrlearn.kernels.waist import GATE_WINDOW_S
    from pdrlearn.waist.ahrs import waist_imu

    imu = source if isinstance(source, WaistIMU) else waist_imu(source)
    thr = gate_threshold(imu, walk_threshold, relative=relative)[0]
    ev = table["event_s"].to_numpy(float) if len(table) else np.zeros(0)
    order = np.argsort(ev, kind="stable")
    events = [(float(ev[i]), int(i)) for i in order]  # the kernel reads e[0]; the row rides along
    var_min = thr * thr  # W4: the SD threshold squared (as steps decision 23's gate_var)
    kept, state = motion_gate_kernel(imu.t, imu.acc_v, events, GateState(), GATE_WINDOW_S, var_min)
    kept += motion_gate_flush(state, GATE_WINDOW_S, var_min)
    out = table.iloc[np.sort([e[1] for e in kept]).astype(int)] if kept else table.iloc[:0]
    out.attrs = dict(table.attrs)
    return out


def walking_gate(imu: WaistIMU, *, walk_threshold: float = WALK_THRESHOLD_MPS2, causal: bool = False,
                 turn_gate_rps: float | None = None) -> np.ndarray:
    """Samples where the motion state (seed 000 sec. II-B) is walking or running; with ``turn_gate_rps``
    (decision 28 of docs/decisions/steps.md) also where the levelled vertical rate's mean over the same window
    reaches it in absolute value (the pelvis turns: a turn on the spot bounces too little for the std)."""
    return K.motion_gate(imu.acc_v, imu.w_z, imu.fs, walk_threshold=walk_threshold, causal=causal,
                         turn_gate_rps=turn_gate_rps)


def steps_from_events(t: np.ndarray, ic: np.ndarray, fc: np.ndarray | None = None, *,
                      max_step_s: float = 1.5, detector: str = "") -> pd.DataFrame:
    """Steps table from contact indices: one row per IC (``event_s``), ``start_s`` = the IC,
    ``end_s`` = the next IC when it follows within ``max_step_s`` (else ``end_s == start_s``: the contact
    closes a walking sequence and carries no displacement). ``fc_s`` holds the FC after each IC."""
    ic = np.asarray(ic, dtype=int)
    ts = t[ic] if ic.size else np.zeros(0)
    end, has_next, conf = K.contact_rows(ts, max_step_s)
    df = pd.DataFrame({"start_s": ts, "end_s": end, "event_s": ts, "unit": "waist", "confidence": conf})
    df["fc_s"] = t[np.asarray(fc, dtype=int)] if fc is not None and len(fc) == ic.size else np.nan
    df["has_next"] = has_next
    df.attrs["detector"] = detector
    return df


class InitialContactDetector:
    """Seed 003 IC/FC detector on the waist's vertical and antero-posterior accelerations.

    Parameters
    ----------
    realtime : ``False`` -> zero-lag FIR offline method; ``True`` -> causal: with ``delay_s`` (default)
        the offline method on the data up to each decision time (W31), else seed 003's causal variant
        (11th-order FIR on the AP acceleration, positive-to-negative zero crossings, lobe check).
    cutoff_hz : FIR cutoff (seed 003 sec. 3.1: 2.5 Hz)
    fir_order_s : offline FIR order in seconds of samples (seed 003: order 30; 0.3 s at 100 Hz)
    walk_threshold : motion-gate threshold on the std of vertical acceleration (m/s^2)
    ap_cutoff_hz : light low-pass of the AP acceleration before locating its maximum (Hz; capped at
        0.4 x rate)
    max_step_s : contacts further apart than this end a walking sequence (s)
    rhythm : offline (and realtime with ``delay_s``): complete each walking sequence at its local step
        period (gaps of weak turning/shuffling steps, sequence ends cut by the motion gate; decision W18)
    lobe_ratio : realtime with ``delay_s=None``: reject a zero crossing whose positive lobe lasts more
        than this times the running median of the sequence's accepted lobes (seed 003's false-crossing
        check); ``None`` (default) = no lobe check: on our data it rejected more true steps than false ones
        (docs/decisions/steps.md, decision 13)
    alternate : offline, with ``rhythm``: make the sequences alternate left/right, with the step side
        from the pelvis's lateral velocity (same-side maxima too close for a step between them lose the
        weaker one, gaps are filled with a step count of the right parity; decision W20)
    weight_shift : offline, with ``alternate``: a maximum accepted by the height threshold alone, with no
        lateral weight shift (undecided side) and under half its sequence neighbours' height, is no step
        (decision W23)
    end_steps : offline, with ``alternate``: one step of gait initiation / termination beyond each
        walking sequence on the alternating side, up to ``max_step_s`` away (decision W28)
    delay_s : realtime: decide each contact this long after it (to ``delay_s + hop_s``) with the offline
        detector run on the samples up to the decision time only -- its sequence rules W18, W20, W23,
        W28 (``rhythm``, ``alternate``, ``weight_shift``, ``end_steps``; ``ap_above_mean`` too) see
        ``delay_s`` of the gait that follows (decision W31; 1.75 s: the thesis allows < 2 s);
        ``None`` = seed 003's causal zero-crossing detector (decided about one filter delay after the
        contact, no sequence rules)
    hop_s : realtime with ``delay_s``: decision interval (s)
    history_s : realtime with ``delay_s``: seconds of data before the decided stretch the rules see
    ap_above_mean : offline: the IC is the last local AP maximum above the AP acceleration's 2 s mean
        in the search window, if there is one (decision W29; off by default: it moves the simulator's
        contacts earlier)
    learned : offline (and realtime with ``delay_s``): a learned second stage decides the contacts
        (decision W33; off by default): every maximum of the filtered vertical acceleration is a candidate,
        gradient-boosted trees (:mod:`pdrlearn.waist.learned`, shipped as JSON) score it from local features
        and the rule detector's outcomes, and the kept candidates are at least the shortest step (0.3 s)
        apart. ``True`` = the shipped model; a path = a model file of the same form
    turn_gate_rps : the motion gate is also open where the pelvis's mean yaw rate over the gate window reaches
        this (rad/s; decision 28 of docs/decisions/steps.md: 0.45, the turning component of W7's mixture, finds
        a TUG's turning steps but lowers MS001 Test11's F1, not adopted); ``None`` (default) = the std gate alone (W4)
    turn_bridge : offline only: the motion gate is also open over a yaw-rate turn with walking on both sides
        (:func:`pdrlearn.kernels.waist.turn_bridge_gate`, decision W374; off by default); ``"side"``: and a contact
        whose maximum lies only in the bridged span is dropped when its W20 side equals the previous kept contact's
        (:func:`pdrlearn.kernels.waist.alternating_bridged`, decision W384)
    turn_shift_rps : offline (and realtime with ``delay_s``): a maximum where the pelvis's mean yaw rate over the
        gate window (centred) reaches this (rad/s) is exempt from W23's weight-shift test (``weight_shift``;
        decision 29 of docs/decisions/steps.md: 0.45, decision 28's turning test); ``None`` (default) = W23 everywhere
    min_step_s : the shortest step (s) of every variant (W16: 0.3); ``None`` (default, decision W113) = relative to
        the recording's own step rhythm (0.75 of its step period, at most 0.3 s), so a child's 3-4 Hz steps are
        found; W31's repeat check and seed 003's causal variant take it from their contacts' spacing
    contact_shift : offline, with ``rhythm`` and ``alternate``: after the sequence rules every kept contact (W18 / W28
        additions too) is judged once more by W23's weight-shift test, with the side read at the initial contact as
        W129 reads it; a contact where the pelvis turns (decision 29's 0.45 rad/s) is not judged (decision W131,
        adopted: on by default). The realtime detector and the W33 learned stage ignore it (measured offline only;
        the learned stage's trees were trained on the rule outcomes without it)
    realtime_shift : realtime (W31's ``delay_s``): ``contact_shift`` applied inside each decision window too (decision
        W166: measured, not adopted -- Test11's pooled calibrated bout median vs the strides rose 13.280 -> 13.556 %;
        default False)
    weak_fill : offline, with ``rhythm`` and ``alternate``: a weak step (any positive vertical maximum) on the decided
        alternating side where the alternation and the local rhythm ask for one -- between two kept contacts of the
        same side, one local period (+-35 %, W18) from each, and beyond a sequence end where W28 finds no
        full-height step, one local period away (decision W148; measured, not adopted: off by default). The realtime
        detector and the learned stage ignore it (measured offline only)
    parity_fill : offline, with ``rhythm`` and ``alternate``: a contact without a vertical maximum between two kept
        contacts of the same decided side about two local periods apart, at the opposite side's lateral-sway extreme
        one local period (+-35 %) from each (decision W152; off by default); ``"within"``: only where it lies inside
        one walking sequence of the other contacts (decision W159). The realtime detector and the learned stage
        ignore it (measured offline only)
    side_at_contact : offline, with ``rhythm`` and ``alternate``: the sequence rules (W20's pruning and parity, W18's
        side-filtered fills, W23, W28, W152) read each candidate maximum's side at its initial contact (W129's cue)
        instead of at the maximum (decision W235; off by default). The realtime detector and the learned stage
        ignore it (measured offline only)
    fast_fill : offline, with ``rhythm`` and ``alternate``: one contact where a gap between two kept contacts has room
        for exactly one step and the vertical acceleration low-passed at twice the cut-off (5 Hz) has a maximum of
        its own there (decision W242; off by default); ``"outside_freeze"``: none inside an episode of the lower
        back's freeze index (W213's, as freezes.csv finds them; decision W255). The realtime detector and the learned
        stage ignore it

    Attributes
    ----------
    steps_ : steps table (see :func:`steps_from_events`); ic_, fc_ : sample indices
    anchor_ : sample index each IC was found from (offline and realtime with ``delay_s``: the vertical
        maximum; realtime without: the delayed zero crossing)
    decided_ : sample index at which each contact was decided (the first sample the decision did not
        use; offline: the end of the data). ``(decided_ - ic_) / fs`` is the decision delay.
    """

    def __init__(self, *, realtime: bool = False, cutoff_hz: float = 2.5, fir_order_s: float = 0.3,
                 walk_threshold: float = WALK_THRESHOLD_MPS2, ap_cutoff_hz: float = 20.0,
                 max_step_s: float = 1.5, rhythm: bool = True, alternate: bool = True,
                 lobe_ratio: float | None = None, weight_shift: bool = True, end_steps: bool = True,
                 ap_above_mean: bool = False, learned: bool | str = False,
                 delay_s: float | None = K.DECISION_DELAY_S,
                 hop_s: float = K.DECISION_HOP_S, history_s: float = K.DECISION_HISTORY_S,
                 turn_gate_rps: float | None = None, turn_shift_rps: float | None = None,
                 min_step_s: float | None = None, contact_shift: bool = True, weak_fill: bool = False,
                 parity_fill: bool | str = "within", realtime_shift: bool = False,  # W159/W160: adopted by its rule
                 side_at_contact: bool = False, fast_fill: bool | str = False,  # W235, W242, W255
                 turn_bridge: bool | str = False):  # W374, W384
        self.turn_bridge = turn_bridge
        self.side_at_contact = side_at_contact
        self.fast_fill = fast_fill
        self.realtime = realtime
        self.realtime_shift = realtime_shift
        self.parity_fill = parity_fill
        self.weak_fill = weak_fill
        self.contact_shift = contact_shift
        self.min_step_s = min_step_s
        self.turn_shift_rps = turn_shift_rps
        self.turn_gate_rps = turn_gate_rps
        self.delay_s = delay_s
        self.hop_s = hop_s
        self.history_s = history_s
        self.lobe_ratio = lobe_ratio
        self.rhythm = rhythm
        self.alternate = alternate
        self.weight_shift = weight_shift
        self.end_steps = end_steps
        self.ap_above_mean = ap_above_mean
        self.learned = learned
        self.cutoff_hz = cutoff_hz
        self.fir_order_s = fir_order_s
        self.walk_threshold = walk_threshold
        self.ap_cutoff_hz = ap_cutoff_hz
        self.max_step_s = max_step_s

    def rule_settings(self) -> dict:
        """The keywords of :func:`pdrlearn.kernels.waist.contacts_offline` (the lean runtime's detector, W92); W131's
        ``contact_shift``, W148's ``weak_fill`` and W152's ``parity_fill`` only offline and without the learned
        stage; ``contact_shift`` in realtime (W31's window) too with ``realtime_shift`` (decision W166, an option)."""
        kw = {k: getattr(self, k) for k in ("walk_threshold", "cutoff_hz", "fir_order_s", "ap_cutoff_hz", "rhythm",
                                            "max_step_s", "alternate", "weight_shift", "end_steps",
                                            "ap_above_mean", "turn_gate_rps", "turn_shift_rps", "min_step_s")}
        offline = not self.realtime and not self.learned
        shift = self.contact_shift and not self.learned and (not self.realtime or self.realtime_shift)  # W166
        return kw | {"contact_shift": bool(shift), "side_at_contact": bool(self.side_at_contact and offline),  # W235
                     "fast_fill": bool(self.fast_fill and offline),  # W242
                     "turn_bridge": (self.turn_bridge if self.turn_bridge == K.TURN_BRIDGE_SIDE  # W384
                                     else bool(self.turn_bridge)) if offline else False,  # W374: reads ahead
                     "weak_fill": bool(self.weak_fill and offline),
                     "parity_fill": self.parity_fill if offline and self.parity_fill else False}

    def _offline(self, imu: WaistIMU) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The offline detector's contacts (zero-lag filters, sequence rules) on ``imu``."""
        fs = imu.fs
        kw = self.rule_settings()
        if kw["fast_fill"] and self.fast_fill == FAST_FILL_OUTSIDE_FREEZE:  # W255: no W242 fill inside a freeze
            kw["frozen"] = frozen_samples(imu)
        rules_only = self.learned is False or self.learned is None  # the learned stage reads the filtered AP
        ic, fc, vmax, ap = K.contacts_offline(imu.acc_v, imu.acc_ap, imu.acc_ml, imu.w_z, fs, with_ap=not rules_only,
                                              **kw)
        if rules_only:
            return ic, fc, vmax
        from pdrlearn.waist import learned as L  # W33: the rule outcomes are features of the learned stage

        model = L.shipped_model(None if self.learned is True else self.learned)
        ic, vmax = L.learned_contacts(imu.acc_v, ap, imu.acc_ml, imu.w_z, fs, vmax, model=model,
                                      walk_threshold=self.walk_threshold, cutoff_hz=self.cutoff_hz,
                                      fir_order_s=self.fir_order_s, max_step_s=self.max_step_s)
        return ic, K.fc_after(ap, vmax, fs), vmax

    def detect(self, imu: WaistIMU, *, final: bool = True) -> InitialContactDetector:
        """Detect the contacts of ``imu``. ``final`` (realtime with ``delay_s``): the end of the data
        decides the contacts of its last ``delay_s`` (a stream that ended); ``False`` leaves them out, as a
        live stream at that moment would."""
        fs = imu.fs
        if self.realtime and self.delay_s is not None:  # W31: offline rules, decided delay_s later
            if self.lobe_ratio is not None:
                log.warning("lobe_ratio applies to seed 003's zero-crossing detector only (delay_s=None)")
            ic, fc, ref, self.decided_ = K.delayed_decisions(
                len(imu.t), fs, lambda lo, hi: self._offline(_window(imu, lo, hi)), delay_s=self.delay_s,
                hop_s=self.hop_s, history_s=self.history_s, final=final, min_step_s=self.min_step_s)
        elif self.realtime:
            gate = walking_gate(imu, walk_threshold=self.walk_threshold, causal=True,
                                turn_gate_rps=self.turn_gate_rps)
            cut = min(self.ap_cutoff_hz, 0.4 * fs)
            ap = lowpass(imu.acc_ap, cut, fs, causal=True)
            ic, fc, ref = K.ic_realtime(imu.acc_v, ap, fs, gate=gate, cutoff_hz=self.cutoff_hz,
                                        min_step_s=self.min_step_s,
                                        lobe_ratio=np.inf if self.lobe_ratio is None else self.lobe_ratio)
            # the causal low-pass delays the AP peaks: date the contacts back by its group delay (W17)
            lag = int(round(causal_lowpass_delay_s(cut, fs) * fs))
            ic, fc = np.maximum(ic - lag, 0), np.maximum(fc - lag, 0)
            self.decided_ = ref + 1  # the crossing's sample is the last one the decision saw
        else:
            ic, fc, ref = self._offline(imu)
            self.decided_ = np.full(ic.size, len(imu.t), dtype=int)
        self.ic_, self.fc_, self.anchor_ = ic, fc, ref
        name = "alvarez-realtime" if self.realtime else "alvarez-offline"
        self.steps_ = steps_from_events(imu.t, ic, fc, max_step_s=self.max_step_s, detector=name)
        log.info("%s: %d initial contacts", name, len(ic))
        return self


def frozen_samples(imu: WaistIMU) -> np.ndarray:
    """Decision W255: the (n,) mask of ``imu``'s samples inside an episode of the lower back's freeze index (W213:
    :func:`pdrlearn.track.freezes.freezes_of` of the accelerometer's norm, the norm of ``acc_nav`` - the specific
    force rotated, gravity included - the episodes freezes.csv lists; its 4 s windows look 2 s ahead: offline)."""
    from pdrlearn.kernels.freeze import inside_episodes
    from pdrlearn.track.freezes import freezes_of  # lazy: pdrlearn.track imports this module

    rows = freezes_of(imu.t, imu.acc_nav)
    return inside_episodes(imu.t, [(r["start_s"], r["end_s"]) for r in rows])


def _window(imu: WaistIMU, lo: int, hi: int) -> WaistIMU:
    """Samples ``[lo, hi)`` of ``imu`` (same rate)."""
    return WaistIMU(t=imu.t[lo:hi], fs=imu.fs, acc_nav=imu.acc_nav[lo:hi], gyr_nav=imu.gyr_nav[lo:hi],
                    yaw=imu.yaw[lo:hi], acc_v=imu.acc_v[lo:hi], acc_h=imu.acc_h[lo:hi],
                    acc_ap=imu.acc_ap[lo:hi], acc_ml=imu.acc_ml[lo:hi],
                    up_body=None if imu.up_body is None else imu.up_body[lo:hi],
                    gyr_body=None if imu.gyr_body is None else imu.gyr_body[lo:hi])


def refine_to_contacts(imu: WaistIMU, idx: np.ndarray, *, walk_threshold: float = WALK_THRESHOLD_MPS2,
                       max_shift_s: float = 0.3, rhythm: bool = True, alternate: bool = True) -> np.ndarray:
    """Move step events found at vertical-acceleration peaks (e.g. PLL peaks) to the initial contact of
    the nearest vertical maximum within ``max_shift_s`` (decision W11); others are kept. Sorted, unique.

    With ``rhythm`` and ``alternate`` the events then pass the same left/right check as the IC detector
    (decision W20, :func:`pdrlearn.waist._kernels.prune_same_side`): of two consecutive events on the same
    side closer than 1.5 local step periods, the one whose filtered vertical acceleration is under half
    the other's is dropped (a phase-locked peak inside a slow step, where no contact is)."""
    det = InitialContactDetector(walk_threshold=walk_threshold, rhythm=rhythm, alternate=alternate,
                                 contact_shift=False, parity_fill=False).detect(imu)  # W131 / W159 measured on
    # waist-pendulum only
    idx = np.asarray(idx, dtype=int)
    if det.anchor_.size == 0 or idx.size == 0:
        return np.unique(idx)
    j = np.clip(np.searchsorted(det.anchor_, idx), 1, det.anchor_.size) - 1
    j2 = np.minimum(j + 1, det.anchor_.size - 1)
    near = np.where(np.abs(det.anchor_[j2] - idx) < np.abs(det.anchor_[j] - idx), j2, j)
    ok = np.abs(det.anchor_[near] - idx) <= max_shift_s * imu.fs
    out, first = np.unique(np.where(ok, det.ic_[near], idx), return_index=True)
    if not (rhythm and alternate) or out.size < 3:
        return out
    anchor = np.where(ok, det.anchor_[near], idx)[first]  # the vertical maximum each event stands for
    taps = K.fir_taps(det.cutoff_hz, imu.fs, int(round(det.fir_order_s * imu.fs)))  # as ic_offline
    vf = K.fir_zero_lag(imu.acc_v - np.mean(imu.acc_v), taps)
    side = K.step_sides(K.lateral_velocity(imu.acc_ml, imu.fs)[anchor], np.ones(anchor.size, dtype=bool))
    keep = K.prune_same_side(anchor, vf[anchor], np.ones(anchor.size, dtype=bool), side, imu.fs,
                             max_step_s=det.max_step_s)
    return out[keep]
