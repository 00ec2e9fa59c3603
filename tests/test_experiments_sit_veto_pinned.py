"""Session 28 review: the lower-back measurements recorded before W185 made `sit_veto="opposite"` the offline default
(hapt.md, W190's `waist_stand.py`, L208-L211's `turns_transfers.py`) ran with no sit veto; their scripts now say
`sit_veto=False`, so a re-run reproduces the recorded numbers instead of silently measuring the new default."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def _load(name: str):
    spec = importlib.util.spec_from_file_location(f"_exp_{name}", ROOT / "experiments" / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_hapt_rows_name_their_sit_veto():
    hapt = _load("hapt")
    for label, _pipe, kw in hapt.configs(stand_veto=True):
        assert kw.get("sit_veto") is not None, label  # None would be today's default, not what hapt.md measured
        assert (kw["sit_veto"] == "rhythm") == ("sit_veto=rhythm" in label)


@pytest.mark.parametrize("pipeline", ["waist-pendulum", "waist-pll"])
def test_turns_transfers_lower_back_tracks_have_no_sit_veto(monkeypatch, pipeline):
    tt = _load("turns_transfers")
    seen = {}
    monkeypatch.setattr(tt, "track_waist", lambda s, **kw: seen.update(kw))
    tt.TRACKS[pipeline](None)
    assert seen == {"pipeline": pipeline, "sit_veto": False}


def test_hapt_and_waist_stand_measure_with_no_stand_veto():
    """W199 made ``stand_veto="adjacent"`` the offline default (W217 withdrew it); hapt.md and waist_stand.py's runs
    were measured with no
    stand veto (W190-W199), so their rows say so (the option's own row names its value)."""
    hapt = _load("hapt")
    for label, _pipe, kw in hapt.configs(stand_veto="adjacent"):
        assert kw.get("stand_veto") is not None, label
        assert (kw["stand_veto"] == "adjacent") == ("stand_veto=adjacent" in label)
    assert _load("waist_stand").OFF == {"stand_veto": False}


def test_waist_freeze_veto_measures_with_no_stand_veto(monkeypatch):
    """W219 made ``stand_veto="walking"`` the offline default; W215's numbers (``waist_freeze_veto.py``) were measured
    with no stand veto, so its tracks say so."""
    fv = _load("waist_freeze_veto")
    seen = {}

    def fake(s, **kw):
        seen.update(kw)
        raise RuntimeError("stop")

    monkeypatch.setattr(fv, "track_waist", fake)
    with pytest.raises(RuntimeError):
        fv.contacts(None, True)
    assert seen["stand_veto"] is False and seen["freeze_veto"] is True
