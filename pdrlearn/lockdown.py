"""The switches of a locked-down install (decisions E260, E263; docs/deploying.md "Trust: what runs code").

Environment variables, read here only: ``PDRLEARN_NO_PICKLE=1`` refuses every model folder (pickle) before any file
of it is read (:func:`pdrlearn.classify.model_dir.refuse_pickle`); ``PDRLEARN_NO_ENTRY_POINTS=1`` loads no installed
package's ``pdrlearn.*`` entry points (:func:`installed_entry_points`, which the plug-in registries and the help
read). Unset, empty or ``0`` is
off; any other value is on (a security switch fails closed), and the refusal names the value.
"""

from __future__ import annotations

import os

#: decision E260: refuse model folders (pickle); bundles still load
NO_PICKLE_ENV = "PDRLEARN_NO_PICKLE"
#: decision E263: ignore the entry points of installed packages (``--plugin`` modules, named on the command line,
#: still load)
NO_ENTRY_POINTS_ENV = "PDRLEARN_NO_ENTRY_POINTS"


def switch(name: str) -> str | None:
    """The value of the switch ``name`` when it is on (``"1"``, or the odd value given: also on), None when off."""
    value = os.environ.get(name, "").strip()
    return None if value in ("", "0") else value


def switch_text(name: str, value: str, what: str) -> str:
    """``NAME=1 <what>`` for an on switch, naming an odd value and that it counts as 1."""
    if value == "1":
        return f"{name}=1 {what}"
    return f"{name}={value!r} (neither 1 nor 0: taken as 1) {what}"


def installed_entry_points(group: str) -> list:
    """The entry points of ``group`` that installed packages declare (not loaded), or none when
    ``PDRLEARN_NO_ENTRY_POINTS`` is on (decision E263: a locked-down install runs only pdrlearn's own code and the
    ``--plugin`` modules named on the command line); the one place that lists them."""
    if switch(NO_ENTRY_POINTS_ENV) is not None:
        return []
    from importlib.metadata import entry_points

    return list(entry_points(group=group))
