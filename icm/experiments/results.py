"""Helpers shared by the experiments' results: checking a dict of labelled results
(what the comparison tables and figures take), and a Markdown table of measures with
one column per run."""

from icm import _validate


def check_results(name, results, cls):
    """Returns `results` if it is a non-empty dict {label: `cls` instance}, else raises
    (an ArgumentTypeError naming the label of a wrong entry)."""
    if not isinstance(results, dict) or not results:
        raise _validate.ArgumentTypeError(
            f"{name} must be a non-empty dict {{label: {cls.__name__}}}, got "
            f"{_validate.show(results)}")
    for label, result in results.items():
        if not isinstance(label, str):
            raise _validate.ArgumentTypeError(f"{name} must be labelled by strings (they "
                                              f"become column or legend labels), got the "
                                              f"label {label!r}")
        _validate.instance(f"{name}[{label!r}]", result, cls)
    return results


def measures_table(results, measures):
    """A Markdown table with one column per run and one row per measure: narrow enough
    for a book page however many measures there are.

    Args:
      results: a dict {column label: result}.
      measures: a list of (row label, function of a result giving the cell's text).
    """
    labels = list(results)
    # The first column is named too: a header cell left empty says nothing to a screen
    # reader (axe: empty-table-header).
    lines = ["| measure | " + " | ".join(labels) + " |", "|---|" + "---|" * len(labels)]
    for name, cell in measures:
        lines.append(f"| {name} | " + " | ".join(cell(r) for r in results.values()) + " |")
    return "\n".join(lines)
