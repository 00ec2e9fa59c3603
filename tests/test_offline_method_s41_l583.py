"""Decision L583 (session 41, trial T1 finding F11): the offline `track --model` steps.csv says which classifier
classed each stride (``method_<task>``), as the streamed table always did."""

from __future__ import annotations

from pdrlearn.classify.training import train_user
from pdrlearn.columns import undocumented
from pdrlearn.sim.simulate import simulate
from pdrlearn.track.plasys import track_plasys


def test_offline_and_streamed_tables_name_the_classifier():
    model = train_user([simulate("direction", user_seed=11528, seed=0)], tasks=["direction"], methods=["svm"],
                       units=["foot"], cv=3, distance_calibration=False)
    walk = simulate("direction", user_seed=11528, seed=1)
    offline = track_plasys(walk, method="M3", model=model).steps
    streamed = track_plasys(walk, method="M3", model=model, streaming=True).steps
    for table in (offline, streamed):
        assert "method_direction" in table
        used = table["method_direction"].dropna().astype(str)
        assert len(used) and set(used) == {"svm/foot"}
    assert undocumented("steps.csv (foot)", ["method_direction", "method_terrain"]) == []
