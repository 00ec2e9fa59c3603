"""Waist step-length models: the built-ins of the two waist pipelines (``pendulum``, seed 003 sec. 3.2;
``frequency``, seed 000 sec. II-D), ``weinberg`` (Weinberg 2002) and plug-ins (decision E84, docs/extending.md).

The contract (:class:`StepLengthModel`): ``predict(steps, signals, profile)`` returns one length (m) per row of a
waist steps table; ``steps`` has ``start_s`` (this initial contact), ``end_s`` (the next one), ``event_s`` and
``has_next`` (False: the contact closes a walking sequence and carries no length), ``signals`` is the
:class:`pdrlearn.waist.ahrs.WaistIMU` (navigation-frame lower-back signals, ``t`` in s), ``profile`` the
:class:`pdrlearn.waist.params.WaistParams` (leg length, calibrated gains). A plain function with that signature
registers as a model too. The pipeline checks the lengths (one per row, finite, >= 0) and sets 0 on closing rows.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.errors import DataError
from pdrlearn.plugins import Registry
from pdrlearn.settings import Settings
from pdrlearn.waist import _kernels as K
from pdrlearn.waist.params import WaistParams
from pdrlearn.waist.steplength import fragment_mask, fragment_windows, frequency_lengths, pendulum_h

#: the steps-table columns every length model may read
LENGTH_INPUT_COLUMNS = ("start_s", "end_s", "event_s", "has_next")


def step_frequency(steps: pd.DataFrame) -> np.ndarray:
    """Step frequency (Hz) of each row with a next contact, 1 / (end_s - start_s); NaN on closing rows."""
    has_next = steps["has_next"].to_numpy(bool)
    dur = (steps["end_s"] - steps["start_s"]).to_numpy(float)
    return np.where(has_next & (dur > 0), 1.0 / np.where(dur > 0, dur, 1.0), np.nan)


def sample_index(steps: pd.DataFrame, signals, column: str = "event_s") -> np.ndarray:
    """The signals' sample index of each row's ``column`` time (clipped to the recording)."""
    t = steps[column].to_numpy(float)
    return np.clip(np.round((t - signals.t[0]) * signals.fs).astype(int), 0, len(signals.t) - 1)


class StepLengthModel(Settings):
    """Base class of a waist step-length model: set ``name`` (the registered name), keyword-only settings in
    ``__init__`` (``self._store(locals())``), and implement :meth:`predict`. ``uses_leg_length``: the model reads
    ``profile.leg_m`` (False: the pipeline drops the "no sensor height" warning). ``uses_profile``: the model reads
    the profile's calibrated step-length parameters (K, F, the frequency lines), so ``pdrlearn calibrate`` and
    ``track --params`` change it (False: the pipeline drops the "no per-user calibration" line, decision W461).
    ``gain_param``: the name of a setting the lengths are proportional to (a linear gain, no default): ``pdrlearn
    calibrate --length-model NAME`` fits it, PARAMS.json's ``length_models`` keeps it and ``track --params`` sets it
    when the spec does not (decision W460)."""

    name = "base"
    kind = "step-length model"  # C158's line (the check is the base class's, shared with the detectors: steps 82)
    uses_leg_length = True
    uses_profile = True
    gain_param: str | None = None
    #: settings for a model whose defaults cannot run (weinberg's gain): the contract test and examples use them
    example_settings: dict = {}

    def predict(self, steps: pd.DataFrame, signals, profile: WaistParams) -> np.ndarray:
        raise NotImplementedError

    def transform(self, steps: pd.DataFrame, signals, profile: WaistParams) -> pd.DataFrame:
        """``steps`` with ``length_m`` (checked by :func:`check_lengths`; 0 on closing rows). Built-ins also add
        their own columns (``h_m``, ``g_m``, ``merged`` ...)."""
        check_steps(steps, self.name)
        lengths = check_lengths(self.predict(steps, signals, profile), steps, self.name)
        return steps.assign(length_m=lengths)


def check_steps(steps, name: str) -> None:
    """One line when the steps table lacks a column a length model reads (decision E84)."""
    missing = [c for c in LENGTH_INPUT_COLUMNS if not isinstance(steps, pd.DataFrame) or c not in steps]
    if missing:
        raise DataError(f"step-length model {name}: the steps table lacks {', '.join(missing)}; pass a waist steps "
                        "table (pdrlearn.waist.events.steps_from_events, or track_waist(...).steps)")


def check_lengths(lengths, steps: pd.DataFrame, name: str) -> np.ndarray:
    """Decision E84: a model's lengths are one finite number >= 0 (m) per row; closing rows are set to 0."""
    try:
        v = np.asarray(lengths, dtype=float)
    except (TypeError, ValueError):
        raise DataError(f"step-length model {name}: predict returned {type(lengths).__name__}, not numbers; return "
                        "one length in m per steps row") from None
    if v.shape != (len(steps),):
        raise DataError(f"step-length model {name}: predict returned shape {v.shape} for {len(steps)} steps; return "
                        "one length in m per steps row")
    has_next = steps["has_next"].to_numpy(bool)
    v = np.where(has_next, v, 0.0)
    bad = ~np.isfinite(v) | (v < 0)
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise DataError(f"step-length model {name}: {int(bad.sum())} of {len(v)} lengths are negative or not finite "
                        f"(first: {v[i]!r} m at {steps['start_s'].iloc[i]:g} s); return lengths in m, >= 0")
    return v


#: the values of the pendulum's ``pause_steps``: off, W111's one period, W122's trunk travel over a standstill,
#: W134's the same only over a stand of half a local period inside a walk
PAUSE_STEPS_VALUES = (False, True, "progression", "standing")


def check_pause_steps(value):
    """``value`` if it is one of :data:`PAUSE_STEPS_VALUES`, else one line naming them (decisions W111, W122)."""
    if value not in PAUSE_STEPS_VALUES:
        raise DataError(f"pause_steps {value!r} is not one of false, true, \"progression\", \"standing\" (decisions "
                        "W111, W122, W134); "
                        "fix the option, the PARAMS.json \"options\" or the model's setting")
    return value


#: decision W514: over this share of the steps with a length shortened as stands (W134) the track says so -- a
#: walk with a stand every tenth step is not a walk; a steadied trunk (walking aid) is the likelier reading (trial T1)
PAUSE_SCALED_WARN_SHARE = 0.10


def pause_scaled_count(steps: pd.DataFrame) -> tuple[int, int]:
    """Decision W514: (steps shortened as a pause / stand, steps with a length) of a pendulum steps table: rows with
    a next contact and not a W27 fragment; shortened: ``pause_factor`` under 1 (W111, W122, W134). (0, n) without
    the column (``pause_steps`` off)."""
    use = steps["has_next"].to_numpy(bool) if "has_next" in steps else np.ones(len(steps), bool)
    if "merged" in steps:
        use = use & ~steps["merged"].to_numpy(bool)
    if "pause_factor" not in steps:
        return 0, int(use.sum())
    f = steps["pause_factor"].to_numpy(float)
    return int((use & (f < 1.0)).sum()), int(use.sum())


#: the decision of each shortening ``pause_steps`` value (W111, W122, W134)
_PAUSE_DECISIONS = {True: "W111", "progression": "W122", "standing": "W134, W516"}


def pause_scaled_message(n_scaled: int, n_steps: int, value: bool | str = "standing") -> str | None:
    """Decision W514's warning: one line when over :data:`PAUSE_SCALED_WARN_SHARE` of the steps with a length were
    shortened as pauses / stands by ``pause_steps`` ``value``, naming the option that turns it off; None otherwise."""
    if n_steps <= 0 or n_scaled <= PAUSE_SCALED_WARN_SHARE * n_steps:
        return None
    shown = "true" if value is True else f'"{value}"'
    return (f"{n_scaled} of {n_steps} steps ({100.0 * n_scaled / n_steps:.0f} %) were shortened as pauses / stands "
            f"inside a walk (pause_steps {shown}, {_PAUSE_DECISIONS.get(value, 'W111')}): if the subject did not "
            "stop that often (a walking aid steadies the trunk), the distance reads short; track and calibrate with "
            "{\"options\": {\"pause_steps\": false}} in the parameters file (decision W514)")


def check_length_smoothing(mode) -> str:
    """``mode`` as text if it is one of the W56 smoothing modes, else one line naming them."""
    mode = str(mode)
    if mode not in K.LENGTH_SMOOTHING_MODES:
        raise DataError(f"length_smoothing '{mode}' is not one of {', '.join(K.LENGTH_SMOOTHING_MODES)} "
                        "(decision W56); fix the option, the PARAMS.json \"options\" or the model's setting")
    return mode


class PendulumLength(StepLengthModel):
    """``K 2 sqrt(2 L h - h^2) + F`` (seed 003 eq. 1; ``h`` the vertical excursion IC to next IC, decision W10),
    K, F and L from the profile; the waist-pendulum pipeline's model. Settings (the pipeline's options of the same
    name): ``merge_fragments`` (decision W27), ``length_smoothing`` (W56), ``pause_steps`` (W111; ``"progression"``:
    W122; ``"standing"``: W134); ``causal_stands`` (decision W529, set by the realtime track): W516's share of stands
    counted over each walk's steps so far, as the live tracker counts it."""

    name = "pendulum"

    def __init__(self, *, merge_fragments: bool = True, length_smoothing: str = "none",
                 pause_steps: bool | str = False, causal_stands: bool = False):
        self._store(locals())

    def _check_params(self, params: dict) -> None:
        """The numbers (C21) and the text settings' values: a misspelt ``pause_steps`` ran W111 silently."""
        super()._check_params(params)
        if "merge_fragments" in params and params["merge_fragments"] not in (True, False):
            raise DataError(f"step-length model pendulum: merge_fragments={params['merge_fragments']!r} is not true or "
                            "false (decision W27); write pendulum:merge_fragments=false")
        if "length_smoothing" in params:
            check_length_smoothing(params["length_smoothing"])
        if "pause_steps" in params:
            check_pause_steps(params["pause_steps"])

    def predict(self, steps, signals, profile):
        return self.transform(steps, signals, profile)["length_m"].to_numpy(float)

    def transform(self, steps, signals, profile):
        check_steps(steps, self.name)
        mode = check_length_smoothing(self.length_smoothing)
        n, fs, p = len(steps), signals.fs, profile
        idx = sample_index(steps, signals)
        has_next = steps["has_next"].to_numpy(bool)
        start, end = steps["start_s"].to_numpy(float), steps["end_s"].to_numpy(float)
        fc = steps["fc_s"].fillna(-1) if "fc_s" in steps else pd.Series(np.full(n, -1.0))
        fc_idx = np.round((fc.to_numpy(float) - signals.t[0]) * fs).astype(int)
        win = fragment_windows(start, end, has_next) if self.merge_fragments else {}
        merged = fragment_mask(n, win)
        h = np.zeros(n)
        for i in np.flatnonzero(has_next & ~merged):
            if i in win:  # W27: the whole step a spurious contact had split
                h[i] = K.vertical_excursion(signals.acc_v, fs, idx[win[i][0]], idx[win[i][1] + 1])
            else:
                h[i] = pendulum_h(signals.acc_v, fs, idx[i], fc_idx[i], idx[i + 1])
        use = has_next & ~merged
        g = np.where(use, K.pendulum_length(h, p.leg_m), 0.0)  # K = 1, F = 0
        if mode != "none":  # W56; equivariant to K g + F, so calibration sums g_m (W21)
            g = _smoothed_g(steps, g, use, win, mode)
        # a negative F (W22) must not turn a step with a tiny excursion into a backward one
        sl = K.pendulum_length(h, p.leg_m, k=p.k, f=p.f_m) if mode == "none" else p.k * g + p.f_m
        lengths = np.where(use, np.maximum(sl, 0.0), 0.0)
        out = steps.assign(h_m=h, g_m=g, merged=merged)
        if self.pause_steps in ("progression", "standing"):  # W122: the trunk's travel over a step with a standstill
            disp, run_s = _still_displacements(signals, idx, use, win)
            if self.pause_steps == "standing":  # W134: only a stand of half a local period, not at a walk's edges
                stand = K.standing_step_mask(run_s, _spans(start, end, win), use, ~has_next,
                                             causal=bool(self.causal_stands))  # W529: realtime as live
                disp = np.where(stand, disp, np.nan)
            factor = K.progression_factor(disp, lengths)
            lengths = lengths * factor
            out = out.assign(pause_factor=factor)
        elif self.pause_steps:  # W111: the owner of a W27 window spans the whole window
            factor = K.pause_step_factor(_spans(start, end, win), use, ~has_next)
            lengths = lengths * factor
            out = out.assign(pause_factor=factor)
        out = out.assign(length_m=lengths)
        out.attrs["fragment_windows"] = win  # W27: the pipeline gives each owner the turn of its merged step
        return out


def _spans(start: np.ndarray, end: np.ndarray, win: dict[int, tuple[int, int]]) -> np.ndarray:
    """Each row's step duration (s), IC to next IC; a W27 owner spans its whole window (W111, W134)."""
    span = end - start
    for i, (a, b) in win.items():
        span[i] = end[b] - start[a]
    return span


def _still_displacements(signals, idx: np.ndarray, use: np.ndarray,
                         win: dict[int, tuple[int, int]]) -> tuple[np.ndarray, np.ndarray]:
    """Decision W122: per step row (``use``; a W27 owner over its whole window) the unit's horizontal travel from
    its contact to the next when it stands still in between (:func:`~pdrlearn.signal.conditioning.standstill_mask`
    with its defaults, :func:`~pdrlearn.waist._kernels.still_displacement`), and (W134) the duration (s) of the
    step's longest still run (:func:`~pdrlearn.waist._kernels.longest_still_run`); NaN elsewhere. The mask is the
    track's own (:func:`~pdrlearn.waist.ahrs.nav_still`, decision W354)."""
    from pdrlearn.waist.ahrs import nav_still

    still = nav_still(signals)
    bridged = getattr(signals, "bridged", None)
    if bridged is not None:  # W136: samples made up inside a gap of dropped samples (W34) are no standstill
        still = still & ~bridged
    out, run_s = np.full(len(idx), np.nan), np.full(len(idx), np.nan)
    for i in np.flatnonzero(use):
        a, b = win.get(i, (i, i))
        stop = int(idx[min(b + 1, len(idx) - 1)])
        out[i], run_s[i] = K.step_still_travel(signals.acc_h, still, signals.fs, int(idx[a]), stop)
    return out, run_s


def walking_sequences(has_next: np.ndarray) -> list[np.ndarray]:
    """Row indices of each walking sequence: consecutive rows with a next contact plus the closing row."""
    ends = np.flatnonzero(~np.asarray(has_next, dtype=bool))
    bounds = np.concatenate([[0], ends + 1, [len(has_next)]])
    return [np.arange(a, b) for a, b in zip(bounds[:-1], bounds[1:], strict=True) if b > a]


def _smoothed_g(steps: pd.DataFrame, g: np.ndarray, use: np.ndarray, win: dict[int, tuple[int, int]],
                mode: str) -> np.ndarray:
    """``g`` of the rows ``use`` smoothed per walking sequence by
    :func:`~pdrlearn.waist._kernels.smooth_step_lengths` (decision W56); a W27 owner spans its merged rows."""
    out = g.copy()
    t0, t1 = steps["start_s"].to_numpy(float), steps["end_s"].to_numpy(float)
    for seq in walking_sequences(steps["has_next"].to_numpy(bool)):
        rows = seq[use[seq]]
        if not rows.size:
            continue
        a = np.array([t0[win[i][0]] if i in win else t0[i] for i in rows])
        b = np.array([t1[win[i][1]] if i in win else t1[i] for i in rows])
        out[rows] = K.smooth_step_lengths(a, b, g[rows], mode)
    return out


class FrequencyLength(StepLengthModel):
    """``a f - b``, piecewise linear in the step frequency f (seed 000 sec. II-D, seed 001 eq. 23; decisions W37,
    W118), the lines from the profile; the running line where the 2 s SD of the vertical acceleration reaches the
    running level (at or above the motion gate ``steps.attrs["walk_threshold_mps2"]``, default W4's 0.5). The
    waist-pll pipeline's model."""

    name = "frequency"
    uses_leg_length = False

    def __init__(self):
        self._store(locals())

    def predict(self, steps, signals, profile):
        from pdrlearn.waist.events import WALK_THRESHOLD_MPS2

        check_steps(steps, self.name)
        thr = float(steps.attrs.get("walk_threshold_mps2", WALK_THRESHOLD_MPS2))
        sigma = K.rolling_std(signals.acc_v, signals.fs, causal=False)
        running = K.motion_state(sigma[sample_index(steps, signals)], walk_threshold=thr) == 2
        freq = step_frequency(steps)
        return np.where(steps["has_next"].to_numpy(bool),
                        frequency_lengths(np.nan_to_num(freq, nan=0.0), profile, running=running), 0.0)


class WeinbergLength(StepLengthModel):
    """``k (a_max - a_min)^(1/4)`` (Weinberg 2002, Analog Devices AN-602, cited by seed 000 as ref. [18]): the
    fourth root of the range of the vertical acceleration (m/s^2, ``signals.acc_v``) over the step, IC to next IC
    (as ``experiments/waist_steplength_loso.py`` measured it, docs/waist.md). ``k`` (m per (m/s^2)^(1/4)) is the
    user's gain, which Weinberg fits on a walk of known length: no default (decision E84)."""

    name = "weinberg"
    uses_leg_length = False
    uses_profile = False  # decision W461: only its own gain k
    gain_param = "k"  # decision W460: calibrate --length-model weinberg fits it
    example_settings = {"k": 0.45}

    def __init__(self, *, k: float | None = None):
        self._store(locals())

    def predict(self, steps, signals, profile):
        if self.k is None:
            raise DataError("step-length model weinberg: set its gain k (m per (m/s^2)^(1/4), fitted per user on a "
                            "walk of known length, Weinberg 2002), e.g. --length-model weinberg:k=0.45 or "
                            "WeinbergLength(k=0.45), or fit it with 'pdrlearn calibrate DIR --distance M "
                            "--length-model weinberg --out PARAMS.json' and track with --params PARAMS.json (W460)")
        check_steps(steps, self.name)
        idx = sample_index(steps, signals)
        has_next = steps["has_next"].to_numpy(bool)
        out = np.zeros(len(steps))
        for i in np.flatnonzero(has_next[:-1]):
            a = signals.acc_v[idx[i]:idx[i + 1] + 1]
            out[i] = self.k * float(a.max() - a.min()) ** 0.25  # Weinberg 2002 (AN-602)
        return out


class _FunctionLength(StepLengthModel):
    """A registered function ``fn(steps, signals, profile) -> lengths`` as a model without settings."""

    fn = None

    def __init__(self):
        self._store(locals())

    def predict(self, steps, signals, profile):
        check_steps(steps, self.name)
        return type(self).fn(steps, signals, profile)


def _check_length_model(name: str, obj):
    """A plug-in is a :class:`StepLengthModel` subclass named as registered, or a function (wrapped)."""
    if isinstance(obj, type) and issubclass(obj, StepLengthModel):
        if obj.name != name:
            raise DataError(f"step-length model '{name}': the class's name attribute is {obj.name!r}; set "
                            f"name = {name!r} in {obj.__name__}")
        if obj.gain_param is not None and obj.gain_param not in obj._param_names():  # decision W460
            raise DataError(f"step-length model '{name}': gain_param {obj.gain_param!r} is not one of its settings "
                            f"({', '.join(obj._param_names()) or 'none'}); name the setting the lengths are "
                            "proportional to, or set gain_param = None")
        return obj
    if callable(obj) and not isinstance(obj, type):
        return type(f"FunctionLength[{name}]", (_FunctionLength,),
                    {"name": name, "fn": staticmethod(obj), "__module__": getattr(obj, "__module__", "?")})
    raise DataError(f"step-length model '{name}': {obj!r} is neither a StepLengthModel subclass nor a function "
                    "fn(steps, signals, profile) -> lengths (docs/extending.md)")


#: name -> step-length model class (decision E84): the built-ins below, those added by
#: :func:`register_step_length` and installed plug-ins (entry point group ``pdrlearn.step_lengths``)
STEP_LENGTHS = Registry("step-length model", "pdrlearn.step_lengths", adapt=_check_length_model,
                        helper="register_step_length")
for _cls in (PendulumLength, FrequencyLength, WeinbergLength):
    STEP_LENGTHS.register(_cls.name, _cls)


def register_step_length(name: str, model, *, replace: bool = False):
    """Make ``model`` (a :class:`StepLengthModel` subclass, or a function ``fn(steps, signals, profile) ->
    lengths``) the step-length model ``name`` of the waist pipelines (``track_waist(..., length_model=name)``,
    ``pdrlearn track --length-model NAME``). A built-in name is refused unless ``replace=True`` (decision E81)."""
    return STEP_LENGTHS.register(name, model, replace=replace)


def get_step_length(spec, **params) -> StepLengthModel:
    """A model from its registered name (with ``params``), a ``"name:key=value,..."`` string (the CLI's form) or a
    :class:`StepLengthModel` instance (returned as it is)."""
    if isinstance(spec, StepLengthModel):
        return spec
    from pdrlearn.plugins import from_spec, parse_spec

    try:
        return from_spec(STEP_LENGTHS, spec, **params)  # decision E94: the detectors' --detector NAME:key=value too
    except TypeError as exc:
        name = parse_spec(spec, "step-length model")[0]
        raise DataError(f"step-length model {name}: {exc}; its settings are "
                        f"{', '.join(STEP_LENGTHS[name]._param_names()) or 'none'}") from None


def model_spec(model: StepLengthModel, spec=None, gain_from_params: bool = False) -> str:
    """Decision W462: the model as ``"name:key=value,..."`` with the settings the user set - those ``spec`` (its
    ``"name:key=value"`` string) names; for an instance (``spec`` None) those that differ from its defaults - and,
    with ``gain_from_params``, its :attr:`~StepLengthModel.gain_param` (read from PARAMS.json, W460). The pipeline's
    options it takes (``pause_steps`` ...) are the track's ``options``, not repeated here."""
    from pdrlearn.plugins import parse_spec, spec_text

    params = model.get_params()
    keys = set(parse_spec(spec, "step-length model")[1]) if isinstance(spec, str) else set(model.changed_params())
    if gain_from_params and model.gain_param:
        keys.add(model.gain_param)
    return spec_text(model.name, {k: v for k, v in params.items() if k in keys})
