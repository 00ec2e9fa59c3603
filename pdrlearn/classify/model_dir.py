"""The per-user model directory: ``manifest.json`` + one joblib file per fitted model.

Layout (``SCHEMA_VERSION`` 1)::

    MODEL_DIR/
      manifest.json                      schema, versions, user, tasks/classes, units, feature spec,
                                         n_samples, sampling rates, training summary, CV metrics, files
      models/<task>__<method>__<unit>.joblib

The directory is written to a temporary sibling and renamed into place, so a reader never sees a
half-written model. The joblib files are for the training side (Python, scikit-learn, torch); the runtime
bundle (ONNX, no pickles) is written by ``pdrlearn.export``. Every file's SHA-256 is in the manifest and
checked on load.

joblib files are pickle: loading one runs the code it names. The checksums catch a damaged or half-copied
file, not a deliberate change (whoever edits a file can update its checksum in the manifest), so load model
directories only from sources you trust and exchange bundles instead (docs/deploying.md, "Model folders are
pickle"; decision B125). ``PDRLEARN_NO_PICKLE=1`` refuses every model directory before any file is unpickled
(:func:`refuse_pickle`, decision E260): a locked-down install then loads bundles only.
"""

from __future__ import annotations

import hashlib
import json
import logging
import warnings
from pathlib import Path

from pdrlearn.atomic import atomic_directory
from pdrlearn.buildinfo import git_stamp
from pdrlearn.errors import ModelError, shell_quote
from pdrlearn.listed_files import climbs_out, linked_message, linked_outside
from pdrlearn.textfile import read_json

log = logging.getLogger(__name__)

SCHEMA_VERSION = 1
MANIFEST = "manifest.json"


def _sha256(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def feature_spec(est) -> dict:
    """What an estimator computes from the step windows (transformer + params + feature names, DTW
    signals, or its fused members)."""
    from sklearn.pipeline import Pipeline

    from pdrlearn.classify.fusion import UnitFusionClassifier

    if isinstance(est, UnitFusionClassifier):
        return {
            "fusion": "weighted soft vote",
            "members": {name: feature_spec(e) for name, e, _ in est.units},
        }
    if isinstance(est, Pipeline):
        first = est.steps[0][1]
        if est.steps[0][0] == "signals":
            return {
                "dtw_signals": list(first.kw_args["names"]),
                "classifier": type(est.steps[-1][1]).__name__,
            }
        spec = {
            "transformer": type(first).__name__,
            "params": {k: (list(v) if isinstance(v, tuple) else v) for k, v in first.get_params().items()},
            "classifier": type(est.steps[-1][1]).__name__,
        }
        try:
            spec["features"] = [str(n) for n in first.get_feature_names_out()]
        except Exception:  # noqa: BLE001 - names are informative only
            pass
        return spec
    return {"classifier": type(est).__name__}


def manifest_of(model, files: dict[str, str]) -> dict:
    """The manifest dictionary of a :class:`~pdrlearn.classify.training.UserModel`."""
    import sklearn

    import pdrlearn
    from pdrlearn.classify.domain import has_ranges

    tasks = {}
    for name, tm in model.tasks.items():
        tasks[name] = {
            "classes": list(tm.classes),
            "chosen": {"method": tm.chosen[0], "unit": tm.chosen[1]} if tm.chosen else None,
            "models": {m: sorted(per) for m, per in tm.models.items()},
            "cv": tm.cv,
            "fusion_weights": tm.fusion_weights,
            "skipped": tm.skipped,
            "n_steps": tm.n_steps,
            "n_skipped_labels": tm.n_skipped_labels,
            "trained_kinds": tm.trained_kinds,  # decision C161: side / turn steps in the training data
            # decision C16: which models keep the training range of their inputs (the ranges are pickled with
            # each model; absent or false in models saved before C16)
            "training_ranges": {m: {u: has_ranges(est) for u, est in per.items()} for m, per in tm.models.items()},
            "feature_spec": {
                m: {u: feature_spec(est) for u, est in per.items()} for m, per in tm.models.items()
            },
        }
    units = sorted({u for tm in model.tasks.values() for per in tm.models.values() for u in per})
    return {
        "schema_version": SCHEMA_VERSION,
        "kind": "pdrlearn user model",
        "package_version": pdrlearn.__version__,
        **git_stamp(),  # decision E158: the commit of the code that trained the model
        "versions": {
            "scikit-learn": sklearn.__version__,
            "torch": torch_version(),
            "numpy": __import__("numpy").__version__,
        },
        "user": model.user,
        "created": model.created,
        "tasks": tasks,
        "units": units,
        "n_samples": model.n_samples,
        "sampling_rate_hz": model.sampling_rate_hz,
        "training_data": model.data_summary,
        "settings": model.settings,
        "skipped": model.skipped,
        "files": files,
    }


def torch_version() -> str:
    """Decision E267: ``torch.__version__`` (local label included, B355), read from torch's ``version.py`` without
    importing torch (about 1.9 s per process that saves a model, scikit-learn-only models included); the import
    when torch is already imported or its ``version.py`` cannot be read."""
    import ast
    import importlib.util
    import sys

    if "torch" not in sys.modules:
        try:
            spec = importlib.util.find_spec("torch")
            locations = list(spec.submodule_search_locations or ()) if spec is not None else []
            for folder in locations:
                tree = ast.parse((Path(folder) / "version.py").read_text(encoding="utf-8"))
                for node in tree.body:
                    if isinstance(node, ast.Assign) and any(isinstance(t, ast.Name) and t.id == "__version__"
                                                            for t in node.targets):
                        value = ast.literal_eval(node.value)
                        if isinstance(value, str):
                            return value
        except (OSError, SyntaxError, ValueError, UnicodeDecodeError):
            pass
    import torch

    return str(torch.__version__)


def check_out_dir(path) -> Path:
    """Check that ``path`` may receive a model directory: absent, empty or a previous model directory."""
    path = Path(path)
    if path.exists() and not path.is_dir():
        raise ModelError(f"{path}: is a file, not a model directory; choose another --out")
    if path.exists() and not (path / MANIFEST).exists() and any(path.iterdir()):
        raise ModelError(f"{path}: exists and is not a model directory; choose another --out")
    return path


def save_model(model, path) -> Path:
    """Write ``model`` to the directory ``path`` atomically (temp dir + rename); returns ``path``."""
    import joblib

    path = check_out_dir(path)
    with atomic_directory(path) as tmp:
        (tmp / "models").mkdir()
        files = {}
        for task, tm in model.tasks.items():
            for method, per in tm.models.items():
                for unit, est in per.items():
                    rel = f"models/{task}__{method}__{unit}.joblib"
                    joblib.dump(est, tmp / rel)
                    files[rel] = _sha256(tmp / rel)
        manifest = manifest_of(model, files)
        (tmp / MANIFEST).write_text(json.dumps(manifest, indent=2, allow_nan=False, default=_json_default))
    log.info("model written to %s (%d files)", path, len(files))
    return path


def _json_default(o):
    """Like :func:`pdrlearn.io.plasys.json_default`, but any other object is written as its ``str``."""
    from pdrlearn.io.plasys import json_default

    try:
        return json_default(o)
    except TypeError:
        return str(o)


def read_manifest(path) -> dict:
    """Read and validate ``manifest.json`` of a model directory (:class:`ModelError` on any problem)."""
    path = Path(path)
    if not path.is_dir():
        from pdrlearn.runtime.bundle import _is_waist_calibration, waist_only_hint

        if _is_waist_calibration(path):  # decision E53: the belt-phone user's file names their way
            raise ModelError(f"{path}: a waist calibration ('pdrlearn calibrate'), not a model directory: waist "
                             f"pipelines are calibrated, not trained; {waist_only_hint(str(path))}")
        raise ModelError(f"{path}: no such model directory; train one with "
                         f"`pdrlearn train ... --out {shell_quote(path)}`")
    mf = path / MANIFEST
    if not mf.is_file():
        hint = " -- it is a session folder (arguments swapped?)" if any(path.glob("*Accelerometer.csv")) else ""
        raise ModelError(f"{path}: missing {MANIFEST}; not a model directory written by 'pdrlearn train' (pass "
                         f"that folder, or retrain if its manifest was deleted){hint}")
    try:
        manifest = read_json(mf)
    except (OSError, json.JSONDecodeError) as exc:
        raise ModelError(f"{mf}: unreadable manifest ({exc}); retrain the model") from None
    if isinstance(manifest, dict) and manifest.get("schema") == "pdrlearn-bundle":
        raise ModelError(
            f"{path}: an exported runtime bundle, not a model directory; pass the folder written by "
            "'pdrlearn train', or replay sessions through the bundle with 'pdrlearn run'"
        )
    if not isinstance(manifest, dict) or manifest.get("schema_version") != SCHEMA_VERSION:
        got = manifest.get("schema_version") if isinstance(manifest, dict) else None
        raise ModelError(
            f"{mf}: schema version {got!r}, this pdrlearn reads version {SCHEMA_VERSION}; "
            "retrain the model with this version"
        )
    for key in ("tasks", "files", "n_samples", "user"):
        if key not in manifest:
            raise ModelError(f"{mf}: missing key '{key}'; retrain the model")
    problem = manifest_type_problem(manifest)
    if problem:  # decision B208: a wrong type had been an AttributeError / KeyError traceback
        raise ModelError(f"{mf}: {problem}; retrain the model (or restore its manifest.json)")
    return manifest


def manifest_type_problem(manifest: dict) -> str | None:
    """Decision B208: what is wrong with the types of a model manifest that has every key, or None: ``files`` an
    object of checksums, ``n_samples`` a whole number, ``tasks`` an object of tasks each with a ``classes`` list and
    ``models`` (method -> list of units), and a ``chosen`` (null or method / unit) among those models."""
    if not isinstance(manifest["files"], dict) or not all(isinstance(v, str) for v in manifest["files"].values()):
        return f"'files' is {manifest['files']!r:.40}, not an object of file: sha256"
    n = manifest["n_samples"]
    if isinstance(n, bool) or not isinstance(n, int) or n < 0:
        return f"'n_samples' is {n!r:.40}, not a whole number"
    tasks = manifest["tasks"]
    if not isinstance(tasks, dict):
        return f"'tasks' is {tasks!r:.40}, not an object of task: {{classes, models, chosen}}"
    for name, t in tasks.items():
        if not isinstance(t, dict) or not isinstance(t.get("classes"), list):
            return f"task '{name}' is not an object with a 'classes' list"
        models = t.get("models")
        if not isinstance(models, dict) or not all(isinstance(u, list) and all(isinstance(x, str) for x in u)
                                                   for u in models.values()):
            return f"task '{name}': 'models' is {models!r:.40}, not an object of method: [unit, ...]"
        chosen = t.get("chosen")
        if chosen is None:
            continue
        if not isinstance(chosen, dict) or chosen.get("method") not in models or \
                chosen.get("unit") not in models[chosen["method"]]:
            return (f"task '{name}': chosen {chosen!r:.60} is not one of its models "
                    f"({', '.join(f'{m}/{u}' for m, us in models.items() for u in us) or 'none'})")
    return None


#: decision B211: the libraries whose versions a model manifest records (``versions``) -> their distribution names
VERSIONED = {"scikit-learn": "scikit-learn", "torch": "torch", "numpy": "numpy"}


def release(version: str) -> str:
    """Decision B355: a version without its PEP 440 local label (``2.13.0+cpu`` -> ``2.13.0``): the same release
    built for another platform (PyPI's torch on Python 3.13 reports the label, ``importlib.metadata`` may not)."""
    return str(version).split("+", 1)[0]


def version_differences(manifest: dict) -> dict[str, str]:
    """Decision B211: ``{name: "their version (this is ours)"}`` for pdrlearn and each library of
    :data:`VERSIONED` whose release differs from this Python's (local labels ignored, B355)."""
    from importlib.metadata import PackageNotFoundError, version

    from pdrlearn import __version__

    differ = {}
    theirs = manifest.get("package_version")
    if theirs is not None and str(theirs) != __version__:
        differ["pdrlearn"] = f"{theirs} (this is {__version__})"
    libs = manifest.get("versions")
    for name, v in (libs.items() if isinstance(libs, dict) else ()):
        if name not in VERSIONED or v is None:
            continue
        try:
            here = version(VERSIONED[name])
        except PackageNotFoundError:
            here = "not installed"
        if release(v) != release(here):
            differ[name] = f"{v} (this is {here})"
    return differ


def version_warning(path, manifest: dict) -> str | None:
    """Decision B211 (B137's line for bundles, for model directories): one line when the model was trained by another
    pdrlearn version or with other library versions than this Python's (``package_version``, ``versions``). It still
    loads (the schema version is the contract, checked by :func:`read_manifest`)."""
    differ = version_differences(manifest)
    if not differ:
        return None
    return (f"model {path}: trained with {', '.join(f'{n} {d}' for n, d in differ.items())}; it loads (same schema "
            f"version {manifest.get('schema_version')}), but retrain it with these versions if its classes look wrong")


def verify_model_dir(path) -> dict:
    """Validate a model directory without loading it: manifest schema, every listed file inside the folder once its
    links are followed (decision E269, E263's shared check), present and unchanged (SHA-256). Returns the manifest;
    raises :class:`ModelError` (one line) otherwise."""
    path = Path(path)
    manifest = read_manifest(path)
    for rel, digest in manifest["files"].items():
        f = path / rel
        if climbs_out(rel):  # decision E269: E263's rule for bundles (an absolute entry loaded a pickle anywhere)
            raise ModelError(f"{path}: model file entry '{rel}' points outside the model folder; retrain the model "
                             "(or restore its manifest.json)")
        target = linked_outside(path, rel)  # decision E269: a link out would unpickle a file no one copied with it
        if target is not None:
            raise ModelError(f"{path}: model {linked_message(rel, target, 'model')}")
        if not f.is_file():
            raise ModelError(f"{path}: model file {rel} is missing; retrain the model")
        if _sha256(f) != digest:
            raise ModelError(f"{path}: model file {rel} was altered (checksum mismatch); retrain the model")
    return manifest


#: decision B355 amended (review R4): where scikit-learn raises its InconsistentVersionWarning (estimators'
#: ``__setstate__``, ``warnings.warn`` without stacklevel: attributed to sklearn.base)
SKLEARN_VERSION_WARNING_MODULE = r"sklearn\.base\Z"


def _ignore_sklearn_version_blocks() -> None:
    """Decision B355 amended (review R4): ignore scikit-learn's InconsistentVersionWarning raised in sklearn.base
    (a block per estimator, repeating :func:`version_warning`'s one line), by one filter added to the process's list
    once: the first load of a model from another scikit-learn adds it, later loads find it. Not
    ``warnings.catch_warnings()``: it saves and restores the whole process-wide list, so loads in threads at once
    could undo each other's (or any other thread's) filters. The filter stays for the process."""
    from sklearn.exceptions import InconsistentVersionWarning

    if not any(action == "ignore" and category is InconsistentVersionWarning
               and getattr(module, "pattern", None) == SKLEARN_VERSION_WARNING_MODULE
               for action, _message, category, module, _line in warnings.filters):
        warnings.filterwarnings("ignore", category=InconsistentVersionWarning, module=SKLEARN_VERSION_WARNING_MODULE)


def refuse_pickle(path) -> None:
    """Decision E260: raise :class:`ModelError` (one line naming the folder and bundles) when ``PDRLEARN_NO_PICKLE``
    is on (:mod:`pdrlearn.lockdown`), before anything of the folder is read; :func:`load_model` and the CLI's early
    ``--model`` checks call it. Decision E266: silent for a path that is no folder or is a runtime bundle (its
    manifest.json, JSON, says so): the caller's own line names what it is (a missing folder, a bundle)."""
    from pdrlearn.lockdown import NO_PICKLE_ENV, switch, switch_text

    value = switch(NO_PICKLE_ENV)
    if value is None:
        return
    from pdrlearn.outfolder import manifest_kind

    if not Path(path).is_dir() or manifest_kind(Path(path)) == "a runtime bundle":  # decision E266
        return
    raise ModelError(f"{path}: a model folder is pickle (loading it runs any code its files hold) and "
                     f"{switch_text(NO_PICKLE_ENV, value, 'refuses model folders')}; use its bundle instead "
                     "(`pdrlearn export` it where it is trusted, then `pdrlearn run BUNDLE ...` or `pdrlearn evaluate "
                     f"BUNDLE ...`), or unset {NO_PICKLE_ENV} to load a folder you trust")


def load_model(path):
    """Load a model directory written by :meth:`UserModel.save` -> :class:`UserModel`.

    The files are unpickled (joblib): only load directories from a trusted source (see the module docstring);
    ``PDRLEARN_NO_PICKLE=1`` refuses every one (:func:`refuse_pickle`, decision E260).

    Raises :class:`ModelError` (one line) for a missing directory/manifest/model file, a changed file
    (SHA-256 mismatch) or another schema version.
    """
    path = Path(path)
    refuse_pickle(path)  # decision E260: before any file of the folder is read (or joblib imported)
    import joblib

    from pdrlearn.classify.training import TaskModel, UserModel

    manifest = verify_model_dir(path)
    line = version_warning(path, manifest)
    if line:  # decision B211
        log.warning(line)
    models: dict[str, object] = {}
    if "scikit-learn" in version_differences(manifest):  # decision B355: the line above says it once
        _ignore_sklearn_version_blocks()
    for rel in manifest["files"]:
        f = path / rel
        try:
            models[rel] = joblib.load(f)
        except (ModuleNotFoundError, AttributeError) as exc:  # decision B173: a class the pickle names is missing
            raise ModelError(
                f"{f}: cannot be loaded ({type(exc).__name__}: {exc}): the model holds a class this Python cannot "
                "import (your own estimator's module?); put its folder on PYTHONPATH (or import the module before "
                "loading; the CLI: --plugin MODULE, decision C121), or install the pdrlearn version that trained it"
            ) from None
        except Exception as exc:  # noqa: BLE001 - any other unpickling failure is a model problem
            raise ModelError(
                f"{f}: cannot be loaded ({type(exc).__name__}: {exc}); retrain the model"
            ) from None
    tasks = {}
    for name, t in manifest["tasks"].items():
        tm = TaskModel(
            name,
            list(t["classes"]),
            cv=t.get("cv", {}),
            fusion_weights=t.get("fusion_weights", {}),
            skipped=t.get("skipped", []),
            n_steps=t.get("n_steps", 0),
            n_skipped_labels=t.get("n_skipped_labels", 0),
            trained_kinds=t.get("trained_kinds"),  # decision C161: None in a model saved before it
        )
        for method, units in t["models"].items():
            for unit in units:
                rel = f"models/{name}__{method}__{unit}.joblib"
                if rel not in models:
                    raise ModelError(
                        f"{path}: manifest lists {method}/{unit} for {name} but not its file {rel}"
                    )
                tm.models.setdefault(method, {})[unit] = models[rel]
        chosen = t.get("chosen")
        tm.chosen = (chosen["method"], chosen["unit"]) if chosen else None
        tasks[name] = tm
    return UserModel(
        user=manifest["user"],
        tasks=tasks,
        n_samples=int(manifest["n_samples"]),
        sampling_rate_hz=manifest.get("sampling_rate_hz", {}),
        data_summary=manifest.get("training_data", {}),
        settings=manifest.get("settings", {}),
        created=manifest.get("created", ""),
        skipped=manifest.get("skipped", []),
    )
