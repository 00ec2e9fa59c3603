"""PLASYS step rules (thesis ch.7.2.2): terrain picks the distance, direction the sign of ``length_m``, the length
class clamps the distance, stairs give the altitude change. The track places a stride whose sign the class turned
with its heading turned 180 deg (decision L65), so the position follows the measured displacement either way."""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.displace import _kernels as K
from pdrlearn.errors import DataError
from pdrlearn.kernels import bayes as KB

#: Thesis ch.6.3 length classes (per step): short <= 0.30 m, normal 0.30-0.45 m, long > 0.45 m.
#: The upper bound of "long" is open; 10 m stands for "no bound".
THESIS_STEP_BOUNDS: dict[str, tuple[float, float]] = {
    "short": (0.0, 0.30),  # thesis ch.6.3 / ch.7.2.2 ("corrected to 30cm")
    "normal": (0.30, 0.45),  # thesis ch.6.3
    "long": (0.46, 10.0),  # thesis ch.7.2.2 ("minimum value on which a Long step can fit, which is 46cm")
}


def parse_bounds(obj) -> dict[str, tuple[float, float]]:
    """Length-class bounds from a manifest entry: ``{"short": [lo, hi], ...}`` or a list of edges
    ``[e1, e2]`` (short < e1 <= normal < e2 <= long), in metres."""
    if obj is None:
        return dict(THESIS_STEP_BOUNDS)
    if isinstance(obj, dict):
        out = {}
        for k, v in obj.items():
            lo, hi = (float(x) if x is not None else np.inf for x in v)
            out[str(k)] = (0.0 if not np.isfinite(lo) else lo, hi if np.isfinite(hi) else 10.0)
        return out
    edges = [float(e) for e in obj]
    if len(edges) != 2 or not edges[0] < edges[1]:
        raise DataError(f"length-class bounds {obj!r}: expected two increasing edges in metres")
    return {"short": (0.0, edges[0]), "normal": (edges[0], edges[1]), "long": (edges[1], 10.0)}


def model_length_bounds(model):
    """The user's length-class bounds a trained model carries (``pdrlearn train``'s ``length_bounds_m``: in its
    settings or training summary, or set on the object), or None. One reading for ``pdrlearn track`` and
    ``pdrlearn export`` (decision L59: a model without them gets none, not the thesis fallback)."""
    bounds = None
    for holder in (getattr(model, "settings", None) or {}, getattr(model, "data_summary", None) or {}):
        for key in ("length_bounds_m", "length_bounds"):
            if key in holder:
                bounds = holder[key]
    return getattr(model, "length_bounds_m", bounds)


def _class_proba(classes: pd.DataFrame, task: str, names: list[str], labels: np.ndarray) -> np.ndarray:
    """(B, C) probabilities of ``names`` from ``p_<task>_<name>`` columns, else one-hot of ``labels``."""
    cols = [f"p_{task}_{c}" for c in names]
    if all(c in classes for c in cols):
        p = classes[cols].to_numpy(dtype=float)
        p = np.where(np.isfinite(p), p, 0.0)
        s = p.sum(axis=1, keepdims=True)
        return np.where(s > 0, p / np.where(s > 0, s, 1.0), 1.0 / len(names))
    return (np.asarray(labels, dtype=object)[:, None] == np.array(names, dtype=object)[None, :]).astype(float)


class StepRules:
    """Apply the PLASYS rules to per-stride displacements.

    Parameters
    ----------
    bounds : length class -> (min, max) in metres of the unit the displacement is measured for (a
        foot-unit stride); default: the thesis step bounds scaled by ``bounds_scale``
    bounds_scale : factor applied to the default bounds (2.0 turns thesis step bounds into stride bounds)
    down_mode : ``"projected"`` (the default since decision L178; L51: the thesis' eq. 61 norm is the path
        length, its horizontal part moves x/y), ``"norm3"`` (thesis eq. 61, the norm itself moves x/y) or
        ``"horizontal"`` for descending stairs
    clamp, sign, altitude : switch each rule on/off (for ablations)
    mode : ``"thesis"`` (the class prevails: sign flip, hard clamp, altitude from the terrain class) or
        ``"bayes"`` (docs/decisions/localization.md L14): the length is the posterior mean given the
        class probabilities and the estimate's uncertainty, the direction class decides only an
        ambiguous sign (|length| < 2 sigma), and a clear vertical change (|dz| > ``dz_min``) keeps its
        estimated sign whatever the terrain class
    sigma_rel, sigma_min : standard deviation of a stride-length estimate: max(sigma_rel |L|, sigma_min) (m)
    dz_min : vertical change (m) above which the estimate is trusted in "bayes" mode
    """

    def __init__(self, *, bounds: dict[str, tuple[float, float]] | None = None, bounds_scale: float = 1.0,
                 down_mode: str = K.DEFAULT_DOWN_MODE, clamp: bool = True, sign: bool = True, altitude: bool = True,
                 mode: str = "thesis", sigma_rel: float = KB.SIGMA_REL, sigma_min: float = KB.SIGMA_MIN,
                 dz_min: float = KB.DZ_MIN):
        if down_mode not in K.DOWN_MODES:
            raise DataError(f"StepRules: down_mode '{down_mode}' is not one of {', '.join(K.DOWN_MODES)}")
        if mode not in ("thesis", "bayes"):
            raise DataError(f"StepRules: mode '{mode}' is not 'thesis' or 'bayes'")
        self.mode = mode
        self.sigma_rel = sigma_rel
        self.sigma_min = sigma_min
        self.dz_min = dz_min
        self.bounds = bounds
        self.bounds_scale = bounds_scale
        self.down_mode = down_mode
        self.clamp = clamp
        self.sign = sign
        self.altitude = altitude

    def effective_bounds(self) -> dict[str, tuple[float, float]]:
        if self.bounds is not None:
            return dict(self.bounds)
        sc = self.bounds_scale
        return {k: (lo * sc, hi * sc) for k, (lo, hi) in THESIS_STEP_BOUNDS.items()}

    def apply(self, disp: np.ndarray, classes: pd.DataFrame) -> pd.DataFrame:
        """Per-stride ``length_m`` (signed; what moves x/y) and ``dz_m`` from displacements (B, 3) and classes.
        A stride classed down gets the horizontal part of the thesis' 3-axis norm (``"projected"``, the default
        since decision L178; L51: the path length is ``hypot(length_m, dz_m)``), the norm itself (``"norm3"``:
        the norm moves x/y) or the horizontal distance (``"horizontal"``).

        ``classes`` has ``terrain``, ``direction``, ``length_class``; a missing value means "no rule":
        horizontal distance and the estimated vertical change / the sign of the estimate / no clamp.
        """
        disp = np.asarray(disp, dtype=float).reshape(-1, 3)
        n = disp.shape[0]
        if len(classes) != n:
            raise DataError(f"StepRules: {n} displacements but {len(classes)} rows of classes")
        terrain = classes["terrain"].to_numpy(dtype=object) if "terrain" in classes else np.full(n, None)
        known_terrain = pd.notna(terrain)
        dist = K.terrain_distance(disp, terrain, down_mode=self.down_mode)
        est_sign = np.where(disp[:, 0] < 0, -1.0, 1.0)
        length = dist * est_sign
        sigma = np.maximum(self.sigma_rel * dist, self.sigma_min)
        bayes = self.mode == "bayes"
        if self.sign and "direction" in classes:
            d = classes["direction"].to_numpy()
            known = pd.notna(d) & ((dist < 2 * sigma) if bayes else True)
            length = np.where(known, K.apply_direction(length, np.where(known, d, "forward")), length)
        if self.clamp and "length_class" in classes:
            lc = classes["length_class"].to_numpy(dtype=object)
            bounds = self.effective_bounds()
            if bayes:
                names = list(bounds)
                proba = _class_proba(classes, "length", names, lc)
                has = pd.notna(lc)
                mag = K.bayes_length(dist, np.where(has[:, None], proba, 1.0 / len(names)),
                                     [bounds[c] for c in names], sigma)
                length = np.where(has, np.sign(length) * mag, length)
            else:
                length = K.clamp_length(length, np.where(pd.notna(lc), lc, ""), bounds)
        dz = disp[:, 2].copy()
        if self.altitude:
            ruled = np.where(known_terrain, K.altitude_change(disp[:, 2], terrain), dz)
            dz = np.where(np.abs(dz) > self.dz_min, dz, ruled) if bayes else ruled
        length = K.horizontal_part(length, dz, terrain, down_mode=self.down_mode)  # decision L51
        return pd.DataFrame({"length_m": length, "dz_m": dz, "raw_dx_m": disp[:, 0], "raw_dy_m": disp[:, 1],
                             "raw_dz_m": disp[:, 2]})


#: decision L325: a stride whose length the length-class rule sets to more than this times its measured length is
#: "doubled" (trial 31 finding 4: 0.70 m slow strides classed long were set to 1.62 m, x2.3)
DOUBLED_FACTOR = 2.0
#: decision L325: the doubled strides warn when they add more than this share to the track's measured distance:
#: five times the default (bayes) rules' distance error on trial 31's 16 simulated tracks (within +-0.9 %), so a
#: turn's short stride clamped up alone stays silent
DOUBLED_SHARE = 0.05


def doubled_lengths_line(raw_m: np.ndarray, ruled_m: np.ndarray, classes) -> str | None:
    """Decision L325: one line when the thesis length-class clamp (``--rules thesis``) set strides to more than
    :data:`DOUBLED_FACTOR` times their measured horizontal length ``raw_m`` (m) and those strides add more than
    :data:`DOUBLED_SHARE` of the measured distance; None otherwise. ``ruled_m``: the rules' signed lengths;
    ``classes``: the length class per stride (named in the line)."""
    raw, ruled = np.abs(np.asarray(raw_m, float)), np.abs(np.asarray(ruled_m, float))
    ok = np.isfinite(raw) & np.isfinite(ruled)
    doubled = ok & (ruled > DOUBLED_FACTOR * raw)
    total = float(raw[ok].sum())
    added = float((ruled[doubled] - raw[doubled]).sum())
    if not doubled.any() or total <= 0 or added <= DOUBLED_SHARE * total:
        return None
    lc = pd.Series(np.asarray(classes, dtype=object)[doubled]).dropna().value_counts()
    named = ", ".join(f"{n} {c}" for c, n in lc.items()) or "unclassed"
    return (f"the thesis length-class rule (--rules thesis) set {int(doubled.sum())} of {int(ok.sum())} strides to "
            f"more than {DOUBLED_FACTOR:g}x their measured length ({named}; measured median "
            f"{np.median(raw[doubled]):.2f} m, set to median {np.median(ruled[doubled]):.2f} m), adding "
            f"{added:.1f} m (+{100 * added / total:.0f} % of the measured {total:.1f} m): the classes disagree with "
            "the strides (a slow or short gait outside the training walks?); the default rules (--rules bayes) weigh "
            "the class against the measured length (decision L325)")
