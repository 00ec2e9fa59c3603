"""Decision L70 (new-user trial s15, finding 7): `pdrlearn plot` wrote PNG only ("output must end in .png" for
fig.pdf / fig.svg), had no resolution option (neither had track's and run's path.png), drew a --start/--end
window on an axis widened by the strides it cut (4.2-11.2 s for 5-10 s) with their shading spilling over,
titled it with the whole session's count of labelled steps, and could not shade detected strides."""

from __future__ import annotations

import json
import struct

import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.plots import DEFAULT_DPI, DPI_RANGE, PLOT_CREATOR, session_figure, steps_in_window


def _png_size(path) -> tuple[int, int]:
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    return struct.unpack(">II", data[16:24])


@pytest.fixture(scope="module")
def stairs(real_dir):
    return real_dir / "gaitmap_stairs_up_left"


@pytest.fixture(scope="module")
def tracked(stairs, tmp_path_factory):
    """`pdrlearn track --method M1` of the stairs at the default resolution, once per module: its path.png for the
    dpi test and its steps.csv for the shading test (each ran it before session 32)."""
    out = tmp_path_factory.mktemp("plot_track") / "T"
    assert main(["track", str(stairs), "--method", "M1", "--out", str(out)]) == 0
    return out


def test_pdf_and_svg_are_written_marked_and_replaced_only_when_ours(stairs, tmp_path, capsys):
    for suffix, head in ((".pdf", b"%PDF-"), (".svg", b"<?xml")):
        out = tmp_path / f"fig{suffix}"
        assert main(["plot", str(stairs), "--out", str(out)]) == 0, capsys.readouterr().err
        data = out.read_bytes()
        assert data.startswith(head) and PLOT_CREATOR.encode() in data
        assert main(["plot", str(stairs), "--out", str(out), "--force"]) == 0  # our own figure: replaced
        foreign = tmp_path / f"other{suffix}"
        foreign.write_bytes(head + b" not a pdrlearn figure")
        assert main(["plot", str(stairs), "--out", str(foreign), "--force"]) == 2
        assert "is not a session plot" in capsys.readouterr().err
        assert foreign.read_bytes() == head + b" not a pdrlearn figure"
    assert main(["plot", str(stairs), "--out", str(tmp_path / "fig.jpg")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "must end in .png, .pdf or .svg" in err


def test_dpi_scales_the_plot_and_the_track_figure(stairs, tracked, tmp_path, capsys):
    assert DPI_RANGE[0] <= DEFAULT_DPI <= DPI_RANGE[1]
    sizes = {}
    for dpi in (None, 2 * DEFAULT_DPI):
        out = tmp_path / f"p{dpi}.png"
        assert main(["plot", str(stairs), "--out", str(out), *(["--dpi", str(dpi)] if dpi else [])]) == 0
        sizes[dpi] = _png_size(out)
    w0, w1 = sizes[None][0], sizes[2 * DEFAULT_DPI][0]
    assert 1.9 < w1 / w0 < 2.1, sizes  # bbox "tight" rounds a few pixels
    sizes[("track", None)] = _png_size(tracked / "path.png")
    assert main(["track", str(stairs), "--method", "M1", "--out", str(tmp_path / "t55"), "--dpi", "55"]) == 0, \
        capsys.readouterr().err
    sizes[("track", 55)] = _png_size(tmp_path / "t55" / "path.png")
    assert 0.45 < sizes[("track", 55)][0] / sizes[("track", None)][0] < 0.55, sizes
    for cmd in ("plot", "track", "run"):  # the bounds of every --dpi are DPI_RANGE
        assert main([cmd, "--help"]) == 0
        assert f"{DPI_RANGE[0]}<=x<={DPI_RANGE[1]}" in capsys.readouterr().out
    assert main(["plot", str(stairs), "--out", str(tmp_path / "x.png"), "--dpi", str(DPI_RANGE[1] + 1)]) == 2
    capsys.readouterr()
    assert main(["run", str(tmp_path / "no_bundle"), str(stairs), "--dpi", "200"]) == 2  # no --out: refused
    assert "only --out writes" in capsys.readouterr().err


def test_window_is_the_axis_shading_is_clipped_and_the_title_counts_the_window(stairs):
    s = read_session(stairs)
    lo, hi = 5.0, 10.0
    t0 = s.t_start
    shown, cut = steps_in_window(s.steps, t0 + lo, t0 + hi)
    assert 0 < len(shown) < len(s.steps) and cut >= 1  # the window cuts a stride: the case of the trial
    plt, fig = session_figure(s, start=lo, end=hi)
    try:
        for ax in fig.axes:
            assert ax.get_xlim() == (lo, hi)
            spans = [p for p in ax.patches]
            assert len(spans) == len(shown)
            for p in spans:
                x0, x1 = p.get_x(), p.get_x() + p.get_width()
                assert lo - 1e-9 <= x0 <= x1 <= hi + 1e-9, (x0, x1)
        title = fig._suptitle.get_text()
        assert f"{len(shown)} labelled step(s) in the window" in title and f"({cut} cut by the window)" in title
        assert f" {len(s.steps)} labelled" not in title
    finally:
        plt.close(fig)
    plt, fig = session_figure(s)  # no window: the whole session, every labelled step
    try:
        assert fig.axes[0].get_xlim() == pytest.approx((0.0, s.t_end - t0))
        assert f"{len(s.steps)} labelled step(s)" in fig._suptitle.get_text()
    finally:
        plt.close(fig)


def test_detected_and_tracked_strides_can_be_shaded(stairs, tracked, tmp_path, capsys, monkeypatch):
    import pdrlearn.plots as plots
    from pdrlearn.cli.steps import auto_detector

    seen = {}
    real = plots.session_figure

    def spy(session, **kw):
        seen.update(kw)
        return real(session, **kw)

    monkeypatch.setattr(plots, "session_figure", spy)
    s = read_session(stairs)
    det = auto_detector(s)
    n = len(det.detect(s))
    assert main(["plot", str(stairs), "--out", str(tmp_path / "d.png"), "--steps", "detected"]) == 0
    assert seen["steps_what"] == f"detected stride(s) ({det.name})" and len(seen["steps"]) == n
    rows = pd.read_csv(tracked / "steps.csv")
    assert main(["plot", str(stairs), "--out", str(tmp_path / "t.svg"), "--steps", str(tracked)]) == 0
    assert len(seen["steps"]) == len(rows) and "steps.csv" in seen["steps_what"]
    capsys.readouterr()
    bad = tmp_path / "bad.csv"
    bad.write_text("a,b\n1,2\n")
    far = tmp_path / "far.csv"
    far.write_text("start_s,end_s\n5000,5001\n")
    for arg, needle in ((str(bad), "no start_s or end_s column"), (str(far), "outside session"),
                        (str(tmp_path / "nothing"), "no such file or folder")):
        assert main(["plot", str(stairs), "--out", str(tmp_path / "x.png"), "--steps", arg]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and needle in err, err
    other = tmp_path / "T2"
    other.mkdir()
    (other / "steps.csv").write_text((tracked / "steps.csv").read_text())
    (other / "summary.json").write_text(json.dumps({"session": "another_walk"}))
    assert main(["plot", str(stairs), "--out", str(tmp_path / "o.png"), "--steps", str(other)]) == 0
    assert "tracked from session 'another_walk'" in capsys.readouterr().err
