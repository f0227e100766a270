"""The chapter "Actor-critic" (book/actor_critic.ipynb): the claims about Figure 6 it
states in words (`CLAIMS`), checked by `icm.experiments.actor_critic.ActorCriticResult.
claims` on the chapter's run."""


CLAIMS = {
    "red_sooner": "the red error reaches zero for good sooner than the green one on average",
    "red_first_mostly": "the red error reaches zero first in most seeds",
    "green_below_only_before_red_press": "the green error is below the red one only before "
                                         "the red button was first pressed",
}
"""The claims about Figure 6 that the book states in words (`ActorCriticResult.claims`)."""
