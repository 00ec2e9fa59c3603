"""Matplotlib's config folder when the home folder cannot be written (decision B226).

Matplotlib writes its font cache under ``MPLCONFIGDIR``, else ``$XDG_CONFIG_HOME/matplotlib`` or
``~/.config/matplotlib`` (``~/.matplotlib`` off Linux). When that cannot be created or written (a service account,
``nobody``, a read-only home) it makes a temporary folder itself but prints two lines ("mkdir -p failed for path
...", "Matplotlib created a temporary cache directory ...") on every command, breaking "each warning once". This
does what matplotlib then does - a temporary folder, removed at exit - silently, before matplotlib is imported.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path


def _default_dir() -> Path | None:
    """Matplotlib's default config folder (``matplotlib._get_config_or_cache_dir``), None without a home."""
    try:
        xdg = os.environ.get("XDG_CONFIG_HOME") if sys.platform.startswith(("linux", "freebsd")) else None
        home = Path.home()
    except (RuntimeError, KeyError):
        return None
    if sys.platform.startswith(("linux", "freebsd")):
        return Path(xdg) / "matplotlib" if xdg else home / ".config" / "matplotlib"
    return home / ".matplotlib"


def ensure_config_dir() -> None:
    """Before the first ``import matplotlib``: when ``MPLCONFIGDIR`` is unset and the default folder cannot be
    made or written, point ``MPLCONFIGDIR`` at a new temporary folder removed at exit (decision B226). A no-op
    once matplotlib is imported or when the user set ``MPLCONFIGDIR``."""
    if os.environ.get("MPLCONFIGDIR") or "matplotlib" in sys.modules:
        return
    default = _default_dir()
    try:
        if default is not None:
            default.mkdir(parents=True, exist_ok=True)
            if os.access(default, os.W_OK) and default.is_dir():
                return
    except OSError:
        pass
    import atexit
    import shutil
    import tempfile

    tmp = tempfile.mkdtemp(prefix="matplotlib-")
    atexit.register(shutil.rmtree, tmp, ignore_errors=True)
    os.environ["MPLCONFIGDIR"] = tmp
