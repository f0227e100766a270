"""Files and folders that icm's commands write: checked before any work, written whole.

A command never writes over or deletes what it did not write. Before it starts, it
checks each of its destinations (`check_file`, `check_folder`):

- a file it would replace must be one it wrote (the command says how it recognises
  its own, from the file's own format) unless the user says `force`;
- a folder it would fill must be new, empty, or one it wrote: such a folder holds the
  marker file `MARKER` (as `CACHEDIR.TAG` marks a cache folder: git and nbgrader
  refuse a destination that exists; the Cache Directory Tagging convention marks a
  folder that a program may empty). Only a folder with the marker is emptied or
  replaced;
- no destination may be one of the command's inputs, lie inside one, or hold one (the
  feedback folder inside the submissions, the slides over the built book), links
  followed; a destination that is itself a symbolic link is refused (writing through
  it would change its target).

Files are written under a temporary name in their own folder, then renamed
(`write_bytes`, `write_text`): a run killed half-way leaves the old file whole.
"""

import os
import pathlib
import shutil
import tempfile

MARKER = "ICM-OUTPUT.TAG"
"""The file that marks a folder an icm command wrote (and may empty)."""
MARKER_TEXT = ("Signature: icm output folder\n"
               "# This folder was written by a command of icm (the course's grading,\n"
               "# assignments or slides, a study). That command may empty or replace it\n"
               "# when it is run again. Delete this file to keep the folder from it.\n")


class DestinationError(ValueError):
    """A destination a command refuses to write (the message names it and says why)."""


def _resolved(path):
    return pathlib.Path(os.path.realpath(path))


def _inside(path, folder):
    """Whether `path` is `folder` or lies inside it (both resolved)."""
    return path == folder or folder in path.parents


def _check_inputs(path, inputs, what):
    target = _resolved(path)
    for source in inputs:
        source_path = _resolved(source)
        if _inside(target, source_path):
            raise DestinationError(f"{what} {path} is {'' if target == source_path else 'inside '}"
                                   f"the input {source}: choose a destination outside it")
        if _inside(source_path, target):
            raise DestinationError(f"{what} {path} holds the input {source}: choose a "
                                   f"destination that does not")


def check_file(path, own=None, force=False, inputs=(), what="the output"):
    """Refuses a file destination that the command must not write.

    Args:
      path: the file to write.
      own: own(path) -> whether an existing file there is one the command wrote
        (None: no existing file is the command's).
      force: replace an existing file that is not the command's.
      inputs: the command's inputs (files or folders).
      what: how the message names the destination, e.g. "--out".

    Returns:
      The path, a `pathlib.Path`.

    Raises:
      DestinationError: naming the destination and why.
    """
    path = pathlib.Path(path)
    if path.is_symlink():
        raise DestinationError(f"{what} {path} is a symbolic link: name the file itself")
    if path.exists() and path.is_dir():
        raise DestinationError(f"{what} {path} is a folder: name a file")
    for parent in path.parents:
        if parent.exists() and not parent.is_dir():
            raise DestinationError(f"{what} {path}: {parent} is a file, not a folder")
    _check_inputs(path, inputs, what)
    if path.exists() and not force and not (own is not None and _owned(own, path)):
        raise DestinationError(f"{what} {path} exists and was not written by this "
                               f"command: choose another name, or pass --force to "
                               f"replace it")
    return path


def _owned(own, path):
    try:
        return bool(own(path))
    except (OSError, ValueError, UnicodeDecodeError):
        return False


def check_folder(path, force=False, inputs=(), what="the output folder"):
    """Refuses a folder destination that the command must not fill or empty.

    Args:
      path: the folder.
      force: accept an existing, non-empty folder without the marker (it is then
        emptied of what the command writes, never removed).
      inputs: the command's inputs (files or folders).
      what: how the message names the destination.

    Returns:
      The path, a `pathlib.Path`.

    Raises:
      DestinationError: naming the folder and why.
    """
    path = pathlib.Path(path)
    if path.is_symlink():
        raise DestinationError(f"{what} {path} is a symbolic link: name the folder itself")
    if path.exists() and not path.is_dir():
        raise DestinationError(f"{what} {path} is a file, not a folder")
    for parent in path.parents:
        if parent.exists() and not parent.is_dir():
            raise DestinationError(f"{what} {path}: {parent} is a file, not a folder")
    _check_inputs(path, inputs, what)
    if path.is_dir() and not force and not is_ours(path) and any(path.iterdir()):
        raise DestinationError(f"{what} {path} exists, is not empty and was not written "
                               f"by icm (it has no {MARKER}): choose another folder, or "
                               f"pass --force")
    return path


def is_ours(folder):
    """Whether a folder holds the marker of a folder icm wrote."""
    marker = pathlib.Path(folder) / MARKER
    try:
        return marker.is_file() and marker.read_text().startswith(MARKER_TEXT.split("\n")[0])
    except (OSError, UnicodeDecodeError):
        return False


def fresh_folder(path):
    """Makes `path` an empty folder with the marker: a folder `check_folder` accepted
    (new, empty, or icm's: its contents are removed; with `force`, a folder of
    someone else's keeps its files and gains the marker).

    Args:
      path: the folder.

    Returns:
      The path, a `pathlib.Path`.
    """
    path = pathlib.Path(path)
    if is_ours(path):
        for child in path.iterdir():
            if child.is_dir() and not child.is_symlink():
                shutil.rmtree(child)
            else:
                child.unlink()
    path.mkdir(parents=True, exist_ok=True)
    write_text(path / MARKER, MARKER_TEXT)
    return path


def write_bytes(path, data):
    """Writes a file whole: into a temporary file in its folder, then renamed over it.

    Args:
      path: the file.
      data: its bytes.
    """
    path = pathlib.Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    handle, temporary = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".part",
                                         dir=path.parent)
    try:
        with os.fdopen(handle, "wb") as file:
            file.write(data)
            file.flush()
            os.fsync(file.fileno())
        os.replace(temporary, path)
    except BaseException:
        try:
            os.unlink(temporary)
        except OSError:
            pass
        raise


def write_text(path, text):
    """Writes a text file whole (UTF-8, a character it cannot hold written as its
    escape, e.g. a file name's undecodable byte; see `write_bytes`).

    Args:
      path: the file.
      text: its text.
    """
    write_bytes(path, text.encode("utf-8", "backslashreplace"))
