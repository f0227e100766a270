"""Files and folders that icm's commands write: checked before any work, written whole.

A command never writes over or deletes what it did not write. Before it starts, it
checks each of its destinations (`check_file`, `check_folder`):

- a file it would replace must be one it wrote (the command says how it recognises
  its own, from the file's own format) unless the user says `force`;
- a folder it would fill must be new, empty, or one it wrote: such a folder holds the
  marker file `MARKER` (as `CACHEDIR.TAG` marks a cache folder: git and nbgrader
  refuse a destination that exists; the Cache Directory Tagging convention marks a
  folder that a program may empty), which names the command that wrote it. Only a
  folder with the command's own marker is emptied or replaced (the slides' command
  never empties the assignments');
- no destination may be one of the command's inputs, lie inside one, or hold one (the
  feedback folder inside the submissions, the slides over the built book), links
  followed; a destination that is itself a symbolic link is refused (writing through
  it would change its target);
- a destination whose folder is read-only (no write permission for this user, or no
  write bit at all: its owner made it read-only, which root could write anyway) is
  refused.

Files are written under a temporary name in their own folder, then renamed
(`write_bytes`, `write_text`): a run killed half-way leaves the old file whole. A
folder's new contents are written into a staging folder inside it, then each put in
place of the old entry of its name by renames (`staged`): a run that fails or is
killed before then leaves the old contents whole, and the next run tidies what a
killed one left (`tidy`).
"""

import os
import pathlib
import secrets
import shutil
import stat
import tempfile

MARKER = "ICM-OUTPUT.TAG"
"""The file that marks a folder an icm command wrote (and may empty)."""
STAGING_PREFIX = ".icm-part-"
"""The name's start of a folder's staging folder (`staged`), inside it."""
ASIDE_PREFIX = ".icm-old-"
"""The name's start of an old entry put aside while its new one takes its place
(`staged`): ".icm-old-<8 hex digits>.<its name>"."""
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


def writable(folder):
    """Whether a command may write into an existing folder: this user may, and its
    owner has not made it read-only (a folder with no write bit at all is refused even
    to root, who could write it anyway).

    Args:
      folder: the folder (a `pathlib.Path`).

    Returns:
      True or False.
    """
    try:
        mode = folder.stat().st_mode
    except OSError:
        return False
    return stat.S_ISDIR(mode) and bool(mode & 0o222) and \
        os.access(folder, os.W_OK | os.X_OK)


def _check_place(path, what, kind):
    """Refuses a destination whose way there is broken: a file or a broken link among
    its folders, or a read-only folder where it would be made."""
    for parent in path.parents:
        if parent.is_symlink() and not parent.exists():
            raise DestinationError(f"{what} {path}: {parent} is a broken symbolic link")
        if parent.exists() and not parent.is_dir():
            raise DestinationError(f"{what} {path}: {parent} is a file, not a folder")
    home = path if kind == "folder" and path.is_dir() else \
        next(parent for parent in path.parents if parent.exists())
    if not writable(home):
        raise DestinationError(f"{what} {path}: the folder {home} is read-only")


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
    if path.exists() and not path.is_file():
        raise DestinationError(f"{what} {path} is not a regular file")
    _check_inputs(path, inputs, what)
    _check_place(path, what, "file")
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


def check_folder(path, force=False, inputs=(), what="the output folder", command=None):
    """Refuses a folder destination that the command must not fill or empty.

    Args:
      path: the folder.
      force: accept an existing, non-empty folder without the marker, or with another
        command's (its files are kept; those of the command's names are replaced).
      inputs: the command's inputs (files or folders).
      what: how the message names the destination.
      command: the command's name, e.g. "python -m icm.course slides": a folder whose
        marker names another command is not its own (None: a marker naming no command).

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
    _check_inputs(path, inputs, what)
    _check_place(path, what, "folder")
    if path.is_dir() and not force and not is_ours(path, command) and any(path.iterdir()):
        other = marker_command(path)
        why = (f"was not written by icm (it has no {MARKER})" if other is None else
               f"was written by {other}, not by this command" if other else
               "was written by another of icm's commands")
        raise DestinationError(f"{what} {path} exists, is not empty and {why}: choose "
                               f"another folder, or pass --force")
    return path


def marker_text(command=None):
    """The marker's text, naming the command that wrote the folder (if given).

    Args:
      command: e.g. "slides", or None.

    Returns:
      The text.
    """
    return MARKER_TEXT + (f"Command: {command}\n" if command else "")


def _marker(folder):
    """The marker's text, or None for a folder without icm's marker."""
    marker = pathlib.Path(folder) / MARKER
    try:
        if marker.is_symlink() or not marker.is_file() or marker.stat().st_size > 4096:
            return None
        text = marker.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError):
        return None
    return text if text.startswith(MARKER_TEXT.split("\n")[0]) else None


def marker_command(folder):
    """The command a folder's marker names ("" for a marker that names none, None for
    a folder without icm's marker).

    Args:
      folder: the folder.

    Returns:
      The name, "" or None.
    """
    text = _marker(folder)
    if text is None:
        return None
    for line in text.splitlines():
        if line.startswith("Command: "):
            return line[len("Command: "):].strip()
    return ""


def is_ours(folder, command=None):
    """Whether a folder holds the marker of a folder this command wrote: one that
    names `command`, or, for None, one that names no command (so that a command that
    gives no name never empties the folder of one that does: the grader's feedback
    folder is never the slides').

    Args:
      folder: the folder.
      command: the command's name, or None.

    Returns:
      True or False.
    """
    return marker_command(folder) == (command or "")


def fresh_folder(path, command=None):
    """Makes `path` an empty folder with the marker: a folder `check_folder` accepted
    (new, empty, or icm's: its contents are removed; with `force`, a folder of
    someone else's keeps its files and gains the marker).

    Args:
      path: the folder.
      command: the command's name, written in the marker; a folder of another
        command's is not emptied (see `is_ours`).

    Returns:
      The path, a `pathlib.Path`.
    """
    path = pathlib.Path(path)
    if is_ours(path, command):
        for child in path.iterdir():
            if child.is_dir() and not child.is_symlink():
                shutil.rmtree(child)
            else:
                child.unlink()
    path.mkdir(parents=True, exist_ok=True)
    write_text(path / MARKER, marker_text(command))
    return path


class staged:
    """A folder's new contents, written into a staging folder inside it and put in
    place only when all of them are written: a context manager.

        with files.staged(out) as staging:
            ... write the new entries into staging ...

    On entering, the folder (accepted by `check_folder`) is made if missing and gets
    the marker, what a killed run left in it is tidied (`tidy`), and the staging folder
    ("<folder>/.icm-part-...") is made. On leaving without an error, each entry of the
    staging folder takes the place of the folder's entry of its name: a file by one
    rename (`os.replace`), a folder by two (the old one put aside, the new one put in,
    then the old one removed; a symbolic link there is replaced, never followed). With
    `replace`, the folder's other entries are then removed too, if the folder was
    icm's before (a folder of someone else's, accepted with `force`, keeps its files).
    On an error, the staging folder is removed and the folder is as it was: removed if
    this run made it (and the folders made for it), its marker as it was.

    Args:
      folder: the folder.
      replace: whether the new contents replace all the old (True) or only the
        entries of their names (False: an assignment's other chapters stay).
      command: the command's name, written in the marker (a folder is this command's
        only if its marker names it).
    """

    def __init__(self, folder, replace=False, command=None):
        self.folder = pathlib.Path(folder)
        self.replace = replace
        self.command = command
        self.path = None
        self._made = None
        self._was_ours = False
        self._old_marker = None

    def __enter__(self):
        folder = self.folder
        self._was_ours = is_ours(folder, self.command)
        marker = folder / MARKER
        if marker.is_file() and not marker.is_symlink() and not self._was_ours:
            self._old_marker = marker.read_bytes()  # (another's, replaced with force)
        missing = [path for path in [folder, *folder.parents] if not path.exists()]
        self._made = missing[-1] if missing else None  # (the highest folder made)
        folder.mkdir(parents=True, exist_ok=True)
        try:
            if self._was_ours:
                tidy(folder)
            else:
                write_text(folder / MARKER, marker_text(self.command))
            self.path = pathlib.Path(tempfile.mkdtemp(prefix=STAGING_PREFIX, dir=folder))
        except BaseException:
            self._undo()
            raise
        return self.path

    def __exit__(self, kind, value, traceback):
        if kind is not None:
            self._undo()
            return False
        written = set()
        for entry in sorted(self.path.iterdir()):
            put_in_place(entry, self.folder / entry.name)
            written.add(entry.name)
        self.path.rmdir()
        if self.replace and self._was_ours:
            for child in self.folder.iterdir():
                if child.name not in written and child.name != MARKER:
                    _remove(child)
        return False

    def _undo(self):
        if self.path is not None:
            shutil.rmtree(self.path, ignore_errors=True)
        if self._made is not None:
            shutil.rmtree(self._made, ignore_errors=True)
        elif not self._was_ours:
            try:
                if self._old_marker is None:
                    (self.folder / MARKER).unlink()
                else:
                    write_bytes(self.folder / MARKER, self._old_marker)
            except OSError:
                pass


def _remove(path):
    """Removes a file, a link (never what it points to) or a folder."""
    if path.is_dir() and not path.is_symlink():
        shutil.rmtree(path)
    else:
        path.unlink()


def put_in_place(new, old):
    """Puts a new file or folder in the place of `old` (whatever is there) by renames
    within one folder: a file over a file in one `os.replace`; otherwise the old entry
    is renamed aside (".icm-old-<hex>.<name>"), the new one renamed in, then the old
    one removed. A run killed between the two renames leaves the old entry whole under
    the aside name, which `tidy` puts back.

    Args:
      new: the new file or folder (in the same file system).
      old: where it goes.
    """
    new, old = pathlib.Path(new), pathlib.Path(old)
    if not old.exists() and not old.is_symlink():
        os.rename(new, old)
        return
    if new.is_file() and old.is_file() and not old.is_symlink():
        os.replace(new, old)
        return
    aside = old.with_name(f"{ASIDE_PREFIX}{secrets.token_hex(4)}.{old.name}")
    os.rename(old, aside)
    os.rename(new, old)
    _remove(aside)


def tidy(folder):
    """Tidies what a killed run left in a folder of icm's: its staging folders are
    removed; an old entry put aside (`put_in_place`) is removed if its new one is in
    place, and put back otherwise.

    Args:
      folder: the folder (icm's: `is_ours`).
    """
    folder = pathlib.Path(folder)
    for child in sorted(folder.iterdir()):
        if child.name.startswith(STAGING_PREFIX):
            _remove(child)
        elif child.name.startswith(ASIDE_PREFIX):
            name = child.name[len(ASIDE_PREFIX) + 9:]
            place = folder / name
            if not name or place.exists() or place.is_symlink():
                _remove(child)
            else:
                os.rename(child, place)


def write_bytes(path, data):
    """Writes a file whole: into a temporary file in its folder, then renamed over it;
    the file's mode is the one open() would give it (this process's umask), not the
    temporary file's owner-only one.

    Args:
      path: the file.
      data: its bytes.
    """
    path = pathlib.Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    handle, temporary = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".part",
                                         dir=path.parent)
    umask = os.umask(0)
    os.umask(umask)
    os.chmod(temporary, 0o666 & ~umask)
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
