"""Decision W232: experiments/hapt_transfers.py's matching rule on hand-made rows."""
import importlib.util
from pathlib import Path

import pandas as pd

_spec = importlib.util.spec_from_file_location(
    "hapt_transfers", Path(__file__).resolve().parents[1] / "experiments" / "hapt_transfers.py")
ht = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(ht)


def _labels():
    act = pd.DataFrame({"start_ms": [0, 10000, 13000, 30000, 33000, 50000, 53000],
                        "end_ms": [9980, 12980, 29980, 32980, 49980, 52980, 70000],
                        "activity": ["standing", "stand_to_sit", "sitting", "sit_to_stand", "walking",
                                     "sit_to_lie", "lying"]})
    return ht.labels(act)


def test_matching_rule_kinds_tolerance_and_false_rows():
    rows = pd.DataFrame({"kind": ["stand-to-sit", "stand-to-sit", "stand-to-sit", "sit-to-stand", "sit-to-stand"],
                         "start_s": [10.5, 11.0, 29.0, 51.0, 80.0], "end_s": [12.0, 12.5, 31.0, 52.0, 81.0],
                         "peak_s": [11.2, 11.9, 29.5, 51.5, 80.5]})
    r, tr = ht.match(rows, _labels())
    # 11.2 and 11.9 both in stand_to_sit [10, 13]; the one nearer its middle (11.5) wins, the other is false
    assert list(r.verdict) == ["right", "false", "kind error", "lying", "false"]
    assert list(r.in_activity) == ["stand_to_sit", "stand_to_sit", "sitting", "sit_to_lie", "unlabelled"]
    # 29.5 s lies 0.5 s before sit_to_stand (30 s): within the 1 s tolerance, matched with the wrong kind
    assert tr.set_index("activity").row.to_dict() == {"stand_to_sit": 0, "sit_to_stand": 2, "sit_to_lie": 3}


def test_a_peak_beyond_the_tolerance_matches_nothing():
    rows = pd.DataFrame({"kind": ["sit-to-stand"], "start_s": [27.0], "end_s": [28.5], "peak_s": [28.9]})
    r, tr = ht.match(rows, _labels())
    assert list(r.verdict) == ["false"] and (tr.row == -1).all()
    r, _ = ht.match(rows, _labels(), tol=1.2)
    assert list(r.verdict) == ["right"]
