"""Decisions B359-B362 (session 36, trial T7 #4): a session uploaded as a zip archive, given as a path, bytes or a
binary file object, reads as its folder does, without writing outside a private temporary folder; an unsafe, oversized,
nested or non-zip archive is one line naming the archive (and member). Simulated users 8850-8859 only."""

from __future__ import annotations

import io
import stat
import tempfile
import zipfile
from pathlib import Path

import numpy as np
import pytest

from pdrlearn.cli import main
from pdrlearn.cli.train import find_session_dirs
from pdrlearn.errors import DataError
from pdrlearn.io import read_session, read_session_zip, write_session
from pdrlearn.sim import simulate


@pytest.fixture(scope="module")
def folder(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("b359") / "walk8850"
    write_session(simulate("walk", 8850, length_m=10), out)
    return out


def _zip(folder: Path, dest: Path, *, top: bool = True, extra: dict | None = None) -> Path:
    """``zip -r dest folder`` (``top``: members under ``walk8850/``) or of its files only, plus ``extra`` members."""
    with zipfile.ZipFile(dest, "w", zipfile.ZIP_DEFLATED) as zf:
        for p in sorted(folder.iterdir()):
            zf.write(p, f"{folder.name}/{p.name}" if top else p.name)
        zf.writestr("__MACOSX/walk8850/._fAccelerometer.csv", b"\x00\x05")  # what macOS Finder adds: skipped
        for name, data in (extra or {}).items():
            zf.writestr(name, data)
    return dest


def _same(a, b) -> None:
    assert a.name == b.name and a.meta == b.meta and a.frames == b.frames
    assert sorted(a.streams) == sorted(b.streams)
    for k in a.streams:
        np.testing.assert_array_equal(a.streams[k].t, b.streams[k].t)
        np.testing.assert_array_equal(a.streams[k].values, b.streams[k].values)
    assert a.steps.equals(b.steps) and a.trajectory.equals(b.trajectory)
    assert sorted(a.extras) == sorted(b.extras) and all(a.extras[k].equals(b.extras[k]) for k in a.extras)


def test_folder_zip_round_trip_reads_the_folders_session_and_leaves_nothing_b359(folder, tmp_path, monkeypatch):
    private = tmp_path / "tmp"
    private.mkdir()
    monkeypatch.setattr(tempfile, "tempdir", str(private))
    want = read_session(folder)
    for top in (True, False):
        z = _zip(folder, tmp_path / f"walk8850_{top}.zip", top=top)
        got = read_session(z)
        _same(want, got)
        assert got.folder is None  # its files are gone; warnings name the session by its name
    assert list(private.iterdir()) == []  # the temporary copy is gone
    assert sorted(p.name for p in tmp_path.iterdir()) == ["tmp", "walk8850_False.zip", "walk8850_True.zip"]


def test_bytes_and_binary_file_objects_read_as_the_zip_does_b359(folder, tmp_path):
    want = read_session(folder)
    data = _zip(folder, tmp_path / "up.zip").read_bytes()

    class Stream(io.RawIOBase):  # a request body: read once, not seekable
        def __init__(self, b):
            self._b = io.BytesIO(b)

        def readable(self):
            return True

        def seekable(self):
            return False

        def readinto(self, buf):
            return self._b.readinto(buf)

    with open(tmp_path / "up.zip", "rb") as fh:
        sources = [data, bytearray(data), io.BytesIO(data), fh, Stream(data)]
        for src in sources:
            _same(want, read_session(src))
    _same(want, read_session_zip(data, name="customer.zip", max_archive_bytes=10 ** 8))


def _one_line(exc: pytest.ExceptionInfo, start: str, *parts: str) -> str:
    text = str(exc.value)
    assert "\n" not in text and text.startswith(start), text
    assert "pdrlearn-zip-" not in text, text  # the temporary copy is not named
    for part in parts:
        assert part in text, text
    return text


def test_zip_slip_absolute_and_link_members_are_refused_and_nothing_is_written_b360(folder, tmp_path):
    for member, why in [("../evil.csv", "zip slip"), ("walk8850/../../evil.csv", "zip slip"),
                        ("/tmp/evil.csv", "absolute path"), ("C:/evil.csv", "absolute path")]:
        z = _zip(folder, tmp_path / "bad.zip", extra={member: b"timestamp,x\n0,1\n"})
        with pytest.raises(DataError) as exc:
            read_session(z)
        _one_line(exc, f"{z}:{member}:", why)
        assert not (tmp_path.parent / "evil.csv").exists() and not (tmp_path / "evil.csv").exists()
    z = tmp_path / "link.zip"
    _zip(folder, z)
    with zipfile.ZipFile(z, "a") as zf:
        info = zipfile.ZipInfo("walk8850/notes.csv")
        info.external_attr = (stat.S_IFLNK | 0o777) << 16
        zf.writestr(info, "/etc/passwd")
    with pytest.raises(DataError) as exc:
        read_session(z)
    _one_line(exc, f"{z}:walk8850/notes.csv:", "symbolic link")
    with zipfile.ZipFile(z, "w") as zf:  # two members of one name: the second would replace the first unseen
        zf.writestr("walk8850/fAccelerometer.csv", b"timestamp,x,y,z\n")
        with pytest.warns(UserWarning, match="Duplicate name"):
            zf.writestr("walk8850/fAccelerometer.csv", b"timestamp,x,y,z\n0,0,0,9.81\n")
    with pytest.raises(DataError) as exc:
        read_session(z)
    _one_line(exc, f"{z}:walk8850/fAccelerometer.csv:", "named twice")


def test_a_bad_or_missing_file_in_the_zip_names_the_archive_and_member_b359(folder, tmp_path):
    z = tmp_path / "labels.zip"
    with zipfile.ZipFile(z, "w") as zf:  # the labels without a sensor file
        for name in ("meta.json", "steps.csv"):
            zf.write(folder / name, f"walk8850/{name}")
    with pytest.raises(DataError) as exc:
        read_session(z)
    _one_line(exc, f"{z}:walk8850: no sensor files found", "fAccelerometer.csv")
    text = (folder / "fGyroscope.csv").read_text().splitlines()
    bad = "\n".join([*text[:5], "12,abc,0,0", *text[6:]]) + "\n"
    with zipfile.ZipFile(tmp_path / "garbage.zip", "w") as zf:
        for p in folder.iterdir():
            zf.writestr(f"walk8850/{p.name}", bad if p.name == "fGyroscope.csv" else p.read_bytes())
    with pytest.raises(DataError) as exc:
        read_session(tmp_path / "garbage.zip", check_units=False)
    _one_line(exc, f"{tmp_path / 'garbage.zip'}:walk8850/fGyroscope.csv")
    with pytest.raises(DataError) as exc:
        read_session_zip((tmp_path / "garbage.zip").read_bytes(), name="customer42.zip")
    _one_line(exc, "customer42.zip:walk8850/fGyroscope.csv")


def test_a_zip_of_a_zip_not_a_zip_and_a_text_stream_are_one_line_b362(folder, tmp_path):
    inner = _zip(folder, tmp_path / "inner.zip")
    outer = tmp_path / "outer.zip"
    with zipfile.ZipFile(outer, "w") as zf:
        zf.write(inner, "inner.zip")
    with pytest.raises(DataError) as exc:
        read_session(outer)
    _one_line(exc, f"{outer}: holds another archive (inner.zip)", "unpack it")
    (tmp_path / "notes.zip").write_text("not a zip")
    for src, start in [(tmp_path / "notes.zip", f"{tmp_path / 'notes.zip'}: not a zip archive"),
                       (b"PK\x03\x04 broken", "<upload>: not a zip archive"),
                       (io.BytesIO(b"csv,text"), "<upload>: not a zip archive"),
                       (io.StringIO("text"), "<upload>: a text file object"),
                       (tmp_path / "absent.zip", f"{tmp_path / 'absent.zip'}: zip archive not found")]:
        with pytest.raises(DataError) as exc:
            read_session(src)
        _one_line(exc, start)
    xlsx = _zip(folder, tmp_path / "export.xlsx")  # a zip by content, not by name: not sniffed (B359)
    with pytest.raises(DataError, match=r"export\.xlsx: not a folder; pass the session folder"):
        read_session(xlsx)


def test_members_over_the_size_cap_are_refused_before_and_while_unpacking_b361(folder, tmp_path):
    data = _zip(folder, tmp_path / "w.zip").read_bytes()
    with pytest.raises(DataError) as exc:
        read_session_zip(data, name="w.zip", max_archive_bytes=1000)
    _one_line(exc, "w.zip:", "max_archive_bytes", "1000 bytes")
    big = tmp_path / "big.zip"  # 200 kB of zeros compress to a few hundred bytes: the unpacked size counts
    with zipfile.ZipFile(big, "w", zipfile.ZIP_DEFLATED) as zf:
        zf.writestr("walk8850/fAccelerometer.csv", b"0" * 200_000)
    assert big.stat().st_size < 50_000
    with pytest.raises(DataError) as exc:
        read_session_zip(big, max_archive_bytes=50_000)
    _one_line(exc, f"{big}: its members unpack to more than 50000 bytes", "max_archive_bytes")
    with pytest.raises(DataError, match="max_archive_bytes=0: give a positive whole number"):
        read_session_zip(data, max_archive_bytes=0)


def test_session_commands_take_a_zip_and_track_all_says_to_unzip_it_b360(folder, tmp_path, capsys):
    z = _zip(folder, tmp_path / "walk8850.zip")
    assert main(["info", str(z), "--json"]) == 0
    assert '"fAccelerometer"' in capsys.readouterr().out
    assert main(["track", "--no-plot", str(z), "--out", str(tmp_path / "trk"), "--json"]) == 0
    capsys.readouterr()
    assert (tmp_path / "trk" / "steps.csv").is_file()
    assert find_session_dirs([z, folder]) == [z, folder]  # train and evaluate: a zip is one session
    assert main(["track-all", str(z), "--out", str(tmp_path / "all")]) == 2  # it searches a tree of folders
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "a zip archive" in err and "unzip" in err and "Traceback" not in err, err
    assert not (tmp_path / "all").exists()
    (tmp_path / "bad.zip").write_bytes(b"nope")
    assert main(["info", str(tmp_path / "bad.zip")]) == 2
    assert capsys.readouterr().err.strip() == f"error: {tmp_path / 'bad.zip'}: not a zip archive; pass a session " \
                                              f"folder, or a zip of one (e.g. 'zip -r walk1.zip walk1')"
