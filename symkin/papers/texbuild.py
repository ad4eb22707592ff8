"""Compile a LaTeX document to PDF with pdflatex (TeX Live's base is enough).

pdflatex is an optional system tool: :func:`find_pdflatex` says whether it is there,
and :data:`MISSING` is the message to show when it is not.

    >>> from symkin.papers.texbuild import overfull_boxes
    >>> overfull_boxes("Overfull \\\\hbox (12.5pt too wide) in paragraph at lines 3--4\\n")
    [12.5]
"""

from __future__ import annotations

import contextlib
import os
import re
import select
import shutil
import subprocess
import sys
import tempfile
import threading
import time
from dataclasses import dataclass
from pathlib import Path

from symkin.errors import ToolError

__all__ = ["find_pdflatex", "compile_pdf", "start_pdf", "StreamedPdf", "PdfBuild", "overfull_boxes", "MISSING"]

#: What to tell a user who has no pdflatex.
MISSING = (
    "pdflatex was not found, so equations.pdf was not written (equations.tex was); install TeX Live's "
    "base packages (Debian/Ubuntu: sudo apt-get install texlive-latex-base) and run again"
)


def find_pdflatex() -> str | None:
    """The pdflatex executable on PATH (or ``$SYMKIN_PDFLATEX``; empty means none), or None.

    >>> exe = find_pdflatex()
    >>> exe is None or "pdflatex" in exe
    True
    """
    override = os.environ.get("SYMKIN_PDFLATEX")
    if override is not None:
        return shutil.which(override) if override else None
    return shutil.which("pdflatex")


@dataclass(frozen=True)
class PdfBuild:
    """A compiled document: the PDF and the widths (pt) of any overfull boxes in the log."""

    pdf: Path
    overfull: tuple[float, ...]
    log: str


def overfull_boxes(log: str) -> list[float]:
    """How far each overfull box in a pdflatex log sticks out, in points."""
    return [float(m) for m in re.findall(r"Overfull \\[hv]box \(([\d.]+)pt too (?:wide|high)\)", log)]


def _first_error(log: str) -> str:
    lines = log.splitlines()
    for i, line in enumerate(lines):
        if line.startswith("!") or re.match(r"^\S+\.tex:\d+: ", line):
            context = " ".join(s.strip() for s in lines[i : i + 3] if s.strip())
            return context[:300]
    return (lines[-1] if lines else "no log")[:300]


def compile_pdf(tex: Path, *, pdflatex: str | None = None, timeout: float = 180.0, keep_log: bool = False) -> PdfBuild:
    """Run pdflatex on ``tex`` in its own folder and return the PDF beside it.

    Shell escape is off and pdflatex never waits for input.  Auxiliary files are removed
    (the log too unless ``keep_log``).

    Raises
    ------
    ToolError
        When pdflatex is missing, times out, or cannot compile the document.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> tex = pathlib.Path(tempfile.mkdtemp()) / "x.tex"
    >>> _ = tex.write_text(r"\\documentclass{article}\\begin{document}$z_1 + z_2$\\end{document}")
    >>> find_pdflatex() is None or compile_pdf(tex).pdf.read_bytes().startswith(b"%PDF")
    True
    """
    tex = Path(tex).resolve()
    exe = pdflatex or find_pdflatex()
    if exe is None:
        raise ToolError(MISSING)
    try:
        proc = subprocess.run(
            _command(exe, tex.stem, tex.name), cwd=tex.parent, stdin=subprocess.DEVNULL, capture_output=True,
            timeout=timeout, env=_environment(tex.parent),
        )
    except subprocess.TimeoutExpired:
        raise ToolError(f"pdflatex did not finish {tex.name} within {timeout:.0f} s; check the TeX installation") from None
    except OSError as err:
        raise ToolError(f"pdflatex could not be started ({err.strerror}); check the TeX installation") from None
    return _result(tex.parent, tex.stem, tex.name, proc.returncode, proc.stdout.decode(errors="replace"), keep_log)


def _command(exe: str, job: str, source: str) -> list[str]:
    return [exe, "-interaction=nonstopmode", "-halt-on-error", "-no-shell-escape", "-file-line-error",
            f"-jobname={job}", source]


def _environment(folder: Path) -> dict[str, str]:
    return {**os.environ, "TEXINPUTS": f"{folder}{os.pathsep}"}


def _result(folder: Path, job: str, name: str, returncode: int | None, output: str, keep_log: bool) -> PdfBuild:
    """The PDF pdflatex wrote as ``job`` in ``folder``, its auxiliary files removed (the log
    too unless ``keep_log``); ToolError when it failed."""
    log_file = folder / f"{job}.log"
    log = log_file.read_text(errors="replace") if log_file.exists() else output
    pdf = folder / f"{job}.pdf"
    for suffix in (".aux", ".out") + (() if keep_log else (".log",)):
        (folder / f"{job}{suffix}").unlink(missing_ok=True)
    if returncode != 0 or not pdf.exists():
        raise ToolError(f"pdflatex could not compile {name}: {_first_error(log)} (a symkin bug: please report it)")
    return PdfBuild(pdf, tuple(overfull_boxes(log)), log)


class StreamedPdf:
    """pdflatex started on a document whose beginning is known before the rest of it.

    pdflatex reads the document from a pipe, its standard input (``\\input /dev/stdin``):
    ``head`` (the preamble) at once, the rest when :meth:`finish` writes it, so only the body
    is compiled after it exists.  ``symkin reproduce`` starts it while the papers are derived
    (the process's start-up and the preamble, about 0.12 s, off the end of the run).

    The pipe is pdflatex's from its start: when this process ends, whatever the way, its end
    of the pipe closes and pdflatex reads the end of its input and stops (processes forked from
    this one hold the pipe too: ``reproduce``'s workers end before :meth:`finish`).
    :meth:`cancel` ends it at once.  Messages name ``job.tex`` and its line numbers (the head
    and the body are that file).
    """

    def __init__(self, folder: Path, job: str, head: str, exe: str, timeout: float):
        self.folder, self.job, self.timeout = folder, job, timeout
        self._lock = threading.Lock()  # (finish writes in a thread; cancel may come from another)
        # pdflatex's terminal output, read if it writes no log; a file, not a pipe nobody reads meanwhile
        self.output = tempfile.TemporaryFile()  # noqa: SIM115 - closed by finish or cancel
        read, self.fd = os.pipe()
        try:
            self.proc = subprocess.Popen(
                _command(exe, job, r"\input /dev/stdin"), cwd=folder, stdin=read, stdout=self.output,
                stderr=subprocess.STDOUT, env=_environment(folder),
            )
        except BaseException:
            os.close(self.fd)
            self.fd = -1
            self.output.close()
            raise
        finally:
            os.close(read)
        os.set_blocking(self.fd, False)
        try:
            self._write(head.encode("utf-8"), time.monotonic() + timeout)
        except BaseException:
            self.cancel()
            raise

    def _write(self, data: bytes, deadline: float) -> None:
        """Write ``data`` into the pipe as pdflatex reads it, until ``deadline`` (TimeoutExpired);
        stops where pdflatex has stopped reading (it ended)."""
        view = memoryview(data)
        while view:
            with self._lock:
                if self.fd < 0:  # cancelled
                    return
                try:
                    view = view[os.write(self.fd, view):]
                    continue
                except BlockingIOError:
                    fd = self.fd
                except BrokenPipeError:  # pdflatex ended: its log says why
                    return
            if time.monotonic() > deadline:
                raise subprocess.TimeoutExpired(self.proc.args, self.timeout)
            with contextlib.suppress(OSError, ValueError):  # (closed meanwhile by cancel: seen above)
                select.select([], [fd], [], 0.05)

    def finish(self, body: str, *, keep_log: bool = False) -> PdfBuild:
        """Give pdflatex the rest of the document (``body``, ending with ``\\end{document}``)
        and return the PDF; ToolError as :func:`compile_pdf`."""
        deadline = time.monotonic() + self.timeout
        try:
            self._write(body.encode("utf-8"), deadline)
            self._close()  # the end of its input: a body that does not end the document is an error
            self.proc.wait(max(0.0, deadline - time.monotonic()))
        except subprocess.TimeoutExpired:
            self.cancel()
            raise ToolError(f"pdflatex did not finish {self.job}.tex within {self.timeout:.0f} s; check the TeX "
                            "installation") from None
        except BaseException:
            self.cancel()
            raise
        if self.output.closed:  # cancelled meanwhile (a second Ctrl-C)
            raise ToolError(f"pdflatex was stopped before it finished {self.job}.tex")
        self.output.seek(0)
        output = self.output.read().decode(errors="replace")
        self.output.close()
        log_file = self.folder / f"{self.job}.log"
        if log_file.exists():  # the document came from /dev/stdin: its messages name it so
            log_file.write_text(log_file.read_text(errors="replace").replace("/dev/stdin", f"{self.job}.tex"))
        return _result(self.folder, self.job, f"{self.job}.tex", self.proc.returncode,
                       output.replace("/dev/stdin", f"{self.job}.tex"), keep_log)

    def cancel(self) -> None:
        """End pdflatex and remove what it wrote."""
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait()
        self._close()
        self.output.close()
        for suffix in (".aux", ".out", ".log", ".pdf"):
            (self.folder / f"{self.job}{suffix}").unlink(missing_ok=True)

    def _close(self) -> None:
        with self._lock:
            if self.fd >= 0:
                os.close(self.fd)
                self.fd = -1


def start_pdf(folder: Path, job: str, head: str, *, pdflatex: str | None = None, timeout: float = 180.0) -> StreamedPdf | None:
    """Start pdflatex on ``head``, the beginning of ``folder/job.tex``, before the rest exists
    (see :class:`StreamedPdf`); None where a pipe cannot be read as ``/dev/stdin`` (only on
    Linux), and the document is then compiled whole with :func:`compile_pdf`.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> early = start_pdf(folder, "x", r"\\documentclass{article}\\begin{document}")
    >>> early is None or early.finish(r"$z_1$\\end{document}").pdf.read_bytes().startswith(b"%PDF")
    True
    >>> sorted(p.name for p in folder.iterdir()) in ([], ["x.pdf"])
    True
    """
    exe = pdflatex or find_pdflatex()
    if exe is None or not sys.platform.startswith("linux") or not os.path.exists("/dev/stdin"):
        return None
    try:
        return StreamedPdf(Path(folder), job, head, exe, timeout)
    except OSError:  # pdflatex cannot be started: compiled whole, where the error is reported
        return None
