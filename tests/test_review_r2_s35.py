"""Review R2 of session 35 (MATLAB and German inputs, scoring against a lab's reference): the offset check against
one foot's contacts (steps 56), --events-out (steps 59), Excel copies of copies (E178), headerless ';' files (B351),
a waist import's IC list (B352), --encoding's scope (B344), and tests pinning what B333, B336, B345, E172 and
steps 59 say. Simulated users 8590-8599."""

from __future__ import annotations

import json
import shutil

import numpy as np
import pandas as pd
import pytest
import scipy.io

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io import read_session
from pdrlearn.io.importer import import_csv
from pdrlearn.io.session import Session
from pdrlearn.steps import score_steps
from pdrlearn.steps.evaluate import event_rows
from tests.sim_helpers import lab_columns, quiet_walk, straight_walk

G = 9.80665


@pytest.fixture(scope="module")
def sim(tmp_path_factory):
    return straight_walk(tmp_path_factory.mktemp("r2"), 8590, metres=30.0) / "u8590"


@pytest.fixture(scope="module")
def walk():
    return quiet_walk("straight:12", 8591, seed=4)


def _err(capsys) -> str:
    return capsys.readouterr().err


# --- steps 56 amended: no offset advice against one foot's contacts (W96) ---

def test_one_foot_reference_gets_no_offset_advice_steps_56():
    """A lower-back detector whose right-foot contacts are 0.08 s late and left-foot ones on time, scored against
    the right foot's steps.csv: the left foot's contacts, one step away, match tighter; that is no clock."""
    rng = np.random.default_rng(8592)
    right = 2.0 + np.cumsum(1.1 + 0.02 * rng.standard_normal(30))
    det = pd.DataFrame({"event_s": np.sort(np.concatenate([right + 0.08, right - 0.55])), "unit": "waist"})
    st = pd.DataFrame({"start_s": right - 1.1, "end_s": right, "ic_s": right})
    sc = score_steps(det, Session(name="w96", steps=st, meta={"foot": "right"}), unit="waist")
    assert sc["one_foot"] and sc["recall"] == 1.0
    assert "ref_offset_suspect" not in sc and "ref_offset_estimate_s" not in sc


def test_a_w96_session_does_not_warn_steps_56(tmp_path, capsys):
    """User 8595's waist-ic was told "--ref-offset -0.5x" (one step) before the amendment; pelvic-gyro was not."""
    w96 = straight_walk(tmp_path, 8595, metres=30.0) / "u8595"
    for name in ("ics.csv", "bouts.csv"):
        (w96 / name).unlink(missing_ok=True)
    for det in ("waist-ic", "pelvic-gyro"):
        assert main(["steps", str(w96), "-d", det, "--json"]) == 0
        out, err = capsys.readouterr()
        d = json.loads(out)
        assert d["one_foot"] and "steps 56" not in err and not d.get("ref_offset_suspect"), det


# --- steps 59 amended: --events-out ---

def test_events_out_is_refused_against_a_detected_segmentation_steps_59(sim, tmp_path, capsys):
    seg = tmp_path / "seg"
    shutil.copytree(sim, seg)
    st = pd.read_csv(seg / "steps.csv")
    st["source"] = "detected"
    st.to_csv(seg / "steps.csv", index=False)
    ev = tmp_path / "ev.csv"
    assert main(["steps", str(seg), "--events-out", str(ev)]) == 2
    err = _err(capsys)
    assert err.count("\n") == 1 and "NOT ground truth" in err and "steps 59" in err and not ev.exists()


def test_events_out_follows_time_origin_export_steps_59(sim, tmp_path, capsys):
    s = read_session(sim)
    a, w = s.streams["fAccelerometer"], s.streams["fGyroscope"]
    origin = 100.0
    pd.DataFrame({"time_s": a.t - a.t[0] + origin, **{f"acc_{c}": a.values[:, i] for i, c in enumerate("xyz")},
                  **{f"gyr_{c}": w.values[:, i] for i, c in enumerate("xyz")}}).to_csv(tmp_path / "foot.csv",
                                                                                       index=False)
    st = pd.read_csv(sim / "steps.csv")
    ms = [c for c in st if c.endswith("_ms")]
    st[ms] = st[ms] - a.t[0] * 1e3 + origin * 1e3
    st.to_csv(tmp_path / "lab_steps.csv", index=False)
    assert main(["import", str(tmp_path / "foot.csv"), "--acc-unit", "m/s^2", "--gyro-unit", "rad/s",
                 "--steps", str(tmp_path / "lab_steps.csv"), "--out", str(tmp_path / "imp")]) == 0
    capsys.readouterr()
    out, ev = tmp_path / "st.csv", tmp_path / "ev.csv"
    assert main(["steps", str(tmp_path / "imp"), "--out", str(out), "--time-origin", "export",
                 "--events-out", str(ev)]) == 0
    assert f"{out} and {ev}: times in s on the export's clock" in _err(capsys)
    table, events = pd.read_csv(out), pd.read_csv(ev)
    matched = events[events["match"] == "matched"]
    assert len(matched) > 10
    def near(x, y):  # each of x within 1 us of some y
        return np.abs(np.asarray(x)[:, None] - np.asarray(y)[None, :]).min(axis=1) < 1e-6

    assert near(matched["detected_s"], table["event_s"]).all()  # the two files on one clock
    assert near(matched["reference_s"], st["ic_ms"] / 1e3).all()  # the lab's own times back


def test_event_foot_is_the_reference_s_first_steps_59():
    rows = event_rows(np.array([1.0, 5.0]), np.array([1.02]), 0.25, "ic", np.array(["right", "right"], dtype=object),
                      np.array(["left"], dtype=object))
    assert list(rows["foot"]) == ["left", "right"]  # the matched pair: the reference's foot; the false positive's own
    rows = event_rows(np.array([1.0]), np.array([1.02]), 0.25, "ic", np.array(["right"], dtype=object),
                      np.array([""], dtype=object))
    assert list(rows["foot"]) == ["right"]  # no reference foot: the detection's


# --- E178 amended: Excel copies are not copied again ---

def test_excel_copies_are_left_out_e178(tmp_path, capsys):
    from pdrlearn.excel import main as excel_main

    res = tmp_path / "R"
    res.mkdir()
    pd.DataFrame({"event_s": [105.91, 106.96], "n": [1, 2]}).to_csv(res / "steps.csv", index=False)
    assert excel_main([str(res), str(res / "excel")]) == 0
    capsys.readouterr()
    assert excel_main([str(res), str(res / "excel2")]) == 0
    out, err = capsys.readouterr()
    assert "1 CSV file(s) copied" in out and "excel/steps.csv" in err and "not comma-separated" in err
    assert not (res / "excel2" / "excel").exists()
    assert (res / "excel2" / "steps.csv").read_text(encoding="utf-8-sig").splitlines()[1] == "105,91;1"
    assert excel_main([str(res / "excel" / "steps.csv"), str(tmp_path / "x")]) == 2
    assert "not comma-separated" in capsys.readouterr().err and not (tmp_path / "x").exists()


# --- B351: a headerless ';' file with decimal commas ---

def test_headerless_semicolon_decimal_comma_file_is_read_b351(tmp_path, walk, capsys):
    df = lab_columns(walk, 100.0, g_units=True)
    df.to_csv(tmp_path / "comma.csv", index=False, header=False, float_format="%.10g")
    df.to_csv(tmp_path / "de.csv", index=False, header=False, sep=";", decimal=",", float_format="%.10g",
              encoding="cp1252")
    units = ["--no-header", "--acc-unit", "g", "--gyro-unit", "deg/s"]
    assert main(["import", str(tmp_path / "comma.csv"), "--out", str(tmp_path / "c"), *units]) == 0
    assert main(["import", str(tmp_path / "de.csv"), "--out", str(tmp_path / "d"), *units, "--encoding",
                 "cp1252"]) == 0
    c, d = read_session(tmp_path / "c"), read_session(tmp_path / "d")
    for name in ("fAccelerometer", "fGyroscope"):
        assert len(d[name]) == len(df)
        np.testing.assert_allclose(d[name].values, c[name].values, atol=1e-9)
        np.testing.assert_allclose(d[name].t, c[name].t, atol=1e-9)


# --- B352: a waist import's IC list of both feet ---

def test_waist_import_names_labels_for_an_ic_list_b352(tmp_path, walk, capsys):
    lab_columns(walk).to_csv(tmp_path / "waist.csv", index=False)
    ics = pd.DataFrame({"ic_ms": [1000.0, 1550.0, 2100.0, 2650.0], "foot": ["left", "right", "left", "right"]})
    ics.to_csv(tmp_path / "ics_vicon.csv", index=False)
    assert main(["import", str(tmp_path / "waist.csv"), "--unit", "waist", "--steps", str(tmp_path / "ics_vicon.csv"),
                 "--out", str(tmp_path / "o")]) == 2
    err = _err(capsys)
    assert "--labels ics.csv" in err and "pass --foot" not in err and err.count("\n") == 1


# --- B344 amended: --encoding reads the label tables too, and is refused on a MAT file ---

def test_encoding_reads_steps_and_labels_tables_b344(sim, tmp_path, capsys):
    s = read_session(sim)
    a, w = s.streams["fAccelerometer"], s.streams["fGyroscope"]
    exp = pd.DataFrame({"Zeit [s]": a.t, **{f"acc_{c}": a.values[:, i] for i, c in enumerate("xyz")},
                        **{f"gyr_{c}": w.values[:, i] for i, c in enumerate("xyz")}, "Bemerkung": "Gangstörung"})
    exp.to_csv(tmp_path / "de.csv", index=False, encoding="cp1252")
    st = pd.read_csv(sim / "steps.csv")[["start_ms", "end_ms", "ic_ms"]].assign(Bemerkung="Gangstörung")
    st.to_csv(tmp_path / "steps_cp.csv", index=False, encoding="cp1252")
    ic = pd.read_csv(sim / "ics.csv")["ic_ms"]
    bouts = pd.DataFrame({"start_ms": [ic.min() - 100.0], "end_ms": [ic.max() + 100.0], "Ort": "Flur Süd"})
    bouts.to_csv(tmp_path / "bouts.csv", index=False, encoding="cp1252")
    ascii_ics = tmp_path / "ics.csv"
    shutil.copy(sim / "ics.csv", ascii_ics)  # a UTF-8 (ASCII) table beside them: read as UTF-8
    assert main(["import", str(tmp_path / "de.csv"), "--acc", "acc_x,acc_y,acc_z", "--gyro", "gyr_x,gyr_y,gyr_z",
                 "--acc-unit", "m/s^2", "--gyro-unit", "rad/s", "--encoding", "cp1252", "--steps",
                 str(tmp_path / "steps_cp.csv"), "--labels", str(tmp_path / "bouts.csv"), "--labels", str(ascii_ics),
                 "--out", str(tmp_path / "o")]) == 0, _err(capsys)
    steps, bouts = pd.read_csv(tmp_path / "o" / "steps.csv"), pd.read_csv(tmp_path / "o" / "bouts.csv")
    assert list(steps["Bemerkung"].unique()) == ["Gangstörung"] and len(steps) == len(st)
    assert list(bouts["Ort"]) == ["Flur Süd"] and len(read_session(tmp_path / "o").extras["ics"]) == len(ic)


def test_encoding_on_a_mat_file_is_refused_b344(tmp_path, walk, capsys):
    df = lab_columns(walk, g_units=True)
    scipy.io.savemat(tmp_path / "t.mat", {"acc": df[["acc_x", "acc_y", "acc_z"]].to_numpy(),
                                          "gyr": df[["gyr_x", "gyr_y", "gyr_z"]].to_numpy(), "fs": 100.0})
    with pytest.raises(DataError, match="--encoding is for a CSV's text, and this is a MAT file"):
        import_csv(tmp_path / "t.mat", encoding="cp1252")


# --- tests pinning what the decisions say (R2 findings 9-13) ---

def test_labels_offset_moves_labels_tables_too_steps_56(sim, tmp_path, capsys):
    s = read_session(sim)
    a, w = s.streams["fAccelerometer"], s.streams["fGyroscope"]
    pd.DataFrame({"time_s": a.t, **{f"acc_{c}": a.values[:, i] for i, c in enumerate("xyz")},
                  **{f"gyr_{c}": w.values[:, i] for i, c in enumerate("xyz")}}).to_csv(tmp_path / "foot.csv",
                                                                                       index=False)
    ics = pd.read_csv(sim / "ics.csv")
    (tmp_path / "v").mkdir()
    ics.assign(ic_ms=ics["ic_ms"] + 30000.0).to_csv(tmp_path / "v" / "ics.csv", index=False)
    assert main(["import", str(tmp_path / "foot.csv"), "--acc-unit", "m/s^2", "--gyro-unit", "rad/s", "--labels",
                 str(tmp_path / "v" / "ics.csv"), "--labels-offset", "30", "--out", str(tmp_path / "o")]) == 0
    got = read_session(tmp_path / "o").extras["ics"]
    np.testing.assert_allclose(got["ic_s"].to_numpy(), ics["ic_ms"].to_numpy() / 1e3 - a.t[0], atol=1e-6)


def test_import_labels_offset_must_be_finite_b333(sim, tmp_path, capsys):
    assert main(["import", str(sim / "fAccelerometer.csv"), "--steps", str(sim / "steps.csv"), "--labels-offset",
                 "nan", "--out", str(tmp_path / "o")]) == 2
    err = _err(capsys)
    assert "B333" in err and "--labels-offset" in err and not (tmp_path / "o").exists()


def test_six_headerless_columns_are_acc_then_gyro_b336(tmp_path, walk, capsys):
    df = lab_columns(walk, g_units=True).drop(columns="time_s")
    df.to_csv(tmp_path / "m.csv", index=False, header=False, float_format="%.10g")
    assert main(["import", str(tmp_path / "m.csv"), "--no-header", "--rate", "100", "--acc-unit", "g",
                 "--gyro-unit", "deg/s", "--out", str(tmp_path / "o")]) == 0
    got = read_session(tmp_path / "o")
    np.testing.assert_allclose(got["fAccelerometer"].values, df.iloc[:, :3].to_numpy() * G, atol=1e-6)
    np.testing.assert_allclose(got["fGyroscope"].values, np.radians(df.iloc[:, 3:].to_numpy()), atol=1e-6)


def test_minus_mat_variable_negates_its_three_columns_e172(tmp_path, walk, capsys):
    df = lab_columns(walk, g_units=True)
    acc, gyr = df[["acc_x", "acc_y", "acc_z"]].to_numpy(), df[["gyr_x", "gyr_y", "gyr_z"]].to_numpy()
    scipy.io.savemat(tmp_path / "t.mat", {"acc": acc, "gyr": gyr, "fs": 100.0})
    units = ["--acc-unit", "g", "--gyro-unit", "deg/s", "--gyro", "gyr"]
    assert main(["import", str(tmp_path / "t.mat"), "--acc", "acc", *units, "--out", str(tmp_path / "p")]) == 0
    assert main(["import", str(tmp_path / "t.mat"), "--acc", "-acc", *units, "--out", str(tmp_path / "n")]) == 0
    p, n = read_session(tmp_path / "p"), read_session(tmp_path / "n")
    np.testing.assert_allclose(n["fAccelerometer"].values, -p["fAccelerometer"].values, atol=1e-9)
    np.testing.assert_allclose(p["fAccelerometer"].values, acc * G, atol=1e-6)


def test_subject_is_kept_and_set_by_merge_b345(tmp_path, walk, capsys):
    lab_columns(walk).to_csv(tmp_path / "u.csv", index=False)
    waist = lab_columns(walk)
    waist.iloc[:, 4:] = waist.iloc[:, 4:] * 0.5  # the lower back's own (slower) rotation, not a copy (B91)
    waist.to_csv(tmp_path / "w.csv", index=False)
    units = ["--acc-unit", "m/s^2", "--gyro-unit", "rad/s"]
    foot, back = ["import", str(tmp_path / "u.csv"), *units], ["import", str(tmp_path / "w.csv"), *units]
    assert main([*foot, "--subject", "P01", "--out", str(tmp_path / "a")]) == 0
    assert main([*back, "--unit", "waist", "--merge", "--out", str(tmp_path / "a")]) == 0, _err(capsys)
    assert json.loads((tmp_path / "a" / "meta.json").read_text())["subject"] == "P01"
    assert main([*foot, "--out", str(tmp_path / "b")]) == 0
    assert main([*back, "--unit", "waist", "--merge", "--subject", "P02", "--out", str(tmp_path / "b")]) == 0
    assert json.loads((tmp_path / "b" / "meta.json").read_text())["subject"] == "P02"
