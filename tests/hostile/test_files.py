"""Hostile train files and output paths at the command line: each one line on stderr, exit 2,
within a bound of CPU time (a wall-clock alarm stops a run that waits), nothing left behind.

The shapes of issue 35's review: a train file that is a device, a link to one or a FIFO (read
until memory ran out, or waited for ever), nested 1000 deep (a RecursionError), a dotted key of
50,000 parts (2 GB), 1,000 planets (16 s; 10,000: past 300 s), a number near 1 with 300,000
digits in a file's module or arm; a FIFO or a folder where a figure is to be written."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from symkin.trains import file as train_file
from tests.support.hostile import many_planets, run, verdict

SIMPLE = (train_file._library() / "simple.toml").read_text(encoding="utf-8")
NEAR_ONE = '"(1-10**-300)**1000"'
SPEEDS = ("speeds", "--train", "TRAIN", "--omega", "S=1", "--omega", "R=0", "--json")


#: name -> (how to make the train file in a folder, words the one-line error holds)
FILES = {
    "device": (lambda d: Path("/dev/zero"), "not a regular file"),
    "link to a device": (lambda d: _link(d / "zero.toml", "/dev/zero"), "not a regular file"),
    "fifo": (lambda d: _fifo(d / "pipe.toml"), "not a regular file"),
    "folder": (lambda d: _folder(d / "train.toml"), "is a folder"),
    "nested 1000 deep": (lambda d: _text(d, "a = " + "[" * 1000 + "]" * 1000), "nested"),
    "dotted key of 50,000 parts": (lambda d: _text(d, ".".join(["a"] * 50_000) + " = 1"), "dotted parts"),
    "1,000 planets": (lambda d: _text(d, many_planets(1000)), "more than the 200"),
    "module near 1": (lambda d: _text(d, SIMPLE.replace("module = 1", f"module = {NEAR_ONE}")), "1000 are accepted"),
    "arm near 1": (lambda d: _text(d, SIMPLE.replace('carrier = "C"', f'carrier = "C"\narm = {NEAR_ONE}')),
                   "1000 are accepted"),
}


def _text(folder: Path, text: str) -> Path:
    (folder / "train.toml").write_text(text)
    return folder / "train.toml"


def _link(path: Path, to: str) -> Path:
    path.symlink_to(to)
    return path


def _fifo(path: Path) -> Path:
    os.mkfifo(path)
    return path


def _folder(path: Path) -> Path:
    path.mkdir()
    return path


@pytest.mark.skipif(not hasattr(os, "mkfifo") or not os.path.exists("/dev/zero"), reason="POSIX files")
@pytest.mark.parametrize("name", list(FILES))
def test_a_hostile_train_file_is_one_line_and_exit_2_quickly(name, tmp_path):
    make, words = FILES[name]
    argv = tuple(str(make(tmp_path)) if a == "TRAIN" else a for a in SPEEDS)
    outcome = run(argv, tmp_path, limit=10)
    assert verdict(outcome, tmp_path) is None, verdict(outcome, tmp_path)
    assert outcome.code == 2 and words in outcome.err and outcome.seconds < 10


#: every option of issue 35's review that took the near-1 number: (argv with VALUE in its place)
AI1 = ("AI1", "--teeth", "20,30,80", "--omega", "4=0")
NEAR_ONE_OPTIONS = [
    ("cardan", "--length", "VALUE", "--speed", "1"),
    ("cardan", "--length", "1", "--speed", "1", "--guide-angle", "VALUE"),
    ("cardan", "--length", "1", "--speed", "1", "--pin-radius", "VALUE"),
    ("cardan", "--length", "1", "--angle-law", "t*VALUE", "--t-end", "1"),
    ("speeds", "AA", "--teeth", "54,45,44,55", "--omega", "1=VALUE", "--omega", "4=0"),
    ("trajectory", *AI1, "--omega", "H=VALUE", "--point", "2:10,0", "--out", "t.png"),
    ("trajectory", *AI1, "--omega", "H=1", "--point", "2:VALUE,0", "--out", "t.png"),
    ("trajectory", *AI1, "--omega", "H=1", "--base-yaw", "t*VALUE", "--out", "t.png"),
    ("split", "--total", "5000", "--stages", "3", "--umin", "2", "--umax", "12", "--model", "1 + u*VALUE"),
]


@pytest.mark.parametrize("argv", NEAR_ONE_OPTIONS, ids=lambda a: f"{a[0]} {next(x for x in a if 'VALUE' in x)}")
def test_a_number_near_one_with_300000_digits_is_refused_at_its_option(argv, tmp_path):
    value = "(1-10**-300)**1000"  # 18 characters: 117 s then exit 3, or a hang, before
    outcome = run(tuple(a.replace("VALUE", value) for a in argv), tmp_path, limit=10)
    assert outcome.code == 2 and "at most 1000 are accepted" in outcome.err, outcome.err
    assert outcome.err.count("\n") == 1 and outcome.seconds < 10 and not list(tmp_path.iterdir())
