"""Every command that writes a file writes it whole or not at all: a failing or interrupted
run keeps the previous file and leaves no temporary file (the report folder: test_report_folder.py)."""

import os
from pathlib import Path

import pytest
from matplotlib import animation
from matplotlib.figure import Figure

from symkin.cli import main
from symkin.errors import InputError
from symkin.viz import figures

AI1 = ["AI1", "--teeth", "20,30,80", "--omega", "4=0", "--omega", "H=1"]
#: command line, files it writes (relative to the working folder), the writers to break (a figure is written by
#: savefig, or with one layout and one draw by figures._print_once)
FIGURE_WRITERS = ((Figure, "savefig"), (figures, "_print_once"))
WRITERS = {
    "trajectory": (["trajectory", *AI1, "--out", "t.png"], ["t.png"], FIGURE_WRITERS),
    "curves": (["curves", *AI1, "--out", "c.pdf"], ["c.pdf"], FIGURE_WRITERS),
    "animate": (["animate", *AI1, "--frames", "3", "--dpi", "20", "--out", "a.gif"], ["a.gif"], ((animation.Animation, "save"),)),
    "split --plot": (["split", "--total", "100", "--stages", "2", "--umin", "2", "--umax", "12", "--model", "1 + u/10",
                      "--plot", "s.png"], ["s.png"], FIGURE_WRITERS),
}
MAGIC = {".png": b"\x89PNG", ".pdf": b"%PDF", ".gif": b"GIF8"}


def leftovers(folder: Path) -> list[str]:
    return [p.name for p in folder.iterdir() if ".partial-" in p.name]


@pytest.mark.parametrize("name", list(WRITERS))
@pytest.mark.parametrize("failure, code", [(KeyboardInterrupt, 130), (RuntimeError("disk on fire"), 3)],
                         ids=["interrupted", "failing"])
def test_a_broken_write_keeps_the_previous_file(name, failure, code, tmp_path, monkeypatch, capsys):
    argv, files, writers = WRITERS[name]
    monkeypatch.chdir(tmp_path)
    for f in files:
        (tmp_path / f).write_bytes(MAGIC[Path(f).suffix] + b" previous")  # an earlier output
    seen = []

    def broken(self, path, *args, **kwargs):
        path = Path(path)
        seen.append(path)
        path.write_bytes(b"half a fi")  # a partial file, then the failure
        raise failure

    for owner, method in writers:
        monkeypatch.setattr(owner, method, broken)
    assert main(argv) == code
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1
    assert seen and all(p.name not in files and p.resolve().parent == tmp_path for p in seen)  # a temporary name
    assert all((tmp_path / f).read_bytes() == MAGIC[Path(f).suffix] + b" previous" for f in files)
    assert leftovers(tmp_path) == []


@pytest.mark.parametrize("name", list(WRITERS))
def test_a_complete_write_replaces_the_previous_file(name, tmp_path, monkeypatch, capsys):
    argv, files, _ = WRITERS[name]
    monkeypatch.chdir(tmp_path)
    for f in files:
        (tmp_path / f).write_bytes(MAGIC[Path(f).suffix] + b" previous")
    assert main(argv) == 0, capsys.readouterr().err
    for f in files:
        assert (tmp_path / f).read_bytes().startswith(MAGIC[Path(f).suffix])
    assert leftovers(tmp_path) == []


@pytest.mark.parametrize("name, content", [("mine.png", b"my notes"), ("mine.gif", b"\x89PNG not a gif"),
                                           ("mine.pdf", b"draft"), ("mine.mp4", b"0123notavideo"), ("mine.eps", b"notes")])
def test_an_existing_file_of_another_kind_is_not_replaced(tmp_path, name, content):
    """--out names a file that is not an earlier output of that kind (a user's notes called
    mine.png): refused, and the file kept.  An earlier output, or an empty file, is replaced."""
    from symkin._io.atomic import replacing

    target = tmp_path / name
    target.write_bytes(content)
    with pytest.raises(InputError, match="it exists and is not") as err:
        with replacing(target) as (tmp,):
            tmp.write_bytes(b"new")
    assert "\n" not in str(err.value) and target.read_bytes() == content
    assert sorted(p.name for p in tmp_path.iterdir()) == [name]
    earlier = {".png": b"\x89PNG\r\n", ".gif": b"GIF89a", ".pdf": b"%PDF-1.4", ".mp4": b"\0\0\0\x18ftypmp42",
               ".eps": b"%!PS-Adobe-3.0 EPSF-3.0"}[target.suffix]
    for before in (earlier + b"old", b""):
        target.write_bytes(before)
        with replacing(target) as (tmp,):
            tmp.write_bytes(b"new")
        assert target.read_bytes() == b"new"


def test_a_temporary_name_that_is_taken_is_never_removed(tmp_path, monkeypatch):
    # the temporary name is this process's id and a random part; if a path of that name is there
    # (another run's, across pid namespaces, at odds of 2^-64), the write fails and leaves it
    from symkin._io import atomic

    monkeypatch.setattr(atomic.secrets, "token_hex", lambda n: "deadbeef")
    theirs_file = tmp_path / f".note.partial-{os.getpid()}-deadbeef.txt"
    theirs_file.write_text("another run's")
    with pytest.raises(InputError, match="cannot write to"):
        with atomic.replacing(tmp_path / "note.txt") as (tmp,):
            tmp.write_text("mine")
    assert theirs_file.read_text() == "another run's" and not (tmp_path / "note.txt").exists()
    theirs_folder = tmp_path / f".report.partial-{os.getpid()}-deadbeef"
    theirs_folder.mkdir()
    (theirs_folder / "a.txt").write_text("another run's")
    with pytest.raises(InputError, match="cannot write to"):
        atomic.write_atomically(tmp_path / "report", lambda folder: (folder / "b.txt").write_text("mine"))
    assert (theirs_folder / "a.txt").read_text() == "another run's" and not (tmp_path / "report").exists()
