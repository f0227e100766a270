"""Sphinx extension: the References page labels each work as the text cites it.

The text cites author-year (`bibtex_reference_style: author_year`: "[Baranes and
Oudeyer, 2009]"), but sphinxcontrib-bibtex labels the bibliography's entries with
pybtex's default label style, "alpha" ("[BO09]"), so that a reader cannot match the
two. This registers a pybtex formatting style, `icm_author_year` (the book's
`bibtex_default_style`): pybtex's "unsrt" formatting, sorted by author and year, with
labels as the citations show them: one author "Schmidhuber, 2010", two "Deci and
Ryan, 1985", more "Weng et al., 2001", and "a", "b", ... after the year where two
works would share a label.
"""

from pybtex.plugin import register_plugin
from pybtex.style.formatting.unsrt import Style as UnsrtStyle
from pybtex.style.labels import BaseLabelStyle
from pybtex.style.sorting.author_year_title import SortingStyle


def _surname(person):
    return " ".join(person.prelast_names + person.last_names).replace("{", "").replace("}", "")


def author_year(entry):
    """The label of `entry` as an author-year citation shows it."""
    people = entry.persons.get("author") or entry.persons.get("editor") or []
    names = [_surname(person) for person in people]
    if not names:
        who = entry.fields.get("title", entry.key).split()[0]
    elif len(names) == 1:
        who = names[0]
    elif len(names) == 2:
        who = f"{names[0]} and {names[1]}"
    else:
        who = f"{names[0]} et al."
    return f"{who}, {entry.fields.get('year', 'n.d.')}"


class AuthorYearLabels(BaseLabelStyle):
    """Labels "Author, year", "Author and Author, year", "Author et al., year"."""

    def format_labels(self, sorted_entries):
        entries = list(sorted_entries)
        labels = [author_year(entry) for entry in entries]
        repeated = {label for label in labels if labels.count(label) > 1}
        seen = {}
        for label in labels:
            if label in repeated:
                seen[label] = seen.get(label, 0) + 1
                yield label + "abcdefghijklmnopqrstuvwxyz"[seen[label] - 1]
            else:
                yield label


class AuthorYearStyle(UnsrtStyle):
    """pybtex's unsrt formatting with `AuthorYearLabels`, sorted by author and year."""

    default_label_style = AuthorYearLabels
    default_sorting_style = SortingStyle


def setup(app):
    register_plugin("pybtex.style.formatting", "icm_author_year", AuthorYearStyle)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
