"""What a runtime-only install lacks, and how to install the rest (decisions B157, E185, B354, E190, E191).

Standard library only: ``import pdrlearn``, the ``pdrlearn`` script and the lean runtime read it in a venv with
numpy alone.
"""

#: the packages of the full install that a runtime-only one (numpy [+ onnxruntime], decision E76) lacks and the
#: ``pdrlearn`` commands import (pyproject's dependencies, by import name, and what those bring that pdrlearn
#: imports: click, joblib, distributed, threadpoolctl)
FULL_INSTALL = frozenset({"typer", "click", "rich", "pandas", "scipy", "sklearn", "torch", "cv2", "matplotlib",
                          "dtaidistance", "onnx", "skl2onnx", "dask", "distributed", "tabulate", "joblib",
                          "threadpoolctl"})

#: the distribution to name where its import name differs (``import sklearn`` is scikit-learn's)
DISTRIBUTION = {"sklearn": "scikit-learn", "cv2": "opencv-python-headless"}

#: decision E185: the distribution name is not on PyPI (trial T5: `pip index versions pdrlearn` found nothing, and
#: a later package of that name would be someone else's), so the advice names the wheel or the clone; decision
#: E191: installing either (without --no-deps) brings every required package, the toolkit's
INSTALL_EVERYTHING = ("pip install PATH/pdrlearn-*.whl (the wheel) or pip install PATH/TO/CLONE "
                      "(pdrlearn is not on PyPI)")

#: decision B354: where a runtime-only install reads and replays a session
LEAN_ROUTE = ("python -m pdrlearn.runtime BUNDLE SESSION, or in Python pdrlearn.runtime.load_bundle and "
              "pdrlearn.runtime.replay.read_streams")


def missing_full_package(exc: ModuleNotFoundError) -> str | None:
    """The package of :data:`FULL_INSTALL` whose absence raised ``exc``; None for any other missing module. Decision
    E190 amended (review R1): a missing submodule (``scipy.signal.windows``) of a package that is installed is None
    too (a version mismatch or a broken install, which "not installed" would hide)."""
    import importlib.util

    full = exc.name or ""
    top = full.split(".")[0]
    if top not in FULL_INSTALL:
        return None
    if full == top:
        return top
    try:
        absent = importlib.util.find_spec(top) is None
    except (ImportError, ValueError):  # a broken package: not "not installed"
        absent = False
    return top if absent else None


def missing_package_line(needer: str, name: str) -> str:
    """Decision E190: the one line (without ``error:``) of ``needer`` (``the pdrlearn command``, ``pdrlearn
    train``) when package ``name`` (an import name of :data:`FULL_INSTALL`) is not installed: how to install the
    toolkit's dependencies (all required, E191), and where a runtime-only install replays a session instead."""
    dist = DISTRIBUTION.get(name, name)
    what = dist if dist == name else f"{dist} (import {name})"
    return (f"{needer} needs {what}, which is not installed; install the toolkit's dependencies: "
            f"{INSTALL_EVERYTHING}, or make venv in the clone; a runtime-only install (numpy, onnxruntime, "
            "pdrlearn --no-deps) replays a session through a bundle with `python -m pdrlearn.runtime BUNDLE SESSION`")


def lean_import_error(what: str, exc: ModuleNotFoundError) -> ModuleNotFoundError | None:
    """Decision B354: the one-line error of ``pdrlearn.<what>`` in a runtime-only install (``exc`` a missing
    package of the full install), naming the lean reader; None when ``exc`` is some other missing module."""
    name = missing_full_package(exc)
    if name is None:
        return None
    return ModuleNotFoundError(f"pdrlearn.{what} needs {name}, which is not installed (a runtime-only install); "
                               f"read and replay a session there with {LEAN_ROUTE}; or install everything: "
                               f"{INSTALL_EVERYTHING}", name=exc.name)


#: decision E277: the lean command's one line when numpy is absent (it was a ModuleNotFoundError traceback, trial T2
#: F5; onnxruntime's absence was already one line, ``runtime.bundle``)
NUMPY_MISSING = ("the pdrlearn runtime needs numpy, which is not installed; pip install numpy (and onnxruntime for "
                 "svm, nn and ensemble models; a device without network: docs/deploying.md, 'A device without "
                 "network') (decision E277)")


def runs_module(argv: list[str], module: str) -> bool:
    """Whether the interpreter command line ``argv`` (``sys.orig_argv``) runs ``python [options] -m module``."""
    i = 1
    while i < len(argv):
        a = argv[i]
        if a == "-m":
            return i + 1 < len(argv) and argv[i + 1] == module
        if a.startswith("-m"):
            return a[2:] == module
        if a == "-c" or not a.startswith("-") or a == "-":  # a command, a script or stdin: not -m
            return False
        i += 2 if a in ("-X", "-W") else 1  # the two options whose value is the next argument
    return False


def numpy_missing(exc: ModuleNotFoundError) -> None:
    """Decision E277: numpy is absent. Under ``python -m pdrlearn.runtime`` (the package is imported before its
    ``__main__`` can catch anything) one ``error:`` line on stderr and exit 2, as every other problem of the lean
    command; in a program's ``import pdrlearn.runtime`` a ModuleNotFoundError with that line."""
    import sys

    if runs_module(list(getattr(sys, "orig_argv", [])), "pdrlearn.runtime"):
        print(f"error: {NUMPY_MISSING}", file=sys.stderr)
        raise SystemExit(2)
    raise ModuleNotFoundError(NUMPY_MISSING, name="numpy") from exc
