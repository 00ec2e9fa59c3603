# cohort C262 measurement (session 51, FN): run from a scratch folder; prints one line per user and --turns
export PYTHONPATH="$(cd "$(dirname "$0")/.." && pwd)"; P=${PYTHON:-python}
for U in $(seq 18730 18744); do
  [ -d u$U ] || $P -m pdrlearn simulate --route "stand:3, straight:10, turn:180, straight:10, stand:3" --user-seed $U --rate 100 --out u$U >/dev/null 2>&1
  for T in 0.5 1; do
    rm -f c${U}_$T.json
    L=$($P -m pdrlearn calibrate u$U --pipeline waist-pendulum -d 20 --turns $T --out c${U}_$T.json 2>&1 | grep -c "warning: calibrate: --turns")
    B=$(grep -o '"gyro_bias_rps": [^,]*' c${U}_$T.json)
    echo "user $U --turns $T: C262 line $L, $B"
  done
done
