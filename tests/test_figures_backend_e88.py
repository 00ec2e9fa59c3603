"""Decision E88 (docs/decisions/export.md): no figure helper switches the matplotlib backend.

A new-user trial (session 24, notebook API): every figure helper called ``matplotlib.use("Agg")``, so a
notebook's inline backend was replaced by Agg after the first path figure and ``plt.show()`` showed nothing.
Run in a child process: the backend set there is the user's.
"""

from __future__ import annotations

import subprocess
import sys
import textwrap
from pathlib import Path

SCRIPT = textwrap.dedent('''
    import sys
    from pathlib import Path

    import matplotlib
    matplotlib.use("svg")
    import pandas as pd

    from pdrlearn.aid.track import plot_aided
    from pdrlearn.classify.evaluation import plot_confusions
    from pdrlearn.plots import plot_session
    from pdrlearn.report.batch import plot_batch
    from pdrlearn.sim import simulate
    from pdrlearn.track import TrackResult, path_figure, plot_paths

    out = Path(sys.argv[1])
    s = simulate("A", user_seed=1831, speed="normal")
    tr = pd.DataFrame({"t": [0.0, 1.0, 2.0], "x": [0.0, 1.0, 2.0], "y": [0.0, 0.0, 1.0], "z": 0.0})
    r = TrackResult(steps=pd.DataFrame({"length_m": [1.0, 1.4]}), trajectory=tr)
    seen = []
    plot_paths({"t": r}, out / "p.png", session=s); seen.append(matplotlib.get_backend())
    path_figure({"t": r}); r.plot(s); seen.append(matplotlib.get_backend())
    plot_session(s, out / "s.svg"); seen.append(matplotlib.get_backend())
    plot_batch(pd.DataFrame({"path": ["a"], "group": ["g"], "status": ["ok"], "distance_m": [1.0]}), out / "b.png")
    seen.append(matplotlib.get_backend())
    plot_confusions("terrain", {"classes": ["flat", "up"], "n_steps": 6, "methods": {"svm": {"units": {"foot": {
        "confusion": [[3, 1], [0, 2]], "accuracy": 0.83}}}}}, out / "c.png"); seen.append(matplotlib.get_backend())
    aided = TrackResult(steps=r.steps, trajectory=tr.assign(x_pdr=tr.x, y_pdr=tr.y))
    plot_aided(aided, out / "a.png"); seen.append(matplotlib.get_backend())
    print(",".join(seen))
''')


def test_no_figure_helper_switches_the_backend(tmp_path):
    env_root = Path(__file__).resolve().parents[1]
    done = subprocess.run([sys.executable, "-c", SCRIPT, str(tmp_path)], capture_output=True, text=True,
                          cwd=env_root, env={"PYTHONPATH": str(env_root), "PATH": "/usr/bin:/bin"})
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stdout.strip() == ",".join(["svg"] * 6)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.png", "b.png", "c.png", "p.png", "s.svg"]
