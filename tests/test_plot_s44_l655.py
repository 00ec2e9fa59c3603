"""Decision L655 (trial T2, finding F11): `pdrlearn plot --shade travel` shades a foot track's strides by steps.csv
``travel`` (forward / backward / left / right / side / turn) - main shaded by terrain only, every stride of a
side-step walk "flat" - and path.png marks the end of each backward and side stride. Fresh user 12544."""

from __future__ import annotations

import logging

import pytest
from matplotlib.colors import to_hex

from pdrlearn.cli import main
from pdrlearn.plots import SHADE_COLOURS, session_figure
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import get_pipeline
from pdrlearn.track.plots import TRAVEL_MARKERS, path_figure

ROUTE = "stand:2, straight:3, backward:2, side:1.5, straight:1, stand:2"


@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    from pdrlearn.io.plasys import write_session

    s = simulate_path(parse_route(ROUTE), UserProfile.from_seed(12544), speed="normal", rate_hz=50.0, seed=3,
                      scenario="route")
    where = tmp_path_factory.mktemp("l655")
    write_session(s, where / "walk")
    out = where / "track"
    assert main(["track", str(where / "walk"), "--out", str(out)]) == 0
    return s, where / "walk", out


def test_the_figure_shades_by_travel(walk):
    import pandas as pd

    s, _, out = walk
    st = pd.read_csv(out / "steps.csv")
    assert {"backward", "forward"} <= set(st["travel"].dropna())
    _, fig = session_figure(s, steps=st, steps_what="strides", shade="travel")
    colours = {to_hex(p.get_facecolor()) for p in fig.axes[0].patches}
    assert SHADE_COLOURS["travel"]["backward"] in colours  # main: no shade keyword, backward shaded as flat
    legend = [t.get_text() for lg in fig.legends for t in lg.get_texts()]
    assert "backward" in legend and "turn" in legend


def test_plot_takes_shade_travel_and_refuses_it_without_a_travel_column(walk, tmp_path, capsys):
    _, folder, out = walk
    assert main(["plot", str(folder), "--out", str(tmp_path / "t.png"), "--steps", str(out), "--shade",
                 "travel"]) == 0
    capsys.readouterr()
    assert main(["plot", str(folder), "--out", str(tmp_path / "x.png"), "--shade", "travel"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--shade travel" in err and "no travel column" in err
    assert not (tmp_path / "x.png").exists()


def test_path_png_marks_backward_and_side_strides(walk):
    s = walk[0]
    logging.disable(logging.WARNING)
    try:
        res = get_pipeline("plasys")(s)
    finally:
        logging.disable(logging.NOTSET)
    _, fig = path_figure({"M3": res}, session=s)
    labels = [ln.get_label() for ln in fig.axes[0].get_lines()]
    assert TRAVEL_MARKERS[0][3] in labels  # the backward strides' markers
