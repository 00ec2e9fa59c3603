"""Decision L304 (measured in L305, not adopted): L39's level threshold judged on the mean |dz| of a run of
same-sign strides, ``kernels.distance.level_dz(dz, run_mean=True)``; the default stays L39's per-stride rule."""

import numpy as np

from pdrlearn.kernels import distance as KD

# a closed 1:12 loop as the foot integrates it (L291): up strides ~+0.12 m, down strides ~-0.105 m, a third of
# them under L39's 0.10 m; landings and level strides of a few cm between the runs
UP_RUN = [0.118, 0.121, 0.116, 0.119, 0.122, 0.117]
DOWN_RUN = [-0.108, -0.096, -0.111, -0.093, -0.107, -0.098]
LOOP = np.array([0.01, -0.02] + UP_RUN + [0.02] + UP_RUN + [0.0, 0.01, -0.01] + DOWN_RUN + [0.01] + DOWN_RUN
                + [0.02, 0.0])


def test_default_is_l39_and_leaves_the_loop_up():
    assert KD.RUN_MEAN_LEVEL is False  # L305: not adopted
    out = KD.level_dz(LOOP)
    np.testing.assert_array_equal(out, np.where(np.abs(LOOP) < 0.10, 0.0, LOOP))
    assert out.sum() > 0.3  # the asymmetry L291 diagnosed: 4 down strides levelled, no up stride


def test_run_mean_keeps_a_slope_run_whole_and_closes_the_loop():
    out = KD.level_dz(LOOP, run_mean=True)
    kept = KD.run_mean_kept(LOOP)
    assert kept.sum() == 24  # every stride of the four runs, none of the level ones
    np.testing.assert_array_equal(out, np.where(kept | (np.abs(LOOP) >= 0.10), LOOP, 0.0))
    # what is left is the integration's own bias (up 0.119, down 0.102 m per stride), not the level rule's
    assert abs(out.sum() - LOOP[kept].sum()) < 1e-12
    assert KD.level_dz(LOOP).sum() - out.sum() > 0.5  # L39 levelled 0.574 m of the descent


def test_a_run_under_the_threshold_on_average_is_level_and_stair_strides_keep_theirs():
    # L39's right level walk kept isolated strides of 0.12 / 0.10 m: a run's mean under 0.10 m does not keep the
    # strides under 0.10 m, and a stride >= 0.10 m keeps its height as under L39
    dz = np.array([0.06, 0.12, 0.07, 0.05, 0.0, 0.3, 0.31, 0.29])
    out = KD.level_dz(dz, run_mean=True)
    np.testing.assert_array_equal(out, [0.0, 0.12, 0.0, 0.0, 0.0, 0.3, 0.31, 0.29])


def test_runs_need_three_same_sign_strides_each_of_at_least_5_cm():
    two = np.array([0.0, 0.09, 0.13, 0.0])  # two strides: no run (mean 0.11 m)
    assert not KD.run_mean_kept(two).any()
    small = np.array([0.0, 0.13, 0.04, 0.13, 0.13, 0.0])  # 0.04 m breaks the run into 1 + 2
    assert not KD.run_mean_kept(small).any()
    mixed = np.array([0.12, 0.09, -0.09, -0.12, 0.11])  # a change of sign ends a run
    assert not KD.run_mean_kept(mixed).any()
    three = np.array([0.09, 0.13, 0.09])
    assert KD.run_mean_kept(three).all()
    assert KD.run_mean_kept(-three).all()  # symmetric in sign


def test_non_finite_dz_is_no_run_member():
    dz = np.array([0.12, np.nan, 0.10, 0.12, 0.09, np.inf])
    np.testing.assert_array_equal(KD.run_mean_kept(dz), [False, False, True, True, True, False])
