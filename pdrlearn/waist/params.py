"""Per-user parameters of the waist pipelines: defaults from ``meta.json`` and JSON round-trip.

A ``PARAMS.json`` written by ``pdrlearn calibrate`` holds a :class:`WaistParams`; without one the
pipelines derive defaults from what the session's ``meta.json`` gives and say so in ``info["warnings"]``.
"""

from __future__ import annotations

import json
import math
import os
from dataclasses import asdict, dataclass, field, fields
from pathlib import Path

import numpy as np

from pdrlearn.decision_refs import decision_ref
from pdrlearn.errors import DataError
from pdrlearn.io import Session
from pdrlearn.settings import Rule, broken, broken_line
from pdrlearn.textfile import is_inline_json, parse_json, read_json

SCHEMA = "pdrlearn.waist-params/1"
DEFAULT_HEIGHT_M = 1.70  # used only when meta.json gives no height (a warning says so)
# Anthropometric ratios (Drillis & Contini 1966, as tabulated by Winter, Biomechanics of Human Movement):
LEG_PER_HEIGHT = 0.53  # greater-trochanter height / body height
# (the pendulum's L is the sensor height, W10/W69; seed 003's malleolus-to-trochanter L2 is not used)
#: the start of the warning line for a leg length taken from the height (decision W62)
NO_SENSOR_HEIGHT = "meta.json gives no sensor height"
#: the start of the warning line of an uncalibrated step length (dropped for a model that reads no profile, W461)
NO_CALIBRATION = "no per-user calibration"
FOOT_PER_HEIGHT = 0.152  # foot length / body height
# Pendulum gain K without calibration (decision W46): mobgap's SlZijlstra default scaling factor
# (step_length_scaling_factor_ms_ms = 4.587 / 4, optimised on the Mobilise-D MS project), the same
# whole-step-h inverted pendulum (Zijlstra & Hof 2003) on the sensor height as here (W10)
DEFAULT_K = 4.587 / 4
# Between-subject spread of K about DEFAULT_K for `calibrate --shrink` (decision W48, not the default): method of
# moments over the three mobgap subjects' Test5 calibration walks (HA001, HA002, MS001), as
# `experiments/waist_k_shrinkage.py` prints it ("tau from all three subjects")
TAU_K = 0.0403
# Step length vs frequency default (decision W6): 0.415 x height at 1.8 Hz, slope 0.25 x height per Hz.
STEP_PER_HEIGHT_AT_F0 = 0.415
F0_HZ = 1.8  # seed 000 sec. II-C: free-running walking frequency 1.8 Hz
SLOPE_PER_HEIGHT = 0.25
# Decision W118: the frequency line is read at the frequency a leg of this length would have at the same
# dimensionless frequency f sqrt(L / g) (Hof 1996, Gait & Posture 4:222-223): the default height's leg, so a 1.70 m
# adult without a leg length keeps W6's line exactly
SL_LEG_REF_M = LEG_PER_HEIGHT * DEFAULT_HEIGHT_M
RUN_STEP_PER_HEIGHT_AT_3HZ = 0.65
RUN_SLOPE_PER_HEIGHT = 0.20


#: decision B210: the parameters that must be positive when given (a negative ``walk_threshold_mps2`` gated
#: every sample as walking)
POSITIVE_KEYS = ("walk_threshold_mps2",)


def misplaced_option_error(d: dict, unknown: list[str], where: str) -> None:
    """Decision B472: raise one DataError when every unknown top-level key of the waist parameters ``d`` is a
    waist track option (:data:`pdrlearn.track.waist.OPTION_DEFAULTS`), which a PARAMS.json sets under "options":
    the line gives the corrected JSON (``{"mount_drift": true}`` -> ``{"options": {"mount_drift": true}}``).
    Returns None otherwise (the caller's "not a waist parameter file" line)."""
    from pdrlearn.track.waist import OPTION_DEFAULTS  # lazy: only on this error path (the track module is heavy)

    if not unknown or not set(unknown) <= set(OPTION_DEFAULTS):
        return
    moved = {k: v for k, v in d.items() if k not in unknown}
    opts = d.get("options") if isinstance(d.get("options"), dict) else {}
    moved["options"] = {**opts, **{k: d[k] for k in unknown}}
    raise DataError(f"{where}: {', '.join(unknown)} {'is a track option' if len(unknown) == 1 else 'are track options'}"
                    f", set under \"options\": give {json.dumps(moved)} ({decision_ref('B472')})")


@dataclass
class WaistParams:
    """Parameters of both waist pipelines (SI units).

    leg_m : leg length L of the pendulum (m); k, f_m : pendulum gain K and double-stance term F (m)
    (seed 003 eq. 1); a_walk, b_walk / a_run, b_run : ``SL = a f - b`` (m/Hz, m) for walking and running
    (seed 001 eq. 23, piecewise per seed 000 sec. II-D); gyro_bias_rps : vertical gyro bias (rad/s,
    seed 003 eq. 2); turn_gmm : ``{"means": [...], "sds": [...], "weights": [...]}`` of the straight /
    turning classifier on |MRZ| (rad/s); walk_threshold_mps2 : motion gate; source : "defaults" or
    "calibrated"; pipeline : the pipeline the step length was calibrated for; options : pipeline options
    (``realtime``, ``heading``, ``integrate_stops`` ..., see :data:`pdrlearn.track.waist.OPTION_DEFAULTS`);
    sl_leg_m : the leg length L (m) of the frequency line's dimensionless frequency (decision W118: the line is read
    at f sqrt(L / :data:`SL_LEG_REF_M`); NaN: at f, W6's line);
    rate_hz : the waist accelerometer's rate (Hz) of the walks the step length was calibrated on (decision W87;
    NaN when not recorded: defaults, or a file written before W87); k_shrinkage : the calibrated K's standard
    error and what shrinking it toward :data:`DEFAULT_K` gives (decision
    W48: ``k_cal``, ``se``, ``n_strides``, ``k0``, ``tau``, ``k_shrunk``, ``k``, ``applied``); gait : the calibration
    walks' ``median_cadence_spm``, ``step_length_m``, ``speed_mps`` and ``n_steps`` (decision W140; None: defaults, or
    a file written before W140); length_models : the gains ``pdrlearn calibrate --length-model NAME`` fitted, as
    ``{NAME: {GAIN_SETTING: value}}`` (decision W460: ``{"weinberg": {"k": 0.43}}``; None: none fitted);
    detector : the step detector whose contacts the step length was calibrated on, as ``NAME:key=value,...`` (the
    settings that differ from its defaults; decision W471: ``calibrate --detector``); None: the pipeline's own;
    notes : how each value was obtained.
    """

    leg_m: float = float("nan")
    k: float = DEFAULT_K  # seed 003 eq. 1's K; without calibration mobgap's population factor (W46)
    f_m: float = float("nan")
    a_walk: float = float("nan")
    b_walk: float = float("nan")
    a_run: float = float("nan")
    b_run: float = float("nan")
    gyro_bias_rps: float = 0.0
    turn_gmm: dict | None = None
    walk_threshold_mps2: float | None = None
    source: str = "defaults"
    pipeline: str | None = None
    options: dict | None = None
    k_shrinkage: dict | None = None
    gait: dict | None = None
    rate_hz: float = float("nan")
    sl_leg_m: float = float("nan")
    length_models: dict | None = None
    detector: str | None = None
    notes: list[str] = field(default_factory=list)

    def frequency_scale(self) -> float:
        """Decision W118: sqrt(``sl_leg_m`` / :data:`SL_LEG_REF_M`), the factor from a step frequency to the frequency
        the frequency line is read at (1: today's line, also when ``sl_leg_m`` is not set)."""
        leg = self.sl_leg_m
        return float(np.sqrt(leg / SL_LEG_REF_M)) if leg is not None and np.isfinite(leg) and leg > 0 else 1.0

    def to_dict(self) -> dict:
        d = asdict(self)
        d["schema"] = SCHEMA
        return {k: (None if isinstance(v, float) and not np.isfinite(v) else v) for k, v in d.items()}

    @classmethod
    def from_dict(cls, d: dict, where: str = "params") -> WaistParams:
        if not isinstance(d, dict):
            raise DataError(f"{where}: waist parameters must be a JSON object")
        names = {f.name for f in fields(cls)}
        unknown = sorted(set(d) - names - {"schema", "fit", "paths_redacted", "pdrlearn_version",  # E136; E176
                                           "frames"})  # E367: the calibration walks' waist frame
        if unknown:
            misplaced_option_error(d, unknown, where)  # decision B472: a track option given at the top level
            more = f" and {len(unknown) - 5} more" if len(unknown) > 5 else ""
            raise DataError(f"{where}: not a waist parameter file (unknown key(s) {', '.join(unknown[:5])}{more}); "
                            "pass the PARAMS.json written by `pdrlearn calibrate`")
        kw = {}
        for k, v in d.items():
            if k not in names:
                continue
            if k == "detector":  # decision W471: the spec calibrate --detector recorded, or null
                if v is not None and not (isinstance(v, str) and v.strip()):
                    raise DataError(f"{where}: detector {json.dumps(v)} is not a step detector's name; give the "
                                    "--detector NAME the file was calibrated with, null for the pipeline's own, or "
                                    "re-run 'pdrlearn calibrate' (decision W471)")
                kw[k] = v
                continue
            if k in ("turn_gmm", "notes", "source", "pipeline", "options", "k_shrinkage", "gait", "length_models"):
                if (k in ("turn_gmm", "options", "k_shrinkage", "gait", "length_models") and v is not None
                        and not isinstance(v, dict)):
                    raise DataError(f"{where}: {k} must be a JSON object")
                if k == "gait" and v is not None:
                    _check_gait(v, where)  # decision B198
                if k == "length_models" and v is not None:
                    _check_length_models(v, where)  # decision W460
                kw[k] = v
                continue
            if v is None:
                kw[k] = float("nan") if k != "walk_threshold_mps2" else None
                continue
            try:
                kw[k] = float(v)
            except (TypeError, ValueError):
                raise DataError(f"{where}: parameter {k}={v!r} is not a number") from None
            if k in POSITIVE_KEYS and not kw[k] > 0:  # decision B210: a negative motion gate had been used
                raise DataError(f"{where}: parameter {k}={v!r} is not a positive number; fix it, set it to null "
                                "(the default), or re-run 'pdrlearn calibrate'")
        return cls(**kw)

    def save(self, path: str | os.PathLike, *, extra: dict | None = None) -> Path:
        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        from pdrlearn import __version__

        d = self.to_dict()
        d["pdrlearn_version"] = __version__  # decision E136: a calibration file is reused across trials
        if extra:
            d.update(extra)
        tmp = path.with_suffix(path.suffix + ".tmp")
        tmp.write_text(json.dumps(d, indent=2) + "\n")
        os.replace(tmp, path)
        return path


#: decision W140's ``gait`` record: its numbers (positive, or null when not recorded)
GAIT_KEYS = ("median_cadence_spm", "step_length_m", "speed_mps", "n_steps", "cadence_range_spm")  # range: W211
#: decision B198: each a positive number, or null when not recorded (B206's shared check)
GAIT_RULES = {k: Rule("number", low=0, open_low=True, none=True) for k in GAIT_KEYS[:4]}


def _check_gait(gait: dict, where: str) -> None:
    """Decision B198: a ``gait`` record (W140) whose numbers are not positive numbers (null: not recorded) is one line;
    its cadence is divided by and its step and speed printed in W140's warning (a text had been a traceback, a
    negative cadence a negative ``calibration_cadence_ratio``)."""
    unknown = sorted(set(gait) - set(GAIT_KEYS))
    if unknown:  # decision B210: a misspelt key ("cadence_spm") had been ignored
        raise DataError(f"{where}: gait has no key(s) {', '.join(unknown)}; decision W140's record of the calibration "
                        f"walks holds {', '.join(GAIT_KEYS)}; fix it, set \"gait\" to null, or re-run 'pdrlearn "
                        "calibrate'")
    bad = broken(gait, GAIT_RULES)
    rng = gait.get("cadence_range_spm")
    if rng is not None and not _cadence_range_ok(rng):  # decision W211: [lowest, highest] walk cadence
        bad.append(("cadence_range_spm", rng, "[lowest, highest], two positive numbers in order"))
    if bad:
        raise DataError(f"{where}: gait {broken_line(bad)} (decision W140's record of the "
                        "calibration walks); fix it, set \"gait\" to null, or re-run 'pdrlearn calibrate'")


def _check_length_models(models: dict, where: str) -> None:
    """Decision W460: ``length_models`` is ``{NAME: {SETTING: positive number}}`` (a gain ``calibrate
    --length-model`` fitted); anything else is one line."""
    for name, gains in models.items():
        ok = isinstance(gains, dict) and all(
            isinstance(v, int | float) and not isinstance(v, bool) and math.isfinite(v) and v > 0
            for v in gains.values())
        if not ok:
            raise DataError(f"{where}: length_models {name!r} is {json.dumps(gains)}; give {{SETTING: positive "
                            "number}} (e.g. \"weinberg\": {\"k\": 0.43}), set length_models to null, or re-run "
                            "'pdrlearn calibrate --length-model NAME' (decision W460)")


def _cadence_range_ok(rng) -> bool:
    if not isinstance(rng, (list, tuple)) or len(rng) != 2:
        return False
    if not all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) and v > 0 for v in rng):
        return False
    return rng[0] <= rng[1]


def load_params(params) -> WaistParams | None:
    """``None`` | :class:`WaistParams` | dict | path to a PARAMS.json -> :class:`WaistParams` or ``None``."""
    if params is None or isinstance(params, WaistParams):
        return params
    if isinstance(params, dict):
        return WaistParams.from_dict(params)
    if is_inline_json(params):  # decision B466 (trial T2 F10 of session 48: the lower back read it as a file name)
        text = str(params).strip()
        try:
            d = parse_json(text)
        except json.JSONDecodeError as exc:
            raise DataError(f"--params {text}: not a file, and not a JSON object either ({exc.msg} at character "
                            f"{exc.pos}); pass a file, or quote the JSON") from None
        return WaistParams.from_dict(d, where=f"--params {text}")
    p = Path(params)
    if not p.is_file():
        raise DataError(f"{p}: parameter file not found; write one with 'pdrlearn calibrate'")
    try:
        d = read_json(p)
    except json.JSONDecodeError as exc:
        raise DataError(f"{p}: invalid JSON (line {exc.lineno}); re-run 'pdrlearn calibrate'") from None
    return WaistParams.from_dict(d, where=str(p))


def _subject(meta: dict) -> dict:
    sub = meta.get("subject")
    return sub if isinstance(sub, dict) else {}


def _meta_number(meta: dict, *keys: str) -> float | None:
    found = _meta_numbers(meta, *keys)
    return found[0][1] if found else None


def _meta_numbers(meta: dict, *keys: str) -> list[tuple[str, float]]:
    """Every usable (finite, positive) value of ``keys`` in meta.json, as ``(key as written, value)``, in the order
    they are taken: the ``subject`` object's before the top level's, each in the order of ``keys``."""
    got = []
    for prefix, src in (("subject.", _subject(meta)), ("", meta)):
        for k in keys:
            v = src.get(k)
            if isinstance(v, int | float) and not isinstance(v, bool) and np.isfinite(v) and v > 0:
                got.append((prefix + k, float(v)))
    return got


def leg_length_note(meta: dict) -> str | None:
    """Decision B155: where the pendulum's leg length comes from, one line: the meta.json key used (``leg_length_m``
    is taken before ``sensor_height_m``, waist decision W10's ``L``) and the values not used; ``None`` when meta.json
    gives neither (then 0.53 x height, warned)."""
    found = _meta_numbers(meta, "leg_length_m", "sensor_height_m")
    if not found:
        return None
    (key, leg), rest = found[0], found[1:]
    unused = "; not used: " + ", ".join(f"{k} {v:g} m" for k, v in rest) if rest else ""
    return (f"leg length {leg:.3f} m from meta.json {key} (leg_length_m is taken before sensor_height_m{unused}; "
            "decision B155)")


def subject_height(meta: dict | None, *, infer: bool = False) -> tuple[float, str | None]:
    """``(height m, warning)``: meta.json's ``height_m``, else :data:`DEFAULT_HEIGHT_M`. Decision W115: the leg
    length meta.json gives (``leg_length_m``, else ``sensor_height_m``: the pendulum's L, W10) / :data:`LEG_PER_HEIGHT`
    (the inverse of the default that derives the leg from the height) is the height it implies: the warning names it
    (a 0.57 m sensor height is a ~1.1 m child, not a 1.70 m adult), and with ``infer`` it is used (not the default:
    its adoption rule failed, docs/decisions/waist.md W115). The warning is None when ``height_m`` is given."""
    meta = meta or {}
    height = _meta_number(meta, "height_m")
    if height is not None:
        return height, None
    found = _meta_numbers(meta, "leg_length_m", "sensor_height_m")
    if not found:
        return DEFAULT_HEIGHT_M, f"meta.json gives no subject height: assumed {DEFAULT_HEIGHT_M} m"
    key, leg = found[0]
    implied = leg / LEG_PER_HEIGHT
    if infer:
        return implied, (f"meta.json gives no subject height: {implied:.2f} m inferred from its {key} {leg:g} m / "
                         f"{LEG_PER_HEIGHT} (decision W115; give meta.json height_m, the uncalibrated step length "
                         "scales with it)")
    return DEFAULT_HEIGHT_M, (f"meta.json gives no subject height: assumed {DEFAULT_HEIGHT_M} m, though its {key} "
                              f"{leg:g} m implies about {implied:.2f} m ({key} / {LEG_PER_HEIGHT}, decision W115); the "
                              "uncalibrated step length scales with the height: give meta.json height_m")


def line_leg_m(meta: dict | None, height: float) -> float:
    """Decision W118: the leg length L (m) of the frequency line's dimensionless frequency: meta.json's
    ``leg_length_m``, else :data:`LEG_PER_HEIGHT` x ``height`` (not the sensor height: the pendulum's L, W10)."""
    leg = _meta_number(meta or {}, "leg_length_m")
    return leg if leg is not None else LEG_PER_HEIGHT * height


def default_params(session: Session, *, infer_height: bool = False) -> tuple[WaistParams, list[str]]:
    """Defaults from ``meta.json`` (height, sensor height / leg length, foot length) and the warnings
    that say what was assumed; ``infer_height``: without ``height_m`` the height the leg length implies (decision
    W115, an option: :func:`subject_height`)."""
    meta = session.meta or {}
    warnings = [f"{NO_CALIBRATION}: step length from meta.json defaults "
                "(run 'pdrlearn calibrate' on walks of known length, 20 steps or more: decision W169)"]
    notes = []
    height, line = subject_height(meta, infer=infer_height)  # W115: the warning names the height the leg implies
    if line:
        warnings.append(line)
    leg = _meta_number(meta, "leg_length_m", "sensor_height_m")  # B155: leg_length_m first (leg_length_note)
    if leg is None:
        leg = LEG_PER_HEIGHT * height
        notes.append(f"leg length {leg:.3f} m = {LEG_PER_HEIGHT} x height")
        # decision W62: the pendulum's step length scales with sqrt(leg); a guessed leg says so on one line
        warnings.append(f"{NO_SENSOR_HEIGHT}: leg length assumed {leg:.3f} m = {LEG_PER_HEIGHT} x height "
                        f"{height:.2f} m (the pendulum step length grows with its square root); give the unit's "
                        "height with 'pdrlearn import --sensor-height M' or meta.json sensor_height_m")
    else:
        notes.append(leg_length_note(meta))
    foot = _meta_number(meta, "foot_length_m")
    if foot is None:
        cm = _meta_number(meta, "foot_length_cm")
        foot = cm / 100.0 if cm is not None else None
    if foot is None:
        foot = FOOT_PER_HEIGHT * height
        notes.append(f"foot length {foot:.3f} m = {FOOT_PER_HEIGHT} x height")
    a_w = SLOPE_PER_HEIGHT * height
    b_w = a_w * F0_HZ - STEP_PER_HEIGHT_AT_F0 * height
    a_r = RUN_SLOPE_PER_HEIGHT * height
    b_r = a_r * 3.0 - RUN_STEP_PER_HEIGHT_AT_3HZ * height
    notes.append(f"height {height:.2f} m -> SL = {a_w:.3f} f - {b_w:.3f} (walking)")
    # seed 003 sec. 3.2 relates F to the foot size for an h measured over the single stance; h is measured
    # over the whole step here (decision W10), so F defaults to 0 (Zijlstra & Hof) and the foot length is
    # only recorded in the notes
    notes.append(f"foot length {foot:.3f} m (not used: F = 0 with whole-step h)")
    notes.append(f"K = {DEFAULT_K:.3f} (mobgap SlZijlstra's population factor, decision W46)")
    p = WaistParams(leg_m=leg, k=DEFAULT_K, f_m=0.0, a_walk=a_w, b_walk=b_w, a_run=a_r, b_run=b_r,
                    source="defaults", notes=notes)
    return p, warnings


#: decision W87: a calibrated step length applied at a rate more than this fraction off its calibration rate warns
#: (the trial's K: 1.0674 at 100 Hz, 1.1032 at 25 Hz; cross-applied -3.75 / +3.13 % distance); B22's 10 %
from pdrlearn.kernels.waist import RATE_MISMATCH  # noqa: E402,F401  (W92)


def rate_mismatch(p: WaistParams, session: Session, where: str = "the waist parameters") -> str | None:
    """Decision W87: the warning line when ``p`` was calibrated at a waist rate more than :data:`RATE_MISMATCH` off
    the session's waist accelerometer rate, else ``None``."""
    if p.source != "calibrated" or not np.isfinite(p.rate_hz) or not session.has("wAccelerometer"):
        return None
    from pdrlearn.kernels.waist import rate_mismatch_line

    return rate_mismatch_line(p.rate_hz, float(session["wAccelerometer"].rate_hz), where)


#: decision W542: a calibration's leg length more than this fraction off the tracked session's own (meta.json) warns
LEG_MISMATCH = 0.05


def leg_mismatch(p: WaistParams, session: Session, where: str = "the waist parameters") -> str | None:
    """Decision W542 (trial T2 finding F5: another subject's calibration file was applied without a word, +5.48 %
    distance): the warning line when a calibration's leg length ``p.leg_m`` is more than :data:`LEG_MISMATCH` off the
    leg the session's own meta.json gives (``leg_length_m``, else ``sensor_height_m``, as B155 reads it), else None;
    nothing when meta.json gives neither (the calibration's leg then stands alone)."""
    leg = _meta_number(session.meta or {}, "leg_length_m", "sensor_height_m")
    if p.source != "calibrated" or leg is None or not np.isfinite(p.leg_m) or not leg > 0:
        return None
    off = p.leg_m / leg - 1.0
    if abs(off) <= LEG_MISMATCH:
        return None
    return (f"{where} was calibrated for a leg of {p.leg_m:.3f} m, but this session's meta.json gives {leg:.3f} m "
            f"({100 * -off / (1 + off):+.1f} %): another subject's calibration? calibrate this subject on a walk of "
            f"known length, or correct meta.json (decision W542)")


def resolve_params(session: Session, params) -> tuple[WaistParams, list[str]]:
    """User parameters completed with the session's defaults for any value left undefined."""
    user = load_params(params)
    base, warnings = default_params(session)
    if user is None:
        return base, warnings
    merged = WaistParams(**{f.name: getattr(user, f.name) for f in fields(WaistParams)})
    filled = set()
    for f in fields(WaistParams):
        v = getattr(merged, f.name)
        if isinstance(v, float) and not np.isfinite(v):
            setattr(merged, f.name, getattr(base, f.name))
            filled.add(f.name)
    where = str(params) if isinstance(params, str | os.PathLike) else "the waist parameters"
    lines = [x for x in (rate_mismatch(merged, session, where), leg_mismatch(merged, session, where)) if x]  # W87, W542
    return merged, _default_lines(warnings, user, filled) + lines


def _default_lines(warnings: list[str], user: WaistParams, filled: set[str]) -> list[str]:
    """Decision B241: :func:`default_params`' lines that still hold for parameters ``user`` completed with the
    defaults in ``filled`` (the fields it left undefined). None for a calibration (``source`` "calibrated", as
    before: it holds the values its pipeline uses and fills the others, unused). Otherwise "no per-user
    calibration", the height line while a value derived from the height (``a_walk`` / ``b_walk`` / ``a_run`` /
    ``b_run`` / ``leg_m``) was filled and the leg-length line while ``leg_m`` was. A file holding only ``"options"``
    keeps all three: the track is as uncalibrated as without it."""
    if user.source == "calibrated":
        return []
    keep = []
    for w in warnings:
        if w.startswith(NO_CALIBRATION):
            ok = True
        elif w.startswith("meta.json gives no subject height"):
            ok = bool(filled & {"a_walk", "b_walk", "a_run", "b_run", "leg_m"})
        elif w.startswith(NO_SENSOR_HEIGHT):
            ok = "leg_m" in filled
        else:
            ok = False
        keep += [w] if ok else []
    return keep
