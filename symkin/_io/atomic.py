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

A folder (the report of ``symkin reproduce``) is replaced in one atomic step where the
platform has one (Linux's ``renameat2(RENAME_EXCHANGE)`` swaps the new folder and the old
one); elsewhere in two renames, old aside and new in, and a run killed between them is
recovered by the next one, which puts the old folder back.  Temporary names carry the
process id (``.report.partial-<pid>-<random>``, ``.report.old-<pid>-<random>``), so the
next run removes what a dead process left and never what a running one is building.

A folder symkin wrote holds a manifest (:data:`MANIFEST`) of every file in it with its
SHA-256.  Only a folder with a valid manifest is replaced; files a user added to it since
(notes, data) are carried over into the new folder, and a file symkin wrote that was
changed since is a reason to refuse (:func:`check_replaceable`), so nothing a user put there is lost.
"""

from __future__ import annotations

import ctypes
import errno
import hashlib
import json
import os
import re
import secrets
import shutil
import signal
import stat
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path

from symkin.errors import InputError

__all__ = ["replacing", "write_atomically", "MANIFEST", "check_replaceable", "recover", "write_manifest", "PLACED",
           "placed"]

#: Every output this process put in place, or was about to: its path and the inode of the new file
#: or folder, noted before the rename.  An interrupt can land just after a rename (a signal is
#: handled between any two steps, by whichever thread has it unblocked), so what was written is
#: read from the disk, not from how far the code got: see :func:`placed`.
PLACED: list[tuple[Path, int]] = []


def placed(since: int = 0) -> list[Path]:
    """The outputs of :data:`PLACED` from the ``since``-th on that are in place: their path holds
    the file or folder this process built (so they are whole).

    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as d:
    ...     start = len(PLACED)
    ...     with replacing(Path(d) / "a.txt") as (tmp,):
    ...         _ = tmp.write_text("x")
    ...     [p.name for p in placed(start)]
    ['a.txt']
    """
    out = []
    for path, inode in PLACED[since:]:
        try:
            if os.stat(path).st_ino == inode:
                out.append(path)
        except OSError:
            pass
    return list(dict.fromkeys(out))

#: The manifest symkin writes into a folder it owns: every file's relative path and SHA-256.
MANIFEST = ".symkin-manifest.json"
_KIND = "symkin folder manifest"

#: errno values that say the disk or the folder cannot take the output (not a bug).
_UNWRITABLE = {errno.ENOSPC, errno.EDQUOT, errno.EROFS, errno.EACCES, errno.EPERM, errno.EFBIG, errno.EMLINK}


def _unwritable(err: OSError, where: Path, option: str) -> InputError:
    return InputError(f"cannot write {where}: {err.strerror or err}; free some space or choose another {option}")


@contextmanager
def replacing(target: str | os.PathLike[str]) -> Iterator[tuple[Path]]:
    """A temporary file beside ``target`` (same suffix) that replaces it on success.

    On any error or interrupt inside the block the temporary file is removed and the target
    is left as it was.

    Raises
    ------
    InputError
        The target's folder does not exist or cannot be written, the target is a folder or an
        existing file of another kind, or the disk is full (the previous file is kept).
    """
    out = Path(target)
    folder = out.resolve().parent
    if not folder.is_dir():
        raise InputError(f"cannot write {out}: the folder {folder} does not exist")
    if out.is_dir():
        raise InputError(f"cannot write {out}: it is a folder; give a file name")
    special = _special(out)
    if special:  # (a FIFO would block the check below, and the writer waiting on it for ever)
        raise InputError(f"cannot write {out}: it is {special}, not a file; give a file name")
    kind = _not_its_kind(out)
    if kind:
        raise InputError(f"cannot write {out}: it exists and is not {kind} (a file of yours?); choose another "
                         "name, or remove it first")
    # the name is this process's (its id and a random part) and known before the file exists: an
    # interrupt at any step leaves nothing that the cleanup below does not remove
    tmp = _partial(folder, out.stem, out.suffix)
    ours = True
    try:
        try:
            os.close(os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666))  # the umask applies: an ordinary file
        except OSError as err:
            ours = not isinstance(err, FileExistsError)  # (that name is another's: never removed)
            raise InputError(f"cannot write to {folder}: {err.strerror}; choose a writable folder") from None
        try:
            yield (tmp,)
        except OSError as err:
            if err.errno in _UNWRITABLE:
                raise _unwritable(err, out, "--out") from None
            raise
        PLACED.append((out, os.stat(tmp).st_ino))
        os.replace(tmp, out)
    finally:
        if ours:
            tmp.unlink(missing_ok=True)


def _partial(folder: Path, name: str, suffix: str = "") -> Path:
    """A temporary name beside ``folder / name``: this process's id and 64 random bits, so that
    :func:`recover` tells a dead run's from a running one's and two runs never meet."""
    return folder / f".{name}.partial-{os.getpid()}-{secrets.token_hex(8)}{suffix}"


#: What a file of each suffix symkin writes holds at a given offset: an existing target that
#: does not is not an earlier output of the same kind, and is not replaced.
_SIGNATURES = {
    ".png": ("a PNG image", 0, (b"\x89PNG",)), ".gif": ("a GIF image", 0, (b"GIF8",)),
    ".pdf": ("a PDF file", 0, (b"%PDF",)), ".eps": ("an EPS file", 0, (b"%!PS",)),
    ".svg": ("an SVG image", 0, (b"<?xml", b"<svg")), ".html": ("an HTML page", 0, (b"<",)),
    ".mp4": ("an MP4 video", 4, (b"ftyp",)), ".dxf": ("a DXF drawing", 0, (b"0", b"999")),
}


def _special(path: Path) -> str:
    """What ``path`` is when it exists and is neither a regular file nor a folder (links followed), else ""."""
    try:
        mode = path.stat().st_mode
    except (OSError, ValueError):
        return ""
    if stat.S_ISREG(mode) or stat.S_ISDIR(mode):
        return ""
    return {stat.S_IFIFO: "a named pipe (FIFO)", stat.S_IFSOCK: "a socket", stat.S_IFCHR: "a device",
            stat.S_IFBLK: "a device"}.get(stat.S_IFMT(mode), "not a regular file")


def _not_its_kind(out: Path) -> str:
    """The kind of file ``out``'s suffix names when ``out`` exists, is not empty and is not one
    (a user's text file called result.png); else ""."""
    known = _SIGNATURES.get(out.suffix.lower())
    if known is None:
        return ""
    try:
        with open(out, "rb") as f:
            head = f.read(16)
    except OSError:  # missing, or unreadable: the write will say what is wrong
        return ""
    kind, offset, starts = known
    return "" if not head or head[offset:].lstrip().startswith(starts) else kind


#: The signals that stop a run (Ctrl-C, and SIGTERM, which the command line turns into Ctrl-C).
STOP_SIGNALS = frozenset({signal.SIGINT, signal.SIGTERM})


@contextmanager
def stop_signals_held() -> Iterator[None]:
    """Ctrl-C and SIGTERM held back (on POSIX) while the block runs, delivered at its end: for
    steps that must not be cut in two, such as forking a pool's workers (a fork inherits the
    mask, so a worker starts with them held too).  The mask is the calling thread's: in a
    process that runs other threads one of them can take the signal, so hold it only where
    the process runs one thread (as :func:`symkin.papers.reproduce` forks only then).

    >>> with stop_signals_held():
    ...     pass
    """
    if not hasattr(signal, "pthread_sigmask"):  # not on POSIX: nothing to hold
        yield
        return
    held = signal.pthread_sigmask(signal.SIG_BLOCK, STOP_SIGNALS)
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, held)


# --------------------------------------------------------------------------- the manifest
def _hash(path: Path) -> str:
    if path.is_symlink():
        return "symlink:" + os.readlink(path)
    mode = path.lstat().st_mode
    if not stat.S_ISREG(mode):  # a FIFO or a device in place of a file: never opened (it could block or never end)
        return f"special:{stat.S_IFMT(mode):o}"
    digest = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            digest.update(block)
    return "sha256:" + digest.hexdigest()


def _entries(folder: Path) -> tuple[list[str], list[str]]:
    """(files and symbolic links, folders) under ``folder``, as relative POSIX paths; links not followed."""
    files: list[str] = []
    folders: list[str] = []
    for root, dirs, names in os.walk(folder, followlinks=False):
        here = Path(root).relative_to(folder)
        for d in list(dirs):
            if (Path(root) / d).is_symlink():  # a link to a folder is an entry, not a folder to walk
                dirs.remove(d)
                names.append(d)
            else:
                folders.append((here / d).as_posix())
        files += [(here / n).as_posix() for n in names]
    return sorted(f for f in files if f != MANIFEST), sorted(folders)


def write_manifest(folder: Path, version: str) -> None:
    """Write :data:`MANIFEST` into ``folder``: every file in it, with its SHA-256."""
    files, _ = _entries(folder)
    data = {"kind": _KIND, "written_by": f"symkin {version}", "files": {f: _hash(folder / f) for f in files}}
    (folder / MANIFEST).write_text(json.dumps(data, indent=1, sort_keys=True) + "\n")


def _read_manifest(folder: Path) -> dict[str, str] | None:
    try:
        data = json.loads((folder / MANIFEST).read_text())
    except (OSError, ValueError, UnicodeDecodeError):
        return None
    if not isinstance(data, dict) or data.get("kind") != _KIND or not isinstance(data.get("files"), dict):
        return None
    files = data["files"]
    for name, digest in files.items():
        parts = Path(name).parts
        if not isinstance(digest, str) or not parts or Path(name).is_absolute() or ".." in parts:
            return None
    return files


def _carry(old: Path, new: Path, added: list[str], out: Path) -> None:
    """Put the user's files of the old folder into the new one: hard links (no copy, and the old
    folder keeps its own until it is removed), or copies where links cannot be made."""
    clashes = [a for a in added if os.path.lexists(new / a)
               or any(os.path.lexists(new / p) and not (new / p).is_dir() for p in Path(a).parents)]
    if clashes:
        raise InputError(
            f"--out {out} holds {_names(clashes)}, which you added and where the new report writes its own; "
            "move them out of the folder, or choose another --out"
        )
    for name in added:
        src, dst = old / name, new / name
        dst.parent.mkdir(parents=True, exist_ok=True)
        if src.is_dir() and not src.is_symlink():
            dst.mkdir(exist_ok=True)
            continue
        try:
            os.link(src, dst, follow_symlinks=False)
        except OSError:  # (a file system without hard links; a link is copied as a link)
            shutil.copy2(src, dst, follow_symlinks=False)


def _names(paths: list[str], most: int = 5) -> str:
    shown = ", ".join(paths[:most])
    return shown + (f" and {len(paths) - most} more" if len(paths) > most else "")


# --------------------------------------------------------------------------- litter and recovery
_LITTER = re.compile(r"^\.(?P<name>.+)\.(?P<kind>partial|old)-(?P<pid>\d+)(?:-.*)?$|^\.(?P<name2>.+)\.partial-[^-]*$")


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # another user's process
        pass
    return True


def recover(out: Path) -> None:
    """Tidy what a killed run left beside folder ``out``: put an old folder set aside back in
    place if the new one never arrived, and remove temporary folders of dead processes.

    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as d:
    ...     old = Path(d) / ".report.old-999999999-x"; old.mkdir(); _ = (old / "a.txt").write_text("kept")
    ...     partial = Path(d) / ".report.partial-999999999-y"; partial.mkdir()
    ...     recover(Path(d) / "report")
    ...     sorted(p.name for p in Path(d).iterdir()), (Path(d) / "report" / "a.txt").read_text()
    (['report'], 'kept')
    """
    target = Path(out).resolve()
    parent = target.parent
    if not parent.is_dir():
        return
    olds: list[Path] = []
    partials: list[Path] = []
    for entry in parent.iterdir():
        m = _LITTER.match(entry.name)
        if m is None or (m.group("name") or m.group("name2")) != target.name:
            continue
        pid = m.group("pid")
        if pid is not None and _alive(int(pid)):
            continue  # a running symkin is using it
        if pid is None and not (entry.is_dir() and not entry.is_symlink()):
            continue  # only folders of the former naming (a file of that name is another command's)
        (olds if m.group("kind") == "old" else partials).append(entry)
    if olds and not os.path.lexists(target):
        newest = max(olds, key=lambda p: p.lstat().st_mtime)
        os.rename(newest, target)
        olds.remove(newest)
    for entry in olds + partials:
        if entry.is_dir() and not entry.is_symlink():
            shutil.rmtree(entry, ignore_errors=True)
        else:
            entry.unlink(missing_ok=True)


# --------------------------------------------------------------------------- the swap
_RENAME_EXCHANGE = 2
_AT_FDCWD = -100


def _exchange(a: Path, b: Path) -> bool:
    """Swap two paths in one atomic step (Linux renameat2 RENAME_EXCHANGE); False where the
    platform or the file system has no such step."""
    try:
        renameat2 = ctypes.CDLL(None, use_errno=True).renameat2
    except (AttributeError, OSError):
        return False
    renameat2.argtypes = [ctypes.c_int, ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p, ctypes.c_uint]
    if renameat2(_AT_FDCWD, os.fsencode(a), _AT_FDCWD, os.fsencode(b), _RENAME_EXCHANGE) == 0:
        return True
    code = ctypes.get_errno()
    if code in (errno.ENOSYS, errno.EINVAL, errno.ENOTSUP, errno.EOPNOTSUPP):
        return False
    raise OSError(code, os.strerror(code), str(b))


def _swap(tmp: Path, target: Path) -> Path | None:
    """Put ``tmp`` at ``target``; returns where the old ``target`` now is (to be removed), or None."""
    if not os.path.lexists(target):
        os.rename(tmp, target)
        return None
    if _exchange(tmp, target):
        return tmp  # the old folder now has the temporary name
    backup = target.parent / f".{target.name}.old-{os.getpid()}-{secrets.token_hex(4)}"
    os.rename(target, backup)
    try:
        os.rename(tmp, target)
    except BaseException:
        os.rename(backup, target)
        raise
    return backup


def write_atomically(out: Path, build: Callable[[Path], None], *, version: str | None = None) -> None:
    """Call ``build(tmp)`` on a fresh folder, then put it at ``out`` in one step.

    If ``build`` raises (or the run is interrupted, or killed), ``out`` is left exactly as
    it was.  The new folder gets the permissions of a folder made with ``mkdir`` (the umask
    applies).  With ``version``, a manifest (:data:`MANIFEST`) of every file written is added,
    and an existing ``out`` is replaced only if it holds such a manifest and no file symkin
    wrote was changed since; files added to it are carried into the new folder.

    Raises
    ------
    InputError
        ``out`` is a file or a folder symkin did not write, holds changed files, or cannot
        be written (no such parent, no permission, a full disk).
    """
    out = Path(out)
    target = out.resolve()
    if target.exists() and not target.is_dir():
        raise InputError(f"{out} exists and is not a folder; choose another --out")
    parent = target.parent
    if not parent.is_dir():
        raise InputError(f"cannot write {out}: its parent folder {parent} does not exist")
    # the name is known before the folder exists, so an interrupt at any step leaves nothing the
    # cleanup below does not remove; os.mkdir applies the umask (a report is an ordinary folder)
    tmp = _partial(parent, target.name)
    ours = True
    old: Path | None = None
    try:
        try:
            recover(out)
            os.mkdir(tmp)
        except OSError as err:
            ours = not isinstance(err, FileExistsError)  # (that name is another's: never removed)
            raise InputError(f"cannot write to {parent}: {err.strerror}; choose a writable --out") from None
        build(tmp)
        if version is not None:
            write_manifest(tmp, version)
            if target.is_dir():
                _carry(target, tmp, check_replaceable(out), out)
        PLACED.append((out, os.stat(tmp).st_ino))
        old = _swap(tmp, target)
    except OSError as err:
        if err.errno in _UNWRITABLE:
            raise _unwritable(err, out, "--out") from None
        raise
    finally:
        if old is None and ours:
            shutil.rmtree(tmp, ignore_errors=True)
    if old is not None:
        shutil.rmtree(old, ignore_errors=True)


def check_replaceable(out: Path, what: str = "a folder symkin wrote") -> list[str]:
    """What a user added to folder ``out`` since symkin wrote it (files, links and empty folders,
    as relative paths), or InputError if symkin must not replace it: it is not empty and has no
    valid manifest (:data:`MANIFEST`), or a file symkin wrote there was changed since.

    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as d:
    ...     _ = (Path(d) / "report.txt").write_text("symkin's")
    ...     write_manifest(Path(d), "0.2")
    ...     _ = (Path(d) / "notes.txt").write_text("mine")
    ...     check_replaceable(Path(d))
    ['notes.txt']
    >>> with tempfile.TemporaryDirectory() as d:
    ...     _ = (Path(d) / "thesis.tex").write_text("years of work")
    ...     check_replaceable(Path(d), "a symkin report")
    Traceback (most recent call last):
    ...
    symkin.errors.InputError: --out ... is not a symkin report (it has no .symkin-manifest.json, the list of the files symkin wrote there) and symkin replaces the whole folder; choose a new or empty folder
    """
    folder = Path(out)
    files, folders = _entries(folder)
    manifest = _read_manifest(folder)
    if manifest is None:
        if not files and not folders and not (folder / MANIFEST).exists():
            return []  # an empty folder
        raise InputError(
            f"--out {out} is not {what} (it has no {MANIFEST}, the list of the files symkin wrote there) and symkin "
            "replaces the whole folder; choose a new or empty folder"
        )
    changed = [f for f in files if f in manifest and _hash(folder / f) != manifest[f]]
    if changed:
        raise InputError(
            f"--out {out}: {_names(changed)} changed since symkin wrote them and would be replaced; "
            "move them out of the folder (or delete them), or choose another --out"
        )
    added = [f for f in files if f not in manifest]
    needed = {p.as_posix() for f in [*manifest, *added] for p in Path(f).parents}
    return sorted(added + [d for d in folders if d not in needed])
