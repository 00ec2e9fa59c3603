"""``python -m pdrlearn`` runs the command-line interface; :func:`console` is the ``pdrlearn`` script too."""

import sys

from pdrlearn.install import FULL_INSTALL, INSTALL_EVERYTHING, missing_full_package  # noqa: F401 (B157)


def console() -> int:
    """Run ``pdrlearn`` (:func:`pdrlearn.cli.main`); in a runtime-only install, where it lacks one of
    :data:`FULL_INSTALL`, one ``error:`` line naming the lean command instead of a traceback (decision B157)."""
    try:
        from pdrlearn.cli import main

        return main()
    except ModuleNotFoundError as exc:
        name = missing_full_package(exc)
        if name is None:
            raise
        print(f"error: the pdrlearn command needs {name}, which is not installed (a runtime-only install); replay a "
              "session through a bundle with `python -m pdrlearn.runtime BUNDLE SESSION`, or install everything: "
              f"{INSTALL_EVERYTHING}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(console())
