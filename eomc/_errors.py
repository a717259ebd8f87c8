"""eomc's errors as Python exceptions, and its warnings as Python warnings.

eomc says what went wrong on stderr, in three kinds the command line tells
apart by exit status: a spec it cannot read (``FILE:LINE:COL: error: ...``
with a caret, exit 2), a usage error (a bad option, name or value, exit 2)
and a numerical failure (exit 3, the rows computed so far kept).  Each
becomes its exception here, carrying eomc's message whole.
"""

import errno
import re
import warnings

__all__ = ["EomcError", "SpecError", "FileNotFound", "UsageError", "NumericalFailure",
           "ControllerError", "EomcWarning"]


class EomcError(Exception):
    """Anything eomc refused or could not do; ``message`` is eomc's text."""

    def __init__(self, message):
        super().__init__(message)
        self.message = message


class SpecError(EomcError, ValueError):
    """The spec (or MJCF/URDF model) is wrong: ``file``, ``line`` and ``column``
    say where, as eomc's ``file:line:column: error:`` does; the message has
    the quoted line and its caret."""

    def __init__(self, message, file=None, line=None, column=None):
        super().__init__(message)
        self.file, self.line, self.column = file, line, column


class FileNotFound(EomcError, FileNotFoundError):
    """A spec or model file that is not there: a FileNotFoundError, with
    ``filename``."""

    def __init__(self, message, filename=None):
        super().__init__(message)
        self.filename = filename
        self.errno, self.strerror = errno.ENOENT, message

    def __str__(self):  # eomc's message, not OSError's "[Errno 2] ..."
        return self.message


class UsageError(EomcError, ValueError):
    """A bad option, name or value (the command line's exit status 2)."""


class NumericalFailure(EomcError, ArithmeticError):
    """A run failed (exit status 3): ``t`` is the time eomc names, ``rows``
    the rows computed before it (a :class:`eomc.Run`), as the CSV keeps them."""

    def __init__(self, message, t=None, rows=None):
        super().__init__(message)
        self.t, self.rows = t, rows


class ControllerError(EomcError):
    """A controller given to a run failed: it raised (the exception is the
    ``__cause__``), or returned what is not the inputs (the wrong length,
    a name that is not an input, a value that is not a finite number).
    ``t`` is the time it was called at, ``rows`` the rows computed before
    (a :class:`eomc.Run`), as a numerical failure keeps them."""

    def __init__(self, message, t=None, rows=None):
        super().__init__(message)
        self.t, self.rows = t, rows


class EomcWarning(UserWarning):
    """What eomc says may be wrong with an answer (``warning:``), or what it
    left out (``note:``): the message is eomc's line."""


_WHERE = re.compile(r"^(.*?):(\d+):(\d+): error: ")
# a model file's error without a place in it (MuJoCo said none)
_FILE = re.compile(r"^(.*?\.(?:yaml|yml|xml|urdf|URDF|XML))(?: \(as imported\))?: error: ")
_TIME = re.compile(r"error: t = ([-+0-9.eEinfa]+):")


def spec_error(text):
    """The SpecError of eomc's stderr text if it starts with a located error."""
    first = text.lstrip("\n").split("\n", 1)[0]
    m = _WHERE.match(first)
    if m:
        return SpecError(text.strip("\n"), m.group(1), int(m.group(2)), int(m.group(3)))
    m = _FILE.match(first)
    if m:
        return SpecError(text.strip("\n"), m.group(1))
    return None


_OPTION = re.compile(r"'--([a-z][a-z0-9-]*)'")
_LEADING = re.compile(r"^(\S+: )--([a-z][a-z0-9-]*)(:| )", re.M)


def as_keywords(text):
    """eomc's usage message in the Python call's terms: an option
    '--t-end' as the keyword 't_end' ("unknown keyword 'tend' (did you mean
    't_end'?)"), without the line that points to --help."""
    def kw(m):
        return "'%s'" % m.group(1).replace("-", "_")

    text = _OPTION.sub(kw, text)
    text = _LEADING.sub(lambda m: m.group(1) + m.group(2).replace("-", "_") + m.group(3), text)
    text = text.replace("unknown option ", "unknown keyword ")
    return "\n".join(line for line in text.split("\n")
                     if not (line.startswith("(see ") and line.endswith("--help)")))


def failure_time(text):
    """The time a numerical failure's message names ("error: t = 1.25: ..."), or None."""
    m = _TIME.search(text)
    return float(m.group(1)) if m else None


def raise_for(status, err, rows=None):
    """Raise the exception of a nonzero exit status with eomc's stderr text err."""
    text = err.strip("\n")
    if status == 0:
        return
    located = spec_error(text)
    if located is not None:
        raise located
    if status == 2:
        raise UsageError(text)
    if status == 3:
        t = failure_time(text)
        if t is None and rows is not None and len(rows):
            t = float(rows["t"][-1])
        raise NumericalFailure(text, t, rows)
    raise EomcError(text or "eomc failed (exit status %d)" % status)


def warn_lines(err, stacklevel=3):
    """Each ``warning:`` or ``note:`` line of eomc's stderr as an EomcWarning;
    returns them."""
    said = []
    for line in err.splitlines():
        if ": warning: " in line or ": note: " in line:
            said.append(line)
            warnings.warn(line, EomcWarning, stacklevel=stacklevel)
    return said
