"""Decision B27 (docs/decisions/bad-input.md): a `track` option that the chosen pipeline or PLASYS method
ignores is one error line, not a silent exit 0 (new-user trial: `track D --pipeline waist-pendulum --method
M3 --model X` tracked the lower back without the model)."""

from __future__ import annotations

import pytest

from pdrlearn.cli import main


@pytest.fixture(scope="module")
def sim_a(tmp_path_factory):
    s = tmp_path_factory.mktemp("ignored") / "A"
    assert main(["simulate", "-s", "A", "-u", "1", "--out", str(s), "--json"]) == 0
    return s


@pytest.mark.parametrize("pipeline", ["waist-pendulum", "waist-pll"])
@pytest.mark.parametrize("extra", [["--method", "M3"], ["--model", "oracle"], ["--rules", "bayes"],
                                   ["--min-confidence", "0.5"], ["--length-bounds", "1,1.5"], ["--streaming"]])
def test_plasys_options_refused_by_waist_pipelines(sim_a, tmp_path, capsys, pipeline, extra):
    out = tmp_path / "o"
    rc = main(["track", "--no-plot", str(sim_a), "--pipeline", pipeline, *extra, "--out", str(out)])
    err = [ln for ln in capsys.readouterr().err.splitlines() if not ln.startswith("warning: ")]
    assert rc == 2 and len(err) == 1, err
    assert extra[0] in err[0] and "plasys pipeline only" in err[0] and pipeline in err[0]
    assert not out.exists()


@pytest.mark.parametrize("method", ["M1", "M2"])
@pytest.mark.parametrize("extra", [["--model", "oracle"], ["--rules", "thesis"], ["--min-confidence", "0"],
                                   ["--length-bounds", "1,1.5"]])
def test_class_options_refused_by_m1_m2(sim_a, tmp_path, capsys, method, extra):
    rc = main(["track", "--no-plot", str(sim_a), "--method", method, *extra, "--out", str(tmp_path / "o")])
    err = [ln for ln in capsys.readouterr().err.splitlines() if not ln.startswith("warning: ")]
    assert rc == 2 and len(err) == 1 and extra[0] in err[0] and f"--method {method} ignores" in err[0], err


@pytest.mark.parametrize("extra", [["--gnss-period", "5"], ["--fix-period", "10"]])
def test_period_without_its_fix_file_refused(sim_a, tmp_path, capsys, extra):
    rc = main(["track", "--no-plot", str(sim_a), "--method", "M2", *extra, "--out", str(tmp_path / "o")])
    err = [ln for ln in capsys.readouterr().err.splitlines() if not ln.startswith("warning: ")]
    assert rc == 2 and len(err) == 1 and extra[0] in err[0], err


def test_options_a_pipeline_reads_still_run(sim_a, tmp_path):
    assert main(["track", "--no-plot", str(sim_a), "--pipeline", "waist-pendulum", "--start", "41.1,-8.6",
                 "--out", str(tmp_path / "w")]) == 0
    assert main(["track", "--no-plot", str(sim_a), "--method", "M3", "--model", "oracle", "--rules", "thesis",
                 "--out", str(tmp_path / "p")]) == 0
