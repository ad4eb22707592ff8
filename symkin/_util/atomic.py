"""Outputs that appear whole or not at all.

Every file or folder symkin writes is built under a temporary name beside its target
and renamed into place when complete, so a failing or interrupted command leaves the
previous output exactly as it was, and never a half-written file.

    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as d:
    ...     target = Path(d) / "note.txt"
    ...     with replacing(target) as (tmp,):
    ...         _ = tmp.write_text("done")
    ...     target.read_text(), sorted(p.name for p in Path(d).iterdir())
    ('done', ['note.txt'])
"""

from __future__ import annotations

import os
import shutil
import tempfile
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path

from symkin.errors import InputError

__all__ = ["replacing", "write_atomically"]


@contextmanager
def replacing(*targets: str | os.PathLike[str]) -> Iterator[list[Path]]:
    """Temporary files beside ``targets`` (same suffixes); each replaces its target on success.

    On any error or interrupt inside the block the temporary files are removed and the
    targets are left as they were.  Several targets (a PNG and a PDF of one figure) are
    renamed only once all of them are written.

    Raises
    ------
    InputError
        A target's folder does not exist or cannot be written, or a target is a folder.
    """
    outs = [Path(t) for t in targets]
    for out in outs:
        folder = out.resolve().parent
        if not folder.is_dir():
            raise InputError(f"cannot write {out}: the folder {folder} does not exist")
        if out.is_dir():
            raise InputError(f"cannot write {out}: it is a folder; give a file name")
    temps: list[Path] = []
    try:
        for out in outs:
            try:
                fd, name = tempfile.mkstemp(prefix=f".{out.stem}.partial-", suffix=out.suffix, dir=out.resolve().parent)
            except OSError as err:
                raise InputError(f"cannot write to {out.resolve().parent}: {err.strerror}; choose a writable folder") from None
            os.close(fd)
            temps.append(Path(name))
            os.chmod(name, 0o666 & ~_umask())  # mkstemp makes the file private; the result is an ordinary file
        yield list(temps)
        for tmp, out in zip(temps, outs):
            os.replace(tmp, out)
    finally:
        for tmp in temps:
            tmp.unlink(missing_ok=True)


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def write_atomically(out: Path, build: Callable[[Path], None]) -> None:
    """Call ``build(tmp)`` on a fresh folder, then put it at ``out`` in one step.

    If ``build`` raises (or the run is interrupted), the temporary folder is removed
    and ``out`` is left exactly as it was.
    """
    out = Path(out)
    target = out.resolve()
    if target.exists() and not target.is_dir():
        raise InputError(f"{out} exists and is not a folder; choose another --out")
    parent = target.parent
    if not parent.is_dir():
        raise InputError(f"cannot write {out}: its parent folder {parent} does not exist")
    try:
        tmp = Path(tempfile.mkdtemp(prefix=f".{target.name}.partial-", dir=parent))
    except OSError as err:
        raise InputError(f"cannot write to {parent}: {err.strerror}; choose a writable --out") from None
    backup = None
    try:
        build(tmp)
        if target.exists():
            backup = parent / f".{target.name}.old-{os.getpid()}"
            os.rename(target, backup)
        try:
            os.rename(tmp, target)
        except OSError:
            if backup is not None:
                os.rename(backup, target)
                backup = None
            raise
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    if backup is not None:
        shutil.rmtree(backup, ignore_errors=True)
