"""GNSS/PDR fusion (seed 001, Basso et al. 2021): a step-triggered multi-rate Kalman filter, a finite-state
machine with best-performance and energy-saving modes, compensation of the systematic step-length and
heading errors while the receiver is off, and the per-user step-length model ``a*f - b`` refined online.

States of the receiver machine (energy-saving mode)::

    OFF --(time since last valid fix >= period_s)--> ACQUIRING   (receiver switched on)
    ACQUIRING --(ttff_s elapsed)--> ON                           (fixes available)
    ON --(valid fix used)--> OFF                                 (receiver switched off)
    ON/ACQUIRING --(max_on_s without a valid fix)--> OFF         (give up, retry after period_s)

In best-performance mode the receiver stays ON; ``mode="off"`` never switches it on (PDR only).
"""

from __future__ import annotations

import logging
from dataclasses import dataclass

import numpy as np
import pandas as pd

from pdrlearn.aid._base import ParamsMixin
from pdrlearn.aid._kernels import (
    fix_at_step,
    kf_predict,
    kf_update,
    length_scale_se,
    length_scale_windows,
    scalar_kf,
    scale_from_windows,
    stretch_between_fixes,
    wrap_angle,
)
from pdrlearn.aid.fixes import sigma_from_accuracy
from pdrlearn.errors import DataError

log = logging.getLogger(__name__)

MODES = ("best", "saving", "off")
OFF, ACQUIRING, ON = "off", "acquiring", "on"
#: chi-square 99.9 % quantile with 2 degrees of freedom: innovation gate of one 2-D fix.
CHI2_2DOF_999 = 13.82


def check_steps(steps: pd.DataFrame, what: str = "steps table") -> pd.DataFrame:
    """The steps columns the aiding filters need, sorted by ``end_s``; DataError when missing or NaN."""
    need = ("start_s", "end_s", "length_m", "heading_rad")
    if steps is None or any(c not in steps.columns for c in need):
        have = "none" if steps is None else ", ".join(map(str, steps.columns))
        raise DataError(f"{what}: needs columns {', '.join(need)} (has: {have}); run a tracking pipeline first")
    df = steps.loc[:, list(need)].astype(float)
    if not np.isfinite(df.to_numpy()).all():
        raise DataError(f"{what}: NaN/inf in {', '.join(need)}; drop the steps without length or heading")
    return df.sort_values("end_s", kind="stable").reset_index(drop=True)


def fsm_next(
    state: str,
    *,
    mode: str,
    t: float,
    switched_on_s: float,
    last_fix_s: float,
    fix_used: bool,
    period_s: float,
    ttff_s: float,
    max_on_s: float,
) -> str:
    """One transition of the receiver state machine (module docstring) at time ``t`` (s)."""
    if mode == "off":
        return OFF
    if mode == "best":
        return ON
    if state == OFF:
        return ACQUIRING if t - last_fix_s >= period_s else OFF
    if fix_used:
        return OFF
    if t - switched_on_s >= max_on_s:
        return OFF
    if state == ACQUIRING and t - switched_on_s >= ttff_s:
        return ON
    return state


@dataclass
class StepLengthModel:
    """Per-user step length ``SL = a * f - b`` (m; f in Hz) (seed 001 eq. 23), refined by recursive least
    squares from GNSS baselines (mean step frequency, mean GNSS step length) (seed 001 Sec. 2.2.5).

    The defaults give 0.70 m at 1.8 Hz and 0.55 m at 1.3 Hz (no values in seeds 000/001; decision in
    docs/decisions/aided.md). ``forgetting`` < 1 lets the model follow a changing gait.
    """

    a: float = 0.30
    b: float = -0.16
    prior_var: float = 0.05
    forgetting: float = 0.98

    def __post_init__(self) -> None:
        self.P_ = np.eye(2) * self.prior_var
        self.n_updates_ = 0

    def predict(self, freq_hz) -> np.ndarray:
        return self.a * np.asarray(freq_hz, float) - self.b

    def update(self, mean_freq_hz: float, mean_length_m: float, var_m2: float = 0.01) -> StepLengthModel:
        """One RLS step with the observation ``mean_length = a f - b`` of variance ``var_m2``."""
        h = np.array([mean_freq_hz, -1.0])
        P = self.P_ / self.forgetting
        k = P @ h / (h @ P @ h + var_m2)
        theta = np.array([self.a, self.b]) + k * (mean_length_m - h @ np.array([self.a, self.b]))
        self.a, self.b = float(theta[0]), float(theta[1])
        self.P_ = P - np.outer(k, h @ P)
        self.n_updates_ += 1
        return self


class GnssPdrFusion(ParamsMixin):
    """Step-triggered multi-rate KF with the receiver state machine (seed 001 Sec. 2.2.6, Fig. 8).

    Parameters (keyword-only)
    ----------
    mode : ``"best"`` (use every valid fix), ``"saving"`` (switch the receiver on every ``period_s``),
        ``"off"`` (PDR only).
    period_s : energy-saving interval between activations (s); seed 001 uses 60 s and 180 s.
    ttff_s : time to first fix after switching on (s) (hot start; seed 001 Sec. 2.1).
    max_on_s : give up an activation without a valid fix after this long (s).
    max_accuracy_m : fixes with a worse reported accuracy are invalid (seed 001 Fig. 10: up to 250 m).
    gate_chi2 : innovation gate (chi-square, 2 dof); ``None`` disables it.
    sigma_length_rel, sigma_length_m : step-length standard deviation = rel * length + abs (m).
    sigma_heading_rad : per-step heading standard deviation (rad).
    compensate : estimate the step-length scale and heading bias between valid fixes and apply them to
        the following steps (seed 001 Sec. 3.1.2).
    compensate_when : ``"always"`` (default: apply the compensation to every prediction once estimated) or
        ``"off"`` (only while the receiver is not ON, as seed 001 describes it); see docs/decisions/aided.md.
    heading_drift_deg_per_min, scale_drift_per_min : ``None`` (default): the compensation uses the latest
        estimate ("the last information considered valid", seed 001 Sec. 3.1.2); numbers: how fast the
        heading bias (deg/min) and the length scale (1/min) may change, and successive estimates are averaged
        by a scalar Kalman filter with these as process noise.
    min_baseline_m : minimum PDR path between two fixes used for the compensation (m); decision D36: 100 m (was
        50 m: two 5 m fixes 50 m apart give the scale +-14 % and the heading bias +-8 deg of noise; 200 m lags a
        drifting heading).
    step_length : ``"pdr"`` (the track's lengths) or ``"model"`` (a*f - b refined online from GNSS).
    model : the :class:`StepLengthModel` used with ``step_length="model"``.
    initial_sigma_m : standard deviation of the start position (m).
    sigma_bias_deg : decision D36: standard deviation (deg) of the heading's systematic error left after the
        compensation; the position variance grows by (sigma_bias x the path walked since the last used fix)^2 (a
        constant heading error grows linearly with the path, where the per-step noise grows with its square root), so
        the first fix after an outage takes the correction in full. 0 = seed 001's per-step noise only.
    smooth : decision D36: ``trajectory_``'s ``x``, ``y`` are the offline path (each jump at a used fix spread
        linearly back over the steps since the previous used fix, seed 004 eq. 26;
        :func:`~pdrlearn.kernels.fixes.stretch_between_fixes`), the causal filter in ``x_rt``, ``y_rt``; ``False``:
        ``x``, ``y`` are the causal filter (seed 001's real-time output).
    start_known : decision D38: the start position is known (``start_xy`` is where the walk starts); ``False`` (the
        walk is assumed to start at the first fix): with ``smooth`` the path before the first used fix is projected
        back from it.
    """

    def __init__(
        self,
        *,
        mode: str = "best",
        period_s: float = 60.0,
        ttff_s: float = 1.0,
        max_on_s: float = 30.0,
        max_accuracy_m: float = 50.0,
        gate_chi2: float | None = None,
        sigma_length_rel: float = 0.10,
        sigma_length_m: float = 0.02,
        sigma_heading_rad: float = np.radians(8.0),
        compensate: bool = True,
        compensate_when: str = "always",
        heading_drift_deg_per_min: float | None = None,
        scale_drift_per_min: float | None = None,
        min_baseline_m: float = 100.0,
        step_length: str = "pdr",
        model: StepLengthModel | None = None,
        initial_sigma_m: float = 1.0,
        smooth: bool = True,
        start_known: bool = True,
        sigma_bias_deg: float = 10.0,
    ):
        self.mode = mode
        self.period_s = period_s
        self.ttff_s = ttff_s
        self.max_on_s = max_on_s
        self.max_accuracy_m = max_accuracy_m
        self.gate_chi2 = gate_chi2
        self.sigma_length_rel = sigma_length_rel
        self.sigma_length_m = sigma_length_m
        self.sigma_heading_rad = sigma_heading_rad
        self.compensate = compensate
        self.compensate_when = compensate_when
        self.heading_drift_deg_per_min = heading_drift_deg_per_min
        self.scale_drift_per_min = scale_drift_per_min
        self.min_baseline_m = min_baseline_m
        self.step_length = step_length
        self.model = model
        self.initial_sigma_m = initial_sigma_m
        self.smooth = smooth
        self.start_known = start_known
        self.sigma_bias_deg = sigma_bias_deg

    def _check(self) -> None:
        if self.mode not in MODES:
            raise DataError(f"GnssPdrFusion: mode '{self.mode}' unknown; choose one of {', '.join(MODES)}")
        if self.compensate_when not in ("off", "always"):
            raise DataError(f"GnssPdrFusion: compensate_when '{self.compensate_when}' unknown; choose off or always")
        if self.step_length not in ("pdr", "model"):
            raise DataError(f"GnssPdrFusion: step_length '{self.step_length}' unknown; choose pdr or model")
        if self.mode == "saving" and not self.period_s > 0:
            raise DataError(f"GnssPdrFusion: period_s must be > 0 s in saving mode (got {self.period_s})")

    def run(
        self,
        steps: pd.DataFrame,
        fixes: pd.DataFrame | None,
        *,
        start_xy=(0.0, 0.0),
        t_start: float | None = None,
    ) -> GnssPdrFusion:
        """Fuse a steps table (``start_s``, ``end_s``, ``length_m``, ``heading_rad``) with a fix table
        (``t``, ``x``, ``y``, ``accuracy_m``; local ENU metres) and return ``self``.

        Results: ``trajectory_`` (row 0 = start, then one row per step: ``t``, ``x``, ``y``, ``x_pdr``,
        ``y_pdr``, ``sigma_m``, ``gnss``, ``fix_used``), ``fixes_used_`` (table), ``stats_`` (counts,
        ``gnss_on_fraction``), ``scale_``, ``heading_bias_rad_``, ``model_``.
        """
        self._check()
        st = check_steps(steps)
        fx = (
            pd.DataFrame(columns=["t", "x", "y", "accuracy_m"], dtype=float)
            if fixes is None
            else fixes.sort_values("t", kind="stable").reset_index(drop=True)
        )
        ft, fxy = fx["t"].to_numpy(float), fx[["x", "y"]].to_numpy(float)
        fsig = sigma_from_accuracy(fx["accuracy_m"].to_numpy(float))
        facc = fx["accuracy_m"].to_numpy(float)
        model = self.model if self.model is not None else StepLengthModel()
        t0 = float(st["start_s"].iloc[0]) if t_start is None and len(st) else float(t_start or 0.0)
        x = np.asarray(start_xy, float).copy()
        P = np.eye(2) * self.initial_sigma_m**2
        raw = x.copy()  # uncompensated PDR position
        state = ON if self.mode == "best" else (OFF if self.mode == "off" else ACQUIRING)
        switched_on, last_fix = t0, t0
        on_time, on_since = 0.0, (t0 if state != OFF else None)
        scale, bias = 1.0, 0.0
        log_scale, p_ls, p_b, t_comp = 0.0, np.inf, np.inf, None  # compensation smoother
        anchors: list[tuple] = []  # (raw xy, fix xy, sigma, path length, n steps, sum freq)
        path = 0.0
        nsteps, fsum = 0, 0.0
        counts = dict(
            fixes_total=int(len(fx)),
            fixes_used=0,
            fixes_before_ttff=0,
            fixes_inaccurate=0,
            fixes_gated=0,
            fixes_superseded=0,
            fixes_while_off=0,
            activations=1 if state == ACQUIRING else 0,
            compensations=0,
            model_updates=0,
        )
        rows = [(t0, x[0], x[1], raw[0], raw[1], self.initial_sigma_m, state, False)]
        priors = [x.copy()]  # decision D36: the prediction at each row, before a fix's update
        paths = [0.0]  # decision D39: the PDR path (m) at each row
        walked = 0.0  # decision D36: the path (m) since the last used fix
        used = []
        j = int(np.searchsorted(ft, t0, side="left"))  # next fix to look at
        j_first = j
        prev_t = t0
        prev_end = None

        def machine(s: str, t: float, fix_used: bool = False) -> str:
            return fsm_next(
                s,
                mode=self.mode,
                t=t,
                switched_on_s=switched_on,
                last_fix_s=last_fix,
                fix_used=fix_used,
                period_s=self.period_s,
                ttff_s=self.ttff_s,
                max_on_s=self.max_on_s,
            )

        for k in range(len(st)):
            t_k = float(st.at[k, "end_s"])
            dur = t_k - prev_end if prev_end is not None else float(st.at[k, "end_s"] - st.at[k, "start_s"])
            prev_end = t_k
            freq = 1.0 / dur if dur > 0 else np.nan
            # --- receiver machine up to this step
            new = machine(state, t_k)
            if state == OFF and new == ACQUIRING:
                switched_on = max(last_fix + self.period_s, prev_t)
                on_since = switched_on
                counts["activations"] += 1
                new = machine(new, t_k)
            if new == OFF and state != OFF and on_since is not None:
                on_time += t_k - on_since
                on_since = None
                last_fix = t_k  # failed activation: retry one period later
            state = new
            # --- prediction with the (compensated) step
            length = float(st.at[k, "length_m"])
            if self.step_length == "model" and np.isfinite(freq):
                length = float(np.sign(length) or 1.0) * max(float(model.predict(freq)), 0.0)
            heading = float(st.at[k, "heading_rad"])
            raw_inc = np.array([length * np.cos(heading), length * np.sin(heading)])
            raw = raw + raw_inc
            path += abs(length)
            nsteps += 1
            fsum += freq if np.isfinite(freq) else 0.0
            # systematic-error compensation only while the receiver is off (seed 001 Sec. 3.1.2)
            comp = state != ON or self.compensate_when == "always"
            lc = length * (scale if self.step_length == "pdr" and comp else 1.0)
            hc = heading + (bias if comp else 0.0)
            x, P = kf_predict(
                x,
                P,
                lc,
                hc,
                sigma_length_m=self.sigma_length_rel * abs(lc) + self.sigma_length_m,
                sigma_heading_rad=self.sigma_heading_rad,
            )
            inc = np.array([lc * np.cos(hc), lc * np.sin(hc)])
            if self.sigma_bias_deg:  # decision D36: a systematic heading error grows with the path since the last fix
                d_new = walked + abs(lc)
                P = P + np.eye(2) * np.radians(self.sigma_bias_deg) ** 2 * (d_new**2 - walked**2)
                walked = d_new
            priors.append(x.copy())
            paths.append(path)
            # --- fixes since the previous step: the latest one is extrapolated to this step
            fix_used = False
            cand = []
            while j < len(ft) and ft[j] <= t_k:
                cand.append(j)
                j += 1
            if cand:
                if state != ON:
                    counts["fixes_while_off"] += len(cand)
                else:
                    ready = [i for i in cand if ft[i] >= switched_on + self.ttff_s]
                    valid = [i for i in ready if facc[i] <= self.max_accuracy_m]
                    counts["fixes_before_ttff"] += len(cand) - len(ready)
                    counts["fixes_inaccurate"] += len(ready) - len(valid)
                    if valid:
                        i = valid[-1]
                        counts["fixes_superseded"] += len(valid) - 1  # decision D40: the latest one is used
                        z = fix_at_step(fxy[i], ft[i], t_k, prev_t, inc)  # seed 001 Sec. 2.2.6: last fix -> last step
                        xn, Pn, _, nis = kf_update(x, P, z, fsig[i : i + 1])
                        if self.gate_chi2 is not None and nis > self.gate_chi2:
                            counts["fixes_gated"] += 1
                        else:
                            x, P = xn, Pn
                            fix_used = True
                            counts["fixes_used"] += 1
                            used.append((ft[i], fxy[i, 0], fxy[i, 1], facc[i], t_k))
                            last_fix = t_k
                            walked = 0.0
                            obs = self._compensation(anchors, raw, z, fsig[i], path, nsteps, fsum, model, counts)
                            if obs is not None:
                                # scalar Kalman smoothing of log-scale and bias: each estimate has the
                                # variance (fix noise / baseline)^2; both drift between estimates
                                dt_min = (t_k - t_comp) / 60.0 if t_comp is not None else 0.0
                                if self.scale_drift_per_min is None:
                                    p_ls = np.inf  # adopt the latest estimate
                                if self.heading_drift_deg_per_min is None:
                                    p_b = np.inf
                                q_ls = (self.scale_drift_per_min or 0.0) ** 2 * dt_min**2
                                q_b = np.radians(self.heading_drift_deg_per_min or 0.0) ** 2 * dt_min**2
                                log_scale, p_ls = scalar_kf(log_scale, p_ls, np.log(obs[0]), obs[2], q_ls)
                                b_obs = bias + float(wrap_angle(obs[1] - bias))
                                bias, p_b = scalar_kf(bias, p_b, b_obs, obs[2], q_b)
                                bias = float(wrap_angle(bias))
                                scale = float(np.exp(log_scale))
                                t_comp = t_k
            if fix_used and self.mode == "saving":
                state = machine(state, t_k, fix_used=True)
                if on_since is not None:
                    on_time += t_k - on_since
                    on_since = None
            rows.append((t_k, x[0], x[1], raw[0], raw[1], float(np.sqrt(np.trace(P) / 2)), state, fix_used))
            prev_t = t_k
        t_end = rows[-1][0]
        counts["fixes_outside_track"] = j_first + (len(ft) - j)  # decision D40: before the start, after the last step
        if on_since is not None:
            on_time += t_end - on_since
        total = max(t_end - t0, 1e-9)
        traj = pd.DataFrame(rows, columns=["t", "x", "y", "x_pdr", "y_pdr", "sigma_m", "gnss", "fix_used"])
        causal = traj[["x", "y"]].to_numpy(float)
        traj.insert(3, "x_rt", causal[:, 0])
        traj.insert(4, "y_rt", causal[:, 1])
        fix_rows = traj["fix_used"].to_numpy(bool)
        if self.smooth:  # decision D36 (D38 before the first fix)
            sm = stretch_between_fixes(causal, np.asarray(priors), fix_rows, start_anchor=self.start_known)
            traj["x"], traj["y"] = sm[:, 0], sm[:, 1]
        self.trajectory_ = traj
        self.fixes_used_ = pd.DataFrame(used, columns=["t", "x", "y", "accuracy_m", "step_t"])
        # decision D39: the step-length scale GNSS measures on stretches of good fixes (not the compensation's latest)
        raw_rows = traj[["x_pdr", "y_pdr"]].to_numpy(float)[fix_rows]
        chords, lengths = length_scale_windows(
            self.fixes_used_[["x", "y"]].to_numpy(float), self.fixes_used_["t"].to_numpy(float), raw_rows,
            np.asarray(paths)[fix_rows])
        self.distance_scale_, self.distance_scale_covered_m_, self.distance_scale_windows_ = scale_from_windows(
            chords, lengths)
        self.distance_scale_se_ = length_scale_se(chords, lengths)  # decision D45
        counts["gnss_on_fraction"] = (
            0.0 if self.mode == "off" else (1.0 if self.mode == "best" else float(min(on_time / total, 1.0)))
        )
        self.stats_ = counts
        self.scale_, self.heading_bias_rad_ = scale, bias
        self.model_ = model
        return self

    def _compensation(self, anchors, raw, z, sigma, path, nsteps, fsum, model, counts):
        """Systematic-error estimate (scale, heading bias rad, variance of both) from the newest anchor at least
        ``min_baseline_m`` of path back, or ``None``."""
        anchors.append((raw.copy(), z.copy(), float(sigma), path, nsteps, fsum))
        if not self.compensate:
            return None
        base = None
        for a in reversed(anchors[:-1]):
            if path - a[3] >= self.min_baseline_m:
                base = a
                break
        if base is None:
            return None
        # keep only anchors that may still serve as a base later
        while len(anchors) > 2 and path - anchors[1][3] >= self.min_baseline_m:
            anchors.pop(0)
        d_raw, d_fix = raw - base[0], z - base[1]
        n_raw, n_fix = float(np.hypot(*d_raw)), float(np.hypot(*d_fix))
        noise = np.hypot(sigma, base[2])
        if n_raw < 1e-6 or n_fix < 10.0 * noise:  # baseline too short for the fixes' noise
            return None
        # straightness: a loop between the fixes says nothing about scale
        if n_raw < 0.5 * (path - base[3]):
            return None
        counts["compensations"] += 1
        if self.step_length == "model":
            n = nsteps - base[4]
            if n > 0:
                mean_len = (path - base[3]) * n_fix / n_raw / n  # GNSS-scaled mean step length (m)
                model.update((fsum - base[5]) / n, mean_len, var_m2=(noise / n) ** 2 + 1e-4)
                counts["model_updates"] += 1
        scale = float(np.clip(n_fix / n_raw, 0.5, 2.0))
        bias = float(wrap_angle(np.arctan2(d_fix[1], d_fix[0]) - np.arctan2(d_raw[1], d_raw[0])))
        return scale, bias, float((noise / n_fix) ** 2)
