"""Session 47, trial T3 (a 1000 Hz lab) findings F4: ``--params`` takes the JSON object inline (B466), and a foot
accelerometer clipped at +-16 g or more names the altitude and ``clip_noise`` (B467)."""
import json

import pytest

from pdrlearn.cli.track import read_params
from pdrlearn.errors import DataError
from pdrlearn.kernels.clipping import saturation_warning

G = 9.80665


def test_b466_inline_json_is_read_and_a_file_still_wins(tmp_path):
    assert read_params('{"clip_noise": true}') == {"clip_noise": True}
    assert read_params('  {"rest_s": 0.05} ') == {"rest_s": 0.05}
    f = tmp_path / "p.json"
    f.write_text(json.dumps({"leg_m": 0.9}))
    assert read_params(f) == {"leg_m": 0.9}


def test_b466_bad_inline_json_and_a_missing_file_say_which_and_how(tmp_path):
    with pytest.raises(DataError, match=r"not a file, and not a JSON object either .*quote the JSON"):
        read_params('{"clip_noise": tru}')
    with pytest.raises(DataError, match="cannot read the parameters JSON"):
        read_params(tmp_path / "none.json")
    with pytest.raises(DataError, match="must be a JSON object"):
        read_params(_write(tmp_path / "l.json", "[1, 2]"))


def _write(p, text):
    p.write_text(text)
    return p


def test_b467_a_16_g_foot_line_names_the_altitude_and_clip_noise():
    line = saturation_warning("f.csv", "accelerometer", 50, 64380, 16 * G, "foot")
    assert "simulated walks" not in line  # B453's 100 Hz table has no 16 g row
    # session 48, B471: the race walks' measured cost replaces "no cost at 100 Hz", and B470's default is named
    assert "simulated race walks at this range (100 Hz, 3.1-3.6 m/s) read the distance -4.34 % off" in line
    assert "which left -0.41 % (B470; --params '{\"clip_noise\": false}' turns it off)" in line
    assert "stair heights" in line and "B467" in line and "B471" in line
    low = saturation_warning("f.csv", "accelerometer", 46, 6878, 4 * G, "foot")
    assert "B467" not in low and "-26.85 %" in low  # B453's measured cost, not B467's clause
    waist = saturation_warning("w.csv", "accelerometer", 6, 6878, 16 * G, "waist")
    assert "B467" not in waist and "clip_noise" not in waist


def test_b466_track_all_keys_an_inline_json_by_its_text_t1_f5(tmp_path):
    """Session 48, trial T1 F5: track-all's resume key read the inline JSON as a file name and stopped ("No such
    file or directory"); the key is now the JSON's own text, a file's its bytes."""
    from pdrlearn.cli.resume import session_keys

    same, other = _write(tmp_path / "p.json", '{"clip_noise": true}'), _write(tmp_path / "q.json", '{"rest_s": 1}')
    keys = [session_keys({}, [tmp_path], [{"params": p}], None)[0]
            for p in ('{"clip_noise": true}', '{"clip_noise": false}', same, other)]
    assert len(set(keys)) == 3 and keys[0] == keys[2]  # the same JSON, inline or in a file: the same key


def test_b466_the_lower_back_reads_inline_json_too_t2_f10():
    """Session 48, trial T2 F10: ``track --units waist --params '{...}'`` said "parameter file not found"."""
    from pdrlearn.waist.params import load_params

    assert load_params('{"options": {"freeze_veto": true}}').options == {"freeze_veto": True}
    with pytest.raises(DataError, match=r"not a file, and not a JSON object either"):
        load_params('{"options": tru}')
    with pytest.raises(DataError, match="waist parameters must be a JSON object|unknown key"):
        load_params('{"clip_noise": true}')
