"""Decision W413 (session 39, closing re-read of session 38): the module-level switches of adopted rules are gone -
the rule is the code (or, for the fused climb bias, a keyword of its kernel with the adopted default) - and no
experiment or test sets one of those names on a module any more (a ``setattr`` of a removed global would silently
do nothing)."""

from __future__ import annotations

import importlib
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
#: module -> the adopted rules' switches W413 removed
REMOVED = {
    "pdrlearn.kernels.barometer": ("FUSED_CLIMB_BIAS", "FUSED_CLIMB_BIAS_MODE"),  # L479 / L503: fuse_altitude keywords
    "pdrlearn.kernels.stride": ("WAIST_GAP_WHOLE", "WAIST_GAP_FOOT_HEADING"),  # L498, E114
    "pdrlearn.track.clinical": ("STRIDE_WINDOW_RHYTHM", "RHYTHM_MOVEMENTS"),  # L482, L500 / L501
    "pdrlearn.track.plasys": ("COMPASS_MOUNT_CHECK", "FOOT_WALK_REFERENCE"),  # D25, L494
    "pdrlearn.track.labelled_asymmetry": ("LABELLED_ASYMMETRY",),  # L416
    "pdrlearn.track.speed_domain": ("SPEED_CRUISE", "CRUISE_CONTIGUOUS"),  # L480 / L481 (rule B)
}


@pytest.mark.parametrize("module", sorted(REMOVED))
def test_adopted_rules_have_no_module_switch_w413(module):
    mod = importlib.import_module(module)
    assert [n for n in REMOVED[module] if hasattr(mod, n)] == []


def switch_setters(names) -> list[str]:
    """``file:line`` of every line in pdrlearn / experiments / tests that sets one of the module globals ``names``
    (``mod.NAME = ...`` or a ``setattr(..., "NAME", ...)``: a removed global set would silently do nothing)."""
    alt = "|".join(names)
    pattern = re.compile(rf"\.(?:{alt})\s*=[^=]|setattr\([^)]*[\"'](?:{alt})[\"']")
    return [f"{p.relative_to(ROOT)}:{i}" for folder in ("pdrlearn", "experiments", "tests")
            for p in sorted((ROOT / folder).rglob("*.py"))
            for i, text in enumerate(p.read_text().splitlines(), 1) if pattern.search(text)]


def test_no_experiment_or_test_sets_a_removed_switch_w413():
    assert switch_setters([n for ns in REMOVED.values() for n in ns]) == []


def test_the_fused_climb_bias_defaults_are_the_adopted_ones_w413():
    import inspect

    from pdrlearn.kernels.barometer import fuse_altitude

    params = inspect.signature(fuse_altitude).parameters
    assert (params["climb_bias"].default, params["bias_mode"].default) == (True, "scale")  # L479, L503
