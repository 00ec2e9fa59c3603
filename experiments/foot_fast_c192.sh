#!/bin/sh
# Decision C192 (docs/decisions/localization.md): the offline foot track (no model) on simulated fast stepping
# (0.3 s steps, 200 steps/min, of 0.4 / 0.5 / 0.6 m). Run from the repository root:
#   sh experiments/foot_fast_c192.sh OUTDIR [USER ...]     (users default 14440 14441 14442)
# prints: user step_length_m n_strides distance_error_pct median_cadence_spm median_speed_straight_mps final_error_m
out=${1:?give an output directory}; shift
py=${PYTHON:-.venv/bin/python}
for u in ${*:-14440 14441 14442}; do for L in 0.4 0.5 0.6; do
  d=$out/u${u}_L$L
  $py -m pdrlearn simulate --route "stand:3, straight:12, turn:180, straight:12, stand:3" --step-time 0.3 \
    --step-length $L --user-seed $u --seed 4 --rate 100 --out $d/sess >/dev/null 2>&1
  $py -m pdrlearn track $d/sess --no-plot --out $d/tr > $d/track.out 2>&1
  echo "$u $L $($py -c "import json; s=json.load(open('$d/tr/summary.json')); print(s.get('n_steps'), \
s.get('distance_error_pct'), s.get('median_cadence_spm'), s.get('median_speed_straight_mps'), s.get('final_error_m'))")"
done; done
