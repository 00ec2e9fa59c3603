"""Decisions L40 / E25: ``track --streaming`` and the runtime apply offline M3's default class rules (the
bayes rule, L14, on the classes the model is >= 0.95 sure of, L18) with one per-stride kernel:
:mod:`pdrlearn.kernels.bayes` (the formula, on floats and on arrays) and
:func:`pdrlearn.kernels.stride.stride_rules_one`."""

from __future__ import annotations

import json
import shutil

import numpy as np
import pandas as pd
import pytest

from pdrlearn.displace import StepRules
from pdrlearn.kernels import bayes as KB
from pdrlearn.kernels import stride as SK
from pdrlearn.runtime.tracker import Tracker
from pdrlearn.track.base import get_pipeline
from tests.runtime_helpers import calibrated_length_model, replay

NAMES = ["short", "normal", "long"]
BOUNDS = {"short": (0.0, 1.0), "normal": (1.0, 1.5), "long": (1.5, 20.0)}


def _reference(distance, proba, bounds, sigma):
    """L14's closed form as first written (scipy's normal cdf/pdf, (B, C) broadcasting)."""
    from scipy.stats import norm

    d, sg = np.abs(distance)[:, None], np.asarray(sigma)[:, None]
    lo, hi = (np.array([b[i] for b in bounds])[None, :] for i in (0, 1))
    a, b = (lo - d) / sg, (hi - d) / sg
    mass = norm.cdf(b) - norm.cdf(a)
    first = d * mass + sg * (norm.pdf(a) - norm.pdf(b))
    w = proba / np.maximum(hi - lo, 1e-9)
    z = (w * mass).sum(axis=1)
    return np.where(z > 1e-300, (w * first).sum(axis=1) / np.where(z > 1e-300, z, 1.0), d[:, 0])


def test_bayes_length_one_formula_on_floats_and_arrays():
    rng = np.random.default_rng(1)
    d = rng.uniform(0.2, 2.5, 300)
    sg = np.maximum(rng.uniform(0.003, 0.05, 300) * d, 0.02)
    p = rng.dirichlet([0.4] * 3, 300)
    b = list(BOUNDS.values())
    arr = KB.bayes_length(d, p, b, sg)
    one = [KB.bayes_length_one(float(x), row, b, float(s)) for x, row, s in zip(d, p.tolist(), sg, strict=True)]
    assert arr.tolist() == one  # the same bits: one formula, the same math calls
    np.testing.assert_allclose(arr, _reference(d, p, b, sg), rtol=1e-12, atol=1e-12)
    # a certain class: the truncated-normal mean in its bounds (the thesis clamp, softened)
    from scipy.stats import truncnorm

    x, s = 1.48, 0.03
    want = truncnorm.mean((1.0 - x) / s, (1.5 - x) / s, loc=x, scale=s)
    assert KB.bayes_length_one(x, [0.0, 1.0, 0.0], b, s) == pytest.approx(want, abs=1e-12)
    assert 1.0 < KB.bayes_length_one(1.7, [0.0, 1.0, 0.0], b, s) < 1.5  # pulled into the class


def test_one_stride_bayes_rules_equal_the_offline_step_rules():
    rng = np.random.default_rng(0)
    n = 400
    disp = np.column_stack([rng.normal(1.2, 0.5, n), rng.normal(0, 0.2, n), rng.normal(0, 0.15, n)])
    p = rng.dirichlet([0.3] * 3, n)
    terrain = rng.choice(np.array(["flat", "up", "down", None], dtype=object), n)
    direction = rng.choice(np.array(["forward", "backward", None], dtype=object), n)
    lc = np.array([NAMES[i] for i in p.argmax(1)], dtype=object)
    lc[rng.random(n) < 0.1] = None
    classes = pd.DataFrame({"terrain": terrain, "direction": direction, "length_class": lc,
                            **{f"p_length_{c}": p[:, i] for i, c in enumerate(NAMES)}})
    off = StepRules(bounds=BOUNDS, mode="bayes", sigma_rel=0.007).apply(disp, classes)
    length, dz = SK.apply_stride_rules(disp, terrain, direction, lc, bounds=BOUNDS, rules="bayes", sigma_rel=0.007,
                                       length_proba=[dict(zip(NAMES, r, strict=True)) for r in p.tolist()])
    assert length.tolist() == off["length_m"].tolist() and dz.tolist() == off["dz_m"].tolist()
    one = SK.stride_rules_one(*disp[0].tolist(), terrain[0], direction[0], lc[0], bounds=BOUNDS, rules="bayes",
                              length_proba=dict(zip(NAMES, p[0].tolist(), strict=True)), sigma_rel=0.007)
    assert one == (length[0], dz[0])
    thesis = SK.apply_stride_rules(disp, terrain, direction, lc, bounds=BOUNDS)
    assert np.abs(thesis[0] - length).max() > 0.05  # the two rules differ on these strides
    # a clear height change keeps its measured sign whatever the terrain class (L14)
    assert SK.stride_rules_one(1.2, 0.0, -0.17, "up", None, None, rules="bayes")[1] == -0.17
    assert SK.stride_rules_one(1.2, 0.0, -0.17, "up", None, None)[1] == 0.17


def test_one_stride_gate_equals_the_offline_gate():
    from pdrlearn.track.plasys import _confident

    rng = np.random.default_rng(3)
    p = rng.dirichlet([0.5] * 3, 200)
    p[5] = np.nan
    lab = np.array([NAMES[i] for i in np.nan_to_num(p).argmax(1)], dtype=object)
    df = pd.DataFrame({"length_class": lab, **{f"p_length_{c}": p[:, i] for i, c in enumerate(NAMES)}})
    for gate in (0.0, 0.6, 0.95):
        want = [None if pd.isna(v) else v for v in _confident(df, gate)["length_class"]]  # pandas writes NaN
        got = [KB.confident_one(c, dict(zip(NAMES, r, strict=True)), gate)
               for c, r in zip(lab, p.tolist(), strict=True)]
        assert got == want
    assert sum(v is None for v in got) > 50


@pytest.fixture(scope="module")
def calibrated_length(tmp_path_factory):
    """A length model with a distance calibration (user 2), its bundle, and scenario A of the same user."""
    return calibrated_length_model(tmp_path_factory.mktemp("bayes"), "fast")


def _xyz(steps) -> np.ndarray:
    return np.array([[st.x, st.y, st.z] for st in steps])


def test_runtime_and_streaming_track_apply_the_offline_rule_by_default(calibrated_length, tmp_path):
    """L41 (L40 / E25 amended): streamed, the default is offline M3's rule (bayes, 0.95 gate) in the bundle,
    the runtime and ``track --streaming``, and runtime and streaming track agree under it."""
    root, model, s = calibrated_length
    disp = json.loads((root / "bundle" / "manifest.json").read_text())["displacement"]
    assert (disp["rules"], disp["min_confidence"]) == ("bayes", 0.95)
    fn = get_pipeline("plasys")
    res = fn(s, method="M3", model=str(root / "model"), streaming=True, heading="foot")
    offline = fn(s, method="M3", model=str(root / "model"))
    for k in ("rules", "min_confidence"):
        assert res.info[k] == offline.info[k]
    assert (res.info["rules"], res.info["min_confidence"]) == ("bayes", 0.95)
    oracle = fn(s, method="M3", model="oracle", streaming=True, heading="foot")
    assert (oracle.info["rules"], oracle.info["min_confidence"]) == ("thesis", 0.0)  # labels prevail, as offline
    rec = model.data_summary["distance_calibration"]
    assert offline.info["stride_sigma_rel"] == pytest.approx(rec["stride_sd"])
    # decision L41: streamed, the stride kernel's own calibrated sd
    assert res.info["stride_sigma_rel"] == pytest.approx(rec["streaming"]["stride_sd"])
    assert (Tracker(root / "bundle").rules, Tracker(root / "bundle").min_confidence) == ("bayes", 0.95)
    tr = Tracker(root / "bundle", heading_source="foot")
    steps = replay(tr, s, 0.5)
    assert (tr.rules, tr.min_confidence) == ("bayes", 0.95)
    assert len(steps) == len(res.steps) >= 10
    assert [st.classes["length"] for st in steps] == list(res.steps["length_class"])  # ungated classes reported
    assert np.abs(_xyz(steps) - res.trajectory[["x", "y", "z"]].to_numpy()[1:]).max() < 1e-3
    # a rule asked for without a gate brings its own gate, in both (thesis: 0, every class prevails)
    assert Tracker(root / "bundle", rules="thesis").min_confidence == 0.0
    assert fn(s, method="M3", model=str(root / "model"), streaming=True, heading="foot",
              rules="thesis").info["min_confidence"] == 0.0
    # the thesis rule stays selectable, in both, and gives another walk (so the parity above is the bayes one)
    thesis = fn(s, method="M3", model=str(root / "model"), streaming=True, heading="foot", rules="thesis",
                min_confidence=0.0)
    steps_t = replay(Tracker(root / "bundle", heading_source="foot", rules="thesis", min_confidence=0.0), s, 0.5)
    assert np.abs(_xyz(steps_t) - thesis.trajectory[["x", "y", "z"]].to_numpy()[1:]).max() < 1e-3
    # beyond the 1e-3 parity tolerance above (0.01 before decision C191 gave contradicted classes their measured one)
    assert np.abs(thesis.steps["length_m"].to_numpy() - res.steps["length_m"].to_numpy()).max() > 1e-3
    # a bundle exported before E25 (no rules / min_confidence) keeps the thesis rule without a gate
    old = tmp_path / "old"
    shutil.copytree(root / "bundle", old)
    m = json.loads((old / "manifest.json").read_text())
    del m["displacement"]["rules"], m["displacement"]["min_confidence"]
    (old / "manifest.json").write_text(json.dumps(m))
    from pdrlearn.runtime.bundle import MANIFEST_SHA, sha256_file

    (old / MANIFEST_SHA).write_text(f"{sha256_file(old / 'manifest.json')}  manifest.json\n")
    tr_old = Tracker(old, heading_source="foot")
    assert (tr_old.rules, tr_old.min_confidence) == ("thesis", 0.0)
    assert np.abs(_xyz(replay(tr_old, s, 0.5)) - _xyz(steps_t)).max() < 1e-9
    assert Tracker(old, rules="bayes").min_confidence == 0.95  # offline's gate with offline's rule


def test_streamed_strides_of_a_doubtful_class_keep_their_measured_length(calibrated_length):
    """Offline and streaming agree on what the gate does: a stride whose length class is below 0.95 keeps
    its (gained) measured length in both; a confident one is weighed against its class."""
    root, model, s = calibrated_length
    fn = get_pipeline("plasys")
    for res in (fn(s, method="M3", model=model, streaming=True, heading="foot", rules="bayes"),
                fn(s, method="M3", model=model)):
        gain = res.info["distance_gain"]  # each engine's own (decision L41)
        st = res.steps
        pmax = st[[f"p_length_{c}" for c in NAMES if f"p_length_{c}" in st]].max(axis=1).to_numpy()
        doubtful = pmax < 0.95
        assert 0 < doubtful.sum() < len(st)  # both kinds occur on this walk
        level = np.abs(st["dz_m"].to_numpy()) < 0.1
        raw = st["raw_length_m"].to_numpy() * np.where(level, gain, 1.0)
        np.testing.assert_allclose(st["length_m"].to_numpy()[doubtful], raw[doubtful], rtol=1e-12)


def test_tracker_refuses_an_unknown_rule(calibrated_length):
    from pdrlearn.errors import DataError

    root, _, _ = calibrated_length
    with pytest.raises(DataError, match="rules 'clamp' is not one of thesis, bayes"):
        Tracker(root / "bundle", rules="clamp")
    with pytest.raises(DataError, match="min_confidence 1.5 must be between 0 and 1"):
        Tracker(root / "bundle", min_confidence=1.5)
