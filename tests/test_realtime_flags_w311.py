"""Decision W311 (session 32 review 2, finding 3): W278's "walking on both sides" test reads the contacts after the
offline sit veto also on a track that applies none (``--realtime``), so offline and realtime flag the same rows."""

from __future__ import annotations

import json

from pdrlearn.cli import main


def _flags(session, out, *extra):
    assert main(["track", "--no-plot", str(session), *extra, "--out", str(out)]) == 0
    return json.loads((out / "summary.json").read_text())["n_transfers_flagged"]


def test_realtime_flags_the_rows_offline_flags(real_dir, tmp_path, capsys):
    session = real_dir / "mobgap_HA001_Test11_Trial1"
    offline = _flags(session, tmp_path / "off")
    realtime = _flags(session, tmp_path / "rt", "--pipeline", "waist-pendulum", "--realtime")
    err = capsys.readouterr().err
    assert offline == realtime == 2  # before W311 realtime flagged 4 (rows 1-2 "walking on both sides")
    assert ": walking on both sides)" not in err and ": walking on both sides;" not in err
