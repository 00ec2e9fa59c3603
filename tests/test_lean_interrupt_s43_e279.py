"""Decision E279: Ctrl-C in the lean command (``python -m pdrlearn.runtime``) is one line and exit 130, as pdrlearn's
own commands (B96), and leaves no output or temporary folder (E276's atomic ``--out``); it printed a traceback."""
from __future__ import annotations

from tests.test_lean_out_s43_e276 import _error_line, _lean, made  # noqa: F401 - the module fixture


def test_ctrl_c_mid_write_is_one_line_130_and_leaves_nothing(made, tmp_path, monkeypatch, capsys):  # noqa: F811
    import pdrlearn.runtime.__main__ as lean

    real_write = lean._write

    def interrupted(folder, steps, start_s):
        real_write(folder, steps, start_s)  # the files are half there, in the temporary folder
        raise KeyboardInterrupt

    monkeypatch.setattr(lean, "_write", interrupted)
    capsys.readouterr()
    assert _lean(made / "A", "--out", tmp_path / "lean") == 130
    assert _error_line(capsys) == "error: interrupted (Ctrl-C); nothing written"
    assert list(tmp_path.iterdir()) == []  # neither the output nor a temporary folder
