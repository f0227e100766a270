"""The words of strength in a chapter's prose, and the checks they need.

Every sentence of a chapter's prose is read: its Markdown cells (the folds'
text and their titles, lists, admonitions) and its figures' captions; code, maths and
the glued Markdown tables are not prose. A sentence *reports a result* when it quotes
one (a glued number or phrase: `{glue:text}`, `{glue:md}`, `{glue}`) or is in bold
(the chapters' claims). In such a sentence, each of `PATTERNS` (a word or phrase of
strength: "every", "always", "never", "in every seed", "at every point", "clear",
"exactly", "most", causal "because", "only because", "so ... no", ...) needs a check
of matching strength, registered in the chapter's module of `icm.chapters`
(`STRONG_WORDS`, or the older `BOLD_CLAIMS`: {a fragment of the sentence, as written
in the notebook: (claim name, kind)}). The claim name must be one the chapter checks
when it is built (`results.require`), and the kind one of those the pattern allows
(`PATTERNS`, `KINDS`).

A few patterns are results wherever they stand ("in every seed", "only because", ...,
`ANYWHERE`): they are read in every sentence, with a glued number or without.
A sentence that quotes no result and speaks of no outcome (`OUTCOMES`: mastered,
learned, toppled, sooner, replicated, held, ...) states a rule of the experiment or
of the code ("each press", "never below the console's top"), which the code's tests
check, not the chapter's data. A strong word in a sentence that does speak of an
outcome needs its check, glued number or not: "Red is always mastered first." fails.

Glued phrases. A glued phrase ("sooner ... in all 8 cases") is chosen by the
library from the data when the book is built, so its words change with the data; the
notebook's source shows only its name. `problems` reads each sentence twice: as
written, and (given `glued`, the build's glued values) with each glued phrase in
place, so that a phrase that says "in all 8 cases" needs its sentence's check like
typed words would. A registry key matches the sentence as written (the glue's name
included), so one entry covers every phrase the data can choose; the check it names
must carry the strongest words the phrase can say. Glued numbers are left as names: a
number is never a word of strength (a share of 100% is `tests/test_book.py`'s).

A share of seeds is a sample: its 100% is not "every seed". The universal patterns
need a check of kind "all", over every case of a finite set that is not a sample of
seeds (every point of a map, every learner, every button), or of kind "rule" (a rule
of the code, which a named test checks: its claim name is "tests/file.py::test_name");
about seeds, say "in at
least X% of the seeds" (the lower bound of the share's interval, kind "bound"). An
"all" entry names its set (a third element: "points", "learners", ...), and the
checker refuses "seeds", "runs" and "trials" there.

tests/test_claim_words.py runs `problems` on every chapter, and plants an overclaim of
each pattern in made-up ones, which must fail.
"""

import re

KINDS = {
    "all": "holds in every case of a finite set, each checked: every point of a map, "
           "every learner, every button (not a sample of seeds: name the set)",
    "bound": "a share of seeds whose interval's lower bound is at or above the share "
             "the sentence states (\"in at least 90% of the seeds\")",
    "corrected": "clear after Holm's correction for the chapter's family of comparisons "
                 "(icm.stats.corrected_verdicts), or a verdict named as not clear",
    "exact": "an equality checked exactly",
    "majority": "a share above one half in every case it is claimed for",
    "share": "a share at or above a threshold below one (e.g. 90% of the seeds)",
    "mean": "a comparison of means, without an interval",
    "causal": "the cause measured, seed by seed: the effect comes where the cause did "
              "and not without it, or goes away when the cause is removed",
    "rule": "follows from the rules of the experiment or the code (an update, a "
            "console's rule), which the code's tests check",
}
"""The kinds of check a claim can have."""
SAMPLES = ("seeds", "runs", "trials")
"""What an "all" check may not be over: a sample, whose 100% is not "every"."""

_UNIVERSAL = {"all", "rule"}
PATTERNS = {
    "in every seed": (r"\b(?:in|on|for|of) every (?:one of the )?(?:seeds?|runs?)\b"
                      r"|\bevery seed\b|\ball (?:the )?seeds\b", set()),
    "at every point": (r"\b(?:at|in|on) every (?:point|setting|map)\b", _UNIVERSAL),
    "in all N": (r"\b(?:in|of|on) all (?:\d+|two|three|four|five|six|seven|eight|nine|ten"
                 r"|⟨\w+⟩) (?:cases|seeds|runs|comparisons|verdicts)\b", _UNIVERSAL),
    "every": (r"\bevery(?:one| one)?\b", _UNIVERSAL),
    "always": (r"\balways\b", _UNIVERSAL),
    "never": (r"\bnever\b", _UNIVERSAL),
    "only because": (r"\bonly because\b", {"causal"}),
    "because": (r"\bbecause\b", {"causal", "rule"}),
    "so ... no": (r"\bso\b[^.;:]*?\b(?:no|not|never|none|nothing)\b", {"causal", "rule"}),
    "clear": (r"\bclear\b", {"corrected"}),
    "clearly": (r"\bclearly\b", {"corrected"}),
    "exactly": (r"\bexactly\b", {"exact"}),
    "fastest": (r"\bfastest\b", {"corrected"}),
    "most": (r"\bmost\b", {"corrected", "majority", "bound", "rule"}),
}
"""Each pattern of strength: (regular expression, the kinds of check that can carry it).
Nothing carries "in every seed": a sample's 100% is not every seed (say "in at least X%
of the seeds", kind "bound"). "every", "always", "never", "at every point" and "in all
N cases" need a check over every case of a finite set ("all"), or a rule of the code
that a test checks over all its cases ("rule": red's place never changes); "only because" a
measured cause; "because" and "so ... no" a measured cause or a rule of the code;
"clear", "clearly" and "fastest" a corrected comparison; "exactly" an exact equality;
"most" a majority in each case, a share's lower bound above one half, a corrected
comparison, or a rule of the code ("the most recent press")."""
ANYWHERE = ("in every seed", "in all N", "only because")
"""The patterns read in every sentence, not only in those that quote a result."""
WORD_KINDS = {word: kinds for word, (_, kinds) in PATTERNS.items()}
"""For each pattern, the kinds of check that can carry it (from `PATTERNS`)."""

_BOLD = re.compile(r"\*\*(.+?)\*\*", re.DOTALL)
_GLUE = re.compile(r"\{glue(?::text|:md)?\}`(\w+)(?::[^`]*)?`")
_FENCE = re.compile(r"^(`{3,}|~{3,}).*?^\1\s*$", re.M | re.S)
_MATH = re.compile(r"\$\$.*?\$\$|\$[^$\n]+\$", re.S)
_ABBREVIATIONS = re.compile(r"\b(e\.g|i\.e|etc|cf|vs)\.")


def normalise(text):
    """`text` with every run of white space made one space, stripped."""
    return " ".join(text.split())


def bold_spans(markdown):
    """The bold spans of a Markdown text, each normalised (`normalise`)."""
    return [normalise(m.group(1)) for m in _BOLD.finditer(markdown)]


def prose(markdown):
    """The prose of a Markdown cell: without code blocks (``` fences, but a fold's
    ::: text kept), maths, directive options (":class: ...") and HTML comments; a
    directive's title ("{dropdown} How do we know?") kept as a line of prose."""
    text = _FENCE.sub("\n\n", markdown)
    text = re.sub(r"<!--.*?-->", " ", text, flags=re.S)
    text = _MATH.sub(" ", text)
    lines = []
    for line in text.splitlines():
        stripped = line.strip()
        if re.match(r"^:\w[\w-]*:", stripped):
            continue  # a directive's option
        directive = re.match(r"^:{3,}\s*(?:\{[\w-]+\})?\s*(.*)$", stripped)
        if directive:
            lines += ["", directive.group(1), ""]
            continue
        lines.append(line)
    return "\n".join(lines)


def sentences(markdown):
    """The sentences of a Markdown cell's prose (`prose`), each normalised: split at a
    full stop, question or exclamation mark followed by a space, at blank lines and at
    list items, never inside a glue role."""
    text = _ABBREVIATIONS.sub(lambda m: m.group(1).replace(".", "\0") + "\0", prose(markdown))
    out = []
    for block in re.split(r"\n\s*\n|\n\s*(?=[-*+] |\d+\. )", text):
        for piece in re.split(r"(?<=[.!?])\s+(?=[^a-z\s])", block):
            piece = normalise(piece.replace("\0", "."))
            if re.search(r"[A-Za-z]", piece):
                out.append(piece)
    return out


OUTCOMES = re.compile(
    r"\b(?:master(?:s|ed|y)?|learn(?:s|ed|t|ing)?|predict(?:s|ed)? well|toppl(?:es|ed)"
    r"|comes? first|sooner|later|earlier|faster|slower|replicat\w*|trapped|fails?"
    r"|holds?|held|outperforms?|beats?|wins?)\b", re.I)
"""Words that speak of what the learners did in the runs (mastered, learned, toppled,
came first, sooner, replicated, held, ...): a sentence with one of them reports a
result even without a glued number ("Red is always mastered first.")."""


def reports_a_result(sentence):
    """Whether a sentence reports a result: it quotes one (a glued value), is in bold
    (the chapters' claims), or speaks of what the learners did (`OUTCOMES`)."""
    return bool(_GLUE.search(sentence) or _BOLD.search(sentence)
                or OUTCOMES.search(with_glued(sentence, {}).replace("**", "")))


def with_glued(sentence, glued):
    """`sentence` with each glued value of `glued` ({name: text}, the phrases the build
    glued) in place of its role, and the other roles as ⟨name⟩."""
    def value(match):
        name = match.group(1)
        return glued[name] if name in glued else f"⟨{name}⟩"
    return _GLUE.sub(value, sentence)


def strength_words(text, every_sentence=False):
    """The patterns of `PATTERNS` found in `text` (any case), in the order of
    `PATTERNS`; with `every_sentence`, only those of `ANYWHERE` (what a sentence that
    reports no result is read for). Bold markers and glue roles are read as their
    text (`with_glued` with nothing glued)."""
    text = with_glued(text, {}).replace("**", "").lower()
    chosen = ANYWHERE if every_sentence else PATTERNS
    found = [word for word in chosen if re.search(PATTERNS[word][0], text)]
    # "every" inside "in every seed" or "at every point" is that pattern's, not a
    # second one; "because" inside "only because" likewise.
    rest = re.sub(PATTERNS["in every seed"][0] + "|" + PATTERNS["at every point"][0], " ",
                  text)
    if "every" in found and not re.search(PATTERNS["every"][0], rest):
        found.remove("every")
    rest = re.sub(PATTERNS["only because"][0], " ", text)
    if "because" in found and not re.search(PATTERNS["because"][0], rest):
        found.remove("because")
    return found


def _entry_problems(sentence, words, entry):
    """What is wrong with a registry entry (claim name, kind[, over]) for a sentence
    that says `words`."""
    name, kind, over = (tuple(entry) + (None,))[:3]
    if kind not in KINDS:
        return [f"{sentence!r}: unknown kind {kind!r} (allowed: {sorted(KINDS)})"]
    out = []
    if kind == "all" and (over is None or over in SAMPLES):
        out.append(f"{sentence!r}: its claim {name!r} is 'all' over "
                   f"{over or 'an unnamed set'}; a share of {over or 'seeds'} is a sample, "
                   f"say 'in at least X% of the seeds' (a 'bound' check)")
    for word in words:
        if kind not in WORD_KINDS[word]:
            needs = " or ".join(sorted(WORD_KINDS[word])) or (
                "nothing: a sample's 100% is not every seed; say 'in at least X% of the "
                "seeds' (a 'bound' check)")
            out.append(f"{sentence!r}: {word!r} needs a check of kind {needs}, its claim "
                       f"{name!r} is {kind!r}")
    return out


def problems(markdown_cells, registry, checked, glued=None):
    """What is wrong with the words of strength of a chapter's prose, in words (an empty
    list: nothing).

    Args:
      markdown_cells: the chapter's prose: its Markdown cells and its captions (texts).
      registry: {a fragment of a sentence (normalised when compared): (claim name, kind
        of `KINDS`[, the set an "all" claim is over])}; a sentence's entry is the first
        whose fragment it contains.
      checked: the claim names the chapter checks when it is built.
      glued: {glue name: text} of the glued phrases of the built chapter, read in place
        (`with_glued`); None reads the sentences as written only.
    """
    registry = {normalise(text): entry for text, entry in registry.items()}
    out = []
    for cell in markdown_cells:
        for sentence in sentences(cell):
            result = reports_a_result(sentence)
            words = strength_words(sentence, every_sentence=not result)
            if glued is not None and result:
                for word in strength_words(with_glued(sentence, glued)):
                    if word not in words:
                        words.append(word)
            if not words:
                continue
            entry = next((e for key, e in registry.items() if key in sentence), None)
            if entry is None:
                out.append(f"{', '.join(words)} with no check: {sentence!r}")
                continue
            if entry[0] not in checked:
                out.append(f"{sentence!r}: its claim {entry[0]!r} is not checked by the "
                           f"chapter")
            out += _entry_problems(sentence, words, entry)
    return out


def unused(markdown_cells, registry):
    """The registry's fragments that no sentence of the chapter contains (a stale entry
    hides nothing, but says a check that no longer has its words)."""
    found = [s for cell in markdown_cells for s in sentences(cell)]
    return [key for key in registry if not any(normalise(key) in s for s in found)]
