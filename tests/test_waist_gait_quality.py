"""Decision W350: a lower-back track's bouts.csv gives each walking bout's gait quality - harmonic ratios (Menz et al.
2003), autocorrelation step / stride regularity and step symmetry (Moe-Nilssen & Helbostad 2004) and acceleration
RMS - in :data:`pdrlearn.waist.gait_quality.QUALITY_COLUMNS`; a bout under 10 strides leaves them empty."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.track.bouts import BOUT_COLUMNS
from pdrlearn.waist.gait_quality import MIN_STRIDES, NOT_VALIDATED, QUALITY_COLUMNS, bout_quality, harmonic_ratio

FS = 100.0


def test_harmonic_ratio_of_known_harmonics():
    """A stride of harmonic 2 (amplitude 3) and harmonics 1 and 3 (1 and 0.5): even / odd = 3 / 1.5 = 2; ML's
    odd / even = 0.5; one harmonic only: NaN denominators give NaN."""
    n = 120
    ph = 2 * np.pi * np.arange(n) / n
    x = 0.7 + np.cos(ph) + 3 * np.cos(2 * ph + 0.4) + 0.5 * np.sin(3 * ph)
    assert harmonic_ratio(x) == pytest.approx(2.0)
    assert harmonic_ratio(x, odd_over_even=True) == pytest.approx(0.5)
    assert np.isnan(harmonic_ratio(np.cos(ph), odd_over_even=True))


def _walk(n_contacts: int, limp: float = 0.0):
    """A synthetic lower back: contacts every 0.55 s (the left ones ``limp`` longer), each step a vertical and AP
    bump, the ML sway one cycle per stride."""
    steps = np.where(np.arange(n_contacts) % 2, 0.55 * (1 + limp), 0.55 * (1 - limp))
    c = 1.0 + np.concatenate([[0.0], np.cumsum(steps[:-1])])
    t = np.arange(0, c[-1] + 1.0, 1 / FS)
    k = np.clip(np.searchsorted(c, t, side="right") - 1, 0, n_contacts - 2)
    phase = (t - c[k]) / (c[k + 1] - c[k])  # 0..1 within each step
    bump = np.sin(2 * np.pi * phase)
    side = np.where(k % 2, 1.0, -1.0)
    return t, bump * (1 + limp * side), np.sin(np.pi * phase) * side, 2 * bump, c


def test_a_symmetric_bout_scores_above_a_limping_one():
    """The same synthetic walk, steps alternately 20 % shorter and longer: every harmonic ratio and the V step
    symmetry drop."""
    t, ap, ml, v, c = _walk(30)
    good = bout_quality(t, ap, ml, v, FS, c)
    t, ap, ml, v, c = _walk(30, limp=0.2)
    bad = bout_quality(t, ap, ml, v, FS, c)
    for col in ("hr_ap", "hr_v", "hr_ml", "step_symmetry_v"):
        assert good[col] > bad[col], col
    assert good["step_symmetry_v"] == pytest.approx(1.0, abs=0.05)
    assert 0 < good["rms_ml_ratio"] < 1


def test_a_bout_under_ten_strides_gives_null():
    t, ap, ml, v, c = _walk(MIN_STRIDES + 2)
    assert all(np.isfinite(list(bout_quality(t, ap, ml, v, FS, c).values())))
    short = bout_quality(t, ap, ml, v, FS, c[:-1])  # 9 strides
    assert set(short) == set(QUALITY_COLUMNS) and all(np.isnan(list(short.values())))


@pytest.fixture(scope="module")
def tracked(tmp_path_factory):
    """Simulated users 7550 (symmetric) and 7551 (S35 / S42 limp: steps onto the left foot 30 % longer in time and
    length), 40 m, lower back only, tracked by ``pdrlearn track --pipeline waist-pendulum --gait-quality`` (W352:
    opt-in); the symmetric one also without the flag (``default``)."""
    from pdrlearn import sim
    from pdrlearn.cli import main
    from pdrlearn.io import write_session

    root = tmp_path_factory.mktemp("gq")
    out = {}
    for name, user, knobs in (("symmetric", 7550, {}),
                              ("limp", 7551, {"step_time_asymmetry": 0.3, "step_length_asymmetry": 0.3})):
        write_session(sim.simulate("walk", user, length_m=40, **knobs), root / name)
        for f in (root / name).glob("f*.csv"):
            f.unlink()
        assert main(["track", "--no-plot", str(root / name), "--pipeline", "waist-pendulum", "--gait-quality",
                     "--out", str(root / f"o{name}")]) == 0
        out[name] = root / f"o{name}"
    assert main(["track", "--no-plot", str(root / "symmetric"), "--pipeline", "waist-pendulum",
                 "--out", str(root / "odefault")]) == 0
    out["default"] = root / "odefault"
    return out


@pytest.fixture(scope="module")
def tracked_bouts(tracked):
    return {name: pd.read_csv(folder / "bouts.csv") for name, folder in tracked.items()}


@pytest.fixture(scope="module")
def tracked_summaries(tracked):
    return {name: json.loads((folder / "summary.json").read_text()) for name, folder in tracked.items()}


def test_bouts_csv_holds_the_columns_and_a_limp_lowers_them(tracked_bouts):
    assert set(QUALITY_COLUMNS) <= set(BOUT_COLUMNS)
    for name in ("symmetric", "limp"):
        b = tracked_bouts[name]
        assert list(b.columns[:len(BOUT_COLUMNS)]) == list(BOUT_COLUMNS)
        long = b[b["n_strides"] >= MIN_STRIDES]
        assert len(long) and long[list(QUALITY_COLUMNS)].notna().all().all()
        assert b.loc[b["n_strides"] < MIN_STRIDES, list(QUALITY_COLUMNS)].isna().all().all()
    sym, limp = (tracked_bouts[k].dropna(subset=["hr_ap"]) for k in ("symmetric", "limp"))
    for col in ("hr_ap", "hr_v", "hr_ml", "step_symmetry_v"):
        assert sym[col].median() > limp[col].median(), col


def test_summary_gives_the_bouts_medians(tracked_summaries):
    for name in ("symmetric", "limp"):
        gq = tracked_summaries[name]["gait_quality"]
        assert gq["n_bouts"] >= 1, name
        assert set(gq) == {"n_bouts", *QUALITY_COLUMNS}
    assert tracked_summaries["symmetric"]["gait_quality"]["hr_ap"] > tracked_summaries["limp"]["gait_quality"]["hr_ap"]


def test_without_the_flag_the_columns_stay_empty_and_no_key(tracked_bouts, tracked_summaries):
    """W352: the gait quality is opt-in; without --gait-quality bouts.csv keeps its columns (one layout) but empty,
    and summary.json has no ``gait_quality`` and no W352 warning."""
    b = tracked_bouts["default"]
    assert list(b.columns[:len(BOUT_COLUMNS)]) == list(BOUT_COLUMNS)
    assert (b["n_strides"] >= MIN_STRIDES).any()  # the flagged track of this walk filled these bouts
    assert b[list(QUALITY_COLUMNS)].isna().all().all()
    summary = tracked_summaries["default"]
    assert "gait_quality" not in summary
    assert NOT_VALIDATED not in summary.get("info", {}).get("warnings", [])


def test_the_flag_warns_once_that_the_values_are_not_validated(tracked_summaries):
    """W352: with --gait-quality one warning line (in summary.json's info.warnings too) says the values are not
    validated against real recordings and to compare within a person."""
    for name in ("symmetric", "limp"):
        warnings = tracked_summaries[name]["info"]["warnings"]
        assert warnings.count(NOT_VALIDATED) == 1, name
    assert "not validated against real recordings" in NOT_VALIDATED and "within a person" in NOT_VALIDATED
    assert "at the same walking speed" in NOT_VALIDATED  # W360: speed alone moves the regularity (trial T1 F3)


def test_the_flag_reaches_track_all():
    """W352: ``track-all`` takes --gait-quality too and passes it on (E93's settings)."""
    import inspect

    from pdrlearn.cli.cohort import track_all
    from pdrlearn.cli.track import settings_of, track_settings

    assert inspect.signature(track_all).parameters["gait_quality"].default.default is False
    assert track_settings()["gait_quality"] is False
    assert settings_of({"gait_quality": True})["gait_quality"] is True


def test_the_flag_on_a_foot_track_says_it_computes_none(tmp_path):
    """W352 amended (session 33, the lead): --gait-quality on a foot (plasys) track wrote nothing and said nothing;
    now one warning line (also in info.warnings) names the lower-back pipeline, and no key or column is filled."""
    from pdrlearn import sim
    from pdrlearn.cli import main
    from pdrlearn.io import write_session

    write_session(sim.simulate("walk", 7552, length_m=20), tmp_path / "s")
    assert main(["track", "--no-plot", str(tmp_path / "s"), "--pipeline", "plasys", "--gait-quality", "--out",
                 str(tmp_path / "o")]) == 0
    summary = json.loads((tmp_path / "o" / "summary.json").read_text())
    lines = [w for w in summary["info"]["warnings"] if w.startswith("--gait-quality:")]
    assert len(lines) == 1 and "--pipeline waist-pendulum" in lines[0] and "gait_quality" not in summary
    assert pd.read_csv(tmp_path / "o" / "bouts.csv")[list(QUALITY_COLUMNS)].isna().all().all()
