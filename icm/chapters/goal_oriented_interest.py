"""The chapter "Goal-oriented interest" (book/goal_oriented_interest.ipynb): the
claims of the paper about Figure 5 it states in words (`CLAIMS`), checked by
`icm.experiments.goal_oriented.GoalOrientedResult.claims` on the chapter's run."""


CLAIMS = {
    "red_first_mostly": "red is mastered first in most seeds",
    "red_sooner": "red is mastered sooner than green on average",
    "red_fades_first": "the mean interest in red fades before the interest in green",
    "green_stays_longer": "the interest in green is spent later than the interest in red",
}
"""The claims of the paper about Figure 5 that the book states (`claims`)."""
