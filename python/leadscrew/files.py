"""Files written whole or not at all.

Every file leadscrew writes (a run's series and figures, a study's CSV,
summary and figure, an FMU, a scene or core spec) is first written to a
temporary file beside its target, which is renamed onto the target only once
it is complete. A write that fails half-way (a full disk, a file size limit,
a writer's error) leaves neither a partial file nor the temporary one, and
raises :class:`leadscrew.WriteError` naming the path and the cause; a file
that was already there stays as it was.
"""

from __future__ import annotations

import contextlib
import os
import tempfile
from pathlib import Path
from typing import Iterator, Union

from .errors import WriteError

__all__ = ["writing", "write_text"]

PathLike = Union[str, "os.PathLike[str]"]


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


@contextlib.contextmanager
def writing(path: PathLike) -> Iterator[Path]:
    """Write a file whole or not at all.

    Yields a temporary path in the target's directory, with the target's
    suffix (so writers that pick a format from it, such as matplotlib's
    ``savefig``, pick the target's); the caller writes the whole file there.
    When the block ends normally it is renamed onto ``path`` (atomically, on
    one file system); when it raises, it is removed.

    Args:
        path: the file to write.

    Yields:
        The temporary file's path.

    Raises:
        WriteError: the temporary file cannot be created, written or renamed
            (an OSError, e.g. no space left on device, a file too large):
            names ``path`` and the cause. Other exceptions from the block pass
            through unchanged (the temporary file removed).
    """
    target = Path(path)
    try:
        handle, name = tempfile.mkstemp(prefix=f".{target.name}.", suffix=target.suffix or ".tmp",
                                        dir=target.parent if str(target.parent) else ".")
        os.close(handle)
    except OSError as error:
        raise WriteError(target, error) from error
    temporary = Path(name)
    try:
        yield temporary
        os.chmod(temporary, 0o666 & ~_umask())  # as open() would have made it
        os.replace(temporary, target)
    except BaseException as error:
        with contextlib.suppress(OSError):
            temporary.unlink()
        if isinstance(error, OSError):
            raise WriteError(target, error) from error
        raise


def write_text(path: PathLike, text: str) -> Path:
    """Write ``text`` (UTF-8, ``\\n`` line ends) to ``path`` whole or not at all.

    Args:
        path: the file to write.
        text: its content.

    Returns:
        ``path`` as a :class:`pathlib.Path`.

    Raises:
        WriteError: as :func:`writing`.
    """
    with writing(path) as temporary:
        with open(temporary, "w", encoding="utf-8", newline="\n") as stream:
            stream.write(text)
    return Path(path)
