"""The one output policy of every file seahelm writes (the CLI's and the library's savers).

A file a user asked for (``--out``, ``-o``, ``--plot``, ``SimResult.to_netcdf(path)``) is
written by :func:`write_output`, which applies :func:`check_output` and then
:func:`atomic_write`:

- an output is never a file the command reads: not the same path, not a symbolic link to it,
  not a hard link to it (the same file under another name);
- a path given with a trailing slash (``-o kv.toml/``) names a directory, never a file;
- an existing file is replaced without ``force`` only when it is a generated output of this
  kind that seahelm wrote (the output of an earlier run: a result over a result, a figure over
  its figure, a report over a report, :data:`KINDS`); anything else needs ``force``
  (``--force``): a user's own file, a file of another kind (a TOML over a NetCDF result, HTML
  over a ship file), and any TOML file -- ship files and scenarios are made to be edited, so
  one seahelm wrote may hold a user's changes since. Even with ``force`` a file the command
  reads is never replaced;
- the file is written to a temporary file in its directory and renamed onto its name
  (nothing half-written is left, also on a full disk or a signal); a new file gets the
  permissions the umask gives (``0666 & ~umask``), a replaced one keeps its mode; an
  ``OSError`` (a full disk, no permission) names the path asked for, not the temporary file.

Below everything but :mod:`seahelm.errors` (imports nothing else of the package), so that
ship files (:mod:`seahelm.ships`), results, figures and reports all use it.
"""

from __future__ import annotations

import contextlib
import contextvars
import os
import re
import stat
import tempfile
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass
from pathlib import Path

from .errors import ParameterError

__all__ = ["FIGURE_METADATA", "KINDS", "REPORT_OF_META", "WRITTEN_BY_ATTR", "FileKind",
           "OutputExistsError", "approved_outputs", "atomic_write", "check_output",
           "describe_file", "kind_for_suffix", "report_owner", "write_output", "write_together",
           "written_by_line"]

#: Inside :func:`approved_outputs`: the existing files a check with ``force`` approved, so that
#: the writer called later (``SimResult.to_netcdf(path)``, without ``force``) replaces them.
_APPROVED: "contextvars.ContextVar[set[Path] | None]" = contextvars.ContextVar(
    "seahelm_approved_outputs", default=None)


@contextlib.contextmanager
def approved_outputs() -> Iterator[None]:
    """A command's scope: an existing file :func:`check_output` approved with ``force`` at the
    start (before any work) may be replaced by the savers the command calls later, which do
    not take ``force`` through every layer; the approval ends with the block (the CLI wraps
    each command in one).

    Yields
    ------
    None
    """
    token = _APPROVED.set(set())
    try:
        yield
    finally:
        _APPROVED.reset(token)


class OutputExistsError(ParameterError):
    """An output path is an existing file that may not be replaced without ``force``."""


_HDF5 = b"\x89HDF\r\n\x1a\n"


def _head(path: Path, n: int = 4096) -> bytes:
    try:
        with path.open("rb") as fh:
            return fh.read(n)
    except OSError:
        return b""


def _tail(path: Path, n: int = 4096) -> bytes:
    try:
        with path.open("rb") as fh:
            fh.seek(max(0, path.stat().st_size - n))
            return fh.read(n)
    except OSError:
        return b""


#: The attribute of a NetCDF file, and the comment line of a TOML file, naming the command
#: that wrote it (``seahelm waves sample``): its own output, which it replaces again.
WRITTEN_BY_ATTR = "seahelm_written_by"


def written_by_line(command: str) -> str:
    """The comment line that marks a TOML file as ``command``'s output.

    Parameters
    ----------
    command : str
        As a user types it (``"seahelm ship scale"``).

    Returns
    -------
    str
    """
    return f"# written by {command}\n"


def _seahelm_netcdf(path: Path, command: str | None = None) -> bool:
    if not _head(path, 8).startswith(_HDF5):
        return False
    try:
        import h5py

        with h5py.File(path, "r") as fh:
            if command is not None:
                by = fh.attrs.get(WRITTEN_BY_ATTR)
                return (by.decode() if isinstance(by, bytes) else str(by)) == command
            return any(str(k).startswith("seahelm") for k in fh.attrs)
    except Exception:  # noqa: BLE001 - unreadable is not ours
        return False


def _seahelm_text(path: Path, command: str | None = None) -> bool:
    """A text file whose first line is seahelm's comment (``# seahelm ship file``, ``# seahelm
    autopilot tune ...``, ``# seahelm RAO table``); with ``command``, one that command wrote
    (its :func:`written_by_line`)."""
    if not _head(path, 64).startswith(b"# seahelm"):
        return False
    if command is None:
        return True
    try:
        return written_by_line(command) in path.read_text(encoding="utf-8", errors="replace")
    except OSError:
        return False


#: The meta element of a seahelm report naming the result files it is the report of
#: (:func:`report_owner`): ``seahelm report b.nc`` does not replace the report of ``a.nc``.
REPORT_OF_META = "seahelm-report-of"


_REPORT_OF = "report of "


def report_owner(sources: Iterable[str | os.PathLike[str]]) -> str:
    """What a report is the report of, as its :data:`REPORT_OF_META` element records it: the
    names of the result files read, sorted (``"report of a-runs.nc b-metrics.nc"``); given
    to :func:`check_output` as the ``command`` of an HTML report.

    Parameters
    ----------
    sources : iterable of path
        The files the report was made from.

    Returns
    -------
    str
    """
    return _REPORT_OF + " ".join(sorted(Path(s).name for s in sources))


def _seahelm_html(path: Path, command: str | None = None) -> bool:
    """A seahelm report; with ``command`` a :func:`report_owner`, the report of those same
    files (a report from before the page named its files is a report of any; any other
    ``command``, the CLI's name, says nothing of an HTML report)."""
    head = _head(path).lower()
    if not (head.lstrip().startswith(b"<!doctype html") and (
            b'name="generator" content="seahelm' in head
            or b"<footer>written by seahelm" in _tail(path))):
        return False
    if command is None or not command.startswith(_REPORT_OF):
        return True
    import html as _html

    found = re.search(rb'<meta name="' + REPORT_OF_META.encode() + rb'" content="([^"]*)"',
                      _head(path))
    return found is None or _REPORT_OF + _html.unescape(
        found.group(1).decode("utf-8", "replace")) == command


#: The metadata :func:`seahelm.plotting.save.save_figure` writes into a figure, by format
#: (the formats whose writer takes none are recognised by nothing, so need ``force``).
FIGURE_METADATA = {"png": "Software", "pdf": "Creator", "svg": "Creator", "eps": "Creator",
                   "ps": "Creator"}


def _figure(path: Path, command: str | None = None) -> bool:
    """A figure seahelm wrote: a PNG, PDF, SVG or PostScript file with seahelm's name in its
    metadata (:data:`FIGURE_METADATA`: the PNG/SVG/EPS header, the PDF trailer)."""
    head = _head(path, 65536)
    if not head.startswith((b"\x89PNG", b"%PDF", b"%!PS", b"<?xml", b"<svg")):
        return False
    return b"seahelm" in head or b"seahelm" in _tail(path, 65536)


def _seahelm_json(path: Path, command: str | None = None) -> bool:
    """A JSON object seahelm wrote: a key naming seahelm, or ``seahelm imo``'s report (its
    ship and criteria)."""
    head = _head(path, 65536)
    return head.lstrip().startswith(b"{") and (
        b'"seahelm' in head or (b'"ship":' in head and b'"criteria":' in head))


def _seahelm_csv(path: Path, command: str | None = None) -> bool:
    """seahelm's CSV tables: a ``# seahelm`` comment first, a result's long format (its
    header starts with the run and time columns), or a samples file (its header, after the
    comments, names key paths: ``vessel.params.N_v,...``)."""
    if _seahelm_text(path) or _head(path, 64).startswith(b"run,time"):
        return True
    import re

    lines = [ln for ln in _head(path).decode("utf-8", "replace").splitlines()
             if ln.strip() and not ln.startswith("#")]
    key = re.compile(r"[A-Za-z_]\w*(\.[A-Za-z_]\w*|\[\d+\])+")
    return bool(lines) and all(key.fullmatch(k.strip()) for k in lines[0].split(","))


def _seahelm_fmu(path: Path, command: str | None = None) -> bool:
    """An FMU seahelm wrote (``seahelm fmu``): a zip archive whose model description names
    seahelm as its author."""
    import zipfile

    try:
        with zipfile.ZipFile(path) as fmu:
            head = fmu.read("modelDescription.xml")[:4096]
    except (OSError, KeyError, zipfile.BadZipFile):
        return False
    return b'author="seahelm"' in head


@dataclass(frozen=True)
class FileKind:
    """What a writer writes, and how to tell that an existing file is seahelm's of that kind.

    Attributes
    ----------
    name : str
        Registry key (``"netcdf"``).
    description : str
        For messages ("a NetCDF result").
    written_by_seahelm : callable(pathlib.Path, str or None) -> bool
        Whether an existing file is one seahelm wrote of this kind (given a command, one that
        command wrote, where the kind records it: TOML and NetCDF).
    edited : bool
        Files of this kind are made to be edited (ship files, scenarios): one seahelm wrote is
        still replaced only with ``force``.
    """

    name: str
    description: str
    written_by_seahelm: Callable[[Path, str | None], bool]
    edited: bool = False


#: The kinds of file seahelm writes (the registry of :func:`check_output`'s ``kind``).
KINDS: dict[str, FileKind] = {k.name: k for k in (
    FileKind("netcdf", "a NetCDF file", _seahelm_netcdf),
    FileKind("toml", "a TOML file", _seahelm_text, edited=True),
    FileKind("html", "an HTML report", _seahelm_html),
    FileKind("figure", "a figure", _figure),
    FileKind("json", "a JSON file", _seahelm_json),
    FileKind("csv", "a CSV table", _seahelm_csv),
    FileKind("fmu", "an FMU", _seahelm_fmu),
)}

_SUFFIX_KINDS = {".nc": "netcdf", ".h5": "netcdf", ".toml": "toml", ".html": "html",
                 ".htm": "html", ".json": "json", ".csv": "csv", ".fmu": "fmu"}


def kind_for_suffix(path: str | os.PathLike[str]) -> str:
    """The kind of a file seahelm writes at a name of its own choosing, by its suffix (any
    suffix not listed is a figure: ``.png``, ``.pdf``, ``.svg``).

    Parameters
    ----------
    path : str or os.PathLike

    Returns
    -------
    str
        A key of :data:`KINDS`.
    """
    return _SUFFIX_KINDS.get(Path(path).suffix.lower(), "figure")


def describe_file(path: str | os.PathLike[str]) -> str:
    """What an existing file looks like, for a message ("a NetCDF/HDF5 file", "a seahelm ship
    file", "an HTML file", "a file").

    Parameters
    ----------
    path : str or os.PathLike

    Returns
    -------
    str
    """
    p = Path(path)
    head = _head(p, 256)
    if head.startswith(_HDF5) and _seahelm_netcdf(p):
        return "a seahelm NetCDF file"
    if head.startswith(_HDF5) or head.startswith(b"CDF"):
        return "a NetCDF/HDF5 file"
    if head.startswith(b"# seahelm ship file"):
        return "a seahelm ship file"
    if head.startswith(b"# seahelm"):
        return "a seahelm " + ("scenario" if p.suffix == ".toml" else "file")
    if head.lower().lstrip().startswith((b"<!doctype html", b"<html")):
        return "an HTML file"
    if head.startswith(b"\x89PNG"):
        return "a PNG image"
    if head.startswith(b"%PDF"):
        return "a PDF file"
    return "a file"


def _same_file(a: Path, b: Path) -> bool:
    try:
        return os.path.samefile(a, b)
    except OSError:
        return False


def check_output(path: str | os.PathLike[str], kind: str, *, reads: Iterable[
        str | os.PathLike[str]] = (), force: bool = False, option: str | None = None,
        force_word: str = "force=True", replace_own: bool = True,
        command: str | None = None) -> Path:
    """Whether ``path`` may be written as a file of ``kind``; returns it as a Path.

    Parameters
    ----------
    path : str or os.PathLike
        The output asked for (a str ending in ``/`` names a directory).
    kind : str
        What is written: a key of :data:`KINDS`.
    reads : iterable of path-like, optional
        The files (and directories) the command reads: never written, whatever ``force``.
    force : bool, optional
        Replace an existing file that is not seahelm's output of this kind (default False).
    option : str, optional
        How the caller names the output in messages (``"--out"``; default ``"path"``).
    force_word : str, optional
        How the caller says ``force`` (``"--force"``; default ``"force=True"``).
    replace_own : bool, optional
        Whether seahelm's own earlier output of this kind is replaced without ``force``
        (default True; :func:`seahelm.ships.write_ship` keeps its ``overwrite`` rule).
    command : str, optional
        The command writing (``"seahelm ship scale"``): an existing TOML or NetCDF file is
        its own earlier output only if that command wrote it (:data:`WRITTEN_BY_ATTR`,
        :func:`written_by_line`), not another command's ship file or result.

    Returns
    -------
    pathlib.Path

    Raises
    ------
    ParameterError
        ``kind`` unknown; ``path`` is a file the command reads (also through a symbolic or a
        hard link, or as the directory it is in), ends with a slash, is a directory, a
        symbolic link, or not a regular file.
    OutputExistsError
        ``path`` exists and may be replaced only with ``force``; the message says what it is.
    """
    if kind not in KINDS:
        raise ParameterError(f"must be one of {', '.join(KINDS)}, got {kind!r}", field="kind")
    name = f"`{option or 'path'}` {os.fspath(path)}"
    raw = os.fspath(path)
    target = Path(raw)
    if raw.endswith(("/", os.sep)):
        what = "a file" if target.is_file() else ("a directory" if target.is_dir()
                                                  else "not there")
        raise ParameterError(f"{name} ends with '/', the name of a directory, but a file is "
                             f"written here ({target} is {what}); give the file's name "
                             "without the slash")
    try:
        resolved = target.resolve()
    except RuntimeError:  # (Python's word for a symbolic-link loop)
        raise ParameterError(f"{name} is a loop of symbolic links") from None
    for read in reads:
        r = Path(read)
        if resolved == r.resolve() or (target.exists() and _same_file(target, r)):
            same = "" if r == target else f" ({r})"
            raise ParameterError(f"{name} is a file this command reads{same}: writing it "
                                 "would destroy it; choose another path")
        if r.is_dir() and r.resolve() in resolved.parents:
            raise ParameterError(f"{name} is inside {r}, which this command reads: writing "
                                 "there would corrupt it; choose a path outside it")
    if target.is_dir():
        raise ParameterError(f"{name} is a directory; give a file name")
    if target.is_symlink():
        raise ParameterError(f"{name} is a symbolic link (to {os.readlink(target)}): the file "
                             "written would replace the link; give the path of the file itself")
    if not target.exists():
        return target
    if not target.is_file():
        raise ParameterError(f"{name} is not a regular file (a device, a FIFO or a socket): "
                             "writing it would replace it; choose a file path")
    approved = _APPROVED.get()
    if force:
        if approved is not None:
            approved.add(resolved)
        return target
    if approved is not None and resolved in approved:
        return target
    spec = KINDS[kind]
    if replace_own and not spec.edited and spec.written_by_seahelm(target, command):
        return target  # seahelm's own output of an earlier run
    found = describe_file(target)
    if found == "a file":
        found = "a file seahelm did not write"
    elif spec.edited and spec.written_by_seahelm(target, None):  # (its own kind: TOML)
        found += ", perhaps edited since"
    elif found.startswith("a seahelm") and command is not None and kind == "netcdf":
        found += f" not written by `{command}`"
    elif kind == "html" and command is not None and command.startswith(_REPORT_OF):
        found = f"a seahelm report of other files, not the {command}"
    raise OutputExistsError(
        f"{name} exists ({found}); this writes {spec.description} there: pass {force_word} "
        "to replace it, or choose another path")


_TOGETHER: "contextvars.ContextVar[list[tuple[str, Path]] | None]" = contextvars.ContextVar(
    "seahelm_write_together", default=None)


@contextlib.contextmanager
def write_together() -> Iterator[None]:
    """Files written inside the block (:func:`atomic_write`) appear together or not at all.

    Each is written to its temporary file as usual; they are renamed onto their names only
    when the block ends without an error. On an error (a full disk at the third file) every
    temporary file is removed and none of the files appears: a manoeuvre's metrics never
    stand without its runs.

    Yields
    ------
    None
    """
    if _TOGETHER.get() is not None:  # (nested: the outer set decides)
        yield
        return
    pending: list[tuple[str, Path]] = []
    token = _TOGETHER.set(pending)
    try:
        yield
    except BaseException:
        for tmp, _ in pending:
            with contextlib.suppress(OSError):
                os.unlink(tmp)
        raise
    finally:
        _TOGETHER.reset(token)
    for tmp, path in pending:
        os.replace(tmp, path)


def _mode_for(path: Path) -> int:
    """An existing file's permission bits (kept when it is replaced), else what the umask
    gives a new file."""
    try:
        st = path.stat()
        if stat.S_ISREG(st.st_mode):
            return stat.S_IMODE(st.st_mode)
    except OSError:
        pass
    umask = os.umask(0)
    os.umask(umask)
    return 0o666 & ~umask


def atomic_write(path: str | os.PathLike[str], writer: Callable[[str], None]) -> Path:
    """Call ``writer(tmp_path)`` then rename the temporary file onto ``path``.

    No policy check (:func:`write_output` makes it first); the file keeps an existing file's
    mode, or gets the umask's.

    Parameters
    ----------
    path : str or os.PathLike
        Destination file (parent directories are created).
    writer : callable(str)
        Writes the content to the temporary path it is given.

    Returns
    -------
    pathlib.Path
        ``path``.

    Raises
    ------
    OSError
        Of the writer or the rename (a full disk, no permission), naming ``path``.
    """
    path = Path(path)
    tmp = None
    together = _TOGETHER.get()
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
        os.close(fd)
        writer(tmp)
        # mkstemp creates the file private (0600): give it the mode of the file it replaces,
        # or the permissions a plain open() would
        os.chmod(tmp, _mode_for(path))
        if together is not None:  # renamed with the others of its set (write_together)
            together.append((tmp, path))
            return path
        os.replace(tmp, path)
    except OSError as exc:
        if tmp is not None and os.path.exists(tmp):
            os.unlink(tmp)
        if exc.errno is None:
            raise
        # said about the file the user asked for, not the temporary one
        raise OSError(exc.errno, exc.strerror or os.strerror(exc.errno), str(path)) from exc
    except BaseException:
        if tmp is not None and os.path.exists(tmp):
            os.unlink(tmp)
        raise
    return path


def write_output(path: str | os.PathLike[str], writer: Callable[[str], None], kind: str, *,
                 reads: Iterable[str | os.PathLike[str]] = (), force: bool = False,
                 option: str | None = None, force_word: str = "force=True",
                 replace_own: bool = True, command: str | None = None) -> Path:
    """Write a file a user asked for: :func:`check_output`, then :func:`atomic_write`.

    Parameters
    ----------
    path, kind, reads, force, option, force_word, replace_own, command : see check_output
        As for :func:`check_output`.
    writer : callable(str)
        Writes the content to the temporary path it is given.

    Returns
    -------
    pathlib.Path
        The file written.

    Raises
    ------
    ParameterError, OutputExistsError
        See :func:`check_output`.
    OSError
        Writing failed (a full disk, no permission); it names ``path``.
    """
    target = check_output(path, kind, reads=reads, force=force, option=option,
                          force_word=force_word, replace_own=replace_own, command=command)
    return atomic_write(target, writer)

