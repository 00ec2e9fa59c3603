"""``python -m pdrlearn`` runs the command-line interface; :func:`console` is the ``pdrlearn`` script too."""

import sys

from pdrlearn.install import FULL_INSTALL, missing_full_package, missing_package_line  # noqa: F401 (B157)


def console() -> int:
    """Run ``pdrlearn`` (:func:`pdrlearn.cli.main`); in a runtime-only install, where it lacks one of
    :data:`FULL_INSTALL`, one ``error:`` line naming the package, how to install the toolkit and the lean command
    instead of a traceback (decisions B157, E190)."""
    try:
        from pdrlearn.cli import main

        return main()
    except ModuleNotFoundError as exc:
        name = missing_full_package(exc)
        if name is None:
            raise
        print(f"error: {missing_package_line('the pdrlearn command', name)}", file=sys.stderr)  # decision E190
        return 2


if __name__ == "__main__":
    sys.exit(console())
