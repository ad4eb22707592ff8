"""Issue 35's attack review as whole processes: each case of the review run by the ``symkin``
script given, under a 30 s wall-clock limit and a 3 GB address-space limit, one at a time.

Run: python benchmarks/hostile_review.py PATH/TO/symkin [WORDS ...]
Prints one Markdown row per case (only the cases whose name holds one of WORDS, if given): the
exit status (or "timeout"), the wall and CPU seconds, and the last line of stderr.  Writes its
files under a temporary folder.  The table of a run is in benchmarks/notes/hostile.md.
"""

from __future__ import annotations

import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))  # the checkout: its tests' helpers
from tests.support.hostile import many_planets

NEAR_ONE = "(1-10**-300)**1000"  # 18 characters, 300,000 digits
SIMPLE = (Path(__file__).resolve().parent.parent / "symkin" / "trains" / "library" / "simple.toml").read_text()
AI1 = ["AI1", "--teeth", "20,30,80", "--omega", "4=0", "--omega", "H=1"]
CARDAN = ["cardan", "--length", "1", "--speed", "1"]
TRAJECTORY = ["trajectory", *AI1, "--point", "2:10,0", "--turns", "1", "--out", "t.png"]
SPEEDS = ["speeds", "--train", "{files}/TRAIN", "--omega", "S=1", "--omega", "R=0"]


def make_files(folder: Path) -> None:
    (folder / "module.toml").write_text(SIMPLE.replace("module = 1", f'module = "{NEAR_ONE}"'))
    (folder / "arm.toml").write_text(SIMPLE.replace('carrier = "C"', f'carrier = "C"\narm = "{NEAR_ONE}"'))
    (folder / "nested.toml").write_text("a = " + "[" * 1000 + "]" * 1000 + "\n")
    (folder / "dotted.toml").write_text(".".join(["a"] * 50_000) + " = 1\n")
    (folder / "planets1000.toml").write_text(many_planets(1000))
    (folder / "planets10000.toml").write_text(many_planets(10_000))
    (folder / "zero.toml").symlink_to("/dev/zero")
    os.mkfifo(folder / "fifo.toml")


def train(name: str) -> list[str]:
    return [a.replace("TRAIN", name) for a in SPEEDS]


CASES: dict[str, list[str]] = {
    "cardan --length P": ["cardan", "--length", NEAR_ONE, "--speed", "1"],
    **{f"cardan {o} P": [*CARDAN, o, NEAR_ONE] for o in ("--guide-angle", "--carrier-angle", "--pin-radius", "--pin-angle")},
    "cardan --angle-law t*P": ["cardan", "--length", "1", "--angle-law", "t*" + NEAR_ONE, "--t-end", "1"],
    "trajectory --omega H=P": [a.replace("H=1", "H=" + NEAR_ONE) for a in TRAJECTORY],
    "trajectory --point 2:P,0": [a.replace("2:10,0", f"2:{NEAR_ONE},0") for a in TRAJECTORY],
    "trajectory --base-yaw t*P": [*TRAJECTORY, "--base-yaw", "t*" + NEAR_ONE],
    "trajectory --base-x P": [*TRAJECTORY, "--base-x", NEAR_ONE],
    "speeds --omega 1=P": ["speeds", "AA", "--teeth", "54,45,44,55", "--omega", "1=" + NEAR_ONE, "--omega", "4=0"],
    "split --model 1+u*P": ["split", "--total", "5000", "--stages", "3", "--umin", "2", "--umax", "12", "--model",
                           f"1 + u*{NEAR_ONE}", "--top", "3"],
    "train file module = P": train("module.toml"),
    "train file arm = P": train("arm.toml"),
    "--train /dev/zero": [a.replace("{files}/TRAIN", "/dev/zero") for a in SPEEDS],
    "--train link to /dev/zero": train("zero.toml"),
    "--train FIFO": train("fifo.toml"),
    "--train nested 1000 deep": train("nested.toml"),
    "--train dotted key of 100 kB": train("dotted.toml"),
    "--train 1,000 planets": ["states", "--train", "{files}/planets1000.toml"],
    "--train 10,000 planets": ["states", "--train", "{files}/planets10000.toml"],
    "cardan --angle-law Abs(t)": ["cardan", "--length", "1", "--angle-law", "Abs(t)", "--t-end", "1"],
    "trajectory --base-x Abs(t)": [*TRAJECTORY, "--base-x", "Abs(t)"],
    "400 chained ~": ["speeds", "AA", "--teeth", "54,45,44,55", "--omega", "1=" + "~" * 400 + "1", "--omega", "4=0"],
    "400 chained .a": ["speeds", "AA", "--teeth", "54,45,44,55", "--omega", "1=x" + ".a" * 400, "--omega", "4=0"],
    "a byte not UTF-8 in --length": ["cardan", "--length", b"1\xff".decode("utf-8", "surrogateescape"), "--speed", "1"],
    "exp(t*exp(t*...)) 20 deep": ["cardan", "--length", "1", "--angle-law", "exp(t*" * 20 + "t" + ")" * 20, "--t-end", "1"],
    "angle law sin nested 30 deep": ["cardan", "--length", "1", "--angle-law", "sin(" * 30 + "t" + ")" * 30, "--t-end", "1"],
    "angle law sin nested 55 deep": ["cardan", "--length", "1", "--angle-law", "sin(" * 55 + "t" + ")" * 55, "--t-end", "1"],
    "--out x.PNG": [*TRAJECTORY[:-1], "x.PNG"],
    "--out a FIFO as figure": [*TRAJECTORY[:-1], "fifo.png"],
    "--out a folder as figure": [*TRAJECTORY[:-1], "dir.png"],
}


def limit_memory() -> None:
    resource.setrlimit(resource.RLIMIT_AS, (3 << 30, 3 << 30))


def main(script: str, words: list[str]) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        files = Path(tmp) / "files"
        files.mkdir()
        make_files(files)
        print("| case | exit | wall s | CPU s | last line of stderr |\n|---|---|---|---|---|")
        for n, (name, argv) in enumerate(CASES.items()):
            if words and not any(w in name for w in words):
                continue
            work = Path(tmp) / str(n)
            work.mkdir()
            if "FIFO as figure" in name:
                os.mkfifo(work / "fifo.png")
            if "folder as figure" in name:
                (work / "dir.png").mkdir()
            before = resource.getrusage(resource.RUSAGE_CHILDREN)
            start = time.monotonic()
            try:
                proc = subprocess.run([script, *(a.replace("{files}", str(files)) for a in argv)], cwd=work,
                                      capture_output=True, timeout=30, preexec_fn=limit_memory,
                                      env={**os.environ, "MPLBACKEND": "Agg"})
                code, lines = str(proc.returncode), proc.stderr.decode(errors="replace").strip().splitlines()
            except subprocess.TimeoutExpired:
                code, lines = "timeout", ["(killed at 30 s)"]
            after = resource.getrusage(resource.RUSAGE_CHILDREN)
            cpu = after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime
            last = (lines[-1] if lines else "")[:120].replace("|", "\\|")
            written = ",".join(sorted(p.name for p in work.iterdir())) if "--out" in name else ""
            print(f"| {name} | {code} | {time.monotonic() - start:.1f} | {cpu:.1f} | {last}"
                  f"{' (files: ' + written + ')' if written else ''} |", flush=True)


if __name__ == "__main__":
    main(os.path.abspath(sys.argv[1]), sys.argv[2:])
