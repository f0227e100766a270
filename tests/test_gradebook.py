"""The grade sheet and the feedback, written from grades made by hand (icm.course.
gradebook): what an instructor and a student read, to the character, with no
submission run (the grading itself is tests/test_grading.py's, in seconds a case)."""

import csv
import io
import types

import pytest

from icm import records
from icm.course import gradebook as gb

LABEL_A, LABEL_B, LABEL_HAND = "ex-slope", "ex-window", "ex-design"


def _exercise(label, number, kind="implement", points=10.0):
    return records.ManifestExercise(label=label, title=f"the {label[3:]}", number=number,
                                    kind=kind, points=points)


ASSIGNMENTS = {"goal_oriented_interest": types.SimpleNamespace(exercises=[
    _exercise(LABEL_A, "2.1"), _exercise(LABEL_B, "2.2", points=5.0),
    _exercise(LABEL_HAND, "2.3", kind="extend", points=5.0)])}


def _graded(submission, slope_cases=(True, True, True), hidden=(True, True), problem=""):
    public = gb.TestGrade("public test", False, 6.0,
                          [gb.CaseGrade(f"case {i}", ok, "" if ok else f"got {i}, expected 0")
                           for i, ok in enumerate(slope_cases)])
    hidden_test = gb.TestGrade("hidden test 1", True, 4.0,
                               [gb.CaseGrade(f"hidden {i}", ok, "" if ok else "a flat line")
                                for i, ok in enumerate(hidden)])
    window = gb.TestGrade("public test", False, 5.0, [gb.CaseGrade("one", True)])
    return gb.Graded(submission, "goal_oriented_interest", exercises={
        LABEL_A: gb.ExerciseGrade(LABEL_A, "Exercise 2.1: the slope", 10.0,
                                  [public, hidden_test]),
        LABEL_B: gb.ExerciseGrade(LABEL_B, "Exercise 2.2: the window", 5.0, [window])},
        hand_marked=[(LABEL_HAND, "Exercise 2.3: the design", 5.0)], problem=problem)


def _sheet(results, roster=None, tmp_path=None):
    out = tmp_path / "grades.csv"
    gb.write_csv(results, ASSIGNMENTS, out, roster)
    return list(csv.reader(io.StringIO(out.read_text())))


def test_points_are_shared_by_case_and_written_with_two_decimals_at_most():
    graded = _graded("a.ipynb", slope_cases=(True, False, True), hidden=(False, True))
    assert graded.exercises[LABEL_A].tests[0].earned == pytest.approx(4.0)
    assert graded.exercises[LABEL_A].tests[1].earned == pytest.approx(2.0)
    assert graded.points == {LABEL_A: pytest.approx(6.0), LABEL_B: pytest.approx(5.0)}
    assert graded.possible == {LABEL_A: 10.0, LABEL_B: 5.0}
    assert graded.total == pytest.approx(11.0)
    assert gb.TestGrade("empty", False, 3.0).earned == 0.0
    assert [gb.number(v) for v in (11.0, 2 / 3, 0.004, 10.125, 0)] == \
        ["11", "0.67", "0", "10.12", "0"]


def test_the_sheet_has_a_column_per_exercise_and_one_for_each_marked_by_hand(tmp_path):
    rows = _sheet([_graded("a.ipynb", slope_cases=(True, False, True)),
                   _graded("b.ipynb", problem="a cell ran past its time")], tmp_path=tmp_path)
    assert rows == [
        ["submission", "chapter", LABEL_A, LABEL_B, f"{LABEL_HAND} (by hand, of 5)",
         "total", "possible", "problem"],
        ["a.ipynb", "goal_oriented_interest", "8", "5", "", "13", "15", ""],
        ["b.ipynb", "goal_oriented_interest", "10", "5", "", "15", "15",
         "a cell ran past its time"]]


def test_the_roster_joins_by_file_lists_the_missing_and_the_unknown(tmp_path):
    roster = [records.RosterRow(id="s1", name="Ada", file="ada.ipynb"),
              records.RosterRow(id="s2", name="Bo", file="BO.ipynb"),
              records.RosterRow(id="s3", name="Cy", file="cy.ipynb"),
              records.RosterRow(id="s4", name="Di", file="di.ipynb")]
    results = [_graded("ada.ipynb"), _graded("bo.ipynb", hidden=(False, False)),
               _graded("stray.ipynb"), _graded("di.ipynb"), _graded("DI.ipynb")]
    rows = _sheet(results, roster, tmp_path)
    assert rows[0][:2] == ["id", "name"] and len(rows) == 7
    assert rows[1] == ["s1", "Ada", "ada.ipynb", "goal_oriented_interest", "10", "5", "",
                       "15", "15", ""]
    # Matched whatever the case of its name; hidden cases all failed: 6 of 10.
    assert rows[2] == ["s2", "Bo", "bo.ipynb", "goal_oriented_interest", "6", "5", "",
                       "11", "15", ""]
    assert rows[3] == ["s3", "Cy", "cy.ipynb", "", "", "", "", "0", "", "no submission"]
    # Two files for one name: the exact one is the student's, the other is listed apart.
    assert rows[4][:3] == ["s4", "Di", "di.ipynb"]
    assert rows[5] == ["", "", "stray.ipynb", "goal_oriented_interest", "10", "5", "", "15",
                       "15", "not on the roster"]
    assert rows[6][:3] == ["", "", "DI.ipynb"] and rows[6][-1] == "not on the roster"
    rows = _sheet([_graded("x.ipynb"), _graded("X.ipynb")],
                  [records.RosterRow(id="s9", name="Xi", file="x.IPYNB")], tmp_path)
    assert rows[1][-1] == "several submissions match this file: x.ipynb, X.ipynb"
    assert [row[-1] for row in rows[2:]] == ["not on the roster"] * 2


def test_a_cell_a_spreadsheet_would_read_as_a_formula_is_written_as_text(tmp_path):
    for text in ("=1+1", "+1", "-1", "@SUM(A1)", "  =1"):
        assert gb.safe_cell(text) == "'" + text, text
    # A tab or a carriage return is escaped first: the cell starts with a backslash.
    assert gb.safe_cell("\tx") == "\\tx" and gb.safe_cell("\r=1") == "\\r=1"
    assert gb.safe_cell("a=1") == "a=1" and gb.safe_cell(12) == "12"
    assert gb.printable("a\x1b[31mb\u202e\n") == "a\\x1b[31mb\\u202e\\n"
    assert gb.printable("na\udcffme") == "na\\udcffme"
    rows = _sheet([_graded("=HYPERLINK(1).ipynb", problem="-oops")], tmp_path=tmp_path)
    assert rows[1][0] == "'=HYPERLINK(1).ipynb" and rows[1][-1] == "'-oops"


def test_names_are_compared_folded_and_fences_outlast_any_backticks():
    assert gb.folded("MI\u212aE.ipynb") == gb.folded("mike.IPYNB")
    assert gb.folded("ﬁle") == "file"
    assert gb._fence("plain") == "```" and gb._fence("a ```` b ``") == "`````"


FEEDBACK = """# Feedback: a&lt;b&gt;.ipynb

Chapter: goal_oriented_interest. Autograded total: **11 of 15 points**.

**The notebook as a whole:** one cell raised.

**Your notebook's cells, run by the grader:**

```text
cell 3: ZeroDivisionError
```

## Exercise 2.1: the slope (`ex-slope`): 6 of 10

- public test (4 of 6): 2 of 3 cases passed
  - "case 1": failed

    ```text
    got 1, expected 0
    ```

- hidden test 1 (2 of 4): 2 of 4 cases passed
  - "hidden 0": failed

    ```text
    a flat line
    ```

  - "hidden 2": failed, for the same reason

## Exercise 2.2: the window (`ex-window`): 5 of 5

- public test (5 of 5): 1 of 1 cases passed

## Exercise 2.3: the design (`ex-design`): marked by hand, of 5
"""


def test_the_feedback_says_each_case_failed_once_with_its_reason():
    graded = _graded("a<b>.ipynb", slope_cases=(True, False, True),
                     hidden=(False, True, False, True), problem="one cell raised")
    graded.exercises[LABEL_A].tests[1].points = 4.0
    graded.notes = ["cell 3: ZeroDivisionError"]
    assert gb.feedback(graded) == FEEDBACK


def test_the_feedback_of_what_could_not_be_graded_says_why():
    assert gb.feedback(gb.Graded("x.ipynb", problem="not a notebook")) == \
        "# Feedback: x.ipynb\n\nNot graded: not a notebook.\n"
    graded = _graded("y.ipynb")
    graded.exercises[LABEL_A].problem = "the function is missing"
    text = gb.feedback(graded)
    assert "Not tested: the function is missing." in text
    assert '"case' not in text  # no case is listed for an exercise not tested
    backticks = _graded("z.ipynb", slope_cases=(False, True, True))
    backticks.exercises[LABEL_A].tests[0].cases[0].message = "```\n# Title"
    assert "    ````text\n    ```\n    # Title\n    ````" in gb.feedback(backticks)


def test_a_roster_is_read_with_its_bom_and_refused_by_line_when_wrong(tmp_path):
    roster = tmp_path / "roster.csv"
    roster.write_text("\ufeffID,Name,File,email\ns1,Ada,ada.ipynb,a@x\ns2, Bo ,bo.ipynb,\n",
                      encoding="utf-8")
    assert [(r.id, r.name, r.file) for r in gb.read_roster(roster)] == \
        [("s1", "Ada", "ada.ipynb"), ("s2", "Bo", "bo.ipynb")]
    for text, words in [
            ("id,name\ns1,Ada\n", "the roster needs the columns id, name and file; missing "
                                  "file"),
            ("name\nAda\n", "missing id, file"),
            ("id,name,file\ns1,Ada,a.ipynb\ns1,Bo,b.ipynb\n",
             "line 3: the id 's1' is also on line 2"),
            ("id,name,file\ns1,Ada,a.ipynb\ns2,Bo,x\ns3,Cy,A.IPYNB\n",
             "line 4: the file 'a.ipynb' is also on line 2"),
            ("id,name,file\ns1,Ada,../a.ipynb\n", "line 2")]:
        roster.write_text(text)
        with pytest.raises(records.RecordError) as error:
            gb.read_roster(roster)
        assert str(error.value).startswith(f"{roster}") and words in str(error.value), \
            (text, str(error.value))


def test_the_edges_of_the_sheet_and_the_feedback(tmp_path):
    # A submission off the roster with a problem of its own; one whose chapter is unknown.
    unknown = gb.Graded("mystery.ipynb", problem="no chapter's setup cell")
    rows = _sheet([_graded("late.ipynb", problem="a cell ran past its time"), unknown],
                  [records.RosterRow(id="s1", name="Ada", file="ada.ipynb")], tmp_path)
    assert rows[2][:3] == ["", "", "late.ipynb"]
    assert rows[2][-1] == "not on the roster; a cell ran past its time"
    assert rows[3][:4] == ["", "", "mystery.ipynb", ""]
    assert rows[3][-1] == "not on the roster; no chapter's setup cell"
    # A known chapter, nothing graded, a problem: not graded, and why.
    stopped = gb.Graded("s.ipynb", "goal_oriented_interest", problem="the kernel died")
    assert gb.feedback(stopped) == "# Feedback: s.ipynb\n\nNot graded: the kernel died.\n"
    noted = _graded("n.ipynb")
    noted.notes = ["cell 2: left out (past its time)", "cell 5: NameError"]
    assert ("```text\ncell 2: left out (past its time)\ncell 5: NameError\n```"
            in gb.feedback(noted))
