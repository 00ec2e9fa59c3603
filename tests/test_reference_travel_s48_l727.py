"""Decision L727 (session 48, trial T1 F8): a reference trajectory that goes tens of metres from its start (a 400 m
athletics oval: 128.72 m) is a travelled path, not a treadmill's lab frame, however far a wrong track went."""

from pdrlearn.track.evaluate import stationary_reference


def test_an_oval_reference_is_no_treadmill_but_a_lab_frame_still_is_l727():
    assert stationary_reference(0.23, 59.87)  # L319's treadmill trial: the pelvis wobbling in the lab frame
    assert not stationary_reference(128.72, 1400.0)  # T1: an oval track against a lower-back track gone straight
    assert not stationary_reference(3.0, 10.0)  # L319's fraction still holds under the cap
    assert not stationary_reference(0.1, 4.0)  # and its 5 m least track
