"""What is read back is checked in one place (icm.records): the one-sentence reason a
record is refused, naming the field."""

import pytest

from icm import records


def _error(model, data):
    with pytest.raises(records.pydantic.ValidationError) as info:
        model.model_validate(data)
    return info.value


def test_a_refused_record_names_its_first_wrong_field_and_counts_the_others():
    one = _error(records.RosterRow, {"id": "s1", "name": "Ada", "file": "a/b.ipynb"})
    assert records.problem(one) == ("file: Value error, must be a file's name in the "
                                    "submissions' folder, not a path")
    nested = _error(records.SubmittedNotebook, {"cells": [], "metadata": {"otter": 3},
                                                "nbformat": 4, "nbformat_minor": 5})
    assert records.problem(nested).startswith("metadata.otter: ")
    several = _error(records.RosterRow, {"name": 7})
    assert records.problem(several) == "id: Field required (and 2 more)"
    whole = _error(records.RosterRow, ["not", "a", "row"])
    assert records.problem(whole).startswith("the whole: ")
    assert "more" not in records.problem(whole)


class _Anything(records.BaseModel):
    model_config = records.ConfigDict(extra="allow")


def test_json_read_back_is_refused_past_its_sizes_by_name(monkeypatch):
    monkeypatch.setattr(records, "MAX_JSON_BYTES", 3 * 2 ** 20)
    monkeypatch.setattr(records, "MAX_JSON_CONTAINERS", 4)
    at_limit = b'{"a": "' + b"x" * (3 * 2 ** 20 - 9) + b'"}'
    assert len(at_limit) == 3 * 2 ** 20
    assert records.parse_json(at_limit, _Anything, "big.json").a.startswith("xx")
    with pytest.raises(records.RecordError) as error:
        records.parse_json(at_limit + b" ", _Anything, "big.json")
    assert str(error.value) == "big.json: larger than 3 MiB"
    for data in (b'{"a": [[[]]]}', '{"a": [{}, []]}'):  # bytes or text: 4 containers
        assert records.parse_json(data, _Anything, "ok.json")
    for data in (b'{"a": [[[[]]]]}', '{"a": [{}, [], {}]}'):
        with pytest.raises(records.RecordError) as error:
            records.parse_json(data, _Anything, "many.json")
        assert str(error.value) == "many.json: more than 4 lists and objects"


def test_json_nested_past_pythons_recursion_is_refused_by_name():
    deep = "[" * 100_000 + "]" * 100_000
    with pytest.raises(records.RecordError) as error:
        records.parse_json(deep, _Anything, "deep.json")
    assert str(error.value) == "deep.json: JSON nested too deeply"
    with pytest.raises(records.RecordError) as error:
        records.parse_json(b"{not json", _Anything, "bad.json")
    assert str(error.value).startswith("bad.json: not JSON (")


def test_a_file_read_back_is_a_regular_file_within_its_limit(tmp_path):
    import os

    data = tmp_path / "data.json"
    data.write_bytes(b"x" * 2 ** 20)
    assert records.read_bytes(data, limit=2 ** 20) == b"x" * 2 ** 20
    bigger = tmp_path / "bigger.json"
    bigger.write_bytes(b"x" * (2 ** 20 + 1))
    with pytest.raises(records.RecordError) as error:
        records.read_bytes(bigger, limit=2 ** 20)
    assert str(error.value) == f"{bigger}: larger than 1 MiB"
    link = tmp_path / "link.json"
    link.symlink_to(data)
    assert records.read_bytes(link, limit=2 ** 20) == data.read_bytes()  # followed
    with pytest.raises(records.RecordError) as error:
        records.read_bytes(link, follow=False)
    assert str(error.value) == f"{link}: a symbolic link, not a file"
    with pytest.raises(records.RecordError) as error:
        records.read_bytes(tmp_path)
    assert str(error.value) == f"{tmp_path}: not a file but a folder"
    fifo = tmp_path / "pipe.json"
    os.mkfifo(fifo)  # never waited on
    with pytest.raises(records.RecordError) as error:
        records.read_bytes(fifo)
    assert str(error.value) == f"{fifo}: not a file"
    with pytest.raises(records.RecordError) as error:
        records.read_bytes(tmp_path / "missing.json")
    assert str(error.value) == f"{tmp_path / 'missing.json'}: does not exist"
    assert records.read_text(data, limit=2 ** 20) == "x" * 2 ** 20
    with pytest.raises(records.RecordError, match="larger than"):
        records.read_text(data, limit=10)


def test_an_input_folder_that_is_missing_says_what_to_do(tmp_path):
    with pytest.raises(records.RecordError) as error:
        records.input_folder(tmp_path / "subs", "the submissions' folder", "hand it in")
    assert str(error.value) == f"the submissions' folder {tmp_path / 'subs'} does not " \
                               f"exist: hand it in"
    with pytest.raises(records.RecordError) as error:
        records.input_folder(tmp_path / "subs", "the submissions' folder")
    assert str(error.value) == f"the submissions' folder {tmp_path / 'subs'} does not exist"
