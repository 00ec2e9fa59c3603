# steps decision 96 data (session 51, FN): run from a scratch folder, writing gen96.out (read by terrain_class_range_s51_96.sh)
export PYTHONPATH="$(cd "$(dirname "$0")/.." && pwd)"; P=${PYTHON:-python}
mkdir -p d96
for U in $(seq 18746 18753); do
  $P -m pdrlearn simulate --scenario terrain --user-seed $U --seed 0 --rate 100 --out d96/train_$U >/dev/null 2>&1
  mkdir -p d96/stairs_$U d96/slope_$U
  $P -m pdrlearn simulate --scenario terrain --user-seed $U --seed 1 --rate 100 --out d96/stairs_$U/s >/dev/null 2>&1
  $P -m pdrlearn simulate --route "stand:3, straight:20, slope:60:12, straight:10, slope:60:-12, straight:10, slope:40:20, slope:40:-20, stand:3" --user-seed $U --seed 1 --rate 100 --out d96/slope_$U/s >/dev/null 2>&1
  echo "gen $U done"
done
