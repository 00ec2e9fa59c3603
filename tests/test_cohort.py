"""Cohorts: train-all / evaluate-all on a Dask LocalCluster equal the serial run; failures are isolated."""

from __future__ import annotations

import json
import os
import time

import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.cohort import HOUSEKEEPING_CONFIG, biggest_first, run_cohort, single_threaded
from pdrlearn.errors import DataError
from pdrlearn.io import write_session
from pdrlearn.sim import simulate


@pytest.fixture(scope="module")
def cohort(tmp_path_factory):
    root = tmp_path_factory.mktemp("cohort")
    for u in (1, 2, 3):
        write_session(simulate("terrain", user_seed=u), root / f"u{u}" / "train" / "terrain")
        write_session(simulate("terrain", user_seed=u, seed=1234), root / f"u{u}" / "test" / "terrain")
    bad = root / "u9_broken" / "train" / "s"
    bad.mkdir(parents=True)
    (bad / "fAccelerometer.csv").write_text("timestamp,x,y,z\n")  # empty session -> this user fails
    return root


def _square(x):
    if x == 3:
        raise ValueError("three is not allowed")
    return x * x


def test_run_cohort_isolates_failures_serial_and_dask():
    items = [(f"u{i}", i) for i in range(5)]
    serial = run_cohort(_square, items, serial=True)
    dask = run_cohort(_square, items, n_workers=2)
    assert [r.ok for r in serial] == [True, True, True, False, True]
    assert [(r.name, r.ok, r.value, r.error) for r in serial] == [(r.name, r.ok, r.value, r.error) for r in dask]
    assert "ValueError: three is not allowed" in serial[3].error


def _threads_seen(_):
    """What a job sees: BLAS/OpenMP pool sizes, the worker's environment, start time, Dask housekeeping."""
    import dask
    import scipy.linalg  # noqa: F401  (loads scipy's own OpenBLAS)
    from threadpoolctl import threadpool_info

    time.sleep(0.05)
    return ({i["num_threads"] for i in threadpool_info()}, os.environ.get("MALLOC_TRIM_THRESHOLD_"),
            time.perf_counter(), {k: dask.config.get(k) for k in HOUSEKEEPING_CONFIG})


def test_single_threaded_limits_and_restores():
    import scipy.linalg  # noqa: F401
    from threadpoolctl import threadpool_info

    before = [i["num_threads"] for i in threadpool_info()]
    with single_threaded():
        assert {i["num_threads"] for i in threadpool_info()} == {1}
    assert [i["num_threads"] for i in threadpool_info()] == before


def test_workers_single_threaded_biggest_first_and_env_restored():
    import dask

    env_before = dict(os.environ)
    config_before = {k: dask.config.get(k) for k in HOUSEKEEPING_CONFIG}
    assert config_before != HOUSEKEEPING_CONFIG  # Dask's interactive defaults in this process
    items = [(f"u{i}", i) for i in range(5)]
    costs = [1.0, 5.0, 3.0, 5.0, 2.0]
    res = run_cohort(_threads_seen, items, n_workers=1, costs=costs)
    assert dict(os.environ) == env_before  # Dask's pre-spawn variables do not leak into this process
    assert [r.name for r in res] == [n for n, _ in items]  # input order kept
    assert all(r.value[0] == {1} for r in res)  # one BLAS/OpenMP thread per pool in the worker
    assert all(r.value[1] is None for r in res)  # glibc's adaptive mmap threshold kept (decision C2)
    assert all(r.value[3] == HOUSEKEEPING_CONFIG for r in res)  # quiet housekeeping in the workers (C6)
    assert {k: dask.config.get(k) for k in HOUSEKEEPING_CONFIG} == config_before  # and not left set here
    started = sorted(range(5), key=lambda i: res[i].value[2])
    assert started == biggest_first(costs) == [1, 3, 2, 4, 0]
    assert all(r.cpu_seconds > 0 for r in res)
    with pytest.raises(ValueError, match="costs"):
        run_cohort(_threads_seen, items, serial=True, costs=[1.0])


def test_local_cluster_leaves_port_8787_alone():
    """No dashboard and no HTTP server on Dask's default port: two cohort runs (or any other Dask cluster)
    on one machine do not collide ("Port 8787 is already in use")."""
    import socket
    import warnings

    from pdrlearn.cohort import _local_cluster

    held = socket.socket()
    try:
        held.bind(("127.0.0.1", 8787))
        held.listen()
    except OSError:
        pass  # someone else's cluster holds it already: the same situation
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            cluster = _local_cluster(1)
            try:
                http = cluster.scheduler.http_server
                ports = {s.getsockname()[1] for s in http._sockets.values()}
                assert 8787 not in ports
            finally:
                cluster.close()
        assert not [w for w in caught if "already in use" in str(w.message)]
    finally:
        held.close()


def test_bad_scheduler_address(monkeypatch):
    import pdrlearn.cohort

    monkeypatch.setattr(pdrlearn.cohort, "SCHEDULER_TIMEOUT_S", 1)  # the error, not the 10 s wait, is under test
    with pytest.raises(DataError, match="cannot reach Dask scheduler"):
        run_cohort(_square, [("a", 1)], scheduler="tcp://127.0.0.1:1")


@pytest.fixture(scope="module")
def scheduler():
    """One LocalCluster shared by the CLI runs below (also exercises --scheduler ADDRESS)."""
    from distributed import LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        yield cluster.scheduler_address


@pytest.mark.extended  # D57: test_run_cohort_isolates_failures_serial_and_dask still runs Dask = serial by default
def test_train_all_dask_equals_serial(cohort, scheduler, tmp_path, capsys):
    args = ["--tasks", "terrain", "--methods", "heuristic,svm", "--cv", "3", "--json"]
    # exit code 1: one user failed, the others completed and the summary is written
    assert main(["train-all", str(cohort), "--out", str(tmp_path / "serial"), "--serial", *args]) == 1
    serial = json.loads(capsys.readouterr().out)
    assert main(["train-all", str(cohort), "--out", str(tmp_path / "dask"), "--scheduler", scheduler, *args]) == 1
    dask = json.loads(capsys.readouterr().out)
    assert serial["n_users"] == 4 and serial["n_failed"] == 1

    def strip(d):
        rows = [{k: v for k, v in u.items() if k not in ("seconds", "cpu_seconds")} for u in d["users"]]
        for r in rows:
            if r.get("error"):
                r["error"] = r["error"].replace(str(tmp_path / "serial"), "M").replace(str(tmp_path / "dask"), "M")
        return rows

    assert strip(serial) == strip(dask)
    broken = next(u for u in serial["users"] if u["user"] == "u9_broken")
    assert broken["status"] == "failed" and "no samples" in broken["error"]
    ok = [u for u in serial["users"] if u["status"] == "ok"]
    assert len(ok) == 3 and all(u["terrain_cv_accuracy"] > 0.6 for u in ok)
    table = pd.read_csv(tmp_path / "dask" / "cohort_summary.csv")
    assert list(table["user"]) == ["u1", "u2", "u3", "u9_broken"]
    # held-out evaluation, serial and distributed
    assert main(["evaluate-all", str(tmp_path / "serial"), str(cohort), "--serial", "--json"]) == 1
    ev_serial = json.loads(capsys.readouterr().out)
    assert main(["evaluate-all", str(tmp_path / "dask"), str(cohort), "--scheduler", scheduler, "--json"]) == 1
    ev_dask = json.loads(capsys.readouterr().out)
    assert strip(ev_serial) == strip(ev_dask)
    accs = [u["terrain_accuracy_labelled"] for u in ev_serial["users"] if u["status"] == "ok"]
    assert len(accs) == 3 and min(accs) > 0.6  # held-out sessions, chance is 1/3
    assert (tmp_path / "serial" / "eval" / "cohort_summary.md").exists()
    # piped output (no terminal): the summary as a Markdown table, not squeezed to 80 columns
    assert main(["evaluate-all", str(tmp_path / "serial"), str(cohort), "--serial", "--out",
                 str(tmp_path / "ev_text")]) == 1
    text = capsys.readouterr().out
    assert "| user " in text and "| u1 " in text and "…" not in text and "failed u9_broken" in text


def test_train_all_errors(tmp_path, capsys):
    assert main(["train-all", str(tmp_path / "none"), "--out", str(tmp_path / "m"), "--serial"]) == 2
    assert "cohort folder not found" in capsys.readouterr().err
    (tmp_path / "empty").mkdir()
    assert main(["train-all", str(tmp_path / "empty"), "--out", str(tmp_path / "m"), "--serial"]) == 2
    assert "no user subfolders" in capsys.readouterr().err


def test_train_all_length_units_reach_the_bundle(tmp_path, capsys):
    """Decision C40: train-all takes --length-units as train does (the same parser) and passes it to every
    user's training; a bad unit is one line naming the option, before anything is written."""
    from pdrlearn.classify import load_model

    write_session(simulate("length", user_seed=3), tmp_path / "cohort" / "u3" / "train" / "length")
    rc = main(["train-all", str(tmp_path / "cohort"), "--out", str(tmp_path / "bad"), "--serial",
               "--length-units", "foot,hand"])
    err = capsys.readouterr().err.strip()
    assert rc == 2 and err.startswith("error: length_units (--length-units): unknown unit hand") and "\n" not in err
    assert not (tmp_path / "bad").exists()
    rc = main(["train-all", str(tmp_path / "cohort"), "--out", str(tmp_path / "m"), "--serial", "--tasks", "length",
               "--methods", "svm", "--cv", "3", "--length-units", "foot,waist,fused", "--json"])
    out = capsys.readouterr()
    assert rc == 0, out.err
    assert json.loads(out.out)["users"][0]["length_method"] == "svm/fused"
    model = load_model(tmp_path / "m" / "u3")
    assert model.settings["length_units"] == ["foot", "waist", "fused"]
    assert set(model.tasks["length"].cv["svm"]) == {"foot", "waist", "fused"}  # no combined model
