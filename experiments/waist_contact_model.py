"""Decision W203: train and measure the learned contact re-scorer of the offline lower-back `waist-pendulum`.

    OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/waist_contact_model.py train     # writes the shipped JSON
    OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/waist_contact_model.py measure   # W203 (a): fresh users
    OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/waist_contact_model.py loso [--external DIR]  # information

Training: simulated users 4600-4639 (100 Hz, seed = user), W189's four routes (``waist_stand.SIM_ROUTES``); every
contact of the offline default detector with ``sit_veto=False`` (the contacts the re-scorer sees inside
``track_waist``: it runs before the stand / sit vetoes), label 1 when matched one-to-one to a true contact within
0.25 s. (a) of W203's rule: fresh users 4640-4659, the same routes, today's default vs ``contact_model="learned"``.
(b) is ``experiments/waist.py --external datasets/external --no-real [--contact-model learned]``, (c)
``experiments/hapt.py --contact-model learned``.
"""

from __future__ import annotations

import argparse
import logging
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]

from pdrlearn.track.waist import track_waist  # noqa: E402
from pdrlearn.waist.ahrs import waist_imu  # noqa: E402
from pdrlearn.waist.contact_model import MODEL_PATH, contact_features, fit_contact_model, save_contact_model  # noqa: E402
from pdrlearn.waist.events import gate_threshold  # noqa: E402
from waist_stand import SIM_ROUTES, matched_truth  # noqa: E402

TRAIN_USERS = range(4600, 4640)  # the lead's training users for W203
FRESH_USERS = range(4640, 4660)  # the lead's fresh users for W203 (a)


def simulate(route: str, kw: dict, user: int):
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route

    return simulate_path(parse_route(route), UserProfile.from_seed(user), rate_hz=100, seed=user, **kw)


def labelled_contacts(session, truth: np.ndarray, params=None) -> tuple[np.ndarray, np.ndarray]:
    """W203's features and labels of the contacts the re-scorer sees: the offline default pendulum's without the sit
    veto (and with the same default gate as ``track_waist``: W76's relative threshold)."""
    steps = track_waist(session, pipeline="waist-pendulum", params=params, sit_veto=False, stand_veto=False).steps
    imu = waist_imu(session)
    thr, sigma, _ = gate_threshold(imu, None if params is None else params.walk_threshold_mps2, relative=True)
    X = contact_features(steps, imu, thr, sigma, 0.0 if params is None else params.gyro_bias_rps)
    m = matched_truth(steps["event_s"].to_numpy(float), truth)
    y = np.zeros(len(steps), dtype=int)
    y[m[m >= 0]] = 1
    return X, y


def training_set(users=TRAIN_USERS) -> tuple[np.ndarray, np.ndarray]:
    Xs, ys = [], []
    for name, (route, kw) in SIM_ROUTES.items():
        for u in users:
            s = simulate(route, kw, u)
            X, y = labelled_contacts(s, s.extras["ics"]["ic_s"].to_numpy(float))
            Xs.append(X)
            ys.append(y)
        print(f"train {name}: {sum(len(y) for y in ys)} contacts so far", flush=True)
    return np.vstack(Xs), np.concatenate(ys)


def train(out: Path = MODEL_PATH) -> None:
    X, y = training_set()
    model = fit_contact_model(X, y, trained_on=f"simulated users {TRAIN_USERS.start}-{TRAIN_USERS.stop - 1}, "
                                               f"routes {', '.join(SIM_ROUTES)} (W203)")
    save_contact_model(model, out)
    p = model.proba(X)
    print(f"trained on {len(y)} contacts ({int((y == 0).sum())} false); temperature {model.temperature:.4f}; "
          f"training contacts dropped (p < 0.5): {int((p < 0.5).sum())} ({int(((p < 0.5) & (y == 0)).sum())} false)")
    print("coefficients:", dict(zip(model.to_json()["features"], np.round(model.coef, 3).tolist(), strict=True)))
    print(f"wrote {out}")


def f1(tp: int, n_det: int, n_true: int) -> float:
    return 2.0 * tp / (n_det + n_true) if n_det + n_true else float("nan")


def measure(users=FRESH_USERS) -> bool:
    """W203 (a): pooled F1 of the contacts, today's default vs the learned re-scorer, per route and pooled."""
    tot = np.zeros((2, 3), dtype=int)  # (off, on) x (tp, detected, true)
    worse = []
    for name, (route, kw) in SIM_ROUTES.items():
        cnt = np.zeros((2, 3), dtype=int)
        for u in users:
            s = simulate(route, kw, u)
            truth = s.extras["ics"]["ic_s"].to_numpy(float)
            for k, opt in enumerate((False, "learned")):
                ev = track_waist(s, pipeline="waist-pendulum", contact_model=opt,
                                 stand_veto=False).steps["event_s"].to_numpy(float)  # W204 predates W199
                cnt[k] += ((matched_truth(ev, truth) >= 0).sum(), ev.size, truth.size)
        tot += cnt
        f0, f1_ = f1(*cnt[0]), f1(*cnt[1])
        worse += [name] if f1_ < f0 else []
        print(f"(a) {name}: {len(users)} walks, true {cnt[0, 2]}, matched {cnt[0, 0]} -> {cnt[1, 0]}, detected "
              f"{cnt[0, 1]} -> {cnt[1, 1]}, F1 {f0:.4f} -> {f1_:.4f}", flush=True)
    f0, f1_ = f1(*tot[0]), f1(*tot[1])
    ok = f1_ > f0 and not worse
    print(f"(a) pooled users {users.start}-{users.stop - 1}: F1 {f0:.4f} -> {f1_:.4f}; routes lower: "
          f"{', '.join(worse) or 'none'} -> {'met' if ok else 'NOT met'}")
    return ok


def loso(ext: Path) -> None:
    """Information beside W203's rule: train on two mobgap subjects' real contacts (Test11 and Test5, labelled by
    their reference ICs within 0.25 s), test on the third, against the shipped simulator-trained model and no model
    (in-bout ``step_f1`` as experiments/waist.py scores it, default parameters)."""
    import json

    from pdrlearn.io.plasys import read_session
    from pdrlearn.waist.contact_model import load_contact_model, rescore_contacts
    from pdrlearn.waist.evaluate import step_metrics

    by_subj: dict[str, list] = {}
    for d in sorted(ext.glob("mobgap_*_Test*_Trial*")):
        meta = json.loads((d / "meta.json").read_text())
        if meta.get("reference", {}).get("available"):
            by_subj.setdefault(d.name.split("_")[1], []).append((d.name, read_session(d)))
    data = {subj: [(n, s, *labelled_contacts(s, s.extras["ics"]["ic_s"].to_numpy(float))) for n, s in runs]
            for subj, runs in by_subj.items()}
    sim_model = load_contact_model()
    for held in sorted(data):
        X = np.vstack([x for sj, rr in data.items() if sj != held for _, _, x, _ in rr])
        y = np.concatenate([v for sj, rr in data.items() if sj != held for _, _, _, v in rr])
        real_model = fit_contact_model(X, y, trained_on=f"mobgap without {held}")
        for name, s, _, _ in data[held]:
            res = track_waist(s, pipeline="waist-pendulum", sit_veto=False, stand_veto=False)
            imu = waist_imu(s)
            thr, sigma, _ = gate_threshold(imu, None, relative=True)
            base = track_waist(s, pipeline="waist-pendulum", stand_veto=False).steps
            row = [f"{step_metrics(base, s).get('step_f1', float('nan')):.4f}"]
            for m in (sim_model, real_model):
                kept = rescore_contacts(res.steps, imu, thr, sigma, model=m)
                row.append(f"{step_metrics(kept, s).get('step_f1', float('nan')):.4f} ({kept.attrs['n_rescored']} "
                           "dropped)")
            print(f"LOSO {name}: default {row[0]}; sim-trained re-scorer (no sit veto) {row[1]}; real-trained "
                  f"(on {len(y)} contacts, {int((y == 0).sum())} false) {row[2]}", flush=True)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("what", choices=("train", "measure", "loso"))
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    ap.add_argument("--out", type=Path, default=MODEL_PATH)
    a = ap.parse_args()
    logging.disable(logging.WARNING)
    if a.what == "train":
        train(a.out)
    elif a.what == "measure":
        measure()
    else:
        loso(a.external)


if __name__ == "__main__":
    main()
