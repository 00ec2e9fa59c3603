"""Decisions E203 and B382 (session 37, trial T1 finding 6): the lean runtime's ``WaistTracker.push`` with a phone's
routine repeated sample and with ns timestamps.

- E203: a repeated timestamp inside one push is named (its index, both times, "repeats") with the fix, not called
  "across pushes"; ``drop_duplicate_timestamps=True`` drops it (the first kept, one warning line, a count) and tracks
  as the clean stream does;
- B382: ns stamps (a rate ratio of ~1e9) are named as ns with ``t_ns / 1e9``, us as us, ms as ms.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.export.waist import export_waist
from pdrlearn.runtime import WaistTracker
from pdrlearn.runtime.resample import check_rate_unit
from pdrlearn.sim import simulate


@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    d = tmp_path_factory.mktemp("wrep")
    s = simulate("B", 9216, rate_hz=100.0)
    (d / "cal.json").write_text(json.dumps({"leg_m": 1.0, "k": 1.2, "f_m": 0.0, "source": "calibrated",
                                            "pipeline": "waist-pendulum", "rate_hz": 100.0}))
    frame = ",".join(f"{k}={v}" for k, v in s.require_frame("waist").to_dict().items())
    export_waist(d / "cal.json", d / "wb", frame=frame)
    a, g = s["wAccelerometer"], s["wGyroscope"]
    return {"bundle": d / "wb", "t": a.t, "acc": a.values, "gyr": g.values}


def _repeated(w, at=(10, 500, 2000)):
    """The walk with the samples at ``at`` pushed twice (a phone's repeated rows)."""
    idx = np.sort(np.concatenate([np.arange(len(w["t"])), np.asarray(at)]))
    return w["t"][idx], w["acc"][idx], w["gyr"][idx]


def _track(tr, t, acc, gyr, chunk=97):
    out = []
    for i in range(0, len(t), chunk):
        out += tr.push(t[i:i + chunk], acc[i:i + chunk], gyr[i:i + chunk])
    return out + tr.flush()


def test_a_repeat_inside_one_push_is_named_with_its_index_and_the_option(walk):
    t, acc, gyr = _repeated(walk)
    tr = WaistTracker(walk["bundle"])
    with pytest.raises(DataError) as e:
        tr.push(t[:100], acc[:100], gyr[:100])
    msg = str(e.value)
    assert "across pushes" not in msg and "sample 11 of this push" in msg and "repeats sample 10" in msg
    assert "drop_duplicate_timestamps=True" in msg and "\n" not in msg


def test_a_repeat_across_pushes_and_a_step_back_say_so(walk):
    t, acc, gyr = walk["t"], walk["acc"], walk["gyr"]
    tr = WaistTracker(walk["bundle"])
    tr.push(t[:50], acc[:50], gyr[:50])
    with pytest.raises(DataError, match=r"across pushes.*first sample \(t=0\.490000 s\) repeats the previous"):
        tr.push(t[49:60], acc[49:60], gyr[49:60])
    back = np.r_[t[50:55], t[53], t[56:60]]
    with pytest.raises(DataError, match=r"sample 5 of this push .* goes back from sample 4.*sort the samples"):
        tr.push(back, acc[50:60], gyr[50:60])


def test_drop_duplicate_timestamps_tracks_as_the_clean_stream(walk):
    clean = _track(WaistTracker(walk["bundle"]), walk["t"], walk["acc"], walk["gyr"])
    tr = WaistTracker(walk["bundle"], drop_duplicate_timestamps=True)
    got = _track(tr, *_repeated(walk, at=(10, 96, 500, 2000)))  # 96: the last of a push repeated by the next
    assert tr.n_dropped_duplicates == 4
    assert [s.t for s in got] == [s.t for s in clean] and len(got) > 10
    assert sum("decision E203" in w for w in tr.warnings) == 1


@pytest.mark.parametrize(("ratio", "said"), [(1e9, "are they in ns (an Android event timestamp)? push t in seconds "
                                                    "(t_ns / 1e9)"),
                                             (1e6, "are they in us? push t in seconds (t_us / 1e6)"),
                                             (1e3, "are they in ms? push t in seconds (t_ms / 1000)")])
def test_the_rate_unit_line_names_the_unit_of_the_ratio(ratio, said):
    with pytest.raises(DataError) as e:
        check_rate_unit("wAccelerometer", 50.0 / ratio, 50.0, "fs=")
    assert str(e.value).endswith(said)


def test_a_refused_push_with_a_dropped_repeat_changes_nothing_and_names_the_pushed_index(walk):
    """E203 amended (review R3 finding 3): ``t[50:53], t[52], t[51], ...`` with drop_duplicate_timestamps=True: the
    step back is sample 4 of the pushed array (it was named 3, counted after the repeat was dropped), and the refused
    push neither counts its repeat nor adds the warning line; the corrected push then counts one repeat (was 2)."""
    t, acc, gyr = walk["t"], walk["acc"], walk["gyr"]
    tr = WaistTracker(walk["bundle"], drop_duplicate_timestamps=True)
    tr.push(t[:50], acc[:50], gyr[:50])
    bad = np.r_[t[50:53], t[52], t[51], t[53:60]]
    with pytest.raises(DataError, match=r"sample 4 of this push \(t=0\.510000 s\) goes back from sample 3 "
                                        r"\(t=0\.520000 s\)"):
        tr.push(bad, acc[50:62], gyr[50:62])
    assert tr.n_dropped_duplicates == 0 and not any("E203" in w for w in tr.warnings)
    tr.push(np.r_[t[50:53], t[52], t[53:60]], acc[50:61], gyr[50:61])
    assert tr.n_dropped_duplicates == 1 and sum("E203" in w for w in tr.warnings) == 1
