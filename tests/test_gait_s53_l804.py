"""Decision L804: a named lower toe-clearance side says the gap and the measure's side-difference error (measured on
simulated symmetric walkers); the 0.005 m gap of L795 is kept (the measured threshold was not adopted)."""

from pdrlearn.track.affected_side import toe_clearance_text
from pdrlearn.track.bilateral import lower_clearance_side


def _walk(left, right):
    w = {"min_toe_clearance_m_left": left, "min_toe_clearance_m_right": right}
    return {**w, "toe_clearance_lower": lower_clearance_side(w)}


def test_a_named_side_says_the_gap_and_the_measured_error_l804():
    text = toe_clearance_text(_walk(0.012, 0.002))  # the trial's user 20012: healthy, right named
    assert text == ("toe clearance (minimum in mid-swing, medians) left 0.012 m / right 0.002 m: right lower by 10 mm "
                    "(a dragging toe, e.g. foot drop - or the measure's error: in simulated symmetric walkers the "
                    "sides' difference read off by a median 6 mm, up to 38 mm, L804) (L795)")
    assert "affected lower by 10 mm" in toe_clearance_text(_walk(0.012, 0.002), "right")


def test_an_unnamed_pair_reads_as_before_and_l795s_gap_is_kept_l804():
    assert lower_clearance_side.__kwdefaults__["min_diff_m"] == 0.005  # L804's 0.039 m was not adopted
    assert toe_clearance_text(_walk(0.012, 0.010)) == (
        "toe clearance (minimum in mid-swing, medians) left 0.012 m / right 0.010 m (L795)")
