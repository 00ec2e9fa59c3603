"""Imports every module that registers a tracking pipeline (add yours to the list)."""

import importlib

PIPELINE_MODULES: list[str] = ["pdrlearn.track.waist", "pdrlearn.track.plasys"]

for _m in PIPELINE_MODULES:
    importlib.import_module(_m)
