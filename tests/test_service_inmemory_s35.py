"""Trial T7's findings on in-memory sessions and API errors in a service (decisions E181, B349, E182, B350)."""

from __future__ import annotations

import logging

import pytest

from pdrlearn import get_pipeline
from pdrlearn.errors import DataError
from pdrlearn.io import Session
from pdrlearn.sim import simulate


@pytest.fixture(scope="module")
def walk():
    return simulate("walk", 8581, length_m=10)


def test_session_built_in_memory_takes_the_frames_its_meta_declares_e181(walk, caplog):
    """T7 #2: ``Session(meta=...)`` ignored meta["frames"] and tracking inferred them with a warning naming a
    meta.json the session does not have."""
    declared = {k: v.to_dict() for k, v in walk.frames.items()}
    up = Session(name="up", streams=walk.streams, meta={**walk.meta, "frames": declared})
    assert up.frames == walk.frames
    r = get_pipeline("plasys")(up)
    assert not [w for w in r.info["warnings"] if "declares no axis frame" in w]
    given = Session(name="given", streams=walk.streams, meta={"frames": {"foot": declared["waist"]}},
                    frames={"foot": walk.frames["foot"]})
    assert given.frames == {"foot": walk.frames["foot"]}  # frames= given wins
    with pytest.raises(DataError, match=r"session 'bad', meta: \"frames\" must be an object"):
        Session(name="bad", streams=walk.streams, meta={"frames": ["foot"]})
    bare = Session(name="bare", streams={k: v for k, v in walk.streams.items() if k.startswith("f")})
    with caplog.at_level(logging.WARNING, logger="pdrlearn"):
        bare.require_frame("foot")
    line = next(r.getMessage() for r in caplog.records if "declares no axis frame" in r.getMessage())
    assert "the Session's frames=" in line and "to meta.json" not in line


def test_import_csv_and_read_stream_given_a_file_object_say_so_in_one_line_b349(tmp_path):
    """T7 #3: ``import_csv(io.BytesIO(...))`` / ``read_stream(io.StringIO(...))`` were a bare TypeError (read_session's
    was one line)."""
    import io

    from pdrlearn.io import read_stream
    from pdrlearn.io.importer import import_csv

    for call, arg, caller in ((import_csv, io.BytesIO(b"t,ax\n0,1\n"), "import_csv"),
                              (read_stream, io.StringIO("timestamp,x,y,z\n"), "read_stream")):
        with pytest.raises(DataError) as info:
            call(arg)
        text = str(info.value)
        assert text.startswith(f"{caller}(<_io.") and "\n" not in text
        assert "a str or pathlib.Path (got " in text and "write it to a file first" in text and "B349" in text
    with pytest.raises(DataError, match=r"import_csv\(42\): expected a CSV or MAT file, a str or pathlib.Path "
                                        r"\(got int\)$"):
        import_csv(42)


def test_auto_pipeline_chooses_as_the_cli_and_plasys_names_the_waist_pipeline_e182(walk):
    """T7 #5: ``get_pipeline("auto")`` was an unknown pipeline, and plasys on a waist-only session said "choose a
    method that does not need it" (no plasys method does)."""
    import dataclasses

    from pdrlearn.errors import MissingSensorError
    from pdrlearn.track.base import resolve_pipeline

    waist = dataclasses.replace(walk, streams={k: v for k, v in walk.streams.items() if k.startswith("w")})
    with pytest.raises(MissingSensorError, match=r"get_pipeline\('waist-pendulum'\)"):
        get_pipeline("plasys")(waist)
    auto = get_pipeline("auto")
    assert auto(walk).info["pipeline"] == resolve_pipeline("auto", walk) == "plasys"
    r = auto(waist)
    assert r.info["pipeline"] == "waist-pendulum"
    assert r.trajectory.equals(get_pipeline("waist-pendulum")(waist).trajectory)
    no_acc = dataclasses.replace(walk, streams={k: v for k, v in walk.streams.items() if k != "fAccelerometer"})
    r = auto(no_acc)  # decision B204's line, logged by the choice, kept with the result
    assert r.info["pipeline"] == "waist-pendulum"
    assert any(w.startswith("fAccelerometer.csv missing: foot unit ignored") for w in r.info["warnings"])


def test_evaluate_model_keeps_its_warnings_with_codes_b350():
    """T7 #6: ``evaluate_model`` printed its warnings (C64's absent classes) to stderr only; its result had no
    ``warnings``, unlike a track's ``info["warnings"]``."""
    from pdrlearn.classify import evaluate_model, train_user
    from pdrlearn.classify.evaluation import absent_warning

    model = train_user([simulate("terrain", user_seed=8583, seed=0)], tasks=["terrain"], methods=["svm"],
                       units=["foot"], cv=3, distance_calibration=False)
    out = evaluate_model(model, [simulate("walk", 8583, length_m=15)], latency=False)
    absent = out["tasks"]["terrain"]["absent_classes"]
    assert absent  # a level walk holds no stairs step
    line = absent_warning("terrain", absent)
    assert line in out["warnings"]
    assert out["warning_codes"][out["warnings"].index(line)] == "C64"
    assert len(out["warning_codes"]) == len(out["warnings"])
