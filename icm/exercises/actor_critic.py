"""Checks of the actor-critic exercises: the softmax that picks a press, and one TD
update of Figure 4 in both readings of the paper's TD error."""

import numpy as np

from icm import _validate
from icm.exercises import _core
from icm.exercises._core import Case
from icm.exercises._own import Forbidden
from icm.learners.actor_critic import ActorCritic, softmax

SOFTMAX_PARAMETERS = ("preferences", "temperature")
TD_PARAMETERS = ("critic", "actor", "state", "action", "reward", "next_state", "td_form",
                 "lr_actor", "lr_critic", "gamma")
TD_FORMS = ("standard", "printed")
"""The two readings of the TD error: "standard" r + gamma V(s') - V(s), and "printed"
r + gamma (V(s) - V(s')), equation 2 as the paper prints it."""
SOFTMAX_FORBIDDEN = Forbidden(("icm.learners.action_selection", "icm.learners.actor_critic"))
"""What a softmax must not call: the library's."""
TD_FORBIDDEN = Forbidden(("icm.learners.actor_critic",))
"""What a TD update must not call: the actor-critic's own."""
STANDARD_HINT = ("The standard TD error is r + gamma * V(s') - V(s): the value of where you "
                 "are going, discounted, minus the value of where you are.")
PRINTED_HINT = ("The printed form (equation 2) is r + gamma * (V(s) - V(s')): V(s) is "
                "inside the parentheses, multiplied by gamma too.")
TD_QUANTITIES = (
    ("td_error", "the TD error", "Compute the TD error in the form `td_form` from the "
     "values before any update (a state the critic does not hold is worth 0)."),
    ("critic", "the critic", "Then V(s) += lr_critic * td, stored in `critic` (a state it "
     "did not hold starts from 0); no other state's value changes."),
    ("actor", "the actor", "Then actor[s][action] += lr_actor * td; the other preferences "
     "do not change."))
"""What a TD update is judged on, in the order it computes them."""


def reference_softmax(preferences, temperature):
    """The softmax of the library (`icm.learners.softmax`).

    Args:
      preferences: the actor's preferences.
      temperature: T > 0.

    Returns:
      The probabilities, a list.
    """
    return softmax(preferences, temperature).tolist()


def public_softmax_cases():
    """The cases the check runs when given none (the ones the book shows the
    student), the paper's edge cases first: a list of `Case`.

    Returns:
      A list of `icm.exercises._core.Case`.
    """
    return [
        Case("ties: every preference the same", ([0.0, 0.0, 0.0, 0.0, 0.0], 0.2),
             "Equal preferences give equal probabilities, 1/n each."),
        Case("one action", ([0.3], 0.2), "With one action its probability is 1."),
        Case("one preferred action", ([0.0, 0.5, 0.0], 0.2),
             "p_i = exp(h_i / T) / sum_j exp(h_j / T): divide by the temperature, do not "
             "multiply."),
        Case("a high temperature: nearly uniform", ([0.0, 1.0, 2.0], 100.0),
             "The higher the temperature, the closer to uniform."),
        Case("a low temperature: nearly greedy", ([0.0, 1.0, 0.9], 0.01),
             "The lower the temperature, the closer to always the best."),
        Case("large preferences: exp would overflow", ([1000.0, 999.0, 0.0], 0.2),
             "In floating point exp(1000 / 0.2) is infinite: subtract the largest "
             "preference before exponentiating (the probabilities do not change)."),
        Case("negative preferences", ([-1.0, -2.0, -0.5], 0.5),
             "Negative preferences are fine: exp of a negative number is small, not "
             "negative."),
        Case("the learner's own preferences", ([0.5, 0.0, 0.25, 0.0, -0.1], 0.2),
             "p_i = exp(h_i / T) / sum_j exp(h_j / T)."),
    ]


def check_softmax(softmax_function, cases=None):
    """Checks a student's softmax, `f(preferences, temperature)`: the probability of each
    action, exp(h_i / T) / sum_j exp(h_j / T), as a list or array, computed without
    overflow.

    Args:
      softmax_function: the student's function.
      cases: the cases to try, a list of `Case` (default: the check's own, the ones
        the book shows; the grader passes its hidden ones).

    Returns:
      A `CheckResult`.

    Raises:
      ArgumentTypeError: if the argument is not a function of (preferences,
        temperature).
    """
    cases = public_softmax_cases() if cases is None else cases
    return _core.run_cases("softmax", "softmax_function", softmax_function,
                           SOFTMAX_PARAMETERS, cases, reference_softmax,
                           returns="a list of probabilities", forbidden=SOFTMAX_FORBIDDEN)


def reference_td_update(critic, actor, state, action, reward, next_state, td_form,
                        lr_actor, lr_critic, gamma):
    """One step of Figure 4 as `ActorCritic.learn` makes it, after the reward is known.

    Args:
      critic: state -> V (a missing state is worth 0), changed in place.
      actor: state -> list of preferences, changed in place.
      state, action, reward, next_state: the step.
      td_form: "standard" or "printed" (`TD_FORMS`).
      lr_actor, lr_critic, gamma: the learner's rates and discount.

    Returns:
      The TD error.
    """
    _validate.one_of("td_form", td_form, TD_FORMS)
    learner = ActorCritic(len(actor[state]), lr_actor=lr_actor, lr_critic=lr_critic,
                          gamma=gamma, variant="standard" if td_form == "standard"
                          else "printed_td")
    learner.critic = dict(critic)
    td_error = learner.td_error(reward, state, next_state)
    # As ActorCritic.learn does, after the TD error:
    critic[state] = learner.value(state) + lr_critic * td_error
    actor[state][action] += lr_actor * td_error
    return td_error


def _after(args, returned):
    """What a TD update is judged on: the TD error it returns, and the critic and the
    actor it leaves."""
    return {"td_error": returned, "critic": args[0], "actor": args[1]}


def public_td_cases():
    """The cases the check runs when given none (the ones the book shows the
    student), the paper's edge cases first: a list of `Case`.

    Returns:
      A list of `icm.exercises._core.Case`.
    """
    standard_hint, printed_hint = STANDARD_HINT, PRINTED_HINT
    s, t = "here", "there"
    cases = [
        Case("standard form, both states valued", ({s: 0.4, t: 0.2}, {s: [0.0, 0.1, 0.0]},
                                                   s, 1, 1.0, t, "standard", 0.5, 0.5, 0.5),
             standard_hint + " Then V(s) += lr_critic * td and actor[s][a] += lr_actor * td."),
        Case("printed form, both states valued", ({s: 0.4, t: 0.2}, {s: [0.0, 0.1, 0.0]},
                                                  s, 1, 1.0, t, "printed", 0.5, 0.5, 0.5),
             printed_hint, "td_error"),
        Case("a state the critic has never valued: V is 0",
             ({}, {s: [0.0, 0.0, 0.0]}, s, 2, 1.0, t, "standard", 0.5, 0.5, 0.5),
             "A state missing from `critic` has value 0: use critic.get(state, 0.0), and "
             "store the new V(s)."),
        Case("no reward: only the values move", ({s: 0.4, t: 0.8}, {s: [0.0, 0.0, 0.0]},
                                                 s, 0, 0.0, t, "standard", 0.5, 0.5, 0.5),
             standard_hint, "td_error"),
        Case("gamma 0: the TD error is the reward minus V(s)",
             ({s: 0.4, t: 0.8}, {s: [0.0, 0.0, 0.0]}, s, 0, 1.0, t, "standard", 0.5, 0.5, 0.0),
             "With gamma 0 the next state's value does not count.", "td_error"),
        Case("the next state is the state itself (standard)",
             ({s: 0.4}, {s: [0.0, 0.2, 0.0]}, s, 1, 0.0, s, "standard", 0.5, 0.5, 0.5),
             "Compute the TD error from the values before any update, then update the "
             "critic and the actor with that same TD error."),
        Case("the next state is the state itself (printed): V(s) - V(s') is 0",
             ({s: 0.4}, {s: [0.0, 0.2, 0.0]}, s, 1, 1.0, s, "printed", 0.5, 0.5, 0.5),
             printed_hint, "td_error"),
        Case("different learning rates for the actor and the critic",
             ({s: 0.1, t: 0.3}, {s: [0.0, 0.0, 0.0]}, s, 0, 1.0, t, "standard", 0.1, 0.9,
              0.5),
             "The critic moves by lr_critic * td, the actor by lr_actor * td: do not swap "
             "them."),
        Case("only the chosen action's preference moves",
             ({s: 0.0, t: 0.0}, {s: [0.3, 0.3, 0.3]}, s, 2, 1.0, t, "printed", 0.5, 0.5, 0.5),
             "actor[s][action] += lr_actor * td; the other actions keep their preferences.",
             "actor"),
    ]
    rng = np.random.default_rng(11)
    for i in range(6):
        form = TD_FORMS[i % 2]
        critic = {s: round(float(rng.normal()), 3), t: round(float(rng.normal()), 3)}
        actor = {s: rng.normal(size=3).round(3).tolist()}
        cases.append(Case(f"random values, {form} form {i // 2 + 1}",
                          (critic, actor, s, int(rng.integers(3)), float(rng.integers(2)), t,
                           form, 0.5, 0.5, float(rng.choice([0.0, 0.5, 0.9]))),
                          standard_hint if form == "standard" else printed_hint, "td_error"))
    return cases


def hidden_td_cases(rng):
    """Cases of the shapes of the public ones, with values drawn from `rng`.

    Args:
      rng: a `numpy.random.Generator`.

    Returns:
      A list of `Case`.
    """
    s, t = f"s{int(rng.integers(100))}", f"t{int(rng.integers(100))}"
    n = int(rng.integers(2, 6))

    def value():
        return round(float(rng.normal()), 3)

    def prefs():
        return {s: rng.normal(size=n).round(3).tolist()}

    def rates():
        return (round(float(rng.uniform(0.05, 1.0)), 2), round(float(rng.uniform(0.05, 1.0)), 2),
                round(float(rng.uniform(0.0, 0.99)), 2))

    cases = []
    for form, hint in (("standard", STANDARD_HINT), ("printed", PRINTED_HINT)):
        cases += [
            Case(f"{form} form, both states valued (hidden)",
                 ({s: value(), t: value()}, prefs(), s, int(rng.integers(n)),
                  value(), t, form) + rates(), hint),
            Case(f"{form} form, a state the critic has never valued (hidden)",
                 ({t: value()}, prefs(), s, int(rng.integers(n)), value(), t, form) + rates(),
                 "A state missing from `critic` has value 0; store the new V(s)."),
            Case(f"{form} form, the next state is the state itself (hidden)",
                 ({s: value()}, prefs(), s, int(rng.integers(n)), value(), s, form) + rates(),
                 "Compute the TD error from the values before any update.", "td_error"),
        ]
    cases.append(Case("different learning rates for the actor and the critic (hidden)",
                      ({s: value(), t: value()}, prefs(), s, int(rng.integers(n)), value(), t,
                       "standard", 0.05, 0.95, round(float(rng.uniform(0.1, 0.9)), 2)),
                      "The critic moves by lr_critic * td, the actor by lr_actor * td."))
    return cases


def hidden_softmax_cases(rng):
    """Cases of the shapes of the public ones, with values drawn from `rng`.

    Args:
      rng: a `numpy.random.Generator`.

    Returns:
      A list of `Case`.
    """
    n = int(rng.integers(2, 8))

    def temperature():
        return float(rng.choice([0.05, 0.2, 0.5, 1.0, 3.0]))

    return [
        Case("ties: every preference the same (hidden)",
             ([round(float(rng.normal()), 3)] * n, temperature()),
             "Equal preferences give equal probabilities."),
        Case("one action (hidden)", ([round(float(rng.normal()), 3)], temperature()),
             "With one action its probability is 1."),
        Case("a high temperature (hidden)", (rng.normal(size=n).round(3).tolist(),
                                             round(float(rng.uniform(50, 200)), 1)),
             "p_i = exp(h_i / T) / sum_j exp(h_j / T)."),
        Case("large preferences: exp would overflow (hidden)",
             ((rng.normal(size=n) + float(rng.uniform(500, 2000))).round(2).tolist(),
              round(float(rng.uniform(0.1, 0.5)), 2)),
             "Subtract the largest preference before exponentiating."),
        Case("negative preferences (hidden)",
             ((-np.abs(rng.normal(size=n)) * 3).round(3).tolist(), temperature()),
             "exp of a negative number is small, not negative."),
        Case("random preferences (hidden)", (rng.normal(size=n).round(3).tolist(),
                                             temperature()),
             "p_i = exp(h_i / T) / sum_j exp(h_j / T)."),
    ]


def check_td_update(td_update, cases=None):
    """Checks a student's TD update of Figure 4, `td_update(critic, actor, state, action,
    reward, next_state, td_form, lr_actor, lr_critic, gamma)`: it computes the TD error
    in the form `td_form` ("standard": r + gamma V(s') - V(s); "printed": r + gamma
    (V(s) - V(s'))), then updates the critic, V(s) += lr_critic * td, and the actor,
    actor[s][action] += lr_actor * td, in place, and returns the TD error. `critic`
    maps states to values (a missing state is worth 0), `actor` states to lists of
    preferences.

    Args:
      td_update: the student's function.
      cases: the cases to try, a list of `Case` (default: the check's own, the ones
        the book shows; the grader passes its hidden ones).

    Returns:
      A `CheckResult`.

    Raises:
      ArgumentTypeError: if the argument is not a function of those ten arguments.
    """
    cases = public_td_cases() if cases is None else cases
    return _core.run_cases("td_update", "td_update", td_update, TD_PARAMETERS, cases,
                           reference_td_update, observe=_after, quantities=TD_QUANTITIES,
                           forbidden=TD_FORBIDDEN)
