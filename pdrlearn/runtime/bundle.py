"""Reading and verifying a model bundle (``manifest.json`` + ONNX + JSON/NPZ files).

Imports only the standard library and numpy; onnxruntime (or OpenCV's dnn module as a fallback for
plain networks) is imported lazily when a model is first run. Every check happens in
:func:`load_bundle`, before the caller produces any output:

* the folder and ``manifest.json`` exist and parse;
* ``schema`` is ``pdrlearn-bundle`` and ``schema_version`` equals :data:`SCHEMA_VERSION`;
* every file listed in ``manifest["files"]`` exists and has the recorded sha256 (no altered files);
* no pickle ever: NPZ files are opened with ``allow_pickle=False``.

:meth:`Bundle.check_streams` compares the data's sensors and rates with the manifest's.
"""

from __future__ import annotations

import hashlib
import json
import logging
import math
import zipfile
from pathlib import Path

import numpy as np

from pdrlearn.errors import DataError, MissingSensorError, ModelError, shell_quote
from pdrlearn.listed_files import climbs_out, linked_message, linked_outside
from pdrlearn.textfile import read_json, read_text

log = logging.getLogger(__name__)

SCHEMA_NAME = "pdrlearn-bundle"
#: Version of the bundle layout; a runtime reads exactly this version (decision E2, docs/decisions/export.md).
SCHEMA_VERSION = 1
MANIFEST = "manifest.json"
#: sha256 of manifest.json itself (the manifest cannot hold its own digest)
MANIFEST_SHA = "manifest.sha256"
#: Keys every manifest carries (see docs/deploying.md for their meaning).
REQUIRED_KEYS = (
    "schema",
    "schema_version",
    "package_version",
    "created_utc",
    "user",
    "tasks",
    "sampling",
    "sensors",
    "units",
    "frames",
    "displacement",
    "training",
    "metrics",
    "files",
)
#: Relative tolerance between the manifest's sampling rate and the data's (decision E3).
DEFAULT_RATE_TOLERANCE = 0.05
#: The body units of a bundle (thesis ch.4: the foot unit and the waist unit / smartphone).
UNITS = ("foot", "waist")

def waist_only_hint(params: str | None = None) -> str:
    """Decisions B107/E53/E55, amended by E59: what a waist-only (belt phone) user can do, named where a foot-unit
    bundle or a model directory cannot serve them: export the calibration as a waist bundle (E57) and run it, or
    track the recording offline with the calibration. ``params``: the user's calibration file, if known."""
    first = ("" if params else "calibrate on a walk of known length (pdrlearn calibrate WALK --distance M --out "
             "cal.json), then ")
    p = shell_quote(params or "cal.json")
    return (f"a waist-only recording runs on a waist bundle: {first}pdrlearn export {p} --out WAIST_BUNDLE "
            "--frame x=up,y=right,z=forward (the unit's axes), then pdrlearn run WAIST_BUNDLE SESSION, or live "
            "pdrlearn.runtime.WaistTracker(load_waist_bundle('WAIST_BUNDLE')); offline: pdrlearn track SESSION "
            f"--pipeline waist-pendulum --params {p}")


def sha256_file(path: str | Path, *, chunk: int = 1 << 20) -> str:
    """Hex sha256 digest of a file."""
    h = hashlib.sha256()
    with open(path, "rb") as f:
        while block := f.read(chunk):
            h.update(block)
    return h.hexdigest()


class SharedByCopies:
    """Decision E252: a loaded model (an onnxruntime session, an OpenCV net, a verified bundle) is read-only, so a
    tracker's ``copy.deepcopy`` (:class:`pdrlearn.runtime.threads.OwnGuard`) shares it instead of copying it (an
    onnxruntime session cannot be copied: "cannot pickle ... InferenceSession")."""

    def __deepcopy__(self, memo: dict):
        return self


class OnnxModel(SharedByCopies):
    """One ONNX model of a bundle, run by onnxruntime (or ``cv2.dnn`` for a plain network).

    Parameters
    ----------
    path : the ``.onnx`` file.
    spec : its manifest entry: ``input`` (name), ``dtype`` (``float32``/``float64``), ``outputs``
        (role -> output name; roles ``label``, ``scores``, ``proba``, ``logits``), ``classes``.
    backend : ``"auto"`` (onnxruntime, else OpenCV for networks), ``"onnxruntime"`` or ``"opencv"``.
    """

    def __init__(self, path: Path, spec: dict, *, backend: str = "auto", fallback_path: Path | None = None):
        self.path = Path(path)
        self.fallback_path = fallback_path
        self.spec = spec
        self.input_name = spec.get("input", "X")
        self.dtype = np.dtype(spec.get("dtype", "float32"))
        self.outputs: dict[str, str] = dict(spec.get("outputs", {}))
        self.backend = self._open(backend)

    def _open(self, backend: str) -> str:
        if backend in ("auto", "onnxruntime"):
            try:
                import onnxruntime as ort
            except ImportError:
                if backend == "onnxruntime":
                    raise ModelError("onnxruntime is not installed; pip install onnxruntime") from None
            else:
                opts = ort.SessionOptions()
                opts.intra_op_num_threads = 1  # one step at a time: threads only add latency
                opts.inter_op_num_threads = 1
                opts.log_severity_level = 3
                try:
                    self._sess = ort.InferenceSession(str(self.path), sess_options=opts,
                                                      providers=["CPUExecutionProvider"])
                except Exception as exc:  # noqa: BLE001 - onnxruntime's own error types (InvalidProtobuf, Fail, ...)
                    why = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
                    raise ModelError(f"{self.path}: onnxruntime cannot open this model ({why}); restore the original "
                                     "bundle or re-export it with 'pdrlearn export' (decision B125)") from None
                self._names = [o.name for o in self._sess.get_outputs()]
                self._wanted = [n for n in self.outputs.values() if n in self._names]
                return "onnxruntime"
        # OpenCV fallback: plain networks only (the ai.onnx.ml SVM operators are not in cv2.dnn).
        if self.spec.get("kind") != "network":
            raise ModelError(
                f"{self.path}: needs onnxruntime (pip install onnxruntime); "
                "OpenCV's dnn module only runs the neural network"
            )
        try:
            import cv2
        except ImportError:
            raise ModelError("neither onnxruntime nor opencv is installed; pip install onnxruntime") from None
        # the float64 network graph has a float32 twin for OpenCV (cv2.dnn computes in float32 only)
        self._net = cv2.dnn.readNetFromONNX(str(self.fallback_path or self.path))
        self.dtype = np.dtype(np.float32)
        self._names = list(self.outputs.values())
        return "opencv"

    def run(self, X: np.ndarray) -> dict[str, np.ndarray]:
        """Run the model on ``(n, n_features)`` rows; returns role -> array."""
        X = np.ascontiguousarray(X, dtype=self.dtype)
        if X.ndim == 1:
            X = X[None, :]
        if self.backend == "onnxruntime":
            values = self._sess.run(self._wanted, {self.input_name: X})  # only the roles' outputs
            by_name = dict(zip(self._wanted, values, strict=True))
        else:
            self._net.setInput(X, self.input_name)
            outs = self._net.forward(self._names)
            by_name = {n: np.asarray(o, dtype=np.float64) for n, o in zip(self._names, outs, strict=True)}
        return {role: by_name[name] for role, name in self.outputs.items() if name in by_name}


class Bundle(SharedByCopies):
    """A verified model bundle. Use :func:`load_bundle`.

    Attributes
    ----------
    path : bundle folder; manifest : parsed ``manifest.json``.
    """

    def __init__(self, path: Path, manifest: dict, *, backend: str = "auto"):
        self.path = path
        self.manifest = manifest
        self.backend = backend
        self._models: dict[str, OnnxModel] = {}
        self._cache: dict[str, object] = {}

    # -- manifest shortcuts ------------------------------------------------------------------------
    @property
    def rate_hz(self) -> float:
        return float(self.manifest["sampling"]["rate_hz"])

    @property
    def tasks(self) -> dict:
        return self.manifest["tasks"]

    def classes(self, task: str) -> list[str]:
        return list(self.manifest["tasks"][task]["classes"])

    def exported(self, task: str) -> list[str]:
        """The ``method/unit`` models exported for ``task``, in the manifest's order."""
        return [f"{m}/{u}" for m, per in self.tasks[task]["methods"].items() for u in per]

    def choose_methods(self, spec: str) -> dict[str, str]:
        """``run --method`` (decision E52): ``spec`` is a comma list of at most one ``METHOD``/``METHOD/UNIT``
        (every task; two are refused, decision E56) and ``TASK=METHOD[/UNIT]`` (one task; it wins over the
        every-task item). A method without a unit
        takes the task's chosen unit when the method has it, else a two-unit model when the chosen one reads
        both units (combined, else fused), else the method's only exported unit. Returns
        task -> ``"method/unit"`` for :class:`Tracker` ``methods``; a task the bundle lacks, a method it did not
        export for a task or an ambiguous unit is a :class:`DataError` naming what the bundle holds."""
        every, per_task = None, {}
        for item in (v.strip() for v in spec.split(",")):
            if not item:
                continue
            task, _, mu = item.rpartition("=")
            if "=" in item and not mu.strip():
                raise DataError(f"run --method {item}: give a method after {item}, e.g. --method {item}svm")
            if not task and every is not None:  # decision E56: one every-task item; the last silently won
                raise DataError(f"run --method {spec}: {every} and {mu} are both for every task; give one, or "
                                f"one per task as TASK=METHOD (the bundle's tasks: {', '.join(self.tasks)})")
            if not task:
                every = mu
            elif task not in self.tasks:
                raise DataError(f"run --method {item}: bundle {self.path} has no task {task!r} (it has "
                                f"{', '.join(self.tasks)})")
            else:
                per_task[task] = mu
        if every is None and not per_task:
            raise DataError("run --method: give METHOD, METHOD/UNIT or TASK=METHOD[/UNIT], e.g. --method svm")
        out = {}
        for task in self.tasks:
            mu = per_task.get(task, every)
            if mu is not None:
                out[task] = self.method_unit(task, mu)
        return out

    def method_unit(self, task: str, mu: str, *, what: str | None = None) -> str:
        """One task's ``method[/unit]`` resolved to an exported ``method/unit`` (:meth:`choose_methods`, and
        :class:`Tracker`'s ``methods``, decision B139); ``what`` names the input in the errors (default ``run
        --method MU``)."""
        what = what or f"run --method {mu}"
        method, _, unit = mu.strip().partition("/")
        methods = self.tasks[task]["methods"]
        have = self.exported(task)
        if method not in methods or (unit and unit not in methods[method]):
            one = all(len(self.tasks[t]["methods"]) == 1 for t in self.tasks)  # `pdrlearn export`'s default
            only = ("; the bundle holds each task's chosen method only: export others with `pdrlearn export MODEL "
                    "--out BUNDLE --methods nn,svm,...`" if one else "; export it with `pdrlearn export --methods`")
            raise DataError(f"{what}: bundle {self.path} has no {mu} model for {task} (it has "
                            f"{', '.join(have)}){only}")
        if not unit:
            chosen = (self.tasks[task].get("chosen") or {}).get("unit")
            units = list(methods[method])
            same = [u for u in ("combined", "fused") if u in units] if chosen in ("combined", "fused") else []
            if chosen in units:
                unit = chosen
            elif same:  # a model reading both units, as the chosen one (combined before fused, decision C23)
                unit = same[0]
            elif len(units) == 1:
                unit = units[0]
            else:
                raise DataError(f"{what}: {task} has {method} for the units {', '.join(units)}; give one, e.g. "
                                + (f"--method {task}={method}/{units[0]}" if what.startswith("run") else
                                   f"methods={{{task!r}: '{method}/{units[0]}'}}"))
        return f"{method}/{unit}"

    # -- files --------------------------------------------------------------------------------------
    def file(self, rel: str) -> Path:
        if rel not in self.manifest["files"]:
            raise ModelError(f"bundle {self.path}: manifest lists no file '{rel}'; re-export the bundle")
        return self.path / rel

    def model(self, rel: str, spec: dict) -> OnnxModel:
        """The ONNX model stored as ``rel`` (opened once)."""
        if rel not in self._models:
            fb = self.file(spec["fallback_file"]) if spec.get("fallback_file") else None
            self._models[rel] = OnnxModel(self.file(rel), spec, backend=self.backend, fallback_path=fb)
        return self._models[rel]

    def json(self, rel: str, keys: tuple[str, ...] = ()) -> dict:
        """The JSON object of the file ``rel``; a file that is not JSON, not an object or lacks one of ``keys``
        is a one-line :class:`ModelError` (decision B125, as :meth:`npz`), whatever its checksum says."""
        if rel not in self._cache:
            try:
                self._cache[rel] = read_json(self.file(rel))
            except (UnicodeDecodeError, json.JSONDecodeError) as exc:
                raise self._bad_file(rel, "a JSON file", exc) from None
        out = self._cache[rel]
        if not isinstance(out, dict):
            raise self._bad_file(rel, "the JSON object this model needs", ValueError(f"a {type(out).__name__}"))
        missing = [k for k in keys if k not in out]
        if missing:
            raise self._bad_file(rel, "the JSON object this model needs", ValueError(f"no key {', '.join(missing)}"))
        return out

    def npz(self, rel: str, keys: tuple[str, ...] = ()) -> dict[str, np.ndarray]:
        """The arrays of the NPZ file ``rel``, read without pickle; a file that is not an NPZ archive of numeric
        arrays (e.g. an object array, which only pickle could load) or lacks one of ``keys`` is a one-line
        :class:`ModelError` (decision B125), whatever its checksum says."""
        if rel not in self._cache:
            try:
                z = np.load(self.file(rel), allow_pickle=False)
                if not isinstance(z, np.lib.npyio.NpzFile):
                    raise ValueError("a single .npy array, not an .npz archive")
                with z:
                    self._cache[rel] = {k: z[k] for k in z.files}
            except (ValueError, OSError, EOFError, zipfile.BadZipFile) as exc:
                raise self._bad_file(rel, "an NPZ archive of numeric arrays (bundles never need pickle)", exc
                                     ) from None
        out: dict[str, np.ndarray] = self._cache[rel]  # type: ignore[assignment]
        missing = [k for k in keys if k not in out]
        if missing:
            raise self._bad_file(rel, "the NPZ archive this model needs", ValueError(f"no array {', '.join(missing)}"))
        return out

    def _bad_file(self, rel: str, what: str, exc: Exception) -> ModelError:
        """Decision B125: a bundle file whose checksum matches but whose content is not what the bundle writes
        (the manifest's checksums were re-made after an edit, or a buggy writer)."""
        why = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        return _fail(self.path, f"file '{rel}' is not {what} ({why}); restore the original bundle or re-export it "
                                "with 'pdrlearn export'")

    # -- compatibility with data --------------------------------------------------------------------
    def check_streams(self, rates_hz: dict[str, float], *, where: str = "data", units=None) -> None:
        """Check that the data has the bundle's required sensors at its sampling rate.

        Parameters
        ----------
        rates_hz : sensor name (``fAccelerometer`` ...) -> the data's rate (Hz); ``nan`` when unknown.
        where : name of the data (session folder, stream) used in the messages.
        units : the body units replayed (default: all the bundle's; decision E26).

        Raises
        ------
        MissingSensorError : a required sensor is absent.
        DataError : a sensor's rate differs from the manifest's by more than the tolerance.
        """
        required = self.sensors_of(units)[0]
        missing = [s for s in required if s not in rates_hz]
        if missing:
            raise MissingSensorError(
                f"{where} has no {', '.join(missing)}, which bundle {self.path} needs "
                f"(it has: {', '.join(rates_hz) or 'none'}); record those sensors"
                + (" or track the foot unit alone (pdrlearn run --units foot, decision E26)"
                   if "foot" in self.body_units and all(s.startswith("w") for s in missing)
                   else f"; {waist_only_hint()}" if {"wAccelerometer", "wGyroscope"} <= set(rates_hz)  # B107: no
                   else " or export a bundle for the sensors you have")  # waist-only bundle exists (E7)
            )
        self.check_rates(rates_hz, where=where)

    @property
    def used_sensors(self) -> list[str]:
        """The sensors the bundle reads: its required ones, then its optional ones (manifest order)."""
        s = self.manifest["sensors"]
        return [*s.get("required", []), *s.get("optional", [])]

    @property
    def body_units(self) -> tuple[str, ...]:
        """The body units whose accelerometer and gyroscope the bundle requires (``foot``, ``waist``)."""
        req = self.manifest["sensors"].get("required", [])
        return tuple(u for u in UNITS if f"{u[0]}Accelerometer" in req)

    def sensors_of(self, units=None) -> tuple[list[str], list[str]]:
        """``(required, optional)`` sensors of the bundle that belong to ``units`` (default: all); a sensor's
        unit is its name's prefix (``f`` foot, ``w`` waist; thesis ch.4.3.3). Decision E26: a foot-only
        replay of a two-unit bundle needs and reads no waist sensor."""
        s = self.manifest["sensors"]
        keep = tuple(u[0] for u in (UNITS if units is None else units))
        return ([n for n in s.get("required", []) if n.startswith(keep)],
                [n for n in s.get("optional", []) if n.startswith(keep)])

    def off_rate(self, rates_hz: dict[str, float]) -> dict[str, float]:
        """The used sensors whose finite rate (Hz) differs from the bundle's by more than its tolerance
        (decision E3; ``nan`` = unknown, never off)."""
        rate = self.rate_hz
        tol = float(self.manifest["sampling"].get("rate_tolerance", DEFAULT_RATE_TOLERANCE))
        return {n: float(rates_hz[n]) for n in self.used_sensors if n in rates_hz
                and math.isfinite(rates_hz[n]) and abs(rates_hz[n] - rate) > tol * rate}

    def check_rates(self, rates_hz: dict[str, float], *, where: str = "data") -> None:
        """Check the rates of the given sensors that the bundle uses (others are ignored)."""
        for name, r in self.off_rate(rates_hz).items():
            raise DataError(
                f"{where}: {name} is sampled at {r:.4g} Hz but bundle {self.path} was trained at "
                f"{self.rate_hz:.4g} Hz; resample the data to {self.rate_hz:.4g} Hz or train a model at {r:.4g} Hz"
            )


def _fail(path: Path, msg: str) -> ModelError:
    return ModelError(f"bundle {path}: {msg}")


#: decision E57: a waist-only bundle (``pdrlearn export CAL.json``) has its own schema, read by
#: :func:`pdrlearn.runtime.waist.load_waist_bundle`
WAIST_SCHEMA_NAME = "pdrlearn-waist-bundle"
WAIST_SCHEMA_VERSION = 1
WAIST_REQUIRED_KEYS = ("schema", "schema_version", "package_version", "created_utc", "user", "pipeline", "sampling",
                       "sensors", "units", "frames", "params", "options", "files")
#: what each bundle kind is and how to run it (decision E58: a bundle of the other kind is one line naming this)
_KINDS = {SCHEMA_NAME: "a foot-unit bundle ('pdrlearn export MODEL_DIR'): run it with pdrlearn.runtime.Tracker("
                       "load_bundle(PATH)) or 'pdrlearn run'",
          WAIST_SCHEMA_NAME: "a waist-only bundle ('pdrlearn export CAL.json'): run it with pdrlearn.runtime."
                             "WaistTracker(load_waist_bundle(PATH)) or 'pdrlearn run'"}


def bundle_kind(path: str | Path) -> str | None:
    """The ``schema`` of the bundle folder ``path`` (None when it has no readable manifest): how ``pdrlearn run``
    tells a waist-only bundle from a foot one before loading it."""
    try:
        m = read_json(Path(path) / MANIFEST)
    except (OSError, ValueError):
        return None
    return m.get("schema") if isinstance(m, dict) else None


def _is_waist_calibration(path: Path) -> bool:
    """Whether ``path`` is a JSON file of a waist pipeline's parameters (``pdrlearn calibrate``'s PARAMS.json)."""
    try:
        d = read_json(path) if path.is_file() and path.suffix.lower() == ".json" else None
    except (OSError, UnicodeDecodeError, ValueError):
        return False
    return isinstance(d, dict) and str(d.get("pipeline", "")).startswith("waist")


def read_manifest(path: str | Path, *, schema: str = SCHEMA_NAME) -> dict:
    """Parse and check ``manifest.json`` of a bundle folder (schema and version, required keys); ``schema``: the
    kind expected (:data:`SCHEMA_NAME` or :data:`WAIST_SCHEMA_NAME`; the other kind is refused naming how it
    runs, decision E58)."""
    path = Path(path)
    if not path.is_dir():
        if _is_waist_calibration(path):  # decision E59: the belt-phone user's calibration is exported first
            raise _fail(path, f"a waist calibration ('pdrlearn calibrate'), not a bundle; {waist_only_hint(str(path))}")
        raise _fail(path, "not a folder; give the folder written by 'pdrlearn export'")
    mpath = path / MANIFEST
    if not mpath.is_file():
        raise _fail(path, f"no {MANIFEST}; give the folder written by 'pdrlearn export'")
    try:
        manifest = read_json(mpath)
    except (json.JSONDecodeError, UnicodeDecodeError) as exc:
        raise _fail(path, f"{MANIFEST} is not valid JSON ({exc}); re-export the bundle") from None
    found = manifest.get("schema") if isinstance(manifest, dict) else None
    if found in _KINDS and found != schema:
        raise _fail(path, f"this is {_KINDS[found]}, not {_KINDS[schema].split(':')[0]}")
    if found != schema:
        raise _fail(path, f"{MANIFEST} is not a {schema} manifest; re-export with 'pdrlearn export'")
    want = SCHEMA_VERSION if schema == SCHEMA_NAME else WAIST_SCHEMA_VERSION
    version = manifest.get("schema_version")
    if version != want:
        raise _fail(
            path,
            f"schema version {version!r}, but this runtime reads version {want}; "
            "re-export the model with this pdrlearn version",
        )
    missing = [k for k in (REQUIRED_KEYS if schema == SCHEMA_NAME else WAIST_REQUIRED_KEYS) if k not in manifest]
    if missing:
        raise _fail(path, f"{MANIFEST} lacks {', '.join(missing)}; re-export the bundle")
    _check_sampling(path, manifest.get("sampling"), required=schema == SCHEMA_NAME)
    return manifest


#: decision E259: the fastest sampling rate a bundle manifest may name (Hz): ten times the fastest rate ``train
#: --resample`` trains at (1000 Hz, decision B212), above every IMU the project reads; -20 ended in a math domain
#: traceback, 1e308 in a 300-digit message
MANIFEST_RATE_MAX_HZ = 10_000.0


def _check_sampling(path: Path, sampling, *, required: bool) -> None:
    """Decision E259: the manifest's ``sampling`` rates (``rate_hz``, required for a foot bundle; each of
    ``source_rates_hz``) are finite numbers above 0 and at most :data:`MANIFEST_RATE_MAX_HZ`, as a session's
    meta.json ``rate_hz`` is checked (``io.plasys.meta_rate``); one line naming the field otherwise."""
    from pdrlearn.errors import message_number

    if not isinstance(sampling, dict):
        raise _fail(path, f"{MANIFEST} sampling is not an object with rate_hz; re-export the bundle")
    rates = {"rate_hz": sampling.get("rate_hz")} if required or sampling.get("rate_hz") is not None else {}
    src = sampling.get("source_rates_hz")
    if isinstance(src, dict):
        rates.update({f"source_rates_hz.{k}": v for k, v in src.items() if v is not None})
    for field, rate in rates.items():
        if rate is None:
            raise _fail(path, f"{MANIFEST} lacks sampling.{field}; re-export the bundle (decision E259)")
        ok = isinstance(rate, int | float) and not isinstance(rate, bool) and math.isfinite(rate)
        if not (ok and 0 < rate <= MANIFEST_RATE_MAX_HZ):
            shown = message_number(rate, 0) if ok else repr(rate)
            raise _fail(path, f"{MANIFEST} sampling.{field} {shown} is not a rate above 0 and at most "
                              f"{MANIFEST_RATE_MAX_HZ:g} Hz; re-export the bundle (decision E259)")


def verify_files(path: Path, manifest: dict, *, checksums: bool = True) -> None:
    """Check that every listed file exists, lies inside the bundle once its links are followed (decision E263), has
    its recorded sha256 and, for an ONNX graph, keeps all its data in the file (E263). ``checksums=False``
    (``load_bundle(verify=False)``) skips only the sha256 checks (manifest.sha256 and each file's): the others are
    safety checks, which run whatever ``verify`` says (decision E270)."""
    files = manifest["files"]
    if not isinstance(files, dict) or not files:
        raise _fail(path, f"{MANIFEST} lists no files; re-export the bundle")
    sha_file = path / MANIFEST_SHA
    if checksums and not sha_file.is_file():
        raise _fail(path, f"{MANIFEST_SHA} is missing; copy the whole bundle folder")
    if checksums and read_text(sha_file).split()[0:1] != [sha256_file(path / MANIFEST)]:
        raise _fail(path, f"{MANIFEST} was altered (sha256 differs from {MANIFEST_SHA}); "
                          "restore the original bundle or re-export it")
    for rel, digest in files.items():
        f = path / rel
        if climbs_out(rel):
            raise _fail(path, f"file entry '{rel}' points outside the bundle; re-export the bundle")
        if not f.is_file():
            raise _fail(path, f"file '{rel}' listed in {MANIFEST} is missing; copy the whole bundle folder")
        target = linked_outside(path, rel)  # decision E263: a symbolic link (a file or a folder) leads out
        if target is not None:
            raise _fail(path, linked_message(rel, target, "bundle"))
        if checksums and sha256_file(f) != digest:
            raise _fail(
                path,
                f"file '{rel}' was altered (sha256 differs from {MANIFEST}); "
                "restore the original bundle or re-export it",
            )
        if rel.endswith(".onnx"):
            _refuse_external_data(path, rel, f)


def _refuse_external_data(path: Path, rel: str, f: Path) -> None:
    """Decision E263: an ONNX graph whose tensors keep their data in another file (which no checksum covers; the
    exporter never writes one) is refused when the bundle is verified, not when a replay first uses the model."""
    from pdrlearn.runtime.onnx_scan import NotOnnx, external_tensor

    try:
        name = external_tensor(f.read_bytes())
    except NotOnnx as exc:
        raise _fail(path, f"file '{rel}' is not an ONNX graph ({exc}); restore the original bundle or re-export it "
                          "with 'pdrlearn export' (decision B125)") from None
    if name is not None:
        raise _fail(path, f"file '{rel}' keeps the data of tensor '{name}' in an external file, which 'pdrlearn "
                          "export' never writes and no checksum covers; restore the original bundle or re-export it")


def load_bundle(path: str | Path, *, verify: bool = True, backend: str = "auto") -> Bundle:
    """Open a bundle folder, verifying schema, version and checksums first.

    Parameters
    ----------
    path : bundle folder written by :func:`pdrlearn.export.write_bundle`.
    verify : check every file's sha256 (default True). False skips the checksums only: a listed file outside the
        folder (a link, an entry with '..') or an ONNX graph with external data is refused either way (E270).
    backend : ``auto`` | ``onnxruntime`` | ``opencv`` (see :class:`OnnxModel`).

    Raises
    ------
    ModelError : missing folder/manifest/file, altered file, other schema version.
    """
    path = Path(path)
    manifest = read_manifest(path)
    verify_files(path, manifest, checksums=verify)  # decision E270: the safety checks run whatever verify says
    log.info("bundle %s: user %s, tasks %s", path, manifest.get("user"), ", ".join(manifest["tasks"]))
    line = version_warning(path, manifest)
    if line:
        log.warning(line)
    return Bundle(path, manifest, backend=backend)


def version_warning(path: Path, manifest: dict) -> str | None:
    """Decision B137: one line when the bundle was exported by another pdrlearn version than this runtime's.
    It still loads (the schema version is the contract, checked by :func:`read_manifest`), but the user learns
    which two versions meet."""
    from pdrlearn import __version__

    theirs = manifest.get("package_version")
    if theirs is None or str(theirs) == __version__:
        return None
    return (f"bundle {path}: exported by pdrlearn {theirs}, this runtime is pdrlearn {__version__}; it loads "
            f"(same schema version {manifest.get('schema_version')}), but re-export it with {__version__} if its "
            "results differ from `pdrlearn track --model`")
