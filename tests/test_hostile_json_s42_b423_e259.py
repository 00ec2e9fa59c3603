"""Trial T1 findings F4, F5 (session 42): a deeply nested JSON file (meta.json, --params, a bundle manifest) gave
a RecursionError traceback (decision B423); a bundle manifest's sampling.rate_hz of -20 a math domain traceback
and 1e308 a 300-digit message (decision E259); a -1e308 timestamp printed 309 digits (decision B424)."""

from __future__ import annotations

import hashlib
import json
import shutil
from pathlib import Path

import numpy as np
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError, message_number
from pdrlearn.io.validate import clock_reset_message
from pdrlearn.textfile import JSON_MAX_BYTES, read_json

BUNDLE = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"
DEEP = "[" * 100000 + "]" * 100000


@pytest.fixture(scope="module")
def walk(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("b423") / "walk"
    assert main(["simulate", "--route", "stand:2, straight:6, stand:2", "--user-seed", "11852", "--out", str(out),
                 "--json"]) == 0
    return out


def _one_error(argv, capsys) -> str:
    capsys.readouterr()
    assert main([str(a) for a in argv]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error: "), err
    return err[0]


def test_read_json_turns_deep_nesting_into_a_json_error(tmp_path):
    p = tmp_path / "deep.json"
    p.write_text(DEEP)
    with pytest.raises(json.JSONDecodeError, match="nested too deep"):
        read_json(p)


def test_read_json_refuses_a_file_over_the_cap(tmp_path):
    p = tmp_path / "big.json"
    with open(p, "wb") as f:
        f.truncate(JSON_MAX_BYTES + 1)  # sparse: no 64 MB written
    with pytest.raises(DataError, match="larger than the 64 MB"):
        read_json(p)


def test_deep_params_meta_and_manifest_are_one_line(walk, tmp_path, capsys):
    params = tmp_path / "deep.json"
    params.write_text('{"a": ' + DEEP + "}")
    err = _one_error(["track", walk, "--params", params, "--out", tmp_path / "t", "--no-plot"], capsys)
    assert str(params) in err and "nested too deep" in err
    session = tmp_path / "deep_session"
    shutil.copytree(walk, session)
    meta = json.loads((session / "meta.json").read_text())
    (session / "meta.json").write_text(json.dumps(meta)[:-1] + ', "deep": ' + DEEP + "}")
    err = _one_error(["info", session], capsys)
    assert "meta.json: invalid JSON (line 1: nested too deep" in err
    bundle = _bundle(tmp_path / "b", lambda m: DEEP)
    err = _one_error(["run", bundle, walk, "--out", tmp_path / "r", "--no-plot"], capsys)
    assert f"bundle {bundle}: manifest.json is not valid JSON (nested too deep" in err


def _bundle(dest: Path, change) -> Path:
    """A copy of the shipped bundle whose manifest is ``change(manifest)`` (JSON text or an object), its checksum
    re-made (what a tampered or hand-edited bundle looks like)."""
    shutil.copytree(BUNDLE, dest)
    m = change(json.loads((dest / "manifest.json").read_text()))
    (dest / "manifest.json").write_text(m if isinstance(m, str) else json.dumps(m, indent=2))
    (dest / "manifest.sha256").write_text(hashlib.sha256((dest / "manifest.json").read_bytes()).hexdigest() + "\n")
    return dest


@pytest.mark.parametrize("rate, shown", [(-20, "-20"), (1e308, "1e+308"), (0, "0"), ("20", "'20'"),
                                         (20000.0, "20000")])
def test_manifest_rate_outside_the_range_is_one_line(rate, shown, walk, tmp_path, capsys):
    def bad(m):
        m["sampling"]["rate_hz"] = rate
        return m

    b = _bundle(tmp_path / "b", bad)
    err = _one_error(["run", b, walk, "--out", tmp_path / "r", "--no-plot"], capsys)
    assert err == (f"error: bundle {b}: manifest.json sampling.rate_hz {shown} is not a rate above 0 and at most "
                   "10000 Hz; re-export the bundle (decision E259)")
    assert len(err) < 300


def test_manifest_source_rate_is_checked_too(walk, tmp_path, capsys):
    def bad(m):
        m["sampling"]["source_rates_hz"]["fGyroscope"] = -1
        return m

    err = _one_error(["run", _bundle(tmp_path / "b", bad), walk, "--out", tmp_path / "r", "--no-plot"], capsys)
    assert "sampling.source_rates_hz.fGyroscope -1 is not a rate" in err


def test_message_numbers_are_short():
    assert message_number(2.4) == "2.40"
    assert message_number(-1e308) == "-1e+308"
    assert message_number(5e306, 0) == "5e+306"
    line = clock_reset_message(np.array([2.4, -1e308]), np.array([0]), "f.csv", "line 3", "split it")
    assert "from 2.40 s to -1e+308 s at line 3" in line and len(line) < 300
