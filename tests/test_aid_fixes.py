"""Fix readers (NMEA 0183, CSV), the local tangent plane and the fix generators."""

import numpy as np
import pandas as pd
import pytest

from pdrlearn.aid.fixes import nmea_checksum, parse_nmea_lines, read_fix_csv, read_fixes, read_nmea, to_local
from pdrlearn.aid.fixgen import gnss_fixes, infrastructure_fixes, landmark_fixes, write_nmea
from pdrlearn.aid.geo import enu_to_geodetic, geodetic_to_enu, haversine_m
from pdrlearn.errors import DataError


def _s(body: str) -> str:
    return f"${body}*{nmea_checksum(body):02X}"


def test_checksum_of_a_known_sentence():
    # the classic NMEA 0183 example sentence has checksum 47
    body = "GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,"
    assert nmea_checksum(body) == 0x47


def test_nmea_bad_checksum_and_empty_fixes_are_skipped_and_counted():
    lines = [
        _s("GPGGA,123519.00,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,"),
        _s("GPRMC,123519.00,A,4807.038,N,01131.000,E,0.5,54.7,230394,,,A"),
        "$GPGGA,123520.00,4807.039,N,01131.001,E,1,08,0.9,545.4,M,46.9,M,,*00",  # bad checksum
        "$GPGGA,123520.50,4807.039,N,01131.001,E,1,08,0.9,545.4,M,46.9,M,,",  # no checksum
        _s("GPGGA,123521.00,,,,,0,00,,,M,,M,,"),  # empty fix
        _s("GPRMC,123521.00,V,,,,,,,230394,,,N"),  # invalid status
        _s("GPGSV,3,1,11,03,03,111,00,04,15,270,00,06,01,010,00,13,06,292,00"),  # unsupported
        _s("GNGGA,123522.00,48xx.040,N,01131.002,E,1,08,0.9,545.4,M,46.9,M,,"),  # malformed number
        "garbage without a dollar sign",
        _s("GNRMC,123523.00,A,4807.041,S,01131.003,W,0.5,54.7,230394,,,A"),  # RMC only: default accuracy
    ]
    log = parse_nmea_lines(lines, uere_m=5.0, rmc_accuracy_m=12.0, t0_s=100.0)
    st = log.stats
    assert st["bad_checksum"] == 2 and st["empty"] == 2 and st["unsupported"] == 1 and st["malformed"] == 1
    assert st["used"] == 2 and len(log) == 2
    f = log.fixes
    assert f["t"].tolist() == pytest.approx([100.0, 104.0])
    assert f["lat"].iloc[0] == pytest.approx(48 + 7.038 / 60) and f["lon"].iloc[0] == pytest.approx(11 + 31.0 / 60)
    assert f["accuracy_m"].iloc[0] == pytest.approx(0.9 * 5.0)  # GGA merged with RMC keeps HDOP * UERE
    assert f["lat"].iloc[1] < 0 and f["lon"].iloc[1] < 0 and f["accuracy_m"].iloc[1] == 12.0


def test_nmea_midnight_rollover():
    lines = [
        _s("GPGGA,235959.00,4807.038,N,01131.000,E,1,08,1.0,545.4,M,46.9,M,,"),
        _s("GPGGA,000001.00,4807.038,N,01131.000,E,1,08,1.0,545.4,M,46.9,M,,"),
    ]
    assert parse_nmea_lines(lines).fixes["t"].tolist() == pytest.approx([0.0, 2.0])


def test_nmea_file_with_only_bad_sentences_is_one_line_error(tmp_path):
    p = tmp_path / "bad.nmea"
    p.write_text("$GPGGA,1,2,3*00\nhello\n")
    with pytest.raises(DataError) as e:
        read_nmea(p)
    assert "bad.nmea" in str(e.value) and "\n" not in str(e.value) and "1 bad checksum" in str(e.value)


def test_generated_fixes_round_trip_through_nmea(tmp_path):
    truth = pd.DataFrame({"t": [0.0, 100.0], "x": [0.0, 100.0], "y": [0.0, 50.0]})
    origin = (43.7696, 11.2558)
    fx = gnss_fixes(truth, accuracy_m=4.0, origin=origin, seed=3)
    path = write_nmea(fx, tmp_path / "walk.nmea")
    back = read_fixes(path)
    assert back.stats["used"] == len(fx) and back.stats["bad_checksum"] == 0
    loc, _ = to_local(back.fixes, origin)
    assert np.allclose(loc["x"], fx["x"], atol=0.03) and np.allclose(loc["y"], fx["y"], atol=0.03)
    assert np.allclose(back.fixes["accuracy_m"], fx["accuracy_m"], rtol=0.01, atol=0.03)
    assert np.allclose(back.fixes["t"], fx["t"] - fx["t"].iloc[0], atol=0.006)


def test_csv_reader_good_and_bad(tmp_path):
    good = tmp_path / "fixes.csv"
    pd.DataFrame({"t": [2.0, 1.0], "lat": [45.0, 45.0001], "lon": [9.0, 9.0], "accuracy_m": [3.0, 4.0]}).to_csv(
        good, index=False
    )
    log = read_fix_csv(good)
    assert log.fixes["t"].tolist() == [1.0, 2.0]  # sorted by time
    miss = tmp_path / "missing.csv"
    pd.DataFrame({"t": [1.0], "lat": [45.0], "lon": [9.0]}).to_csv(miss, index=False)
    with pytest.raises(DataError) as e:
        read_fix_csv(miss)
    assert "missing.csv" in str(e.value) and "accuracy_m" in str(e.value) and "\n" not in str(e.value)
    nan = tmp_path / "nan.csv"
    pd.DataFrame({"t": [1.0, 2.0], "x": [0.0, np.nan], "y": [0.0, 1.0], "accuracy_m": [1.0, 1.0]}).to_csv(
        nan, index=False
    )
    with pytest.raises(DataError, match="NaN"):
        read_fix_csv(nan)
    neg = tmp_path / "neg.csv"
    pd.DataFrame({"t": [1.0], "x": [0.0], "y": [0.0], "accuracy_m": [0.0]}).to_csv(neg, index=False)
    with pytest.raises(DataError, match="accuracy_m must be > 0"):
        read_fix_csv(neg)
    with pytest.raises(DataError, match="no such fix CSV"):
        read_fix_csv(tmp_path / "absent.csv")


def test_local_tangent_plane_round_trip_and_scale():
    lat0, lon0 = 43.7696, 11.2558
    lat, lon = enu_to_geodetic(np.array([100.0, -250.0]), np.array([300.0, 40.0]), lat0, lon0)
    e, n = geodetic_to_enu(lat, lon, lat0, lon0)
    assert np.allclose(e, [100.0, -250.0], atol=1e-6) and np.allclose(n, [300.0, 40.0], atol=1e-6)
    d = haversine_m(lat0, lon0, lat[0], lon[0])
    assert d == pytest.approx(np.hypot(100.0, 300.0), rel=2e-3)
    with pytest.raises(DataError):
        geodetic_to_enu(0.0, 0.0, 95.0, 0.0)


def test_gnss_noise_matches_reported_accuracy_and_outages():
    truth = pd.DataFrame({"t": [0.0, 4000.0], "x": [0.0, 0.0], "y": [0.0, 0.0]})
    fx = gnss_fixes(truth, accuracy_m=5.0, accuracy_spread=0.0, correlation_s=0.0, outages=[(100, 200)], seed=1)
    r = np.hypot(fx["x"], fx["y"])
    assert np.mean(r <= fx["accuracy_m"]) == pytest.approx(0.68, abs=0.03)  # 68 % radius
    assert not ((fx["t"] >= 100) & (fx["t"] < 200)).any()
    ind = gnss_fixes(truth, accuracy_m=5.0, indoor=[(0, 4001)], multipath_bias_m=20.0, seed=2)
    assert np.hypot(ind["x"].mean(), ind["y"].mean()) == pytest.approx(20.0, abs=3.0)
    assert ind["accuracy_m"].median() > 10.0


def test_landmark_and_infrastructure_fixes():
    truth = pd.DataFrame({"t": np.arange(0, 101.0), "x": np.arange(0, 101.0), "y": np.zeros(101)})
    lm = landmark_fixes(truth, [[50.0, 0.5], [10.0, 30.0]], radius_m=1.0)
    assert len(lm) == 1 and lm["t"].iloc[0] == 50.0 and lm["x"].iloc[0] == 50.0
    inf = infrastructure_fixes(truth, rate_hz=10.0, sigma_m=0.05, seed=0)
    assert len(inf) == 1001 and np.std(inf["y"]) == pytest.approx(0.05, rel=0.15)


def test_nmea_parser_never_raises_on_random_text():
    from hypothesis import given, settings
    from hypothesis import strategies as st

    field = st.text(alphabet="0123456789.,NSEWAV-*$GPRMCGA ", max_size=80)

    @settings(max_examples=100, deadline=None)
    @given(st.lists(st.one_of(field, st.text(max_size=40)), max_size=20))
    def run(lines):
        log = parse_nmea_lines(lines)
        s = log.stats
        assert s["used"] + s["bad_checksum"] + s["empty"] + s["malformed"] + s["unsupported"] <= s["sentences"]
        assert len(log) == s["used"]

    run()
    # random bodies with a correct checksum exercise the field parsing as well
    rng = np.random.default_rng(0)
    alphabet = list("0123456789.,NSEWAV-")
    lines = [_s("GPGGA," + "".join(rng.choice(alphabet, 60))) for _ in range(300)]
    lines += [_s("GPRMC," + "".join(rng.choice(alphabet, 60))) for _ in range(300)]
    log = parse_nmea_lines(lines)
    assert log.stats["sentences"] == 600 and log.stats["bad_checksum"] == 0
