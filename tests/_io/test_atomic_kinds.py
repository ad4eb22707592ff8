"""Outputs never wait on a FIFO, refuse what is not a file or a folder with one line, keep the
suffix the user typed, and an interrupt says truthfully what was written."""

from __future__ import annotations

import argparse
import os
import signal
from pathlib import Path

import pytest

from symkin import cli
from symkin._io import atomic
from symkin._io.atomic import replacing, write_atomically
from symkin.errors import InputError
from tests.support.hostile import run

fifo = pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs here")
AI1 = ("AI1", "--teeth", "20,30,80", "--omega", "4=0", "--omega", "H=1", "--point", "2:10,0", "--turns", "1")


@fifo
def test_a_fifo_in_place_of_the_file_is_refused_without_waiting(tmp_path):
    os.mkfifo(tmp_path / "plot.png")
    with pytest.raises(InputError, match="plot.png: it is a named pipe \\(FIFO\\), not a file"):
        with replacing(tmp_path / "plot.png"):
            pass  # (the check of the old file's kind opened the FIFO and waited for a writer)


@fifo
@pytest.mark.parametrize("name", ["fifo.png", "fifo.pdf"])
def test_the_command_line_refuses_a_fifo_figure_with_one_line(name, tmp_path):
    os.mkfifo(tmp_path / name)
    outcome = run(("trajectory", *AI1, "--out", name), tmp_path, limit=20)  # a wall-clock alarm stops a wait
    assert not outcome.hung and outcome.code == 2, outcome.err
    assert outcome.err.count("\n") == 1 and "named pipe" in outcome.err


def report(folder: Path) -> None:
    (folder / "report.json").write_text("{}\n")
    (folder / "report.txt").write_text("table\n")


def written_report(tmp_path: Path) -> Path:
    out = tmp_path / "report"
    write_atomically(out, report, version="test")
    return out


@fifo
def test_a_fifo_in_place_of_a_report_file_is_a_changed_file_never_opened(tmp_path):
    out = written_report(tmp_path)
    (out / "report.json").unlink()
    os.mkfifo(out / "report.json")
    with pytest.raises(InputError, match="report.json changed since symkin wrote them"):
        write_atomically(out, report, version="test")


def test_a_folder_of_the_users_in_place_of_a_report_file_is_a_clash(tmp_path):
    out = written_report(tmp_path)
    (out / "report.txt").unlink()
    (out / "report.txt").mkdir()
    (out / "report.txt" / "note").write_text("mine")
    with pytest.raises(InputError, match="holds report.txt/note, which you added"):  # FileExistsError: exit 3 before
        write_atomically(out, report, version="test")
    assert (out / "report.txt" / "note").read_text() == "mine"


def terminated_after(step):
    """``step`` run, then SIGTERM sent to this process: an interrupt just after the rename."""
    def wrapped(*args, **kwargs):
        result = step(*args, **kwargs)
        os.kill(os.getpid(), signal.SIGTERM)
        return result
    return wrapped


def interrupted_run(run_function) -> tuple[int, str]:
    args = argparse.Namespace(run=run_function, json=False)
    return cli._run(args, "symkin test")


def test_sigterm_at_the_folder_swap_says_the_report_was_written(tmp_path, monkeypatch, capsys):
    out = written_report(tmp_path)
    monkeypatch.setattr(atomic, "_swap", terminated_after(atomic._swap))

    def new_report(folder: Path) -> None:
        report(folder)
        (folder / "report.txt").write_text("new table\n")

    code = interrupted_run(lambda args: write_atomically(out, new_report, version="test"))
    err = capsys.readouterr().err
    assert code == 130 and (out / "report.txt").read_text() == "new table\n"
    assert err.strip() == f"symkin test: interrupted; {out} was written in full before the interrupt; nothing else was written"


def test_sigterm_at_a_files_rename_says_it_was_written(tmp_path, monkeypatch, capsys):
    target = tmp_path / "t.txt"
    monkeypatch.setattr(atomic.os, "replace", terminated_after(os.replace))

    def write(args):
        with replacing(target) as (tmp,):
            tmp.write_text("whole")

    code = interrupted_run(write)
    assert code == 130 and target.read_text() == "whole"
    assert "t.txt was written in full" in capsys.readouterr().err


def test_an_interrupt_before_any_output_says_nothing_was_written(tmp_path, capsys):
    def stopped(args):
        raise KeyboardInterrupt

    assert interrupted_run(stopped) == 130
    assert capsys.readouterr().err.strip() == "symkin test: interrupted; nothing was written"


@pytest.mark.parametrize("name", ["x.PNG", "x.Pdf"])
def test_the_suffix_the_user_typed_is_kept(name, tmp_path):
    outcome = run(("trajectory", *AI1, "--out", name), tmp_path, limit=20)
    assert outcome.code == 0, outcome.err
    assert [p.name for p in tmp_path.iterdir()] == [name]
