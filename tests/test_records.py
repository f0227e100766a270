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
