"""The four step detectors: foot accelerometer (thesis ch.5.1), foot accelerometer + force sensors
(ch.5.2), waist pelvic-rotation gyroscope (ch.5.3) and a phase-locked loop on the waist's vertical
acceleration (seeds 000/001).

Every setting is keyword-only, in seconds and SI units; thesis sample counts are converted at the
thesis' 20 Hz (docs/decisions/steps.md). Detectors run at the session's native rate.
"""

from __future__ import annotations

import logging

import numpy as np

from pdrlearn.displace.force_channels import one_channel_filled
from pdrlearn.errors import DataError
from pdrlearn.io.session import Session
from pdrlearn.kernels.contact import (
    EVENT_CUTOFF_HZ,
    FAST_EVENT_CUTOFF_HZ,
    FAST_PERIOD_S,
    FORCE_AMP,
    FORCE_MIN_SWING_S,
    FORCE_OFF_FRAC,
    FORCE_ON_FRAC,
    FORCE_REF_STANCES,
    IMPACT_CLUSTER_S,
    MAX_STRIDE_S,
    PEAK_FRAC,
    PEAK_PROMINENCE,
    SHORT_MAX_AMP,
    SHORT_MIN_RATE_HZ,
    SHORT_PERIOD_S,
)
from pdrlearn.kernels.step_events import (  # decision L177: the online processors, numpy only given a low-pass
    MIN_STILL_SAMPLES,  # noqa: F401 (re-exported)
    MIN_STILL_WINDOW_SAMPLES,  # noqa: F401
    MIN_STRIDE_S,
    AccelProcessor,
    ForceProcessor,
    GateState,
    GravityTracker,
    PelvicParams,
    PelvicState,
    PLLParams,
    PLLProcessor,
    motion_gate_flush,
    motion_gate_kernel,
    pelvic_flush,
    pelvic_kernel,
    pll_params,
)
from pdrlearn.kernels.step_events import cutoff_below as _cutoff
from pdrlearn.kernels.step_events import shift_events as _shift
from pdrlearn.kernels.waist import accel_relative_gate, accel_step_period_s
from pdrlearn.plugins import Registry
from pdrlearn.signal.conditioning import G, calibrate_standstill
from pdrlearn.signal.filters import CausalLowpass, lowpass_delay_s
from pdrlearn.steps.base import STEP_UNITS, StepDetector, check_stream, stream_on
from pdrlearn.steps.waist_ic import WaistICStepDetector

log = logging.getLogger(__name__)

THESIS_RATE_HZ = 20.0  # thesis ch.4.3: both BSUs sample at 20 Hz
GATE_CUTOFF_HZ = 5.0  # the PLL's input low-pass, on which the waist motion gate was measured (decision 18);
# seed 001 Sec. 2.2.2 uses a Chebyshev IIR at 15 Hz: why ours differs in decision 24


class AccelStepDetector(StepDetector):
    """Foot accelerometer step (stride) detector, thesis ch.5.1 (Fig. 48).

    The acceleration magnitude is low-pass filtered (3rd-order Butterworth, causal); a stride is a swing
    between two still periods of the foot in which the filtered magnitude rises and falls by more than
    ``threshold`` (thesis: max - current > 1.7 m/s^2). One event per stride of the instrumented foot,
    at the initial-contact impact: the last local maximum of the filtered magnitude that rises at least
    ``peak_frac`` of the swing's largest rise above gravity.

    Parameters (keyword-only)
    ----------
    cutoff_hz : low-pass cutoff (Hz); the thesis gives only the order (decision: 3 Hz)
    order : Butterworth order (thesis ch.5.1: 3)
    threshold : minimum rise-and-fall of the filtered magnitude in a stride (m/s^2; thesis ch.5.1: 1.7)
    still_window_s, still_std, still_level_tol : a sample is still when the raw magnitude over the last
        ``still_window_s`` seconds (at least 3 samples) has a standard deviation below ``still_std``
        (m/s^2) and a mean within ``still_level_tol`` (m/s^2) of ``gravity``
    min_quiet_s, max_quiet_s, quiet_frac, quiet_rank, rests_only : a swing ends when the foot has
        been quiet (still window included) for ``quiet_frac`` of its ``quiet_rank``-th longest rest
        among the last 4 (each counted up to 0.6 s), kept within ``min_quiet_s``..``max_quiet_s`` and
        starting at ``max_quiet_s`` (decision 14: 0.1 / 0.2 s, 0.5). Decision 16: the second longest, so
        that one long rest (a hesitation) does not raise the still time for the next strides, and with
        ``rests_only`` only quiet runs of at least ``min_quiet_s`` (long enough to end a swing) are
        rests; ``quiet_rank=1, rests_only=False`` is decision 14 alone. Rest time is the subject's own:
        a healthy walker rests 0.3-0.5 s per stride, an MS patient 0.12-0.19 s, while slow swings can
        look quiet for 0.08-0.15 s. ``quiet_frac=0`` always uses ``min_quiet_s``
    min_swing_s, max_swing_s : accepted swing durations (s)
    min_stride_s : events closer than this are one stride (s). The thesis' 20-sample step period at
        20 Hz (1.0 s, "in average", ch.5.1) becomes this refractory time; steps decision 37: 0.4 s, below a
        fast 3-year-old's 0.52 s stride (decision 3's 0.6 s, an adult's shortest stride, merged children's)
    peak_frac : fraction of the largest rise that the initial-contact peak must reach (decision: 0.3)
    peak_prominence : local maxima of the event signal whose dip from the bump before them stays less than this
        (m/s^2) below the lower of the two are ripples of that bump (steps decision 89, an option, not adopted: 1.7
        keeps gaitmap level left's ICs when it is up-sampled to 409.6 / 1024 Hz; 0 = every local maximum in samples)
    gravity : rest magnitude (m/s^2)
    subsample : the contact's time at the vertex of the parabola through the peak and its two neighbouring
        samples instead of the peak sample (decision 32); None = ``pdrlearn.kernels.contact.SUBSAMPLE``
    short_period_s, fast_period_s, fast_event_cutoff_hz : a stride whose 8 Hz impact comes less than
        ``short_period_s`` (s) after the previous stride's IC takes its impact on |acc| low-passed at the rhythm's
        cutoff, rising linearly from ``event_cutoff_hz`` at ``short_period_s`` to ``fast_event_cutoff_hz`` at
        ``fast_period_s`` and shorter: at a child's short swing the 8 Hz signal merges the terminal-swing
        deceleration and the impact into one peak, 60-88 ms early (steps decisions 87, 88); ``short_period_s=0`` is
        decision 3 alone
    impact_cluster_s : at the rhythm's cutoff the impact is the head of a split impact among the last peak reaching
        the level and those up to this long (s) before it (steps decision 91: a child's impact splits at 20 Hz, its
        tail under 0.75 of the head, ``pdrlearn.kernels.contact.split_head``); 0 = the last peak (steps 88)
    short_min_rate_hz, short_max_amp : the rhythm's re-take only at a foot rate of ``short_min_rate_hz`` (Hz) and up
        and for a swing whose ``amplitude`` is at most ``short_max_amp`` (m/s^2; steps decision 94: a race walker's
        long quick swing spans more than a child's); 0 = every rate / every swing
    event_power : the impact on the RMS envelope sqrt(low-pass(|acc|^2)) instead of low-pass(|acc|), for the 8 Hz
        impact and the rhythm's re-take (steps decision 97: the squared magnitude is band-limited, so an up-sampled
        copy of a walk keeps its contacts); False = before
    """

    name = "accel"
    unit = "foot"
    input_columns = ("acc_x", "acc_y", "acc_z")
    extra_columns = ("amplitude",)

    def __init__(self, *, cutoff_hz: float = 3.0, order: int = 3, threshold: float = 1.7,  # thesis ch.5.1
                 still_window_s: float = 0.08, still_std: float = 0.6, still_level_tol: float = 1.2,
                 min_quiet_s: float = 0.1, max_quiet_s: float = 0.2, quiet_frac: float = 0.5,
                 quiet_rank: int = 2, rests_only: bool = True,
                 min_swing_s: float = 0.2, max_swing_s: float = 2.5,
                 min_stride_s: float = MIN_STRIDE_S, peak_frac: float = PEAK_FRAC,
                 peak_prominence: float = PEAK_PROMINENCE,
                 event_cutoff_hz: float = EVENT_CUTOFF_HZ,
                 gravity: float = G, subsample: bool | None = None,
                 short_period_s: float = SHORT_PERIOD_S,  # steps decisions 87, 88
                 fast_period_s: float = FAST_PERIOD_S, fast_event_cutoff_hz: float = FAST_EVENT_CUTOFF_HZ,
                 impact_cluster_s: float = IMPACT_CLUSTER_S,  # steps decision 91
                 short_min_rate_hz: float = SHORT_MIN_RATE_HZ, short_max_amp: float = SHORT_MAX_AMP,  # steps 93, 94
                 event_power: bool = False):  # steps decision 97
        if int(quiet_rank) != quiet_rank or quiet_rank < 1:
            raise DataError(f"accel detector: quiet_rank must be an integer >= 1 (1 = the longest recent rest, "
                            f"decision 14; 2 = the second longest, decision 16), got {quiet_rank!r}")
        self._store(locals())

    def _inputs(self, session: Session):
        acc = session.require("fAccelerometer", purpose="the foot accelerometer step detector")
        check_stream(acc, session)
        return acc.t, acc.values, {}

    def _make_processor(self, fs: float, **context):
        return AccelProcessor(self, fs, CausalLowpass, lowpass_delay_s)


# ---------------------------------------------------------------------------------------------------
class AccelForceStepDetector(StepDetector):
    """Foot accelerometer + heel/toe force sensors, thesis ch.5.2 (Fig. 51).

    The combined force (heel + toe) marks the stance; during the swing the filtered acceleration's
    maximum and minimum are kept and at the next stance onset a step is counted when max - min exceeds
    ``threshold`` (thesis ch.5.2: 1). Event = stance onset (initial contact).

    Parameters (keyword-only)
    ----------
    cutoff_hz, order : low-pass of the acceleration magnitude (thesis: 3rd order; decision: 3 Hz and the
        orientation-free magnitude instead of the navigation-frame x-axis, docs/decisions/steps.md)
    threshold : m/s^2 (thesis ch.5.2: 1)
    force_on_frac, force_off_frac : stance when the combined force exceeds ``force_on_frac`` of its running
        maximum, swing when it drops below ``force_off_frac`` ("different from zero", with hysteresis
        against sensor noise; works for forces in N or normalised)
    min_swing_s : shortest swing (s)
    ref_stances : the levels are fractions of the median peak of the last this many stances (decisions 53/54: one
        spike cannot move them); 0 = of the running maximum (before decision 54)
    confirm : a stance onset must hold for the next sample too (decision 54: a one-sample spike is no contact;
        False = before it)
    subsample : the stance onset at the time the line between the sample before and the crossing sample reaches
        the on level instead of the crossing sample (decision 32); None = ``pdrlearn.kernels.contact.SUBSAMPLE``
    """

    name = "accel-force"
    unit = "foot"
    input_columns = ("acc_x", "acc_y", "acc_z", "force_heel", "force_toe")
    extra_columns = ("amplitude",)

    def __init__(self, *, cutoff_hz: float = 3.0, order: int = 3, threshold: float = FORCE_AMP,  # thesis ch.5.2
                 force_on_frac: float = FORCE_ON_FRAC, force_off_frac: float = FORCE_OFF_FRAC,
                 min_swing_s: float = FORCE_MIN_SWING_S, subsample: bool | None = None,
                 ref_stances: int = FORCE_REF_STANCES, confirm: bool = True):  # decision 54
        self._store(locals())

    def _inputs(self, session: Session):
        session = one_channel_filled(session)  # steps decision 75: one force channel is the combined force
        purpose = ("the accelerometer + force step detector (thesis ch.5.2; "
                   "use --detector accel without force)")
        session.require("fAccelerometer", "fForceA", "fForceB", purpose=purpose)
        if session.has("fGyroscope"):  # steps decision 73: B284's tare (the CLI's), from the foot IMU's swings
            from pdrlearn.displace.force_check import tared
            from pdrlearn.orient import unit_data

            try:
                foot = unit_data(session, "foot", purpose=purpose, sensor_axes=True)
            except DataError:  # a gyroscope this detector never needed (short, not covering): the online tare only
                foot = None
            session, line = (session, None) if foot is None else tared(session, foot)
            if line:
                log.warning("%s: %s", session.where, line)
        acc = session["fAccelerometer"]
        check_stream(acc, session)
        fa = stream_on(session, "fForceA", acc.t, purpose=purpose)
        fb = stream_on(session, "fForceB", acc.t, purpose=purpose)
        return acc.t, np.column_stack([acc.values, fa[:, 0], fb[:, 0]]), {}

    def _make_processor(self, fs: float, **context):
        return _TaredForceProcessor(self, fs, CausalLowpass, tare=True)  # steps decision 73


class _TaredForceProcessor(ForceProcessor):
    """Steps decision 73: the accel-force detector's processor, whose causal tare (:func:`running_tare`) says once
    which unloaded offset it subtracts (B284's line)."""

    said = False

    def process(self, t, v):
        ev = super().process(t, v)
        if not self.said and any(self.offset_):
            from pdrlearn.displace.force_check import offset_line

            self.said = True
            log.warning("%s online: %s", self.det.name, offset_line(
                {n: o for n, o in zip(self.det.input_columns[3:], self.offset_, strict=True) if o > 0},
                suffix="", fix=f"the strides of the first {MAX_STRIDE_S:g} s after the foot first swung were read "
                "untared (missed); tare the insole or subtract its unloaded reading before pushing the samples"))
        return ev


# ---------------------------------------------------------------------------------------------------
class _PelvicProcessor:
    def __init__(self, det: PelvicGyroStepDetector, fs: float, gyro_bias=None):
        self.det = det
        self.bias = np.zeros(3) if gyro_bias is None else np.asarray(gyro_bias, dtype=float).reshape(3)
        self.grav = GravityTracker(fs, det.gravity_cutoff_hz, CausalLowpass)
        self.lp = CausalLowpass(_cutoff(det.cutoff_hz, fs), fs, order=det.order)
        self.hp = CausalLowpass(det.turn_cutoff_hz, fs, order=2) if det.turn_cutoff_hz > 0 else None
        self.delay = lowpass_delay_s(_cutoff(det.cutoff_hz, fs), fs, order=det.order)
        self.state = PelvicState()
        # decision 23: the PLL's gate signal (its 5 Hz input low-pass, decision 18) for the waist motion gate
        self.gate_lp = CausalLowpass(_cutoff(GATE_CUTOFF_HZ, fs), fs, order=2) if det.gate_var > 0 else None
        self.gate = GateState()
        self.params = PelvicParams(
            threshold=det.threshold, peak_window_s=det.peak_window_s, amp_ref=det.amp_ref,
            length_ref_s=det.length_ref_s, d1_s=det.d1_s, d1_ref=det.d1_ref, d2_s=det.d2_s,
            d2_ref=det.d2_ref, weights=tuple(det.weights), p_min=det.p_min, max_lobe_s=det.max_lobe_s)

    def process(self, t: np.ndarray, v: np.ndarray) -> list:
        up, gnorm = self.grav.push(v[:, 3:6])
        yaw = np.einsum("ij,ij->i", v[:, :3] - self.bias, up)
        w = self.lp.push(yaw)
        if self.hp is not None:  # remove the slow turning rate (decision: turn_cutoff_hz)
            w = w - self.hp.push(w)
        ev, self.state = pelvic_kernel(t, w, self.state, self.params)
        ev = _shift(ev, self.delay)
        if self.gate_lp is None:
            return ev
        vert = self.gate_lp.push(np.einsum("ij,ij->i", v[:, 3:6], up) - gnorm)
        ev, self.gate = motion_gate_kernel(t, vert, ev, self.gate, self.det.gate_window_s, self.det.gate_var)
        return ev

    def flush(self) -> list:
        ev = _shift(pelvic_flush(self.state, self.params), self.delay)
        if self.gate_lp is None:
            return ev
        ev, self.gate = motion_gate_kernel(np.zeros(0), np.zeros(0), ev, self.gate, self.det.gate_window_s,
                                           self.det.gate_var)
        return ev + motion_gate_flush(self.gate, self.det.gate_window_s, self.det.gate_var)


class PelvicGyroStepDetector(StepDetector):
    """Waist gyroscope pelvic-rotation step detector, thesis ch.5.3 (Figs. 54-55, eq. 27).

    The gyroscope offset (from the standstill calibration) is subtracted, the rate about the vertical
    (gravity direction from a slow low-pass of the waist accelerometer, so any mounting works; the thesis
    reads its x axis, vertical in its placement) is low-pass filtered, and each lobe above ``threshold``
    is scored with P(S) = 0.25 P(A) + 0.10 P(L) + 0.40 P(D1) + 0.25 P(D2) (eq. 27); P(S) > 75 % is a step
    (every step, both feet; positive lobes = left steps). Decision: a causal 2nd-order high-pass at
    ``turn_cutoff_hz`` (the filtered signal minus its low-pass) removes the slow turning rate, which
    otherwise merges the lobes of a curve (the thesis' main error source in scenario B); pelvic rotation
    is at the stride frequency (>= 0.7 Hz), turns mostly below; 0.6 Hz, just under the slowest walking
    stride, removes more of a sharp turn (decision 12). ``turn_cutoff_hz=0`` disables it.
    ``gate_var > 0`` (off by default, decision 23) keeps a step only where the PLL's waist motion gate is
    open (variance of the vertical acceleration over ``gate_window_s`` centred on it, e.g. 0.25 m^2/s^4):
    it removes pelvic rotations while standing but, on the daily-activity recordings, slow true steps too.

    Time settings: the thesis gives 50 / 90 / 15 / 25 *samples*. At its 20 Hz they would be 2.5 / 4.5 /
    0.75 / 1.25 s, longer than a step, which makes eq. 27 accept every lobe; decision
    (docs/decisions/steps.md): the numbers are read as 100 Hz samples (0.5 / 0.9 / 0.15 / 0.25 s).
    """

    name = "pelvic-gyro"
    unit = "waist"
    input_columns = ("gyr_x", "gyr_y", "gyr_z", "acc_x", "acc_y", "acc_z")
    extra_columns = ("side", "amplitude")

    def __init__(self, *, cutoff_hz: float = 3.0, order: int = 3,  # thesis ch.5.3: 3rd-order low-pass
                 threshold: float = 0.11,  # thesis ch.5.3
                 peak_window_s: float = 0.5,  # thesis: 50 samples (decision: at 100 Hz)
                 amp_ref: float = 0.20,  # thesis ch.5.3
                 length_ref_s: float = 0.9,  # thesis: 90 samples
                 d1_s: float = 0.15, d1_ref: float = 0.05,  # thesis: 15 samples, 0.05 rad/s
                 d2_s: float = 0.25, d2_ref: float = 0.10,  # thesis: 25 samples, 0.10 rad/s
                 weights: tuple[float, float, float, float] = (0.25, 0.10, 0.40, 0.25),  # thesis eq. 27
                 p_min: float = 0.75,  # thesis ch.5.3: 75 %
                 max_lobe_s: float = 1.0, gravity_cutoff_hz: float = 0.3,
                 turn_cutoff_hz: float = 0.6,  # decision 12 (docs/decisions/steps.md): was 0.5
                 gate_window_s: float = 2.0,  # decision 23: the PLL's waist motion gate (decision 18)
                 gate_var: float = 0.0,  # decision 23: 0.25 m^2/s^4 = W4's std 0.5 m/s^2 squared; 0 = off
                 calibrate: bool = True):
        self._store(locals())

    def _inputs(self, session: Session):
        purpose = "the pelvic-rotation step detector (waist gyroscope + accelerometer)"
        session.require("wGyroscope", "wAccelerometer", purpose=purpose)
        gyr = session["wGyroscope"]
        check_stream(gyr, session)
        acc = stream_on(session, "wAccelerometer", gyr.t, purpose=purpose)
        bias = np.zeros(3)
        if self.calibrate:
            try:
                bias = calibrate_standstill(session, units=("waist",))["waist"].gyro_bias
            except DataError as exc:
                log.warning("%s: no standstill calibration (%s); gyroscope offset taken as 0",
                            session.name, exc)
        self.gyro_bias_ = bias
        return gyr.t, np.column_stack([gyr.values, acc]), {"gyro_bias": bias}

    def _make_processor(self, fs: float, gyro_bias=None, **context):
        return _PelvicProcessor(self, fs, gyro_bias=gyro_bias)


# ---------------------------------------------------------------------------------------------------
class PLLStepDetector(StepDetector):
    """Phase-locked-loop step detector on the vertical acceleration (seed 000 Sec. II-C; seed 001 Sec. 2.2.2).

    The waist acceleration is projected on the gravity direction (slow causal low-pass of the
    accelerometer, so any mounting frame works), gravity is removed, the signal is low-pass filtered and
    normalised by its running RMS, and a second-order PLL (multiplier phase detector, PI loop filter,
    free-running at ``f0_hz``) locks on it. Each peak of the PLL's output sine is a step (both feet); the
    steps table has ``step_freq_hz`` = 1 / time since the previous peak (seed 000: f_k = 1/T_k). Peaks are
    kept only while walking: the vertical acceleration's variance over ``gate_window_s`` centred on the
    peak must exceed ``gate_var`` (seed 001: 4 s window, 1.5 m^2/s^4), so the online detector reports a
    step ``gate_window_s / 2`` after it. The event time is then refined to the largest vertical
    acceleration within ``refine_frac`` periods of the PLL peak (the loading response just after the
    initial contact); ``refine_frac=0`` keeps the PLL peak itself.

    Gate settings (decisions 6 and 18, docs/decisions/steps.md): seed 001's 4 s / 1.5 m^2/s^4 were set for
    a phone in a trouser pocket; at the waist a 2 s window halves the latency and keeps the first and last
    steps of a bout, and the threshold is the waist motion gate's (decision W4: std 0.5 m/s^2, so
    0.25 m^2/s^4; standing < 0.1; seed 000 sec. II-B's gate is 1.5 m/s^2 for brisk walks): the slow
    daily-activity walking of the Test11 recordings has a std of 0.5-0.7 m/s^2 in places, which decision
    6's 0.5 m^2/s^4 dropped (decision 18). ``relative_gate`` None (the default) or True (decision steps 48):
    :meth:`detect` lowers that threshold for a session whose trunk moves little by decision W76's session-relative
    gate, ``track``'s (``min(0.5, max(0.15, 0.5 x P90))`` of the centred 2 s SD of its own low-passed vertical
    acceleration); the streaming detector (:meth:`online`) keeps ``gate_var`` and refuses ``relative_gate=True``
    given explicitly (steps 49). A lower-back run with 0 steps logs W76's line.

    Frequency range (steps decision 6): free-running ``f0_hz``, clamped to ``f_min_hz``-``f_max_hz``;
    ``f_max_hz=None`` (the default, decision W117, docs/decisions/waist.md): offline, a session whose step rhythm
    (W113's autocorrelation period) is faster than 2.4 Hz free-runs at that rhythm, clamped at 1 / 0.75 of it (a
    child at 3.3-3.8 Hz); slower sessions and the streaming detector keep ``f0_hz`` / 3.2 Hz. ``slow_band`` (decision
    W475, on): offline, a waist session whose pelvic-gyro rhythm is under 70 steps/min free-runs at that rhythm f_g,
    clamped to 0.3 Hz .. f_g / 0.75 (:func:`pdrlearn.kernels.waist.pll_slow_band`; the second harmonic, which the
    0.8-3.2 Hz range locked on, is outside); an explicit ``f_max_hz`` turns it off. ``f0_hz`` does not change the
    offline result of a slow walk (steps decision 83).

    Edge lock (decision W356, ``edge_lock``, off; W357 measured it, not adopted): the first and the last peak of a
    run of gated peaks count only when the loop is locked at them, the phase error over the period ending at the peak
    within 45 deg (:data:`pdrlearn.kernels.step_events.EDGE_LOCK_DEG`; seed 000 Sec. II-C: "the PLL can lock the raw
    acceleration data a_z"); a free-running peak at a bout's edge that the centred gate lets in is no step (W345).
    Each gated peak then waits for the next peak's gate: one loop period more latency. ``edge_lock="trailing"``
    (decision W358) judges only a run's last peak and keeps its first (a walk's true first contact often comes
    before the loop locks; W345: only 5 % of the trailing edge extras were locked); ``"both"`` = True.
    ``edge_lock="walk-end"`` (decision W367) judges a run's last peak only where the walk ends: an unlocked last peak
    is kept when the vertical acceleration's SD over the stride after it reaches W76's floor 0.15 m/s^2 (a run broken
    inside a walk, e.g. low bounce in a turn, W366); no more latency than "trailing".

    Loop gains (decision): natural frequency ``loop_hz`` and damping ``damping`` of the linearised loop,
    ``kp = 2 zeta wn / Kd``, ``ki = wn^2 / Kd`` with the phase-detector gain ``Kd = 1/sqrt(2)`` of a
    unit-RMS sine input.
    """

    name = "pll"
    unit = "waist"
    input_columns = ("acc_x", "acc_y", "acc_z")
    extra_columns = ("step_freq_hz",)

    def __init__(self, *, f0_hz: float = 1.8,  # seed 000 Sec. II-C, seed 001 Sec. 2.2.2
                 loop_hz: float = 0.5, damping: float = 0.707, f_min_hz: float = 0.8,
                 f_max_hz: float | None = None,  # decision W117: None = from the session's rhythm
                 cutoff_hz: float = GATE_CUTOFF_HZ, agc_tau_s: float = 1.0, gravity_cutoff_hz: float = 0.3,
                 gate_window_s: float = 2.0,  # seed 001 Sec. 2.2.2 uses 4 s; decision: 2 s
                 gate_var: float = 0.25,  # seed 001: 1.5 m^2/s^4 for a pocket; decision 18: decision W4's
                 # waist motion gate (std 0.5 m/s^2; seed 000 sec. II-B's own is 1.5) squared
                 refine_frac: float = 0.25, placement: str = "waist",
                 relative_gate: bool | None = None,  # decision steps 48: W76's session-relative gate (offline
                 # detect); steps 49: None = steps 48's default (on offline, off streaming), True given is refused by
                 # online()
                 edge_lock: bool | str = False,  # decision W356: a gated run's first / last peak only when
                 # locked; W358: "trailing" its last only; W367: "walk-end" its last only where the walk ends; W372:
                 # "walk-edges" also its first only where the walk starts after it
                 slow_band: bool = True):  # decision W475: a slow walker's band from the pelvic-gyro rhythm
        # (offline, f_max_hz=None); waist-pll's own detector passes False (W475's note)
        self._store(locals())

    def online(self, fs: float, **context):
        """Decision steps 49: a streaming detector; ``relative_gate=True`` given explicitly is refused there (it reads
        the whole session's 2 s SD, which a stream has not got): one line naming it and the fix."""
        if self.relative_gate and "gate_var" not in context:  # detect() passes its judged gate_var
            raise DataError("pll: relative_gate=true acts on the offline detect only (decision steps 48: it reads the "
                            f"whole session); the streaming detector keeps gate_var={self.gate_var:g} m^2/s^4: leave "
                            "relative_gate unset or false, or pass a lower pll:gate_var=V for a quiet trunk")
        return super().online(fs, **context)

    def loop_params(self, period_s: float = float("nan")) -> PLLParams:
        """The loop's parameters; with ``f_max_hz=None`` (decision W117) its free-running frequency and upper clamp
        from the session's step period ``period_s`` (:func:`pdrlearn.kernels.step_events.pll_params`, shared with
        the lean runtime's clock check, decision L177)."""
        return pll_params(self, period_s)

    def _inputs(self, session: Session):
        name = {"waist": "wAccelerometer", "foot": "fAccelerometer"}.get(self.placement)
        if name is None:
            raise DataError(f"pll: placement '{self.placement}' must be 'waist' or 'foot'")
        acc = session.require(name, purpose="the PLL step detector (vertical acceleration)")
        check_stream(acc, session)
        gate_var, self.gate_ = self.gate_var, (float(np.sqrt(self.gate_var)), np.zeros(0), "fixed")
        if acc.t.shape[0] < 3:
            return acc.t, acc.values, {"gate_var": gate_var}  # steps 49: detect's own gate, not a stream's
        fs = acc.rate_hz  # B182's jitter-proof rate
        thr, sigma = accel_relative_gate(  # judged on the PLL's own input: its low-pass of the vertical acceleration
            acc.values, fs, float(np.sqrt(self.gate_var)), window_s=self.gate_window_s,
            lowpass=lambda v: CausalLowpass(_cutoff(self.cutoff_hz, fs), fs, order=2).push(v))
        if self.relative_gate is not False:  # decision steps 48: track's gate (W76) lowers it for a quiet trunk
            gate_var = min(self.gate_var, thr * thr)
        self.gate_ = (float(np.sqrt(gate_var)), sigma, "relative" if gate_var < self.gate_var else "fixed")
        ctx = {"gate_var": gate_var}
        if self.f_max_hz is None:  # decision W117: the session's step rhythm sets the range
            ctx["period_s"] = accel_step_period_s(acc.values, fs, gate_var=gate_var, gate_window_s=self.gate_window_s)
            if self.placement == "waist" and self.slow_band:  # decision W475: a slow walker's band
                from pdrlearn.waist.pelvic_rhythm import pelvic_step_period_s, pelvic_steps, remember  # lazy: it
                # imports this module

                gyro_s = pelvic_steps(session)
                remember(self, session, gyro_s)  # decision W485: the count check reads them from here
                ctx["pelvic_period_s"] = pelvic_step_period_s(session, gyro_s)
        return acc.t, acc.values, ctx

    def _make_processor(self, fs: float, period_s: float = float("nan"), gate_var: float | None = None,
                        pelvic_period_s: float = float("nan"), **context):
        return PLLProcessor(self, fs, period_s, CausalLowpass, lowpass_delay_s, gate_var=gate_var,
                            pelvic_period_s=pelvic_period_s)

    def detect(self, session: Session):
        df = super().detect(session)
        if not len(df) and self.placement == "waist":  # decision W76 / steps 48: never 0 steps without a word
            from pdrlearn.track.waist import no_steps_message  # lazy: pdrlearn.track imports pdrlearn.steps

            thr, sigma, source = self.gate_
            log.warning("pll: %s", no_steps_message(thr, sigma, source, fix=(
                "pass --detector \"pll:relative_gate=true\" (decision W76's session-relative gate) or a lower "
                "\"pll:gate_var=V\" (m^2/s^4)")))
        return df


def _check_detector(name: str, cls) -> type[StepDetector]:
    """A plug-in detector is a :class:`StepDetector` subclass named as registered, on a foot or waist unit."""
    if not (isinstance(cls, type) and issubclass(cls, StepDetector)):
        raise DataError(f"step detector '{name}': {cls!r} is not a StepDetector subclass (docs/extending.md)")
    if cls.name != name:
        raise DataError(f"step detector '{name}': the class's name attribute is {cls.name!r}; set "
                        f"name = {name!r} in {cls.__name__} (its tables and the CLI name it so)")
    if cls.unit not in STEP_UNITS:  # decision B168's units
        raise DataError(f"step detector '{name}': unit {cls.unit!r} is not 'foot' or 'waist'; set the class "
                        "attribute unit (it chooses the reference the steps are scored against)")
    return cls


#: CLI name -> detector class (decisions E81, E82): the built-ins below, those added by
#: :func:`register_detector` and installed plug-ins (entry point group ``pdrlearn.detectors``)
DETECTORS = Registry("step detector", "pdrlearn.detectors", adapt=_check_detector, helper="register_detector")
for _cls in (AccelStepDetector, AccelForceStepDetector, PelvicGyroStepDetector, PLLStepDetector,
             WaistICStepDetector):  # waist-ic: the waist-pendulum pipeline's IC detector (steps/waist_ic.py)
    DETECTORS.register(_cls.name, _cls)


def register_detector(name: str, cls: type[StepDetector], *, replace: bool = False) -> type[StepDetector]:
    """Make the :class:`StepDetector` subclass ``cls`` available as ``name`` to :func:`get_detector`,
    ``pdrlearn steps --detector NAME`` (in a launcher that registers it first, or as an installed plug-in:
    entry point group ``pdrlearn.detectors``), ``pdrlearn track --detector NAME`` and the plasys pipeline's
    ``steps=NAME``. ``cls.name`` must equal ``name``; ``cls.unit`` is "foot" or "waist". A built-in name
    is refused unless ``replace=True`` (decision E81). Returns ``cls``, so it also works as a decorator's body.
    See docs/extending.md."""
    return DETECTORS.register(name, cls, replace=replace)


def get_detector(name: str, **params) -> StepDetector:
    """Detector by CLI name (a name of :data:`DETECTORS`: the built-ins registered below and any registered with
    :func:`register_detector` or installed as a plug-in; ``sorted(DETECTORS)`` lists them), optionally with settings
    in the CLI's form ``"pll:loop_hz=2,damping=0.5"`` (decision E94: the step-length models' ``NAME:key=value``, one
    parser; an unknown setting is one line naming the valid ones)."""
    from pdrlearn.plugins import from_spec

    return from_spec(DETECTORS, name, **params)
