"""Steps decision 99: a contact-to-contact labelled stride (an imported footfall table, B338) pairs with the tracked
stride by its initial contact, not by window overlap; native mid-stance windows keep the overlap."""

from types import SimpleNamespace

import numpy as np
import pandas as pd

from pdrlearn.track.evaluate import contact_windows, match_by_overlap, match_strides, stride_pairs

IC = 10.0 + 1.1 * np.arange(8)  # the labels' initial contacts, a 1.1 s stride


def _tracked(ic_shift: float = 0.06, window_shift: float = 0.41) -> pd.DataFrame:
    """Tracked strides: mid-stance to mid-stance (the window after each label's span by ``window_shift``), their
    IC ``ic_shift`` after the label's (the trial's 13.90-15.00 s stride: IoU ~0.5, IC 59 ms off)."""
    return pd.DataFrame({"start_s": IC[:-1] + window_shift, "end_s": IC[1:] + window_shift,
                         "event_s": IC[1:] + ic_shift, "length_m": 1.3, "heading_rad": 0.0, "gap_s": 0.0,
                         "unit": "foot"})


def _labels(pre: bool = True) -> pd.DataFrame:
    lab = pd.DataFrame({"start_s": IC[:-1], "end_s": IC[1:], "ic_s": IC[1:], "length_m": 1.32})
    return lab.assign(pre_ic_s=IC[:-1]) if pre else lab


def test_contact_windows_found_with_and_without_pre_ic_but_not_in_native_windows():
    assert contact_windows(_labels()).all()
    assert contact_windows(_labels(pre=False))[1:].all()  # a chain: each opens on another's IC
    assert not contact_windows(_labels(pre=False))[0]  # the chain's first: its start is no labelled IC
    native = _labels().assign(start_s=IC[:-1] + 0.4, end_s=IC[1:] + 0.4)  # gaitmap / simulator mid-stance
    assert not contact_windows(native).any()


def test_contact_labels_pair_by_ic_where_overlap_misses_them():
    est, lab = _tracked(), _labels()
    assert match_by_overlap(est, lab) == []  # IoU 0.46 < 0.5: the finding
    assert match_strides(est, lab) == [(k, k) for k in range(7)]
    assert match_strides(est, lab, by_contact=False) == []
    got = stride_pairs(SimpleNamespace(steps=est), SimpleNamespace(steps=lab))
    assert [(r, j) for r, j, _ in got] == [([k], k) for k in range(7)]


def test_ic_beyond_the_event_tolerance_does_not_pair_and_native_labels_keep_overlap():
    assert match_strides(_tracked(ic_shift=0.30), _labels()) == []  # 0.30 s > the 0.25 s event tolerance
    native = _labels().assign(start_s=IC[:-1] + 0.4, end_s=IC[1:] + 0.4)
    est = _tracked(ic_shift=0.3)  # overlap pairs them, IC or not
    assert match_strides(est, native) == match_by_overlap(est, native) == [(k, k) for k in range(7)]
