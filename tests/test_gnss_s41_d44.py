"""Session 41, implementer I4: decision D44 (a fix CSV's blank ``hdop`` cell is a fix of unknown accuracy, kept with
the default accuracy and counted; D43 left it rejecting the whole file)."""

from datetime import UTC, datetime, timedelta

import numpy as np
import pandas as pd
import pytest

from pdrlearn.aid import aid_track, read_fixes
from pdrlearn.aid.fixes import DEFAULT_RMC_ACCURACY_M, DEFAULT_UERE_M
from pdrlearn.aid.fixgen import gnss_fixes
from pdrlearn.errors import DataError
from pdrlearn.io.session import Session
from tests.test_gnss_s40 import ORIGIN, _legs, _pdr

T0 = datetime(2026, 3, 15, 10, 0, tzinfo=UTC)


def _csv(path, hdop: list[str], *, iso: bool = True, lat: str = "51.0001") -> str:
    """A fix CSV (ISO 8601 UTC or session-second times) whose rows' hdop cells are ``hdop``, written as text."""
    rows = []
    for k, h in enumerate(hdop):
        t = (T0 + timedelta(seconds=k)).isoformat() if iso else f"{k}.0"
        rows.append(f"{t},{lat if k == 1 else '51.0'},-1.8,{h}")
    path.write_text("time,latitude,longitude,hdop\n" + "\n".join(rows) + "\n")
    return path


@pytest.mark.parametrize("cell", ["", "   ", "NaN", "nan"])
@pytest.mark.parametrize("iso", [True, False])
def test_a_blank_hdop_cell_keeps_the_fix_with_the_default_accuracy_d44(tmp_path, cell, iso):
    """D44: an empty, whitespace or NaN hdop cell is an unknown accuracy: the fix is kept with the default accuracy
    (a GPX point's without <hdop>), counted in ``blank_hdop``; the other rows keep HDOP x 4 m."""
    p = _csv(tmp_path / "fix.csv", ["1.5", cell, "2.0"], iso=iso)
    if not iso:  # a session-seconds CSV names its column t (D37)
        p.write_text(p.read_text().replace("time,", "t,", 1))
    log = read_fixes(p)
    assert len(log.fixes) == 3 and log.stats["used"] == 3 and log.stats["blank_hdop"] == 1
    acc = log.fixes["accuracy_m"].to_numpy()
    assert acc == pytest.approx([1.5 * DEFAULT_UERE_M, DEFAULT_RMC_ACCURACY_M, 2.0 * DEFAULT_UERE_M])


def test_a_non_number_hdop_and_other_blank_columns_stay_one_line_errors_d44(tmp_path):
    """D44: hdop text that is no number names its row; a blank lat (or t) keeps D43's row-naming error."""
    with pytest.raises(DataError, match=r"hdop value 'good' in data row 2 is not a number") as e:
        read_fixes(_csv(tmp_path / "text.csv", ["1.5", "good", "2.0"]))
    assert "\n" not in str(e.value)
    with pytest.raises(DataError, match=r"1 row\(s\) with NaN/inf \(first: data row 2\)"):
        read_fixes(_csv(tmp_path / "lat.csv", ["1.5", "1.0", "2.0"], lat=""))
    p = tmp_path / "t.csv"
    p.write_text("time,latitude,longitude,hdop\n2026-03-15T10:00:00Z,51,-1.8,1\n,51,-1.8,1\n")
    with pytest.raises(DataError, match=r"1 row\(s\) with NaN/inf \(first: data row 2\)"):
        read_fixes(p)
    full = read_fixes(_csv(tmp_path / "full.csv", ["1.5", "1.0", "2.0"]))
    assert full.stats["blank_hdop"] == 0


def test_aid_track_says_how_many_hdop_cells_were_blank_d44(tmp_path):
    """D44: the aided track uses the blank-hdop fixes, says so in one warning line and counts them in info."""
    steps, truth = _legs((300.0,))
    fx = gnss_fixes(truth, accuracy_m=4.0, origin=ORIGIN, seed=3)
    hdop = (fx["accuracy_m"] / 4.0).map("{:.2f}".format).to_numpy(object)
    hdop[1::5] = ""
    p = tmp_path / "garmin.csv"
    pd.DataFrame({"time": [(T0 + timedelta(seconds=float(s))).isoformat() for s in fx["t"]],
                  "latitude": fx["lat"], "longitude": fx["lon"], "hdop": hdop}).to_csv(p, index=False)
    out = aid_track(_pdr(steps, bias_deg=2.0), Session(name="w"), gnss_path=p, gnss_time_offset_s=0.0,
                    start=ORIGIN)
    g = out.info["aid"]["gnss"]
    n_blank = int((hdop == "").sum())
    assert g["blank_hdop"] == n_blank > 0 and g["fixes_read"] == len(fx)
    lines = [w for w in out.info["warnings"] if "blank hdop" in w]
    assert len(lines) == 1 and f"{n_blank} of {len(fx)} fix(es)" in lines[0] and "D44" in lines[0]
    assert np.isfinite(out.trajectory[["x", "y"]].to_numpy()).all()
