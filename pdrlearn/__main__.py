"""``python -m pdrlearn`` runs the command-line interface; :func:`console` is the ``pdrlearn`` script too."""

import sys

#: the packages of the full install that a runtime-only one (numpy [+ onnxruntime], decision E76) lacks and the
#: ``pdrlearn`` commands import (pyproject's dependencies, by import name)
FULL_INSTALL = frozenset({"typer", "click", "rich", "pandas", "scipy", "sklearn", "torch", "cv2", "matplotlib",
                          "dtaidistance", "onnx", "skl2onnx", "dask", "distributed", "tabulate", "joblib"})


def console() -> int:
    """Run ``pdrlearn`` (:func:`pdrlearn.cli.main`); in a runtime-only install, where it lacks one of
    :data:`FULL_INSTALL`, one ``error:`` line naming the lean command instead of a traceback (decision B157)."""
    try:
        from pdrlearn.cli import main

        return main()
    except ModuleNotFoundError as exc:
        name = (exc.name or "").split(".")[0]
        if name not in FULL_INSTALL:
            raise
        print(f"error: the pdrlearn command needs {name}, which is not installed (a runtime-only install); replay a "
              "session through a bundle with `python -m pdrlearn.runtime BUNDLE SESSION`, or install everything: "
              "pip install pdrlearn", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(console())
