"""One wording for an undeclared unit axis frame (decision B18): the step windows, the orientation filters'
unit data, the waist AHRS and the Colombo tracker all raise ``Session.require_frame``'s error, which names
the session's meta.json and the ``frames`` entry to add. Before: three wordings, none with the path. Since
decision D8 an undeclared frame is inferred from the data; the fixture's units are turned 45 deg about the
vertical, so the data does not fix the axes and the wording (with the reason) is what every caller gives."""

from __future__ import annotations

import json

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from pdrlearn.errors import DataError
from pdrlearn.io.frames import THESIS_FOOT_FRAME


@pytest.fixture(scope="module")
def no_frames(tmp_path_factory):
    from pdrlearn.io import read_session, write_session
    from pdrlearn.sim import simulate
    from pdrlearn.track.frame_inference import remount

    folder = tmp_path_factory.mktemp("nf") / "walk"
    s = simulate("walk", user_seed=2, length_m=15.0)
    turn = Rotation.from_rotvec(np.radians(45.0) * np.array([0.0, 1.0, 0.0])).as_matrix()
    for placement in ("foot", "waist"):  # 45 deg about their up axis (y): the data cannot fix forward (D8)
        s = remount(s, placement, turn)
    write_session(s, folder)
    meta = json.loads((folder / "meta.json").read_text())
    meta.pop("frames", None)
    (folder / "meta.json").write_text(json.dumps(meta))
    return read_session(folder)


def _message(fn) -> str:
    with pytest.raises(DataError) as exc:
        fn()
    return str(exc.value)


def _callers(placement):
    from pdrlearn.aid.colombo import ColomboTracker
    from pdrlearn.features.windows import _declared_forward
    from pdrlearn.orient.filters import unit_data
    from pdrlearn.waist.ahrs import body_data

    out = {"windows": lambda s: _declared_forward(s, placement), "filters": lambda s: unit_data(s, placement)}
    if placement == "waist":
        out |= {"ahrs": body_data, "colombo": lambda s: ColomboTracker().run(s)}
    return out


@pytest.mark.parametrize("placement", ["foot", "waist"])
def test_every_caller_names_meta_json_and_the_entry(no_frames, placement):
    meta = str(no_frames.folder / "meta.json")
    example = {"foot": '"frames": {"foot": {"x": "forward", "y": "up", "z": "right"}}',
               "waist": '"frames": {"waist": {"x": "left", "y": "up", "z": "forward"}}'}[placement]
    msgs = {name: _message(lambda f=f: f(no_frames)) for name, f in _callers(placement).items()}
    assert len(set(msgs.values())) == 1, msgs
    msg = next(iter(msgs.values()))
    assert msg.startswith(f"{meta}: session '{no_frames.name}' declares no axis frame for the {placement} unit")
    assert msg.endswith(example), msg


def test_a_session_built_in_memory_has_no_path_to_name(no_frames):
    s = no_frames.copy()
    s.folder = None
    msg = _message(lambda: s.require_frame("foot"))
    assert msg.startswith(f"session '{s.name}' (its meta.json) declares no axis frame for the foot unit"), msg
    s.frames = {"foot": THESIS_FOOT_FRAME}
    assert s.require_frame("foot") is THESIS_FOOT_FRAME  # a declared frame is returned as is
