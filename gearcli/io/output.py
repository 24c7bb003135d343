"""Where a command's data goes: ``-o FILE``, ``-o -`` (stdout) or stdout, and in which format.

The one module that owns output files (docs/output.md, "Files"). Every command checks its ``-o`` with
:func:`check_output` *before* it computes anything, then writes with :func:`write_output`:

- ``-o -`` is stdout; no ``-o`` is stdout too.
- A symlink is written through: its target is replaced atomically and the link stays.
- A directory, a device, a FIFO or a socket is refused, as is a path ending in ``/``, a missing or
  unwritable parent directory, and the command's own input file (by inode, so ``./in.toml`` or a link
  to it count). Refusals are :class:`~gearcli.errors.OutputError` (exit 2, the path named), and nothing
  is created on disk.
- The suffix chooses the format (``.json``, ``.csv``, ``.md``, ``.txt``, ``.toml``); a suffix that
  contradicts ``--format``, or names a format the command cannot write, is an error. An unknown suffix
  takes ``--format`` or the command's default for files.

New commands reuse :func:`output_option` (the click option) and these two functions.
"""

from __future__ import annotations

import errno
import io
import os
import re
import stat
import sys
import tempfile
from collections.abc import Callable, Iterable
from pathlib import Path
from typing import TextIO, TypeVar

import click

from gearcli.core.records import record
from gearcli.core.text import shorten
from gearcli.errors import OutputError, StdoutClosed
from gearcli.io.atomic import write_atomic

F = TypeVar("F", bound=Callable[..., object])  # a click command function

STDOUT = "-"

#: What a suffix says about the format of the file's content.
SUFFIX_FORMAT = {".json": "json", ".csv": "csv", ".md": "markdown", ".markdown": "markdown", ".txt": "table",
                 ".toml": "toml",
                 # formats no command writes: named, so `-o out.xlsx` is refused rather than given CSV under that name
                 ".xlsx": "an Excel workbook", ".xls": "an Excel workbook", ".ods": "an OpenDocument spreadsheet",
                 ".parquet": "Parquet", ".h5": "HDF5", ".hdf5": "HDF5"}


@record
class OutputTarget:
    """A checked destination. ``path`` is the regular file to replace (a symlink's target), or None for
    stdout; ``shown`` is the path as the user typed it (for messages); ``fmt`` the chosen format."""

    fmt: str
    path: Path | None = None
    shown: str = STDOUT

    @property
    def is_stdout(self) -> bool:
        return self.path is None


def output_option(help_text: str = "Write to FILE atomically ('-' is stdout; the format follows the suffix).") \
        -> Callable[[F], F]:
    """The ``-o/--output`` click option every data command shares (a plain string: the checks are ours)."""
    return click.option("-o", "--output", type=str, metavar="FILE", help=help_text)


def _kind(mode: int, stdout_as: str = "-o -") -> str | None:
    if stat.S_ISREG(mode):
        return None
    if stat.S_ISDIR(mode):
        return "is a directory; give a file name"
    if stat.S_ISFIFO(mode):
        return f"is a FIFO, not a regular file (use {stdout_as} and a shell redirection)"
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        return f"is a device, not a regular file (use {stdout_as} and a shell redirection)"
    return "is not a regular file"


def _refuse(shown: str, message: str) -> OutputError:
    return OutputError(message, path=shorten(shown))


def _is_stdin(target: Path) -> bool:
    """``target`` is the file that standard input reads (``gearcli design - -o f.csv < f.csv``)."""
    try:
        st_in, st_out = os.fstat(0), os.stat(target)
    except (OSError, ValueError):
        return False
    return stat.S_ISREG(st_in.st_mode) and (st_in.st_dev, st_in.st_ino) == (st_out.st_dev, st_out.st_ino)


def _same_file(target: Path, inputs: Iterable[str | None]) -> bool:
    for given in inputs:
        if given == STDOUT:  # the input is stdin: compare what it reads by device and inode
            if _is_stdin(target):
                return True
            continue
        if not given:
            continue
        try:
            if os.path.samefile(target, given):
                return True
        except (OSError, ValueError):
            continue
    return False


def _opened(given: str) -> os.stat_result | None:
    """What a path whose real path names no file still opens: a link into /proc/self/fd (``/dev/stdout`` on a
    pipe resolves to ``pipe:[…]``, which is no file name, but the link opens the pipe); None for a new file."""
    try:
        return os.stat(given)
    except (OSError, ValueError):
        return None


_DESCRIPTOR = re.compile(r"/(?:proc/(?:self|thread-self|\d+)|dev)/fd/(\d+)")


def open_descriptor(given: str) -> int | None:
    """The descriptor of this process that ``given`` names (``/dev/stdout``, ``/dev/fd/1``, ``/proc/self/fd/1``
    and links to them), or None. Such a path is a stream the shell opened (``>> log``, ``| cmd``): replacing the
    file behind it would discard what the shell appends to, so descriptor 1 is stdout and the others are refused."""
    path = os.path.abspath(given)
    for _ in range(40):  # the kernel's own limit on a chain of links
        if (m := _DESCRIPTOR.fullmatch(path)) is not None and path.split("/")[2] in ("self", "thread-self", "fd",
                                                                                    str(os.getpid())):
            return int(m.group(1))
        try:
            link = os.readlink(path)
        except (OSError, ValueError):
            return None
        path = os.path.normpath(os.path.join(os.path.dirname(path), link))
    return None


def _check_given_parent(given: str) -> None:
    """Refuse a path whose directory part the system cannot walk: ``missing/../x.json`` or ``file/../x.json``.
    The kernel resolves ``..`` after the component before it (``open`` there fails with ENOENT or ENOTDIR, as a
    shell's ``>`` does), while ``realpath`` cancels the pair textually and would write ``./x.json``."""
    parent = os.path.dirname(given)
    if not parent:
        return
    try:
        os.stat(parent)
    except FileNotFoundError:
        raise _refuse(given, f"no such directory: {shorten(parent)}") from None
    except NotADirectoryError:
        raise _refuse(given, f"not a directory: {shorten(parent)} (a part of it is a file)") from None
    except (OSError, ValueError):  # other failures (permissions, loops) are reported by the checks that follow
        return


def resolve_path(given: str, inputs: Iterable[str | None] = (), stdout_as: str = "-o -") -> Path:
    """The regular file ``given`` names after symlinks, checked writable; :class:`OutputError` otherwise."""
    if not given:
        raise _refuse("''", "an empty file name; give a file name, or '-' for stdout")
    if "\0" in given:
        raise _refuse(repr(given), "not a valid file name")
    if (fd := open_descriptor(given)) is not None:
        raise _refuse(given, f"names this command's open descriptor {fd}, not a file (use {stdout_as} and a shell "
                             "redirection)")
    if given.endswith(("/", os.sep)) or given in (".", ".."):
        raise _refuse(given, "is a directory path; give a file name")
    _check_given_parent(given)
    target = Path(os.path.realpath(given))
    st: os.stat_result | None
    try:
        st = target.stat()
    except FileNotFoundError:
        st = _opened(given)
    except OSError as exc:
        raise _refuse(given, f"cannot write: {exc.strerror or exc}") from None
    if st is not None:
        if (why := _kind(st.st_mode, stdout_as)) is not None:
            raise _refuse(given, why)
        if _same_file(target, inputs):
            raise _refuse(given, "is the input file; writing it would destroy the input")
        if not os.access(target, os.W_OK):
            raise _refuse(given, "permission denied")
    parent = target.parent
    if not parent.is_dir():
        shown = Path(given).parent  # as given; a symlink's missing directory is its target's
        missing = f"{shorten(str(parent))} (the link's target)" if shown.is_dir() else shorten(str(shown))
        raise _refuse(given, f"no such directory: {missing}")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise _refuse(given, f"directory not writable: {shorten(str(Path(given).parent))}")
    try:  # access() passes for root, and on a filesystem that takes no new entries (/proc): the atomic write's
        # temporary file is made there, so try one now, not after the computing
        fd, probe = tempfile.mkstemp(prefix=".gearcli-probe-", dir=parent)
        os.close(fd)
        os.unlink(probe)
    except OSError as exc:
        raise _refuse(given, f"cannot write in {shorten(str(Path(given).parent) or '.')}: "
                             f"{exc.strerror or exc}") from None
    return target


def check_output(output: str | None, *, formats: tuple[str, ...], fmt: str | None = None,
                 inputs: Iterable[str | None] = (), file_default: str | None = None,
                 stdout_default: Callable[[], str] | None = None, stdout_as: str = "-o -") -> OutputTarget:
    """Check ``-o`` and choose the format, before any computation.

    ``formats``: what the command can write. ``fmt``: ``--format`` if given. ``file_default``: the format
    of a file whose suffix says nothing (default: the first of ``formats``). ``stdout_default``: the
    format for stdout without ``--format`` (default: ``file_default``). ``stdout_as``: how the command spells
    stdout, for the hint on a FIFO or device (``init`` takes FILE, not ``-o``: ``'-'``)."""
    file_default = file_default or formats[0]
    if output is None or output == STDOUT:
        if getattr(sys.stdout, "closed_stdout", False):  # `>&-`: say so now, not after the computing

            raise StdoutClosed()
        chosen = fmt or (stdout_default() if stdout_default else file_default)
        return OutputTarget(fmt=chosen)
    to_stdout = output != STDOUT and "\0" not in output and open_descriptor(output) == 1
    path = None if to_stdout else resolve_path(output, inputs, stdout_as)
    suffix = Path(output).suffix.lower()
    said = SUFFIX_FORMAT.get(suffix)
    if said is not None and said not in formats:
        raise _refuse(output, f"this command cannot write {said} ({suffix}); it writes {', '.join(formats)}")
    if said is not None and fmt is not None and fmt != said:
        raise _refuse(output, f"the suffix {suffix} says {said} but --format is {fmt}; make them agree")
    if to_stdout and getattr(sys.stdout, "closed_stdout", False):
        raise StdoutClosed()
    # /dev/stdout is the stream the shell opened (`>> log` appends to it): written as stdout, in a file's format
    return OutputTarget(fmt=fmt or said or file_default, path=path, shown=output)


def check_not_clobbering(paths: Iterable[Path], protected: Iterable[str | Path | None], option: str) -> None:
    """Refuse ``paths`` (files a command will write besides ``-o``, e.g. ``--plots``) that would replace a
    protected file (the input, the ``-o`` file), that are no regular file, or that are a symlink into a directory
    that does not exist (as :func:`resolve_path` refuses ``-o``: before the run, not after ``-o`` is written)."""
    for path in paths:
        real = os.path.realpath(path)
        for other in protected:
            if other is None or str(other) == STDOUT:
                continue
            if real == os.path.realpath(other) or _same_file(Path(real), [str(other)]):
                raise _refuse(str(path), f"{option} would overwrite {shorten(str(other))}; choose another directory")
        if os.path.islink(path) and not os.path.isdir(os.path.dirname(real)):  # a dangling link, as -o refuses it
            raise _refuse(str(path), f"no such directory: {shorten(os.path.dirname(real))} (the link's target)")
        if os.path.lexists(real):
            try:
                mode = os.stat(real).st_mode
            except OSError:
                continue
            if (why := _kind(mode)) is not None:
                raise _refuse(str(path), why)


def check_writable_dir(directory: str, option: str) -> None:
    """Refuse a directory (``--plots DIR``) that cannot be written, or created, before any computation: the
    directory itself when it exists, else the nearest existing parent it would be created in."""
    probe = Path(directory)
    try:
        while not probe.exists() and probe != probe.parent:
            probe = probe.parent
    except OSError as exc:  # a name the system refuses to look up (longer than NAME_MAX, ...): not a path at all
        raise _refuse(directory, f"{option}: {exc.strerror or exc}; choose a directory you can write") from None
    if not probe.is_dir():
        raise _refuse(directory, f"{option}: {shorten(str(probe))} is not a directory")
    _check_creatable_names(directory, probe, option)
    if not os.access(probe, os.W_OK | os.X_OK):
        what = "directory not writable" if probe == Path(directory) else f"cannot create it in {shorten(str(probe))}"
        raise _refuse(directory, f"{option}: {what}; choose a directory you can write")
    try:  # access() passes for root, and on a filesystem that takes no new entries (/proc): try one
        os.rmdir(tempfile.mkdtemp(prefix=".gearcli-probe-", dir=probe))
    except OSError as exc:
        raise _refuse(directory, f"{option}: cannot create entries in {shorten(str(probe))} "
                                 f"({exc.strerror or exc}); choose a directory you can write") from None


def _check_creatable_names(directory: str, existing: Path, option: str) -> None:
    """Refuse the directories still to create under ``existing`` whose names the filesystem would refuse (a
    component longer than its NAME_MAX): found now, not by the ``mkdir`` after the computing."""
    try:
        name_max = os.pathconf(existing, "PC_NAME_MAX")
    except (OSError, ValueError):  # pathconf unknown here: the mkdir will say
        return
    for part in Path(directory).parts:  # an existing one is within the limit: only those to create can fail
        if len(os.fsencode(part)) > name_max:
            raise _refuse(directory, f"{option}: the name {shorten(part, 40)!r} is longer than the {name_max} bytes a "
                                     "file name may have here; choose a shorter directory name")


def write_output(target: OutputTarget, text: str) -> None:
    """``text`` to the checked target: atomically to its file (through a symlink), else to stdout."""
    if target.path is None:
        _write_stdout(text)
        return
    try:
        write_atomic(target.path, text)
    except OSError as exc:
        raise _refuse(target.shown, f"cannot write: {exc.strerror or exc}") from None


def _write_stdout(text: str) -> None:
    """Text to stdout in its encoding; a character the encoding lacks becomes an escape, never a crash."""
    stream = sys.stdout
    encoding = getattr(stream, "encoding", None) or "utf-8"
    try:
        text.encode(encoding)
    except (UnicodeEncodeError, LookupError):
        text = text.encode(encoding, "backslashreplace").decode(encoding, "replace")
    write_stream(stream, text)


STDOUT_NAME = "standard output"


def write_stream(stream: TextIO, text: str) -> None:
    """``text`` written and flushed to ``stream`` (stdout, or a sweep's row stream on it). A device that
    refuses it (``> /dev/full``: no space, an I/O error) is :class:`OutputError` naming standard output (exit
    2), and what is still buffered is dropped so that the interpreter's last flush cannot fail again. A
    reader gone away stays :class:`BrokenPipeError` (exit 141)."""
    try:
        _write_all(stream, text)
    except BrokenPipeError:
        raise
    except OSError as exc:
        drop_buffered(stream)
        raise _refuse(STDOUT_NAME, f"cannot write: {exc.strerror or exc}") from None


def _write_all(stream: TextIO, text: str) -> None:
    """``text`` to ``stream``, every byte or an error. A pipe whose reader goes away while a large write waits in
    it takes part of the write and sends SIGPIPE, which Python ignores: CPython's buffered writer then returns
    the short count without an error and the text layer drops the rest, so a cut output would end as a success
    (exit 0). The bytes go through the binary buffer until all are taken, so that the next write meets EPIPE."""
    buffer = getattr(stream, "buffer", None)
    if buffer is None or os.linesep != "\n":
        stream.write(text)
        stream.flush()
        return
    stream.flush()
    data = memoryview(text.encode(stream.encoding or "utf-8", stream.errors or "strict"))
    while data:
        n = buffer.write(data)
        if not n:  # a non-blocking stdout that takes nothing: an output that cannot be written
            raise BlockingIOError(errno.EAGAIN, "the output takes no more data")
        data = data[n:]
    buffer.flush()


def drop_buffered(stream: TextIO) -> None:
    try:
        fd = os.open(os.devnull, os.O_WRONLY)
        os.dup2(fd, stream.fileno())
        os.close(fd)
    except (OSError, ValueError, AttributeError, io.UnsupportedOperation):
        pass
