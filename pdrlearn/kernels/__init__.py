"""Pure numpy kernels shared by the training side and the streaming runtime.

Every module of this package imports only numpy, the standard library and :mod:`pdrlearn.errors`, so
:mod:`pdrlearn.runtime` (numpy + onnxruntime only, issue 7) and the training side
(:mod:`pdrlearn.features`, :mod:`pdrlearn.signal`, :mod:`pdrlearn.classify`, :mod:`pdrlearn.displace`)
run *the same* functions: there is one implementation of each kernel, no mirror.

Modules
-------
- :mod:`~pdrlearn.kernels.rotation` - gravity rotation, rotation vector <-> matrix (Rodrigues).
- :mod:`~pdrlearn.kernels.stats` - step attitude (rest sample, gyro propagation, tilt drift, heading) and
  the per-step statistics of the thesis features (peaks, segments, force, eq. 31/32).
- :mod:`~pdrlearn.kernels.window` - one step's levelled, heading-aligned, resampled window.
- :mod:`~pdrlearn.kernels.dtw` - DTW distance of one step to a reference set.
- :mod:`~pdrlearn.kernels.proba` - softmax, class alignment, soft vote.
- :mod:`~pdrlearn.kernels.stride` - per-stride displacement (ZUPT, M3 rules) and position update.
- :mod:`~pdrlearn.kernels.bayes` - the bayes class rule's stride length and the confidence gate (L14, L18).
- :mod:`~pdrlearn.kernels.altitude_check` - the height warnings of a foot track (L69, C28; E47: track and run).
- :mod:`~pdrlearn.kernels.barometer` - the barometric formula and the relative altitude of a barometer (W89).
- :mod:`~pdrlearn.kernels.dsp` - FIR design, peaks, moving mean, Butterworth zero-phase filters (scipy's, W92).
- :mod:`~pdrlearn.kernels.waist` - the waist pipelines' kernels (contacts, pendulum, gyro heading, W27; W92).
- :mod:`~pdrlearn.kernels.yaw_turns` - El-Gohary's turns of a lower-back yaw rate (mobgap TdElGohary; L210).
- :mod:`~pdrlearn.kernels.ahrs` - Madgwick's IMU filter and quaternion <-> matrix (W43, W92).
- :mod:`~pdrlearn.kernels.gaps` - stream gaps: the warning lines and the cut of a contact table (B11).
- :mod:`~pdrlearn.kernels.waist_stream` - the waist contacts on a stream (W31, W59; the live trackers).
- :mod:`~pdrlearn.kernels.fixes` - the fix-fusion EKF one step at a time, live fixes (seed 004; D14, D19).
- :mod:`~pdrlearn.kernels.units` - unit, plausibility and frozen-sensor checks of the values (B119, B120).
- :mod:`~pdrlearn.kernels.strapdown` - the stride strapdown's core: padded batches, quaternion propagation (E72).
- :mod:`~pdrlearn.kernels.handedness` - D11's mirrored-pair test of a foot unit, offline and live (B129).
- :mod:`~pdrlearn.kernels.histospline` - L24's block-mean histospline without scipy (the stride kernel's, L141).
- :mod:`~pdrlearn.kernels.travel` - the walked distance and the foot strides' travel labels and lines (E316, E317).
- :mod:`~pdrlearn.kernels.geodetic` - thesis eq. 56/57 one step at a time (offline lat/lon and the live trackers, W137).
- :mod:`~pdrlearn.kernels.sideways` - side-stepping strides: L219's rule, offline and one stride at a time (E124).
- :mod:`~pdrlearn.kernels.turn_length` - a turning stride's length class from its measured length (C88; C91: track,
  track --streaming and the runtime).
- :mod:`~pdrlearn.kernels.rests` - the spans between a walk's rows: standstills (L464), streamed rests (E205), pauses
  (L110).
- :mod:`~pdrlearn.kernels.order` - the timestamp-order check of the runtime's pushes, the sensor pairing and split.
- :mod:`~pdrlearn.kernels.gait_values` - a stride's cadence / speed, medians, CV and symmetry index: the offline gait
  tables' and the lean runtime's gait values (E320).

This ``__init__`` imports nothing (importing a submodule never loads the others).
"""
