"""The shapes of the files icm reads back, in one place, as pydantic models: a file is
read through `read_json` (or a model's `model_validate`), whose error names the file,
the line where there is one, and the field that is wrong.

Files read here: a submitted notebook (what the grader needs of it), an assignment's
manifest (written by `icm.course.assign`, which checks it with the same model before
it writes it), a class roster (CSV rows), and a study's journal (each line), run log,
file (what produced it) and the earlier file whose seeds a study imports
(`icm.studies.engine`, `icm.experiments.sweep.read_journal`). Every file read back, these and the built
book's pages (`read_text`), is read through `read_bytes`: a regular file of a bounded
size, refused naming the file otherwise (a named pipe would never end; a huge file
would fill the memory).
"""

import errno
import json
import os
import pathlib
import re
import stat

import pydantic
import pydantic_core
from pydantic import BaseModel, ConfigDict, Field

MAX_JSON_BYTES = 64 * 2 ** 20
"""The largest JSON file read back (a notebook with its outputs included)."""
MAX_PAGE_BYTES = 64 * 2 ** 20
"""The largest page of the built book read back (its largest pages are a few MiB)."""


MAX_JSON_CONTAINERS = 1_000_000
"""The most lists and objects (brackets [ and {) a JSON file read back may hold: each
takes 56 bytes or more once read, so a file of empty lists would take over 20 times its
size in memory."""


class RecordError(ValueError):
    """A file that is not what it should be; the message names the file and the
    field."""


def problem(error):
    """A pydantic `ValidationError` in one sentence: the first wrong field and why.

    Args:
      error: the `pydantic.ValidationError`.

    Returns:
      The text, e.g. "metadata.otter: Input should be a valid dictionary".
    """
    first = error.errors()[0]
    where = ".".join(str(part) for part in first.get("loc", ())) or "the whole"
    more = len(error.errors()) - 1
    return f"{where}: {first.get('msg', 'invalid')}" + (f" (and {more} more)" if more else "")


def parse_json(data, model, name):
    """Reads JSON bytes or text into `model`.

    Args:
      data: the bytes or text.
      model: a pydantic model class.
      name: how the error names what was read (a file's name).

    Returns:
      The model instance.

    Raises:
      RecordError: for data too large, not JSON, nested too deeply, or not of the
        model's shape, naming `name` and the field.
    """
    if len(data) > MAX_JSON_BYTES:
        raise RecordError(f"{name}: larger than {MAX_JSON_BYTES // 2 ** 20} MiB")
    brackets = (b"[", b"{") if isinstance(data, bytes) else ("[", "{")
    if sum(data.count(bracket) for bracket in brackets) > MAX_JSON_CONTAINERS:
        raise RecordError(f"{name}: more than {MAX_JSON_CONTAINERS:,} lists and objects")
    try:
        content = json.loads(data)
    except RecursionError:
        raise RecordError(f"{name}: JSON nested too deeply") from None
    except (ValueError, UnicodeDecodeError) as error:
        raise RecordError(f"{name}: not JSON ({error})") from None
    try:
        return model.model_validate(content)
    except pydantic.ValidationError as error:
        raise RecordError(f"{name}: {problem(error)}") from None
    except RecursionError:
        raise RecordError(f"{name}: nested too deeply") from None


def read_bytes(path, limit=MAX_JSON_BYTES, follow=True):
    """A file's bytes: a regular file of at most `limit` bytes, opened without waiting
    (a named pipe put in its place is refused, never waited on).

    Args:
      path: the file.
      limit: the most bytes read.
      follow: whether a symbolic link is followed (False: refused).

    Returns:
      The bytes.

    Raises:
      RecordError: for a file missing, a link (unless `follow`), not a regular file (a
        folder, a named pipe), larger than `limit` or unreadable, naming it.
    """
    path = pathlib.Path(path)
    flags = os.O_RDONLY | os.O_NONBLOCK | (0 if follow else os.O_NOFOLLOW)
    try:
        handle = os.open(path, flags)
    except FileNotFoundError:
        raise RecordError(f"{path}: does not exist") from None
    except OSError as error:
        if error.errno == errno.ELOOP and not follow:
            raise RecordError(f"{path}: a symbolic link, not a file") from None
        if error.errno == errno.EISDIR:
            raise RecordError(f"{path}: not a file but a folder") from None
        raise RecordError(f"{path}: cannot be read ({error.strerror})") from None
    info = os.fstat(handle)
    if not stat.S_ISREG(info.st_mode) or info.st_size > limit:
        os.close(handle)
        if not stat.S_ISREG(info.st_mode):
            raise RecordError(f"{path}: not a file" + (" but a folder" if
                                                        stat.S_ISDIR(info.st_mode) else ""))
        raise RecordError(f"{path}: larger than {limit / 2 ** 20:g} MiB")
    with os.fdopen(handle, "rb") as file:
        try:
            data = file.read(limit + 1)
        except OSError as error:
            raise RecordError(f"{path}: cannot be read ({error.strerror})") from None
    if len(data) > limit:  # (grown since)
        raise RecordError(f"{path}: larger than {limit / 2 ** 20:g} MiB")
    return data


def input_folder(path, what, hint=""):
    """A folder a command reads, refused naming it if it is missing or not a folder.

    Args:
      path: the folder.
      what: how the message names it, e.g. "the built book's folder".
      hint: what to do when it is missing, e.g. "build it first (make book)".

    Returns:
      The folder, a `pathlib.Path`.

    Raises:
      RecordError: naming the folder.
    """
    path = pathlib.Path(path)
    if not path.exists():
        raise RecordError(f"{what} {path} does not exist" + (f": {hint}" if hint else ""))
    if not path.is_dir():
        raise RecordError(f"{what} {path} is not a folder")
    return path


def read_text(path, limit=MAX_PAGE_BYTES):
    """A UTF-8 text file (see `read_bytes`).

    Args:
      path: the file.
      limit: the most bytes read.

    Returns:
      The text.

    Raises:
      RecordError: for a file that `read_bytes` refuses or that is not UTF-8, naming it.
    """
    data = read_bytes(path, limit)
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as error:
        raise RecordError(f"{path}: not UTF-8 text (byte {error.start})") from None


def read_json(path, model):
    """Reads a JSON file into `model` (see `read_bytes` and `parse_json`).

    Args:
      path: a `pathlib.Path`.
      model: a pydantic model class.

    Returns:
      The model instance.

    Raises:
      RecordError: naming the file.
    """
    return parse_json(read_bytes(path), model, str(path))


# --- a submitted notebook ------------------------------------------------------------

class NotebookCell(BaseModel):
    """A cell of a notebook: its kind, its source (a string or a list of lines) and
    its metadata (its tags, for the grader)."""

    model_config = ConfigDict(extra="allow")
    cell_type: str
    source: str | list[str] = ""
    metadata: dict = Field(default_factory=dict)

    @property
    def text(self):
        """The source as one string."""
        return self.source if isinstance(self.source, str) else "".join(self.source)


class OtterMetadata(BaseModel):
    """What otter writes into an assignment's notebook: the assignment's name."""

    model_config = ConfigDict(extra="allow")
    assignment_name: str = Field(min_length=1, max_length=200)


class NotebookMetadata(BaseModel):
    """A notebook's metadata, of which the grader reads otter's."""

    model_config = ConfigDict(extra="allow")
    otter: OtterMetadata


class SubmittedNotebook(BaseModel):
    """What the grader reads of a submitted notebook: its cells and which assignment
    it is."""

    model_config = ConfigDict(extra="allow")
    cells: list[NotebookCell] = Field(max_length=10_000)
    metadata: NotebookMetadata


# --- an assignment's manifest ----------------------------------------------------------

LABEL = r"^ex-[a-z0-9-]+$"


class ManifestExercise(BaseModel):
    """One exercise of an assignment: an implement exercise (graded by its tests) or
    an extend exercise (marked by hand)."""

    model_config = ConfigDict(extra="forbid")
    label: str = Field(pattern=LABEL)
    title: str
    number: str = Field(pattern=r"^\d+\.\d+$")
    kind: str = Field(pattern=r"^(implement|extend)$")
    points: float = Field(gt=0, le=1000)
    function: str | None = None


class Manifest(BaseModel):
    """What the grader reads beside a chapter's assignment (`icm.course.assign`
    writes it): the chapter, its number and title, and its exercises in order."""

    model_config = ConfigDict(extra="forbid")
    chapter: str = Field(pattern=r"^[a-z][a-z0-9_]*$")
    number: int = Field(ge=0, le=1000)
    title: str
    exercises: list[ManifestExercise]


# --- a roster ---------------------------------------------------------------------------

class RosterRow(BaseModel):
    """One student of a class: an id, a name, and the file they handed in."""

    model_config = ConfigDict(extra="ignore", str_strip_whitespace=True)
    id: str = Field(min_length=1, max_length=200)
    name: str = Field(max_length=400)
    file: str = Field(min_length=1, max_length=400)

    @pydantic.field_validator("file")
    @classmethod
    def _a_file_name(cls, value):
        if re.search(r"[/\\]", value) or value in (".", ".."):
            raise ValueError("must be a file's name in the submissions' folder, not a path")
        return value


# --- a study's journal, run log and file --------------------------------------------

def json_digest(value):
    """The SHA-256 (hex) of a JSON value's compact text: what a study's journal keeps
    beside each result, so that a result changed since it was written is refused.

    Args:
      value: a JSON value (dicts, lists, strings, numbers, booleans, None).

    Returns:
      64 hexadecimal digits.
    """
    import hashlib

    text = json.dumps(value, separators=(",", ":"))
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


class JournalHeader(BaseModel):
    """A study journal's first line: what its units were computed with (the study's
    name and settings, for `icm.studies.engine`)."""

    model_config = ConfigDict(extra="forbid")
    header: pydantic.JsonValue


class JournalRecord(BaseModel):
    """One finished unit of a study's journal (a line after the header): the unit, its
    result, the CPU seconds it took, and the SHA-256 of the result as written
    (`json_digest`): a result replaced since (a bare number for a dict, a list cut
    short) does not match it."""

    model_config = ConfigDict(extra="forbid")
    unit: pydantic.JsonValue
    result: pydantic.JsonValue
    cpu: float = Field(ge=0, allow_inf_nan=False)
    sha256: str = Field(pattern=r"^[0-9a-f]{64}$")

    @pydantic.field_validator("sha256")
    @classmethod
    def _result_as_written(cls, sha256, info):
        if "result" in info.data and json_digest(info.data["result"]) != sha256:
            raise pydantic_core.PydanticCustomError(
                "changed", "not that of the result on this line (the result was changed "
                           "after the run wrote it)")
        return sha256


class RunLogLine(BaseModel):
    """One line of a study's run log (``<out>.runs.jsonl``, `icm.studies.engine`): how
    one run went (its settings, backend, units and their CPU seconds)."""

    model_config = ConfigDict(extra="allow")
    study: str | None = None
    started: str
    settings: dict
    backend: str
    units: int = Field(ge=0)
    unit_cpu_seconds: list[float]


class StudyProducedBy(BaseModel):
    """What produced a study's file: the study's name (the rest is not read back)."""

    model_config = ConfigDict(extra="allow")
    study: str = Field(min_length=1)


class StudyFileStamp(BaseModel):
    """A study's file, as far as a command needs to know that it wrote it: its
    "produced_by" names the study."""

    model_config = ConfigDict(extra="allow")
    produced_by: StudyProducedBy


class SeedBlocksFile(BaseModel):
    """A study's file of seed blocks per root (`icm.studies.forming_actions`: "remedies",
    "goal-babbling"), as `--import-seeds` reads it: the seeds per root, the rollouts and
    trials they ran, {label: {root: entry}}, 'reach' if the study has it, and what
    produced it (the study's name)."""

    model_config = ConfigDict(extra="allow")
    n_seeds: int = Field(ge=1)
    n_rollouts: int = Field(ge=1)
    n_trials: int = Field(ge=1)
    runs: dict[str, dict[str, dict[str, pydantic.JsonValue]]] = Field(min_length=1)
    reach: pydantic.JsonValue = None
    produced_by: StudyProducedBy

    @pydantic.field_validator("runs")
    @classmethod
    def _roots(cls, runs):
        for label, by_root in runs.items():
            if not by_root:
                raise ValueError(f"{label!r} has no root seed")
            for root in by_root:
                if not re.fullmatch(r"0|[1-9][0-9]{0,9}", root):
                    raise ValueError(f"{label!r}: {root!r} is not a root seed (an "
                                     f"integer >= 0)")
        return runs
