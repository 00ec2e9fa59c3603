"""Decision C157: an option's help that lists the step detectors or the step-length models reads their registries
(:data:`pdrlearn.steps.DETECTORS`, :data:`pdrlearn.waist.lengths.STEP_LENGTHS`) when the help is shown, so a new
built-in or a plug-in (``--plugin``, an entry point) appears in the help of ``steps``, ``track`` and ``track-all``
with no list of names to edit. The help text holds a placeholder (:data:`DETECTOR_NAMES`, :data:`LENGTH_NAMES`);
``import pdrlearn.cli`` and the root ``--help`` stay free of the numerical libraries (decision C14): a registry is
imported only when the help of an option that names it is formatted."""

from __future__ import annotations

import sys

#: C157 amended (session 41, lead): the built-ins as the help shows them while their registry is not imported yet.
#: Importing a registry loads scipy and pandas (a `steps --help` took 2.1-2.5 s of CPU instead of 0.5-0.7 s), so the
#: help reads these names and the installed plug-ins' entry-point names (not loaded), and reads the registry itself
#: once it is imported (a plug-in registered by `--plugin` or from Python). tests/test_builtins_listed_c157.py pins
#: both tuples to the registries' built-ins, so a new built-in still fails that test until it is listed here.
BUILTIN_DETECTORS = {"foot": ("accel", "accel-force"), "waist": ("pelvic-gyro", "pll", "waist-ic")}
BUILTIN_LENGTHS = ("pendulum", "frequency", "weinberg:k=...")

#: the placeholders an option's help may hold, each replaced by its registry's names when the help is shown
DETECTOR_NAMES = "{DETECTOR_NAMES}"
LENGTH_NAMES = "{LENGTH_NAMES}"
#: the text shown when a registry cannot be imported (a package of the toolkit is missing, decision E190)
UNREADABLE = "a registered name (docs/extending.md)"


def detector_names() -> str:
    """The registered step detectors by unit, in registration order: ``accel, accel-force (foot strides) |
    pelvic-gyro, pll, waist-ic (waist steps)``."""
    said = {"foot": "foot strides", "waist": "waist steps"}
    if "pdrlearn.steps.detectors" not in sys.modules:
        shown = " | ".join(f"{', '.join(names)} ({said[unit]})" for unit, names in BUILTIN_DETECTORS.items())
        return shown + _entry_points("pdrlearn.detectors")
    try:
        from pdrlearn.steps.detectors import DETECTORS
    except ImportError:
        return UNREADABLE
    said = {"foot": "foot strides", "waist": "waist steps"}
    groups = {unit: [n for n in DETECTORS if DETECTORS[n].unit == unit] for unit in said}
    return " | ".join(f"{', '.join(names)} ({said[unit]})" for unit, names in groups.items() if names)


def length_names() -> str:
    """The registered step-length models in registration order; one whose defaults cannot run (its
    ``example_settings``, e.g. weinberg's gain) is shown with the settings to give: ``weinberg:k=...``."""
    if "pdrlearn.waist.lengths" not in sys.modules:
        return ", ".join(BUILTIN_LENGTHS) + _entry_points("pdrlearn.step_lengths")
    try:
        from pdrlearn.waist.lengths import STEP_LENGTHS
    except ImportError:
        return UNREADABLE
    return ", ".join(name + "".join(f"{':' if i == 0 else ','}{k}=..." for i, k in
                                    enumerate(getattr(STEP_LENGTHS[name], "example_settings", None) or {}))
                     for name in STEP_LENGTHS)


def _entry_points(group: str) -> str:
    """`` | plug-ins: a, b`` for the installed plug-ins of an entry-point group (their names only, nothing loaded)."""
    from pdrlearn.lockdown import installed_entry_points

    names = sorted({ep.name for ep in installed_entry_points(group)})  # decision E263: as the registries load them
    return f" | plug-ins: {', '.join(names)}" if names else ""


FILLERS = {DETECTOR_NAMES: detector_names, LENGTH_NAMES: length_names}


def fill_registry_help(command) -> None:
    """Replace the placeholders in the help of ``command``'s options by the registries' names as they are now (the
    template is kept on the option, so a plug-in registered later shows in the next help)."""
    for param in getattr(command, "params", ()):
        template = getattr(param, "_pdrlearn_help_template", None) or getattr(param, "help", None)
        if not template or not any(p in template for p in FILLERS):
            continue
        param._pdrlearn_help_template = template
        text = template
        for placeholder, names in FILLERS.items():
            if placeholder in text:
                text = text.replace(placeholder, names())
        param.help = text
