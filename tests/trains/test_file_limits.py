"""Reading a train file cannot exhaust the machine: only regular files, read without waiting and
only up to the size limit, with keys, nesting and links bounded, each refusal one
TrainFileError naming the file and the limit, in bounded time and memory."""

from __future__ import annotations

import os
import time

import pytest

from symkin.errors import TrainFileError
from symkin.trains import file as train_file
from symkin.trains import load_train, read_train
from tests.support.hostile import many_planets

SIMPLE = (train_file._library() / "simple.toml").read_text(encoding="utf-8")


def refused(source, match):
    start = time.process_time()
    with pytest.raises(TrainFileError, match=match) as info:
        load_train(source)
    assert time.process_time() - start < 2 and "\n" not in str(info.value)
    return str(info.value)


@pytest.mark.skipif(not os.path.exists("/dev/zero"), reason="no /dev/zero")
def test_a_device_or_a_link_to_one_is_not_read(tmp_path):
    refused("/dev/zero", "is not a regular file")  # was read until memory ran out
    (tmp_path / "zero.toml").symlink_to("/dev/zero")
    refused(str(tmp_path / "zero.toml"), "is not a regular file")


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs here")
def test_a_fifo_without_a_writer_is_refused_without_waiting(tmp_path):
    os.mkfifo(tmp_path / "pipe.toml")
    refused(str(tmp_path / "pipe.toml"), "is not a regular file")  # the open itself waited for ever


def test_a_folder_and_a_missing_file_are_one_line(tmp_path):
    (tmp_path / "dir.toml").mkdir()
    refused(str(tmp_path / "dir.toml"), "is a folder")
    refused(str(tmp_path / "none.toml"), "cannot be read")
    refused("a\x00b.toml", "cannot be read")  # a NUL in the name: ValueError, exit 3 before


def test_a_file_beyond_the_size_limit_is_refused_after_reading_only_the_limit(tmp_path, monkeypatch):
    monkeypatch.setattr(train_file, "MAX_FILE_BYTES", 1000)
    path = tmp_path / "big.toml"
    path.write_text(SIMPLE + "#" * 2000 + "\n")
    refused(str(path), "larger than 1000 bytes")


def test_bytes_that_are_not_utf8_are_named(tmp_path):
    path = tmp_path / "latin.toml"
    path.write_bytes(SIMPLE.encode() + b"# caf\xe9\n")
    refused(str(path), "not UTF-8 text")


@pytest.mark.parametrize("text, match", [
    ("a = " + "[" * 1000 + "]" * 1000, "nested too deeply|nested more than 16"),  # a RecursionError before
    ("a = " + "[" * 20 + "]" * 20, "nested more than 16 deep"),
    (".".join(["a"] * 50_000) + " = 1", "more than 16 dotted parts"),  # 2 GB before
    ("x = {" + "a." * 40 + "b = 1}", "more than 16 dotted parts"),  # inside an inline table
    ("[" + ".".join(["t"] * 40) + "]", "more than 16 dotted parts"),  # a table header
    ("\n".join(f"k{i} = {i}" for i in range(25_000)), "more than 20000 keys and values"),
])
def test_shapes_that_grow_without_bound_are_refused_quickly(text, match):
    start = time.process_time()
    with pytest.raises(TrainFileError, match=match):
        read_train(text, "hostile.toml")
    assert time.process_time() - start < 3


def test_dots_in_strings_and_comments_and_numbers_are_not_keys():
    text = SIMPLE.replace('name = "simple planetary"', 'name = "' + "a." * 40 + '"  # ' + "b." * 40)
    train = read_train(text, "dots.toml")
    assert train.name == "a." * 40 and train.shift("low").ratio.rhs == read_train(SIMPLE).shift("low").ratio.rhs


def test_a_train_of_more_links_than_the_limit_is_refused_and_one_below_is_read():
    with pytest.raises(TrainFileError, match=r"\[links\]: 1003 links, more than the 200 symkin models"):
        read_train(many_planets(1000), "many.toml")  # 16 s before (load 2.5 s, ratio 14 s)
    train = read_train(many_planets(20), "twenty.toml")
    # each planet a link of its own, all on one carrier: sun 30, ring 90, ratio 1 + 90/30 with the ring held
    assert train.shift("a").ratio.rhs == 4
