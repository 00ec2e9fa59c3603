"""Decision W554 (session 48, trial T2 F3): fewer alternating lower-back contacts than pelvic-gyro steps is not blamed
on the waist detector alone, and the pelvic-gyro detector is not offered as the count: on irregular, wide-based
walks it counts the trunk's sway as steps."""

from pdrlearn.waist.plausibility import count_mismatch_message


def test_fewer_contacts_names_both_detectors_and_offers_no_pelvic_gyro_count_w554():
    line = count_mismatch_message((20, 33))
    assert "W441" in line and "W554" in line and "misses steps" in line and "trunk's sway" in line
    assert "--detector pelvic-gyro' for the step count" not in line and "foot unit" in line
    more = count_mismatch_message((33, 20))  # more contacts: W441's added-steps line, unchanged
    assert "W554" not in more and "--detector pelvic-gyro' for the step count" in more
    assert count_mismatch_message((20, 21)) is None
