"""Output folders and files partgen writes, and the rules that keep a user's files safe.

A folder is partgen's when it carries partgen's marker (``.partgen``, JSON: the kind of output
and the files partgen wrote into it), or is a kit written by an earlier partgen (a
``manifest.json`` with ``design`` and ``parts``, holding only kit files). partgen replaces only
such a folder, an empty one, or a folder that does not exist yet; anything else — a file, a folder
with a user's files in it, the current folder, a folder holding the design or printer file — is
refused before any work is written (``OptionError``: exit 2).

Writing is all or nothing: the output is made in a temporary folder beside the destination
(``.<name>.tmp-<pid>-<random>``), then swapped in under a lock on the parent folder (one
``renameat2(RENAME_EXCHANGE)`` where Linux has it), so the destination is always either the old
output or the whole new one. A rebuild that writes exactly what is there already changes
nothing (the folder's plates/, trace/ and report/ stay); a rebuild that changes a kit removes
those derived folders and says so. Temporary folders of a process that died (SIGKILL) are
cleaned up by the next run that writes beside them.
"""

from __future__ import annotations

import contextlib
import ctypes
import errno
import json
import os
import re
import shutil
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

from .. import __version__
from ..errors import OptionError

__all__ = ["MARKER", "KIT_DERIVED", "OutputClaim", "claim_output", "read_marker", "atomic_dir", "open_incremental", "check_text_target",
           "write_text_file", "is_partgen_kit"]

MARKER = ".partgen"
KIT_DERIVED = ("plates", "trace", "report", "tolerance")  # outputs that live inside a kit folder and derive from it
# file names an earlier partgen (before the marker) wrote into each kind of folder
_LEGACY = {
    "kit": re.compile(r"^(.+\.stl|manifest\.json|assembly\.glb|design\.yaml|printer\.yaml)$"),
    "plates": re.compile(r"^(plate\d+\.3mf|plates\.png)$"),
    "trace": re.compile(r"^trace\.(png|svg|gif)$"),
    "report": re.compile(r"^index\.html$"),
    "tolerance": re.compile(r"^(chunks\.jsonl|result\.json)$"),
    "sweep": re.compile(r"^(points\.(csv|jsonl)|index\.html)$"),
    "coupon": re.compile(r"^(.+\.stl|coupon\.(3mf|png)|instructions\.html|results\.yaml)$"),
}
_TEMP = re.compile(r"^\.(?P<name>.+)\.(?P<what>tmp|old)-(?P<pid>\d+)(-[A-Za-z0-9_]+)?$")


def read_marker(folder: Path) -> dict | None:
    """The marker of a partgen output folder, or None."""
    try:
        data = json.loads((folder / MARKER).read_text(encoding="utf-8"))
    except (OSError, ValueError, UnicodeDecodeError):
        return None
    return data if isinstance(data, dict) and data.get("generator") == "partgen" else None


def is_partgen_kit(folder: Path) -> bool:
    """A kit folder partgen wrote (marked, or an earlier partgen's manifest)."""
    return _kind_of(Path(folder)) == "kit"


def _kind_of(folder: Path) -> str | None:
    marker = read_marker(folder)
    if marker is not None:
        return marker.get("output")
    try:
        man = json.loads((folder / "manifest.json").read_text(encoding="utf-8"))
        if isinstance(man, dict) and "design" in man and "parts" in man:
            return "kit"
    except (OSError, ValueError, UnicodeDecodeError):
        pass
    return None


def _foreign(folder: Path, kind: str) -> list[str]:
    """Entries of a partgen folder of ``kind`` that partgen did not write (sorted); [] if none."""
    marker = read_marker(folder)
    listed = marker.get("files") if marker else None
    listed = set(listed) if isinstance(listed, list) else None
    out = []
    for entry in sorted(os.listdir(folder)):
        p = folder / entry
        if entry == MARKER and marker is not None:
            continue
        if p.is_symlink():
            out.append(entry)
        elif p.is_dir():
            if kind == "kit" and entry in KIT_DERIVED and _kind_of(p) in (entry, None):
                out += [f"{entry}/{x}" for x in _foreign(p, entry)]  # name the user's files inside it
            elif not (kind == "kit" and entry in KIT_DERIVED and _derived_ok(p, entry)):
                out.append(entry + "/")
        elif not (entry in listed if listed is not None else _LEGACY[kind].match(entry)):
            out.append(entry)
    return out


def _derived_ok(folder: Path, kind: str) -> bool:
    """``folder`` (inside a kit) is a ``kind`` output partgen wrote: marked, or an earlier partgen's
    (only the file names it writes), or empty."""
    found = _kind_of(folder)
    return found in (kind, None) and not _foreign(folder, kind)


def _within(a: Path, b: Path) -> bool:
    """a is b or lies inside b (both resolved)."""
    return a == b or b in a.parents


@dataclass
class OutputClaim:
    """A destination checked for writing ``kind`` into it; ``with claim as tmp:`` writes it.

    ``notes`` collects what the swap did beyond writing (stale derived folders removed, an
    unchanged output kept), one line each, for the CLI to print."""

    dest: Path
    kind: str
    option: str
    protect: tuple[Path, ...] = ()
    notify: object = None  # called with each note as it happens (the CLI prints them)
    notes: list[str] = field(default_factory=list)
    changed: bool = True
    source: str | None = None  # a kit's: the digest of the design it was built from (recorded in its marker)

    def __post_init__(self):
        self.dest = Path(self.dest)
        self.check()

    # -- the rules ---------------------------------------------------------------------------
    def _refuse(self, problem: str) -> OptionError:
        return OptionError(self.option, str(self.dest), problem)

    def check(self) -> None:
        """Raise OptionError unless partgen may replace (or create) ``dest`` with a ``kind`` output."""
        dest = self.dest
        if dest.name in ("", ".", "..") or str(dest) in (".", ".."):
            raise self._refuse("is the current folder or its parent, not a folder partgen made: name a new folder")
        if len(dest.name) > 200:
            raise self._refuse("the folder name is too long")
        try:
            res = dest.resolve()
            cwd = Path.cwd().resolve()
        except (OSError, RuntimeError) as e:
            raise self._refuse(f"cannot be resolved: {e.strerror if isinstance(e, OSError) else e}") from None
        if _within(cwd, res):
            raise self._refuse("is the current folder or holds it: partgen writes only into folders it made")
        for p in self.protect:
            pr = Path(p).resolve()
            if _within(pr, res):
                raise self._refuse(f"holds {p}, which partgen reads: write the output into another folder")
        if dest.is_symlink():
            raise self._refuse("is a symbolic link: give the folder itself")
        if dest.exists() and not dest.is_dir():
            raise self._refuse("is a file, not a folder: partgen never replaces a file with an output folder")
        anc = dest.parent
        while not anc.exists():
            if anc.is_symlink():
                raise self._refuse(f"{anc} is a broken symbolic link")
            anc = anc.parent
        if not anc.is_dir():
            raise self._refuse(f"{anc} is a file, not a folder")
        if not os.access(anc, os.W_OK | os.X_OK):
            raise self._refuse(f"cannot write into {anc}: permission denied")
        if dest.is_dir():
            try:
                entries = os.listdir(dest)
            except OSError as e:
                raise self._refuse(f"cannot be read: {e.strerror}") from None
            if not entries:
                return
            found = _kind_of(dest)
            if found is None:
                if self.kind == "kit" and all(e in KIT_DERIVED and (dest / e).is_dir() and _kind_of(dest / e) == e
                                              and _derived_ok(dest / e, e) for e in entries):
                    return  # only plates/trace/report partgen wrote before the kit was built
                if self.kind in KIT_DERIVED and dest.name == self.kind and is_partgen_kit(dest.parent) \
                        and _derived_ok(dest, self.kind):
                    return  # an earlier partgen's plates/trace/report inside its kit
                shown = ", ".join(sorted(entries)[:3]) + (" …" if len(entries) > 3 else "")
                raise self._refuse(f"is a folder partgen did not make (it holds {shown}): partgen replaces only "
                                   "its own outputs; name a new or empty folder")
            if found != self.kind:
                raise self._refuse(f"holds a partgen {found}, not a {self.kind}: name another folder")
            foreign = _foreign(dest, self.kind)
            if foreign:
                shown = ", ".join(foreign[:3]) + (" …" if len(foreign) > 3 else "")
                raise self._refuse(f"holds {shown}, which partgen did not write: move it out first (partgen never "
                                   "deletes what it did not write)")
            if not os.access(dest, os.W_OK | os.X_OK):
                raise self._refuse("permission denied")

    # -- writing -----------------------------------------------------------------------------
    def __enter__(self) -> Path:
        parent = self.dest.parent
        parent.mkdir(parents=True, exist_ok=True)
        _clean_stale(parent, self.dest.name)
        self.tmp = Path(tempfile.mkdtemp(prefix=f".{self.dest.name}.tmp-{os.getpid()}-", dir=parent))
        umask = os.umask(0)  # mkdtemp makes 0700; give the output the mode a plain mkdir would
        os.umask(umask)
        os.chmod(self.tmp, 0o777 & ~umask)
        return self.tmp

    def __exit__(self, exc_type, exc, tb):
        if exc_type is not None:
            shutil.rmtree(self.tmp, ignore_errors=True)
            return False
        try:
            files = sorted(os.listdir(self.tmp))
            _write_json(self.tmp / MARKER, {"generator": "partgen", "version": __version__, "output": self.kind,
                                            "files": files, **({"source": self.source} if self.source else {})})
            with _locked(self.dest.parent):
                self.check()  # again, under the lock: another process may have written meanwhile
                self._swap()
        except BaseException:
            shutil.rmtree(self.tmp, ignore_errors=True)
            raise
        return False

    def _swap(self) -> None:
        dest, tmp = self.dest, self.tmp
        if not dest.exists():
            os.rename(tmp, dest)
            return
        if _same_content(tmp, dest):
            self.changed = False
            if read_marker(dest) is None or read_marker(dest) != read_marker(tmp):
                os.replace(tmp / MARKER, dest / MARKER)  # an earlier partgen's kit gets its marker
            shutil.rmtree(tmp, ignore_errors=True)
            return
        derived = [e for e in KIT_DERIVED if (dest / e).is_dir()] if self.kind == "kit" else []
        if _exchange(tmp, dest):
            shutil.rmtree(tmp, ignore_errors=True)  # tmp now holds the old output
        else:  # no atomic exchange here: move aside, move in, remove
            old = dest.parent / f".{dest.name}.old-{os.getpid()}"
            os.rename(dest, old)
            os.rename(tmp, dest)
            shutil.rmtree(old, ignore_errors=True)
        if derived:
            self._note(f"removed {', '.join(d + '/' for d in derived)} from {dest}: made from the previous kit, "
                       "which this build changed")

    def _note(self, text: str) -> None:
        self.notes.append(text)
        if callable(self.notify):
            self.notify(text)


def claim_output(dest: str | Path, kind: str, option: str = "-o", protect=(), notify=None,
                 source: str | None = None) -> OutputClaim:
    """Check ``dest`` for a ``kind`` output ("kit", "plates", "trace", "report") before any work;
    ``with`` the result to write it. ``protect``: files partgen reads (the design, the printer);
    ``notify(line)`` hears what the swap did besides writing (stale folders removed); ``source``: what
    the output was made from (a kit's design digest), kept in its marker."""
    return OutputClaim(Path(dest), kind, option, tuple(Path(p) for p in protect), notify, source=source)


def open_incremental(claim: OutputClaim, files: list[str], keep: bool = False) -> Path:
    """Make ``claim.dest`` (checked already) a folder written *as results arrive* rather than
    swapped in whole: it carries the marker listing ``files`` from the start, so an interrupted run
    leaves a folder partgen knows is its own and a later run may continue (``keep``: leave the
    files already there) or replace (the listed files removed first)."""
    dest = claim.dest
    with _locked(dest.parent) if dest.parent.exists() else contextlib.nullcontext():
        claim.check()
        dest.mkdir(parents=True, exist_ok=True)
        if not keep:
            for name in files:
                with contextlib.suppress(FileNotFoundError):
                    (dest / name).unlink()
        _write_json(dest / MARKER, {"generator": "partgen", "version": __version__, "output": claim.kind,
                                    "files": sorted(files)})
    return dest


def atomic_dir(dest, kind: str = "kit", option: str = "-o", protect=(), notify=None) -> OutputClaim:
    """``with atomic_dir(dest) as tmp:`` — write into tmp; dest becomes tmp's content on success.
    ``dest`` may be a path or an ``OutputClaim`` made earlier (checked before the work began)."""
    if isinstance(dest, OutputClaim):
        return dest
    return claim_output(dest, kind, option, protect, notify)


def check_text_target(path: str | Path, option: str, signature: str, protect=()) -> Path:
    """Raise OptionError unless partgen may write the text file ``path``: a new file in an existing
    folder, or a file partgen wrote before (it starts with ``signature``); never a folder, a
    protected file (the design) or a user's file."""
    path = Path(path)
    try:
        res = path.resolve()
    except (OSError, RuntimeError) as e:
        raise OptionError(option, str(path), f"cannot be resolved: {e}") from None
    if any(res == Path(p).resolve() for p in protect):
        raise OptionError(option, str(path), "is a file partgen reads: write to another file")
    if path.is_dir():
        raise OptionError(option, str(path), "is a folder: give a file name")
    if not path.parent.is_dir():
        raise OptionError(option, str(path), f"no such folder: {path.parent}")
    if path.exists() or path.is_symlink():
        try:
            with open(path, encoding="utf-8", errors="replace") as f:
                head = f.read(len(signature))
        except OSError as e:
            raise OptionError(option, str(path), f"cannot be read: {e.strerror}") from None
        if path.is_symlink() or not path.is_file() or head != signature:
            raise OptionError(option, str(path), "exists and is not a file partgen wrote: partgen never overwrites "
                              "a user's file; give a new file name")
    if not os.access(path.parent, os.W_OK | os.X_OK):
        raise OptionError(option, str(path), f"cannot write into {path.parent}: permission denied")
    return path


def write_text_file(path: str | Path, text: str, option: str, protect=()) -> None:
    """Write a text output file atomically (``text`` starts with its signature, see
    ``check_text_target``, which is applied again here)."""
    path = check_text_target(path, option, text.split("\n", 1)[0] + "\n", protect)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.tmp-{os.getpid()}-", dir=path.parent)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write(text)
        os.chmod(tmp, 0o666 & ~_umask())
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


def _umask() -> int:
    m = os.umask(0)
    os.umask(m)
    return m


def _write_json(path: Path, data: dict) -> None:
    path.write_text(json.dumps(data, indent=1, allow_nan=False) + "\n", encoding="utf-8")


def _same_content(new: Path, old: Path) -> bool:
    """``old`` holds exactly ``new``'s files with the same bytes (the marker and derived folders aside)."""
    names = {e for e in os.listdir(new) if e != MARKER}
    have = {e for e in os.listdir(old) if e != MARKER and not (old / e).is_dir()}
    if names != have:
        return False
    for n in names:
        a, b = new / n, old / n
        if a.is_dir() or b.is_dir() or a.stat().st_size != b.stat().st_size or a.read_bytes() != b.read_bytes():
            return False
    return True


def _exchange(a: Path, b: Path) -> bool:
    """Swap two paths atomically (Linux renameat2 RENAME_EXCHANGE); False where unsupported."""
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        fn = libc.renameat2
    except (OSError, AttributeError):
        return False
    AT_FDCWD, RENAME_EXCHANGE = -100, 2
    fn.argtypes = [ctypes.c_int, ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p, ctypes.c_uint]
    if fn(AT_FDCWD, os.fsencode(a), AT_FDCWD, os.fsencode(b), RENAME_EXCHANGE) == 0:
        return True
    err = ctypes.get_errno()
    if err in (errno.EINVAL, errno.ENOSYS, errno.EOPNOTSUPP):
        return False
    raise OSError(err, os.strerror(err), str(b))


@contextlib.contextmanager
def _locked(folder: Path):
    """An exclusive lock on ``folder`` (flock on its descriptor: nothing is written) for the swap."""
    try:
        import fcntl
    except ImportError:  # not on POSIX: no lock
        yield
        return
    fd = os.open(folder, os.O_RDONLY)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)
        yield
    finally:
        os.close(fd)


def _alive(pid: int) -> bool:
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def _clean_stale(parent: Path, name: str) -> None:
    """Remove temporary folders beside ``name`` left by partgen processes that died; an
    ``.old-<pid>`` whose swap was cut short is put back if the output itself is missing."""
    with _locked(parent):
        for entry in os.listdir(parent):
            m = _TEMP.match(entry)
            if not m or m["name"] != name or _alive(int(m["pid"])):
                continue
            p = parent / entry
            if m["what"] == "old" and not (parent / name).exists() and p.is_dir():
                os.rename(p, parent / name)
            elif p.is_dir() and not p.is_symlink():
                shutil.rmtree(p, ignore_errors=True)
            else:
                with contextlib.suppress(OSError):
                    p.unlink()
