# steps decision 96 measurement (session 51, FN): run from the same folder as terrain_class_range_s51_96_gen.sh > gen96.out
export PYTHONPATH="$(cd "$(dirname "$0")/.." && pwd)"; P=${PYTHON:-python}
for U in $(seq 18746 18753); do
  while ! grep -q "gen $U done" gen96.out; do sleep 10; done
  $P -m pdrlearn train d96/train_$U --tasks terrain --methods svm --out d96/m_$U > d96/train_$U.log 2>&1
  for K in stairs slope; do
    $P -m pdrlearn evaluate d96/m_$U d96/${K}_$U --report d96/ev_${K}_$U > d96/ev_${K}_$U.log 2>&1
    L=$(grep -c "steps.md 96" d96/ev_${K}_$U.log)
    A=$(grep -m1 "^terrain:" d96/ev_${K}_$U.log | cut -c1-90)
    O=$(grep "lie outside the model's training range" d96/ev_${K}_$U.log | head -1)
    S=$($P -c "import json;d=json.load(open('d96/ev_${K}_$U/report.json'))['out_of_domain']['tasks']['terrain'].get('by_class',{});print({c:(v['n_out'],v['n_steps']) for c,v in d.items()})")
    echo "user $U $K: line96 $L | $A | $O | by_class $S"
  done
done
