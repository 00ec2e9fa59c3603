"""``train --param METHOD.NAME=VALUE``: the built-in classifiers' hyperparameters (decision C96) and documented
options (decision C139: the heuristics' thresholds / weights / bands, DTW's rule and calibration).

Pure parsing and checking, no numpy: the CLI checks ``--param`` before any data is read."""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Mapping

from pdrlearn.errors import DataError


def _number(text: str, *, low: float, low_open: bool, high: float | None = None) -> float:
    """A finite number in range: nan, inf and 1e400 (inf as a float) are refused, so a value the model's JSON
    manifest cannot store is one line before training (decision B373)."""
    v = float(text)
    if not math.isfinite(v) or (v <= low if low_open else v < low) or (high is not None and v > high):
        raise ValueError(text)
    return v


def _positive(text: str) -> float:
    return _number(text, low=0.0, low_open=True)


def _non_negative(text: str) -> float:
    return _number(text, low=0.0, low_open=False)


def _integer(low: int) -> Callable[[str], int]:
    def parse(text: str) -> int:
        v = int(text)
        if v < low:
            raise ValueError(text)
        return v
    return parse


def _svm_c(text: str) -> float | str:
    return "cv" if text.strip().lower() == "cv" else _positive(text)


def _grid(text: str) -> tuple[float, ...]:
    values = tuple(_positive(v) for v in text.split(",") if v.strip())
    if not values:
        raise ValueError(text)
    return values


def _class_weight(text: str) -> str | None:
    v = text.strip().lower()
    if v not in ("balanced", "none"):
        raise ValueError(text)
    return None if v == "none" else v


def _window(text: str) -> float | None:
    return None if text.strip().lower() == "none" else _number(text, low=0.0, low_open=True, high=1.0)


def _choice(*values: str) -> Callable[[str], str]:
    """One of ``values`` (case-insensitive), the estimator's own check's names (decision C139)."""
    def parse(text: str) -> str:
        v = text.strip().lower()
        if v not in values:
            raise ValueError(text)
        return v
    return parse


def _flag(text: str) -> bool:
    v = text.strip().lower()
    if v not in ("true", "false"):
        raise ValueError(text)
    return v == "true"


#: the heuristic rule classifiers' documented options (decision C139; pdrlearn.classify.heuristic's module text)
_RULE_OPTIONS: dict[str, tuple[Callable[[str], object], str]] = {
    "thresholds": (_choice("joint", "learn", "thesis"), "'joint', 'learn' or 'thesis' (default joint: cut points "
                   "learnt from the user's steps, thesis ch. 6.1.3; 'thesis': the printed thresholds, decision C140)"),
    "weights": (_choice("thesis", "skill"), "'thesis' or 'skill' (default thesis: Tables 26/32 and eq. 32)"),
    "bands": (_flag, "'true' or 'false' (default true: a two-class rule may learn a band)"),
}

#: method -> parameter -> (parse, what a valid value is and its default's source); decisions C96, C139
HYPERPARAMETERS: dict[str, dict[str, tuple[Callable[[str], object], str]]] = {
    "svm": {
        "C": (_svm_c, "a number > 0 or 'cv' (default cv: the inner grid search, thesis ch. 2.4.2.2)"),
        "C_grid": (_grid, "comma list of numbers > 0 (default 0.3,1,3,10, decision C5)"),
        "class_weight": (_class_weight, "'balanced' or 'none' (default balanced, decision C36)"),
    },
    "nn": {
        "hidden": (_integer(1), "an integer >= 1 (default 144 / 10 / 60 per task, thesis ch. 6.1.1.2, 6.2.1.2, "
                   "6.3.1.2)"),
        "learning_rate": (_positive, "a number > 0 (default 0.01, thesis ch. 6.1.1.2)"),
        "max_epochs": (_integer(1), "an integer >= 1 (default 200)"),
        "patience": (_integer(1), "an integer >= 1 (default 15)"),
        "weight_decay": (_non_negative, "a number >= 0 (default 1e-4)"),
    },
    "dtw": {
        "n_references": (_integer(2), "an integer >= 2 per class (default 36 / 12 / 30 per task, thesis ch. "
                         "6.1.2.2, 6.2.2.2, 6.3.2.2)"),
        "window": (_window, "a fraction in (0, 1] of the step or 'none' (default 0.1)"),
        "rule": (_choice("mean", "spread"), "'mean' or 'spread' (default mean: thesis ch. 6.1.2.2; 'spread': decision "
                 "C70)"),
        "calibration": (_choice("cv", "gap"), "'cv' or 'gap' (default cv: decision C67; 'gap': decision C4)"),
    },
    "heuristic": dict(_RULE_OPTIONS),  # decision C139: make_heuristic's keywords, per unit
    "fusion": dict(_RULE_OPTIONS),  # heuristic fusion: the same rules, thesis Table 26 / eq. 32 / Table 32 weights
}


def valid_names() -> str:
    """Every ``METHOD.NAME`` ``--param`` takes, comma-separated."""
    return ", ".join(f"{m}.{n}" for m, names in HYPERPARAMETERS.items() for n in names)


def check_plugin_key(method: str, name: str, factory: Callable, item: str, command: str) -> None:
    """Decision C122: a key the plug-in factory does not take (no such keyword, no ``**kwargs``) is one line naming
    the keywords it takes; ``seed`` is refused naming ``--seed`` (``seed=`` of the API), which sets it."""
    import inspect

    if name == "seed":
        raise DataError(f"{command}: --param {item!r}: the seed of plug-in method {method} is not a --param; "
                        "--seed sets it (seed= in the API) (decision C122)")
    ps = inspect.signature(factory).parameters
    takes = [p.name for p in ps.values() if p.kind in (p.KEYWORD_ONLY, p.POSITIONAL_OR_KEYWORD)
             and p.name not in ("task", "unit", "seed")]
    if name in ("task", "unit") or not (name in takes or any(p.kind == p.VAR_KEYWORD for p in ps.values())):
        raise DataError(f"{command}: --param {item!r}: the factory of plug-in method {method} takes no keyword "
                        f"{name!r} (its keywords: {', '.join(takes) or 'none'}); add it to the factory, e.g. "
                        f"def factory(task, unit, *, seed=0, {name}=...) (decision C122)")


def plugin_param(method: str, name: str, text: str, factory: Callable, item: str, command: str) -> object:
    """Decision C122: ``--param METHOD.KEY=VALUE`` of a registered plug-in method: the key checked
    (:func:`check_plugin_key`), the value read as :func:`pdrlearn.plugins.spec_value` (number, true/false/none,
    text), passed to its factory as ``KEY=VALUE``."""
    from pdrlearn.plugins import spec_value

    check_plugin_key(method, name, factory, item, command)
    return spec_value(text.strip())


def parse_params(items: Iterable[str] | None, command: str = "train",
                 plugins: Mapping[str, Callable] | None = None) -> dict[str, dict[str, object]]:
    """``["svm.C=10", "nn.hidden=32"]`` -> ``{"svm": {"C": 10.0}, "nn": {"hidden": 32}}``; a bad item is one
    :class:`DataError` line naming the ``command``, ``--param``, the item and the valid names or values (decision
    C96; ``train-all`` names itself, C98 as amended by review R2). ``plugins``: registered plug-in methods (name ->
    factory), whose ``METHOD.KEY=VALUE`` goes to the factory as a keyword (:func:`plugin_param`, decision C122)."""
    plugins = plugins or {}
    out: dict[str, dict[str, object]] = {}
    for item in items or ():
        key, eq, text = str(item).partition("=")
        method, dot, name = key.strip().partition(".")
        if not eq or not dot:
            raise DataError(f"{command}: --param {item!r}: write METHOD.NAME=VALUE, e.g. --param svm.C=10; valid "
                            f"names: {valid_names()} (decision C96)")
        spec = HYPERPARAMETERS.get(method, {}).get(name)
        if spec is None and method in plugins and method not in HYPERPARAMETERS:
            if name in out.get(method, {}):
                raise DataError(f"{command}: --param {key.strip()} is given twice; give it once (decision C96)")
            out.setdefault(method, {})[name] = plugin_param(method, name, text, plugins[method], item, command)
            continue
        if spec is None:
            raise DataError(f"{command}: --param {item!r}: unknown name {key.strip()!r}; valid names: {valid_names()} "
                            "or a registered plug-in method's factory keyword, PLUGIN.KEY=VALUE (decisions C96, "
                            "C122)")
        if name in out.get(method, {}):
            raise DataError(f"{command}: --param {key.strip()} is given twice; give it once (decision C96)")
        parse, valid = spec
        try:
            value = parse(text.strip())
        except ValueError:
            raise DataError(f"{command}: --param {item!r}: {text.strip()!r} is not {valid} (decision C96)") from None
        out.setdefault(method, {})[name] = value
    return out


def check_params_methods(params: Mapping[str, Mapping[str, object]], methods: Iterable[str],
                         command: str = "train") -> None:
    """Decision C96 (C78's rule): a ``--param`` of a method that is not trained is refused; the ensemble trains its
    members (nn, svm, dtw)."""
    trained = set(methods)
    if "ensemble" in trained:
        trained |= {"nn", "svm", "dtw"}
    for method in params:
        if method not in trained:
            given = ", ".join(f"{method}.{n}" for n in params[method])
            raise DataError(f"{command}: --param {given}: {method} is not trained (methods: "
                            f"{','.join(sorted(set(methods)))}); add {method} to --methods or drop the --param "
                            "(decision C96)")


def stored(params: Mapping[str, Mapping[str, object]]) -> dict[str, dict[str, object]]:
    """The values as the manifest stores them (JSON: tuples as lists)."""
    return {m: {n: list(v) if isinstance(v, tuple) else v for n, v in names.items()} for m, names in params.items()}


def _as_text(value) -> str:
    if value is None:
        return "none"
    if isinstance(value, (list, tuple)):
        return ",".join(str(v) for v in value)
    return str(value)


def check_params(params: Mapping[str, Mapping[str, object]] | None,
                 methods: Iterable[str], plugins: Mapping[str, Callable] | None = None) -> dict[str, dict[str, object]]:
    """``train_user(params=...)``: the API's ``{"svm": {"C": 10}}`` checked as ``--param`` is (decision C96): known
    names, valid values, trained methods; returns the parsed values ({} for None). ``plugins``: registered plug-in
    methods, whose keyword names are checked and whose values pass unchanged (a tuple stays a tuple, decision C122
    as amended by review R4)."""
    plugins = {m: f for m, f in (plugins or {}).items() if m not in HYPERPARAMETERS}
    given = {m: dict(names or {}) for m, names in (params or {}).items()}
    items = [f"{m}.{n}={_as_text(v)}" for m, names in given.items() if m not in plugins for n, v in names.items()]
    out = parse_params(items)
    for m in (m for m in given if m in plugins):  # decision C122 (review R4): the API's values reach the factory
        for n in given[m]:                         # unchanged; only the keyword names are checked
            check_plugin_key(m, n, plugins[m], f"{m}.{n}", "train")
        out[m] = given[m]
    check_params_methods(out, methods)
    return out
