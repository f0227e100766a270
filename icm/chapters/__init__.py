"""The chapters of the book in words: what each chapter says of the runs
`icm.experiments` makes and the studies it stores, one module (or package) per chapter
that states claims or quotes numbers, named as its notebook: its claims in words and
their checks, its verdicts, its Markdown tables and the numbers and sentences its text
glues. Shared by all of them: the words for numbers (`words`), the paired verdicts,
phrased in one place (`verdicts`), and the replication of the clear ones on fresh roots
(`replication`; `python -m icm.chapters.replicate` writes assets/replications.json)."""

from icm.chapters import (actor_critic, button_experiment, curiosity, forming_actions,
                          goal_oriented_interest, replication, robustness, rod_toppling,
                          simulated_icub, verdicts, words)

__all__ = ["actor_critic", "button_experiment", "curiosity", "forming_actions",
           "goal_oriented_interest", "replication", "robustness", "rod_toppling",
           "simulated_icub", "verdicts", "words"]
