"""`symkin reproduce`: the report folder, its PDF, and bad input (unwritable folder, unknown
paper, interrupted or failed run) that leaves the previous report untouched."""

import json
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path
from types import SimpleNamespace

import pytest
import sympy as sp

from symkin import ToolError, schemes
from symkin import symbols as S
from symkin._io.atomic import MANIFEST, write_manifest
from symkin.cli import main
from symkin.papers.checks import Check, alternative, compare_exact, compare_symbolic, judge
from symkin.papers.document import PREAMBLE, equations_document
from symkin.papers.reproduce import run
from symkin.papers.texbuild import compile_pdf


@pytest.fixture(autouse=True, scope="module")
def _alyushin2009_derived_once():
    """These tests run ``reproduce alyushin2009`` a dozen times for the folder it writes, not for
    what it derives (tests/papers/test_reproduce.py and tests/papers/test_checks.py test that): its checks are
    derived once, here in the test process, and every run (and every worker it forks) reuses them.
    Runs in a new process (the kill and signal tests) derive them as a user's run does."""
    from symkin.derivations import alyushin2009

    derived = alyushin2009.checks()
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(alyushin2009, "checks", lambda: list(derived))
        yield


def previous_report(folder: Path) -> Path:
    """A folder symkin wrote earlier (its manifest lists its files), with a marker file among them."""
    folder.mkdir()
    (folder / "report.json").write_text(json.dumps({"symkin_version": "0.0"}))
    (folder / "marker.txt").write_text("previous")
    write_manifest(folder, "0.0")
    return folder


def assert_untouched(folder: Path) -> None:
    assert (folder / "marker.txt").read_text() == "previous"
    assert not (folder / "equations.tex").exists()
    assert not [p for p in folder.parent.iterdir() if ".partial-" in p.name or ".old-" in p.name]


def cli(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


# ---- the PDF
def test_report_pdf_compiles_without_overfull_lines(tmp_path, pdflatex):
    out = tmp_path / "report"
    run(["alyushin2009"], out, quiet=True)
    pdf = (out / "equations.pdf").read_bytes()
    assert pdf.startswith(b"%PDF") and len(pdf) > 20_000
    assert not list(out.glob("equations.aux")) and not list(out.glob("equations.log"))
    build = compile_pdf(out / "equations.tex", pdflatex=pdflatex)
    assert max(build.overfull, default=0) < 1, build.overfull
    assert "alyushin2009_trajectories.pdf" in (out / "equations.tex").read_text()



def test_report_pdf_references_resolve_in_its_one_pass(tmp_path, pdflatex):
    """compile_pdf runs pdflatex once: the figure numbers and check numbers are printed, not
    ``\\ref``-ed (which one pass leaves as ??), and they are the numbers LaTeX itself gives."""
    out = tmp_path / "report"
    run(["alyushin2009"], out, quiet=True)
    build = compile_pdf(out / "equations.tex", pdflatex=pdflatex, keep_log=True)
    assert "undefined" not in build.log and "??" not in build.log
    tex = (out / "equations.tex").read_text()
    # a heading does not repeat the words its label ends with
    assert "coaxiality AI1: the planet axis" in tex and "AI1: AI1:" not in tex
    # LaTeX's own numbering of the figures, from its .aux
    subprocess.run([pdflatex, "-interaction=nonstopmode", "equations.tex"], cwd=out, capture_output=True, timeout=120)
    numbers = dict(re.findall(r"\\newlabel\{(fig:[^}]*)\}\{\{(\d+)\}", (out / "equations.aux").read_text()))
    assert len(numbers) == 2, numbers
    mentions = [(m.start(), m.group(1)) for m in re.finditer(r"\(Figure~(\d+)\)", tex)]
    assert mentions
    for start, n in mentions:  # a figure follows the last check that points to it: the next figure is it
        label = re.compile(r"\\label\{(fig:[^}]*)\}").search(tex, start).group(1)
        assert numbers[label] == n, (label, n)
    # the index names checks by the numbers that head them
    heads = re.findall(r"\\subsection\*\{\[(\d+)\] ", tex)
    assert heads == [str(k) for k in range(1, len(heads) + 1)]
    index = tex[tex.index("Index of paper items"):]
    cited = {int(k) for k in re.findall(r"\[(\d+)\]", index)}
    assert cited and cited <= set(range(1, len(heads) + 1))


def nasty_result():
    """Checks whose laws are long and whose text holds every LaTeX special character."""
    a, b = sp.symbols("a b", real=True)
    p = schemes.two_row("AI").motion({"1": S.omega("1"), "4": S.omega("4")}).particle("23", (a, b))
    long_law = p.acceleration[0]
    text = r"50% & $x_1^2$ #3 {braces} ~tilde \backslash <a|b> ω ≈ π × 2 – Кинематика 1/(1-99*201/100/200/300/400/500)"
    checks = [
        Check.make("nasty", "long " + text, text, long_law, long_law, compare_symbolic(long_law, long_law)),
        Check.make("nasty", "system", "two equations", list(schemes.two_row("II").contact_conditions()), "?00 % _",
                   judge(compare_exact(1, 2), alternative=alternative(text * 3, 2, 2, compare_exact))),
    ]
    return SimpleNamespace(key="nasty_key_%", citation=text, checks=checks, figures=[], notes=[text])


def test_long_laws_break_over_lines_and_all_text_is_escaped(tmp_path, pdflatex):
    tex = tmp_path / "doc.tex"
    tex.write_text(equations_document([nasty_result()]))
    assert r"\Bigl(" in tex.read_text() or r"\qquad" in tex.read_text()  # the long law was broken
    build = compile_pdf(tex, pdflatex=pdflatex)
    assert build.pdf.exists()
    assert max(build.overfull, default=0) < 1, build.overfull
    # without breaking, the same law does overflow: the test can fail
    unbroken = tmp_path / "unbroken.tex"
    unbroken.write_text(
        "\\documentclass{article}\\usepackage{amsmath}\\begin{document}\\[" + sp.latex(nasty_result().checks[0].derived)
        + "\\]\\end{document}"
    )
    assert max(compile_pdf(unbroken, pdflatex=pdflatex).overfull, default=0) > 50


def test_a_document_pdflatex_rejects_is_a_tool_error_and_the_previous_report_stays(tmp_path, monkeypatch, pdflatex):
    import symkin.papers.reproduce

    out = previous_report(tmp_path / "report")
    monkeypatch.setattr(symkin.papers.reproduce, "equations_document", lambda results, root=None: "\\documentclass{article}\\begin{document}\\undefinedmacro\\end{document}")
    with pytest.raises(ToolError, match="pdflatex could not compile equations.tex.*Undefined control sequence"):
        run(["alyushin2009"], out, quiet=True)
    assert_untouched(out)


def pdflatex_processes(folder: Path) -> list[int]:
    """The pdflatex processes working in ``folder`` or below it (Linux's /proc)."""
    found = []
    for entry in Path("/proc").iterdir():
        try:
            if entry.name.isdigit() and (entry / "comm").read_text().strip() == "pdflatex" \
                    and Path(os.readlink(entry / "cwd")).is_relative_to(folder):
                found.append(int(entry.name))
        except OSError:  # ended meanwhile, or not ours to read
            pass
    return found


@pytest.mark.parametrize("body", [r"\undefinedmacro\end{document}", "a body that never ends the document"])
def test_a_body_pdflatex_rejects_or_that_never_ends_is_a_tool_error_at_once_and_the_previous_report_stays(
        tmp_path, monkeypatch, pdflatex, body):
    import symkin.papers.reproduce

    out = previous_report(tmp_path / "report")
    monkeypatch.setattr(symkin.papers.reproduce, "equations_document", lambda results, root=None: PREAMBLE + body)
    start = time.monotonic()
    with pytest.raises(ToolError, match="pdflatex could not compile equations.tex: .*(Undefined control sequence|Emergency stop)") as err:
        run(["alyushin2009"], out, quiet=True)
    assert time.monotonic() - start < 60
    if "undefined" in body:  # the message names equations.tex and the line of the fault in it
        assert f"equations.tex:{PREAMBLE.count(chr(10)) + 1}: Undefined control sequence" in str(err.value)
    assert_untouched(out)
    assert not pdflatex_processes(tmp_path)


def test_an_interrupt_while_pdflatex_runs_ends_it_and_leaves_the_previous_report(tmp_path):
    """The run is interrupted (Ctrl-C sent to symkin alone) while pdflatex compiles: pdflatex is
    ended with it.  A stand-in that takes its time is called pdflatex, as the real one is."""
    out = previous_report(tmp_path / "report")
    slow = tmp_path / "bin" / "pdflatex"
    slow.parent.mkdir()
    slow.write_text(f"#!{sys.executable}\nimport time\ntime.sleep(120)\n")
    slow.chmod(0o755)
    proc = subprocess.Popen(
        [sys.executable, "-c", "import sys; from symkin.cli import main; sys.exit(main())", "reproduce", "alyushin2009",
         "--out", str(out), "--quiet"],
        cwd=tmp_path, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env={**os.environ, "SYMKIN_PDFLATEX": str(slow)},
    )
    deadline = time.monotonic() + 120
    while not pdflatex_processes(tmp_path) and proc.poll() is None and time.monotonic() < deadline:
        time.sleep(0.02)
    assert proc.poll() is None, "the run ended before pdflatex started"
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 130 and "interrupted; nothing was written" in err, err
    assert_untouched(out)
    assert not pdflatex_processes(tmp_path)


def test_without_pdflatex_the_pdf_is_skipped_with_a_clear_message(tmp_path, monkeypatch, capsys):
    monkeypatch.setenv("SYMKIN_PDFLATEX", "")
    out = tmp_path / "report"
    code, stdout, err = cli(capsys, "reproduce", "alyushin2009", "--out", str(out), "--quiet")
    assert code == 0
    assert "pdflatex was not found, so equations.pdf was not written" in err and "texlive-latex-base" in err
    assert (out / "equations.tex").exists() and not (out / "equations.pdf").exists()
    assert json.loads((out / "report.json").read_text())["equations"]["pdf"] is None
    assert "verdict" in stdout and "kind" in stdout
    assert re.search(r"\d+ of \d+ paper items reproduced genuinely, \d+ more weakly, 1 slip explained, "
                     r"0 paper errors confirmed, 0 differ", stdout)


# ---- bad input
def test_unknown_paper_lists_the_valid_ones(tmp_path, capsys):
    out = previous_report(tmp_path / "report")
    code, _, err = cli(capsys, "reproduce", "nosuch", "--out", str(out))
    assert code == 2 and "no paper called 'nosuch'; choose all or one of alyushin2009" in err
    assert_untouched(out)


@pytest.mark.parametrize(
    "make, message",
    [
        (lambda d: (d / "afile").write_text("x") and d / "afile", "is a file, not a folder"),
        (lambda d: (d / "afile").write_text("x") and d / "afile" / "out", "is a file, not a folder"),
        (lambda d: d / "missing" / "out", "does not exist"),
    ],
)
def test_a_target_that_cannot_be_a_folder_is_refused(tmp_path, capsys, make, message):
    target = make(tmp_path)
    code, _, err = cli(capsys, "reproduce", "--out", str(target), "--no-pdf")
    assert code == 2 and message in err and len(err.strip().splitlines()) == 1
    assert (tmp_path / "afile").read_text() == "x" if (tmp_path / "afile").exists() else True


def test_a_folder_that_is_not_a_report_is_never_replaced(tmp_path, capsys):
    precious = tmp_path / "thesis"
    precious.mkdir()
    (precious / "chapter1.tex").write_text("years of work")
    code, _, err = cli(capsys, "reproduce", "--out", str(precious), "--no-pdf")
    assert code == 2 and "not a symkin report" in err
    assert (precious / "chapter1.tex").read_text() == "years of work"
    code, _, err = cli(capsys, "reproduce", "--out", ".", "--no-pdf")
    assert code == 2 and "holds the current folder" in err


@pytest.mark.skipif(hasattr(os, "geteuid") and os.geteuid() == 0, reason="root can write to a read-only folder")
def test_a_read_only_parent_is_refused(tmp_path, capsys):
    parent = tmp_path / "ro"
    parent.mkdir()
    parent.chmod(0o555)
    try:
        code, _, err = cli(capsys, "reproduce", "--out", str(parent / "out"), "--no-pdf")
    finally:
        parent.chmod(0o755)
    assert code == 2 and "cannot write to" in err and "Permission denied" in err


def test_an_unwritable_parent_is_refused_even_for_root(tmp_path, capsys):
    # /proc refuses new folders to everyone, root included
    if not Path("/proc/self").is_dir():
        pytest.skip("no /proc on this system")
    code, _, err = cli(capsys, "reproduce", "--out", "/proc/symkin-out", "--no-pdf")
    assert code == 2 and "cannot write to /proc" in err and len(err.strip().splitlines()) == 1


def test_an_interrupt_inside_the_run_leaves_the_previous_report(tmp_path, capsys, monkeypatch):
    from symkin.derivations import alyushin2009

    out = previous_report(tmp_path / "report")

    def interrupted(folder):
        (folder / "half.png").write_bytes(b"partial")
        raise KeyboardInterrupt

    monkeypatch.setattr(alyushin2009, "figures", interrupted)
    code, _stdout, err = cli(capsys, "reproduce", "alyushin2009", "--out", str(out))
    assert code == 130 and "interrupted; nothing was written" in err
    assert_untouched(out)


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_a_signal_to_the_process_leaves_the_previous_report(tmp_path, sig):
    out = previous_report(tmp_path / "report")
    proc = subprocess.Popen(
        [sys.executable, "-c", "import sys; from symkin.cli import main; sys.exit(main())", "reproduce", "--out", str(out), "--no-pdf"],
        cwd=tmp_path, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
    )
    deadline = time.monotonic() + 60
    while not list(tmp_path.glob(".report.partial-*")) and proc.poll() is None and time.monotonic() < deadline:
        time.sleep(0.02)
    assert proc.poll() is None, "the run ended before it could be interrupted"
    proc.send_signal(sig)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 130 and "interrupted; nothing was written" in err, err
    assert_untouched(out)


def test_a_complete_run_replaces_the_previous_report(tmp_path, capsys):
    out = previous_report(tmp_path / "report")
    code, _stdout, _ = cli(capsys, "reproduce", "alyushin2009", "--out", str(out), "--quiet", "--no-pdf")
    assert code == 0 and not (out / "marker.txt").exists()
    assert (out / "figures" / "alyushin2009_trajectories.png").exists()
    data = json.loads((out / "report.json").read_text())
    assert data["summary"]["differs"] == 0
    assert not [p for p in tmp_path.iterdir() if p.name != "report"]


# ---- what a report folder is, and what a user added to it
def test_a_folder_with_a_report_json_but_no_manifest_is_not_a_report(tmp_path, capsys):
    # on c69a8be any folder whose report.json held symkin_version was replaced whole
    folder = tmp_path / "thesis"
    folder.mkdir()
    (folder / "report.json").write_text(json.dumps({"symkin_version": "0.2.0"}))
    (folder / "chapter1.tex").write_text("years of work")
    code, _, err = cli(capsys, "reproduce", "alyushin2009", "--out", str(folder), "--no-pdf", "--quiet")
    assert code == 2 and "not a symkin report" in err and MANIFEST in err and len(err.strip().splitlines()) == 1
    assert (folder / "chapter1.tex").read_text() == "years of work"


def test_files_a_user_added_to_a_report_are_kept(tmp_path, capsys):
    # on c69a8be they were deleted without a word when the folder was replaced
    out = tmp_path / "report"
    assert cli(capsys, "reproduce", "alyushin2009", "--out", str(out), "--no-pdf", "--quiet")[0] == 0
    (out / "notes.txt").write_text("my notes")
    (out / "data").mkdir()
    (out / "data" / "measured.csv").write_text("t,x\n0,1\n")
    (out / "figures" / "sketch.png").write_bytes(b"mine")
    (out / "empty").mkdir()
    code, _, err = cli(capsys, "reproduce", "alyushin2009", "--out", str(out), "--no-pdf", "--quiet")
    assert code == 0, err
    assert (out / "notes.txt").read_text() == "my notes"
    assert (out / "data" / "measured.csv").read_text() == "t,x\n0,1\n"
    assert (out / "figures" / "sketch.png").read_bytes() == b"mine" and (out / "empty").is_dir()
    manifest = json.loads((out / MANIFEST).read_text())["files"]
    assert "notes.txt" not in manifest and "report.json" in manifest and "figures/alyushin2009_trajectories.png" in manifest
    assert not [p for p in tmp_path.iterdir() if p.name != "report"]


def test_a_file_symkin_wrote_and_the_user_changed_is_named_and_nothing_is_replaced(tmp_path, capsys):
    out = tmp_path / "report"
    assert cli(capsys, "reproduce", "alyushin2009", "--out", str(out), "--no-pdf", "--quiet")[0] == 0
    (out / "report.txt").write_text("my edited table")
    before = (out / "report.json").read_bytes()
    code, _, err = cli(capsys, "reproduce", "alyushin2009", "--out", str(out), "--no-pdf", "--quiet")
    assert code == 2 and "report.txt changed since symkin wrote them" in err and len(err.strip().splitlines()) == 1
    assert (out / "report.txt").read_text() == "my edited table" and (out / "report.json").read_bytes() == before


@pytest.mark.parametrize("umask, mode", [(0o022, 0o755), (0o027, 0o750), (0o077, 0o700)])
def test_the_report_folder_has_the_permissions_the_umask_gives(tmp_path, umask, mode):
    # on c69a8be it was always 0700 (mkdtemp's), whatever the umask: other users could not read it
    previous = os.umask(umask)
    try:
        run(["alyushin2009"], tmp_path / "report", quiet=True, pdf=False)
    finally:
        os.umask(previous)
    assert (tmp_path / "report").stat().st_mode & 0o777 == mode
    assert (tmp_path / "report" / "figures").stat().st_mode & 0o777 == mode


def test_a_full_disk_is_one_line_and_exit_2_and_the_previous_report_stays(tmp_path, capsys, monkeypatch):
    # on c69a8be: exit 3, an internal error (OSError)
    import errno

    out = previous_report(tmp_path / "report")
    real = Path.write_text

    def full(self, *args, **kwargs):
        if self.name == "report.txt":
            raise OSError(errno.ENOSPC, "No space left on device")
        return real(self, *args, **kwargs)

    monkeypatch.setattr(Path, "write_text", full)
    code, _, err = cli(capsys, "reproduce", "alyushin2009", "--out", str(out), "--no-pdf", "--quiet")
    assert code == 2 and "No space left on device" in err and len(err.strip().splitlines()) == 1
    assert_untouched(out)


# ---- a run killed at any step: the next run finds the report whole
KILL = """
import os, signal, sys
from symkin._io import atomic
from symkin.cli import main
step = sys.argv[1]
real_rename, real_exchange = os.rename, getattr(atomic, "_exchange", None)
def rename(src, dst):
    real_rename(src, dst)
    if step == "between-renames" and ".old-" in str(dst):
        os.kill(os.getpid(), signal.SIGKILL)  # the old report is aside, the new one not yet in
os.rename = rename
if step == "between-renames" and real_exchange is not None:
    atomic._exchange = lambda a, b: False  # as where the platform has no atomic exchange
if step == "after-exchange":
    def exchange(a, b):
        done = real_exchange(a, b)
        os.kill(os.getpid(), signal.SIGKILL)  # swapped, the old one not yet removed
        return done
    atomic._exchange = exchange
if step.startswith("while-building"):
    from symkin.derivations import alyushin2009
    runner = os.getpid()  # figures may be drawn in a worker process: kill the run itself
    def figures(folder):
        (folder / "half.png").write_bytes(b"half")
        os.kill(runner, signal.SIGKILL)
    alyushin2009.figures = figures
pdf = [] if step == "while-building-with-pdflatex" else ["--no-pdf"]
sys.exit(main(["reproduce", "alyushin2009", "--out", sys.argv[2], "--quiet", *pdf]))
"""


def killed_run(step: str, out: Path) -> None:
    proc = subprocess.run([sys.executable, "-c", KILL, step, str(out)], capture_output=True, text=True, timeout=300)
    assert proc.returncode == -signal.SIGKILL, proc.stderr


def test_a_kill_between_the_two_renames_is_recovered_by_the_next_run(tmp_path, capsys, monkeypatch):
    # where there is no atomic exchange: the old report set aside, then killed before the new one is
    # renamed in.  On c69a8be the next run neither restored the old one nor removed it.
    out = previous_report(tmp_path / "report")
    killed_run("between-renames", out)
    assert not out.exists() and [p for p in tmp_path.iterdir() if ".report.old-" in p.name]
    # the next run puts the old report back before anything else; interrupted, it leaves it so
    from symkin.derivations import alyushin2009

    def interrupted(folder):
        raise KeyboardInterrupt

    monkeypatch.setattr(alyushin2009, "figures", interrupted)
    code, _, err = cli(capsys, "reproduce", "alyushin2009", "--out", str(out), "--no-pdf", "--quiet")
    assert code == 130, err
    assert_untouched(out)


def test_a_kill_of_a_run_with_pdflatex_leaves_the_previous_report_and_no_pdflatex_running(tmp_path, pdflatex):
    """Killed while it derives: nothing of the run is left working (its workers die with it, and
    pdflatex, which compiles the finished file at the end, was not started)."""
    out = previous_report(tmp_path / "report")
    killed_run("while-building-with-pdflatex", out)
    deadline = time.monotonic() + 30
    while pdflatex_processes(tmp_path) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert not pdflatex_processes(tmp_path)
    assert (out / "marker.txt").read_text() == "previous"


def test_a_kill_after_the_atomic_exchange_leaves_the_new_report_whole(tmp_path, capsys):
    from symkin._io.atomic import _exchange

    probe_a, probe_b = tmp_path / "a", tmp_path / "b"
    probe_a.mkdir()
    probe_b.mkdir()
    if not _exchange(probe_a, probe_b):
        pytest.skip("no atomic exchange (renameat2) on this platform or file system")
    out = previous_report(tmp_path / "report")
    killed_run("after-exchange", out)
    # in place at once, whole: the new report (its manifest lists what it wrote)
    assert not (out / "marker.txt").exists() and (out / "equations.tex").exists()
    assert json.loads((out / MANIFEST).read_text())["files"].keys() >= {"report.json", "report.txt", "equations.tex"}
    litter = [p for p in tmp_path.iterdir() if ".partial-" in p.name]
    assert litter and (litter[0] / "marker.txt").read_text() == "previous"  # the old one, under the temporary name
    code, _, _ = cli(capsys, "reproduce", "alyushin2009", "--out", str(out), "--no-pdf", "--quiet")
    assert code == 0 and sorted(p.name for p in tmp_path.iterdir()) == ["a", "b", "report"]


def test_a_kill_while_building_leaves_the_previous_report_and_the_next_run_removes_the_litter(tmp_path, capsys):
    out = previous_report(tmp_path / "report")
    killed_run("while-building", out)
    assert (out / "marker.txt").read_text() == "previous"
    assert [p for p in tmp_path.iterdir() if ".report.partial-" in p.name]
    # litter of the former naming too (.X.partial-<random>, .X.old-<pid>)
    (tmp_path / ".report.partial-k2x9_q1z").mkdir()
    (tmp_path / ".report.old-999999999").mkdir()
    code, _, err = cli(capsys, "reproduce", "alyushin2009", "--out", str(out), "--no-pdf", "--quiet")
    assert code == 0, err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["report"]


_PAPERS = """
import json, os, pathlib, sys
from types import SimpleNamespace
import sympy as sp
from symkin.papers.reproduce import run_papers
folder = pathlib.Path(sys.argv[1])
x = sp.Symbol("x", positive=True)

def paper(name):  # modules the workers find as this process has them: never pickled
    return SimpleNamespace(checks=lambda: [name, os.getpid(), sp.Eq(2, 2, evaluate=False), sp.Lt(x, 0, evaluate=False)],
                           figures=lambda folder: [name + " drawn"])

out = {}
for jobs in (1, 2):
    found = {}
    run_papers({n: paper(n) for n in "pqr"}, list("pqr"), folder, jobs=jobs, done=lambda name, value: found.__setitem__(name, value))
    out[jobs] = {n: [v[0][0], v[0][1] != os.getpid(), repr(v[0][2]), repr(v[0][3]), v[1], v[2]] for n, v in found.items()}
failing = SimpleNamespace(checks=lambda: 1 / 0, figures=lambda folder: [])
found = {}
run_papers({"p": paper("p"), "x": failing}, ["p", "x"], folder, jobs=2, done=lambda name, value: found.__setitem__(name, value))
(check,) = found["x"][0]
out["error"] = [check.label, check.kind.value, check.verdict.value, check.comparison.detail, found["p"][0][0]]
print(json.dumps(out))
"""


def test_every_paper_reports_once_alike_for_any_jobs_and_a_failure_is_a_failing_check(tmp_path):
    # in a process of its own: a test worker of pytest-xdist runs threads, and the papers run in
    # worker processes only from a process running one thread
    proc = subprocess.run([sys.executable, "-c", _PAPERS, str(tmp_path)], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    out = json.loads(proc.stdout.strip().splitlines()[-1])
    for jobs, elsewhere in (("1", False), ("2", True)):
        # every paper once, in a worker process with jobs 2; unevaluated relations arrive as they
        # were made, not decided again (Eq(2, 2) is not True): the results do not depend on jobs
        assert out[jobs] == {n: [n, elsewhere, "Eq(2, 2)", "x < 0", [], [n + " drawn"]] for n in "pqr"}
    # a paper that raises in a worker: its failure check, verdict differs, the error as evidence; the other paper runs
    label, kind, verdict, detail, other = out["error"]
    assert (label, kind, verdict, other) == ("checks: failed", "failure", "differs", "p")
    assert "ZeroDivisionError: division by zero" in detail


_KILLED_WITH_WORKERS = """
import os, pathlib, signal, sys, time
from types import SimpleNamespace
from symkin.papers.reproduce import run_papers
folder = pathlib.Path(sys.argv[1])
runner = os.getpid()

def checks(name):
    (folder / f"{name}.pid").write_text(str(os.getpid()))
    if name == "p":
        time.sleep(0.5)
        os.kill(runner, signal.SIGKILL)
    time.sleep(100)  # q: still at work when the run is killed
    return []

papers = {n: SimpleNamespace(checks=lambda n=n: checks(n), figures=lambda folder: []) for n in "pq"}
run_papers(papers, ["p", "q"], folder, jobs=2, done=lambda name, value: None)
"""


def test_the_worker_processes_end_when_the_run_is_killed(tmp_path):
    # (the run's output ends only when the workers, which hold it too, have ended)
    proc = subprocess.run([sys.executable, "-c", _KILLED_WITH_WORKERS, str(tmp_path)], capture_output=True, text=True,
                          timeout=60)
    assert proc.returncode == -signal.SIGKILL, proc.stderr

    def running(pid):
        try:
            return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0] not in "ZX"
        except OSError:
            return False

    pids = [int((tmp_path / f"{n}.pid").read_text()) for n in "pq"]
    assert pids[0] != pids[1]
    # a process closes its files (the run's output ends) a moment before it is gone: on a loaded
    # machine that moment is seen, so the workers get a few seconds to finish ending
    deadline = time.monotonic() + 10
    while any(running(pid) for pid in pids) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert not any(running(pid) for pid in pids)


_CTRL_C_AT_THE_FOLDER = """
import os, pathlib, signal, sys
from symkin._io.atomic import write_atomically
parent = pathlib.Path(sys.argv[1])
made = os.mkdir

def mkdir_then_ctrl_c(*args, **kwargs):
    made(*args, **kwargs)
    os.kill(os.getpid(), signal.SIGINT)  # Ctrl-C the moment the folder exists

os.mkdir = mkdir_then_ctrl_c
try:
    write_atomically(parent / "report", lambda tmp: (tmp / "a.txt").write_text("x"))
    print("not interrupted")
except KeyboardInterrupt:
    print(sorted(p.name for p in parent.iterdir()))
"""


def test_a_ctrl_c_the_moment_the_partial_folder_exists_leaves_nothing(tmp_path):
    # a Ctrl-C between making the folder and registering its removal (a loaded machine's
    # scheduling made the signal test meet it) left .report.partial-*: the name is now known first
    proc = subprocess.run([sys.executable, "-c", _CTRL_C_AT_THE_FOLDER, str(tmp_path)], capture_output=True, text=True,
                          timeout=60)
    assert proc.stdout.strip() == "[]", (proc.stdout, proc.stderr)
