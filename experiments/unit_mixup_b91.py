"""B91 measurement: fresh users 260-262, every scenario, 20 and 100 Hz; real recordings paired foot x waist."""
import glob, logging, types
import numpy as np
logging.disable(logging.WARNING)
from pdrlearn.sim import simulate, SCENARIOS
from pdrlearn.io import read_session
from pdrlearn.io.unit_check import unit_mixup, swing_rate

def fake(streams, meta=None):
    return types.SimpleNamespace(streams=streams, meta=meta or {}, has=lambda *n: all(x in streams for x in n))

def swapped(st):
    m = {"fAccelerometer": "wAccelerometer", "fGyroscope": "wGyroscope",
         "wAccelerometer": "fAccelerometer", "wGyroscope": "fGyroscope"}
    return {m.get(k, k): v for k, v in st.items()}

def copied(st):
    out = dict(st); out["wAccelerometer"] = st["fAccelerometer"]; out["wGyroscope"] = st["fGyroscope"]; return out

fa = [0, 0]; det = [0, 0]; same = [0, 0]
for rate in (20, 100):
    for sc in SCENARIOS:
        for u in (260, 261, 262):
            s = simulate(sc, u, "normal", rate_hz=rate, seed=u, length_m=200.0)
            ok = unit_mixup(fake(s.streams)); sw = unit_mixup(fake(swapped(s.streams)))
            cp = unit_mixup(fake(copied(s.streams)))
            f99, w99 = swing_rate(s.streams["fGyroscope"].values), swing_rate(s.streams["wGyroscope"].values)
            fa[0] += ok is not None; fa[1] += 1
            if sc != "standstill":
                det[0] += sw is not None and "swapped" in sw; det[1] += 1
            same[0] += cp is not None and "same data" in cp; same[1] += 1
            print(f"{rate:3d} Hz {sc:10s} u{u}: foot p99 {np.degrees(f99):6.1f} deg/s waist p99 {np.degrees(w99):6.1f}"
                  f" | correct: {'ALARM' if ok else 'clear'} | swapped: {'called' if sw else 'missed'}"
                  f" | copy: {'refused' if cp else 'missed'}")
feet, waists = [], []
for d in sorted(glob.glob("datasets/external/*")):
    s = read_session(d)
    for p, lst in (("f", feet), ("w", waists)):
        if p + "Gyroscope" in s.streams:
            lst.append((d.split("/")[-1], s.streams[p + "Accelerometer"], s.streams[p + "Gyroscope"]))
            print(f"real {d.split('/')[-1]} {p}: p99 {np.degrees(swing_rate(s.streams[p + 'Gyroscope'].values)):.1f} deg/s")
rfa = [0, 0]; rdet = [0, 0]
for fn, fac, fgy in feet:
    for wn, wac, wgy in waists:
        st = {"fAccelerometer": fac, "fGyroscope": fgy, "wAccelerometer": wac, "wGyroscope": wgy}
        rfa[0] += unit_mixup(fake(st)) is not None; rfa[1] += 1
        rdet[0] += unit_mixup(fake(swapped(st))) is not None; rdet[1] += 1
print(f"simulated: false alarms {fa[0]}/{fa[1]}; swapped walking sessions called {det[0]}/{det[1]}; copies refused {same[0]}/{same[1]}")
print(f"real pairs: false alarms {rfa[0]}/{rfa[1]}; swapped pairs called {rdet[0]}/{rdet[1]}")
