"""What a run of the goal-oriented learner measured (`GoalOrientedResult`, from
`icm.experiments.goal_oriented.run_goal_oriented`) and its readings: the numbers of a
run, per seed and over the seeds, and the curves its panel draws (`panel_curves`)."""

import dataclasses

import numpy as np

from icm import _validate
from icm.stats import PANEL_RESAMPLES, bootstrap_band, comes_first, every_nth, first_below

TASKS = ("red", "green")
"""Order of the task axis in the result arrays."""


FADE_FRACTION = 0.1
"""The share of its peak below which a task's mean interest has faded (`fade_trial`)."""


@dataclasses.dataclass(frozen=True)
class GoalOrientedResult:
    """What `run_goal_oriented` measured. Trials are counted from 1 in `mastery_trial`;
    the arrays' trial axis holds trial 1 at index 0.

    Attributes:
      settings: the arguments of the run, as a dict.
      interest: [seed, trial, task], interest in each task (red, green) at the end of
        each trial (0 before the task was first witnessed).
      prediction_error: [seed, trial, task], after each trial, the share of the 20
        (layout, button) pairs for which the predictor is wrong about that task's box
        (predicts it opens when it stays shut, or the reverse). 0 means mastered.
      mastery_trial: [seed, task], the first trial after which the predictor is right
        for that task in every layout and for every button, and stays right to the end
        of the run; -1 if that never happens.
      practice: [seed, trial, task], presses in the trial that opened each box.
      button_share: [seed, trial, button], the share of the trial's presses on each
        button (5 buttons, or 6 with the noisy button).
      action_interest: [seed, trial, button], at the end of each trial, how
        interesting each button is to the learner (the interest of the task it is
        predicted to achieve, or of its region with `interest_per="region"`), the mean
        over the four layouts.

    With `interest_per="region"`, `interest` holds the interest of the red button's
    region (task red) and the mean over the four buttons that green takes (task green).
    """

    settings: dict
    interest: np.ndarray
    prediction_error: np.ndarray
    mastery_trial: np.ndarray
    practice: np.ndarray
    button_share: np.ndarray
    action_interest: np.ndarray

    @property
    def n_seeds(self):
        return self.interest.shape[0]

    @property
    def n_trials(self):
        return self.interest.shape[1]

    def red_first_fraction(self):
        """Share of seeds in which red is mastered strictly before green (a seed where
        green is never mastered but red is counts as red first)."""
        red, green = self.mastery_trial[:, 0], self.mastery_trial[:, 1]
        return float(comes_first(red, green).mean())

    def mean_interest(self):
        """Mean interest over seeds, [trial, task]."""
        return self.interest.mean(axis=0)

    def peak_trial(self, task):
        """The trial (from 1) at which the mean interest in `task` ("red" or "green")
        is highest."""
        task = _validate.one_of("task", task, TASKS)
        return int(np.argmax(self.mean_interest()[:, TASKS.index(task)])) + 1

    def fade_trial(self, task, fraction=None):
        """The first trial after its peak at which the mean interest in `task` falls
        below `fraction` (in (0, 1]) of that peak; -1 if it never does."""
        task = _validate.one_of("task", task, TASKS)
        fraction = FADE_FRACTION if fraction is None else _validate.real(
            "fraction", fraction, 0.0, 1.0, low_open=True)
        index = first_below(self.mean_interest()[:, TASKS.index(task)], fraction)
        return index + 1 if index >= 0 else -1

    def interest_centre(self, task):
        """The interest-weighted mean trial of `task`: when, on average, the interest in
        it is spent (a robust "when", unlike the peak of a flat curve)."""
        task = _validate.one_of("task", task, TASKS)
        curve = self.mean_interest()[:, TASKS.index(task)]
        if curve.sum() == 0:
            return float("nan")
        return float((np.arange(1, len(curve) + 1) * curve).sum() / curve.sum())

    def summary(self):
        """The numbers the book quotes, as a dict."""
        mastery = self.mean_mastery_trial()
        out = {"red_first": self.red_first_fraction()}
        for i, task in enumerate(TASKS):
            mastered = self.mastery_trial[:, i]
            out[f"{task}_mastery_mean"] = mastery[task][0]
            out[f"{task}_mastery_median"] = (float(np.median(mastered[mastered >= 1]))
                                            if (mastered >= 1).any() else float("nan"))
            out[f"{task}_mastered_share"] = mastery[task][1]
            out[f"{task}_peak_interest"] = float(self.mean_interest()[:, i].max())
            out[f"{task}_peak_trial"] = self.peak_trial(task)
            out[f"{task}_fade_trial"] = self.fade_trial(task)
            out[f"{task}_interest_centre"] = self.interest_centre(task)
            share = self.practice[:, :, i].mean(axis=0) / self.settings["presses_per_trial"]
            out[f"{task}_practice_peak_share"] = float(share.max())
            out[f"{task}_practice_peak_trial"] = int(np.argmax(share)) + 1
        return out

    def seed_summaries(self):
        """One dict per seed of the numbers a sweep compares: each task's mastery trial
        (-1 if never), the gap green - red (NaN unless both are mastered), and whether
        red came first."""
        rows = []
        for red, green in self.mastery_trial.tolist():
            gap = float(green - red) if red >= 1 and green >= 1 else float("nan")
            rows.append({"red_mastery_trial": red, "green_mastery_trial": green,
                         "mastery_gap": gap,
                         "red_first": bool(comes_first(red, green))})
        return rows

    def mean_mastery_trial(self):
        """Mean mastery trial of (red, green) over the seeds that master each task, and
        the share of seeds that do."""
        out = {}
        for i, task in enumerate(TASKS):
            done = self.mastery_trial[:, i] >= 1
            mean = float(self.mastery_trial[done, i].mean()) if done.any() else float("nan")
            out[task] = (mean, float(done.mean()))
        return out


def panel_curves(result, every=1):
    """What the Figure 5 panel draws, as numbers: the mean interest in each task per
    trial over the seeds, with a 95% percentile-bootstrap band.

    The interactive panel and the book's precomputed static panel both draw this, so
    the two show the same numbers for the same settings.

    Args:
      result: a `GoalOrientedResult`.
      every: keep every `every`-th trial (and the last); each kept point's numbers do
        not depend on it.

    Returns:
      {"x": trials [trial], "xlabel", "groups": [{"title", "ylabel", "series":
      {task: (mean, low, high)}}]}.
    """
    _validate.instance("result", result, GoalOrientedResult,
                       "a GoalOrientedResult (from icm.experiments.run_goal_oriented)")
    keep = every_nth(result.n_trials, every)
    series = {task: bootstrap_band(result.interest[:, keep, i], resamples=PANEL_RESAMPLES)
              for i, task in enumerate(TASKS)}
    return {"x": keep + 1, "xlabel": "trial",
            "groups": [{"title": f"Interest in each task, {result.n_seeds} seeds",
                        "ylabel": "interest (mean, 95% band)", "series": series}]}
