"""Bluetooth text protocol parser (thesis ch.4.2.3, Table 10)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from pdrlearn.io import BluetoothParser, format_protocol, parse_protocol
from tests.test_io import make_session

CLEAN = (
    "%$1 0.1 9.8 0.2$2 0.01 -0.02 0.03$3 310.5$4 12.0\n"
    "%$1 0.2 9.7 0.3$2 0.02 -0.01 0.04$3 300.0$4 20.0\n"
    "%$1 0.3 9.6 0.4$2 0.03 0.00 0.05$3 290.0$4 25.0\n"
)


def test_parse_clean_stream():
    session, stats = parse_protocol(CLEAN)
    assert stats.sets == 3 and stats.measurements == 12 and stats.corrupted == 0
    acc = session["fAccelerometer"]
    np.testing.assert_allclose(acc.t, [0.0, 0.05, 0.1])  # 20 Hz (thesis ch.4.2.3)
    np.testing.assert_allclose(acc.values[1], [0.2, 9.7, 0.3])
    np.testing.assert_allclose(session["fForceB"].values[:, 0], [12.0, 20.0, 25.0])


def test_corrupted_measurements_are_counted_and_skipped():
    text = (
        "garbage before start"
        "%$1 0.1 9.8 0.2$2 0.01 -0.02 0.03$3 310.5$4 12.0"
        "%$1 0.2 9.7$2 0.02 -0.01 0.04$9 1 2 3$4 abc"      # acc short, unknown type 9, force non-numeric
        "%$1 0.3 9.6 0.4$2 0.03 0.00 0.05$3 290.0$4 25.0"
        "%$1 0.4,9.5,0.5$1 0.4 9.5 0.5$3 1e400$4 1"         # commas ok, duplicate type, inf value
    )
    session, stats = parse_protocol(text)
    assert stats.sets == 4
    assert stats.corrupted == 1 + 3 + 2  # leading garbage; three in set 2; duplicate + inf in set 4
    # the corrupted set still advances the clock: acc has a gap at t = 0.05
    np.testing.assert_allclose(session["fAccelerometer"].t, [0.0, 0.1, 0.15])
    np.testing.assert_allclose(session["fGyroscope"].t, [0.0, 0.05, 0.1])
    assert session["fForceA"].t.tolist() == [0.0, 0.1]


def test_raw_count_scaling():
    session, _ = parse_protocol("%$1 0 256 0", scales={"fAccelerometer": 9.81 / 256})  # thesis eq. 24
    np.testing.assert_allclose(session["fAccelerometer"].values[0], [0, 9.81, 0])


def test_format_then_parse_round_trip():
    s = make_session(n=30)
    text = "".join(format_protocol(s, decimals=9))
    parsed, stats = parse_protocol(text)
    assert stats.corrupted == 0 and stats.sets == 30
    for name in ("fAccelerometer", "fGyroscope", "fForceA", "fForceB"):
        np.testing.assert_allclose(parsed[name].values, s[name].values, atol=1e-9)


@settings(max_examples=60, deadline=None)
@given(st.lists(st.integers(min_value=1, max_value=40), min_size=1, max_size=30))
def test_chunking_does_not_change_the_result(cuts):
    text = CLEAN * 3 + "%$1 1 2$3 x"  # ends with a corrupted set
    pos, chunks = 0, []
    for c in cuts:
        chunks.append(text[pos:pos + c])
        pos += c
    chunks.append(text[pos:])
    p = BluetoothParser()
    got = []
    for ch in chunks:
        got.extend(p.feed(ch))
    got.extend(p.close())
    whole, stats = parse_protocol(text)
    assert p.stats.to_dict() == stats.to_dict()
    assert len(got) == stats.measurements
    np.testing.assert_allclose(p.streams()["fAccelerometer"].values, whole["fAccelerometer"].values)


def test_empty_stream():
    session, stats = parse_protocol("")
    assert stats.sets == 0 and session.streams == {}


@pytest.mark.parametrize("chunk", ["%", "%%%", "%$", "%$1"])
def test_degenerate_sets_never_crash(chunk):
    _, stats = parse_protocol(chunk)
    assert stats.measurements == 0


def _capture_at(rate_hz: float) -> str:
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route

    s = simulate_path(parse_route("straight:25"), UserProfile.from_seed(1795), speed="normal", rate_hz=rate_hz,
                      seed=0, name="e90", scenario="route")
    return "".join(format_protocol(s, decimals=4))


@pytest.mark.parametrize("pod_hz, read_hz, warns", [(20.0, 20.0, False), (50.0, 50.0, False), (50.0, 20.0, True),
                                                     (10.0, 20.0, True)])
def test_a_capture_read_at_a_wrong_rate_has_a_non_human_stride_rhythm(pod_hz, read_hz, warns):
    """Decision E90: the foot's stride rhythm at the assumed --protocol-rate outside L95's walking range warns,
    naming --protocol-rate and the rate that would make it a walk."""
    from pdrlearn.io.protocol import protocol_rate_line

    session, _ = parse_protocol(_capture_at(pod_hz), rate_hz=read_hz)
    line = protocol_rate_line(session.streams, read_hz, "cap")
    assert (line is not None) == warns
    if warns:
        assert f"--protocol-rate {read_hz:g} Hz" in line and "--protocol-rate HZ" in line and "decision E90" in line
        suggested = float(line.split("at about ")[1].split(" Hz")[0])
        assert 0.7 * pod_hz < suggested < 1.4 * pod_hz


def test_run_refuses_a_protocol_rate_without_a_capture(tmp_path, synthetic_bundle, capsys):
    from pdrlearn.cli import main

    assert main(["run", str(synthetic_bundle.path), str(tmp_path), "--protocol-rate", "52"]) == 2
    assert "--protocol-rate 52 is the rate of a --protocol capture" in capsys.readouterr().err
    assert main(["run", str(synthetic_bundle.path), "--protocol", "-", "--protocol-rate", "0"]) == 2
    assert "--protocol-rate 0: give the capture's sampling rate in Hz" in capsys.readouterr().err


def test_numbered_sets_show_lost_and_repeated_packets():
    """Decision E91: ``%#N`` numbers a set; a jump counts the sets lost and leaves their time empty, a repeated
    number is skipped, a 16-bit counter wraps; text before the first ``$`` was always ignored, so the numbered
    capture reads the same values."""
    text = ("%#65534$1 0 9.8 0\n%#65535$1 1 9.8 0\n%#2$1 2 9.8 0\n%#2$1 2 9.8 0\n%#3$1 3 9.8 0\n")
    session, stats = parse_protocol(text)
    assert stats.numbered == 5 and stats.lost == 2 and stats.corrupted == 1 and stats.sets == 5
    np.testing.assert_allclose(session["fAccelerometer"].t, [0.0, 0.05, 0.2, 0.25])
    np.testing.assert_allclose(session["fAccelerometer"].values[:, 0], [0, 1, 2, 3])
    s = make_session(n=30)
    numbered = list(format_protocol(s, decimals=9, numbered=True))
    assert numbered[3].startswith("%#3$")
    kept = numbered[:10] + numbered[13:]  # three packets lost
    parsed, stats = parse_protocol("".join(kept))
    assert stats.lost == 3 and stats.corrupted == 0
    np.testing.assert_allclose(parsed["fAccelerometer"].t, np.delete(np.arange(30) / 20.0, [10, 11, 12]))
    plain, plain_stats = parse_protocol("".join(format_protocol(s, decimals=9)))
    assert plain_stats.lost == 0 and plain_stats.numbered == 0  # without numbers a loss cannot be seen (D5)


def test_run_warns_of_lost_numbered_sets(tmp_path, synthetic_bundle, capsys):
    from pdrlearn.cli import main

    s = make_session(n=60)
    lines = list(format_protocol(s, numbered=True))
    (tmp_path / "cap.txt").write_text("".join(lines[:20] + lines[26:]))
    main(["run", "--no-plot", str(synthetic_bundle.path), "--protocol", str(tmp_path / "cap.txt")])
    assert "6 set(s) lost (10.0 % of 60" in capsys.readouterr().err


def test_run_refuses_an_empty_or_all_corrupted_capture(tmp_path, synthetic_bundle, capsys):
    """Decision B193: an empty capture (or one with no whole set) had tracked "0 steps, 0.00 m", exit 0."""
    from pdrlearn.cli import main

    for name, text in (("empty.txt", ""), ("garbage.txt", "%$\n%%%\n")):
        cap = tmp_path / name
        cap.write_text(text)
        out = tmp_path / ("out_" + name)
        assert main(["run", str(synthetic_bundle.path), "--protocol", str(cap), "--out", str(out)]) == 2
        err = capsys.readouterr().err
        assert f"protocol {cap}: no measurement sets" in err and "decision" not in err.split("error:")[0]
        assert not out.exists()
