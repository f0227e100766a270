"""What a run of the actor-critic measured (`ActorCriticResult`, from
`icm.experiments.actor_critic.run_actor_critic`) and its readings: the numbers of a run,
per seed and over the seeds, and the curves its panel draws (`panel_curves`)."""

import dataclasses
import math

import numpy as np

from icm import _validate
from icm.stats import PANEL_RESAMPLES, bootstrap_band, comes_first, every_nth

TASKS = ("red", "green")
"""Order of the task axis in the result arrays."""


LATE_TRIALS = 10
"""`summary()` describes the end of a run by its last `LATE_TRIALS` trials."""


@dataclasses.dataclass(frozen=True)
class ActorCriticResult:
    """What `run_actor_critic` measured. Trials are counted from 1 in `zero_trial`;
    the arrays' trial axis holds trial 1 at index 0.

    Attributes:
      settings: the arguments of the run, as a dict.
      prediction_error: [seed, trial, task], after each trial, section 4.1's test:
        the Euclidean distance between the predicted and the true boxes when only the
        red button is lit and pressed (task red), and the same averaged over the 4
        places of the green button when only it is lit and pressed (task green).
      zero_trial: [seed, task], the first trial from which that error is 0 to the end
        of the run; -1 if it is not 0 at the end.
      practice: [seed, trial, task], presses in the trial that opened each box.
      press_probability: [seed, trial, task], after each trial, the actor's
        probability of pressing the red (task red) and the green (task green) button
        at the start of a trial (boxes shut), averaged over the 4 layouts.
      reward: [seed, trial], the rewards the learner received in the trial, summed.
      max_abs_value: [seed, trial], the largest absolute value of the critic after each trial.
    """

    settings: dict
    prediction_error: np.ndarray
    zero_trial: np.ndarray
    practice: np.ndarray
    press_probability: np.ndarray
    reward: np.ndarray
    max_abs_value: np.ndarray

    @property
    def n_seeds(self):
        """Number of runs (seeds)."""
        return self.prediction_error.shape[0]

    @property
    def n_trials(self):
        """Trials per run."""
        return self.prediction_error.shape[1]

    def red_first_fraction(self):
        """Share of seeds in which the red error reaches 0 (for good) strictly before
        the green one (a seed where only red reaches 0 counts as red first)."""
        red, green = self.zero_trial[:, 0], self.zero_trial[:, 1]
        return float(comes_first(red, green).mean())

    def seed_summaries(self):
        """One dict per seed of the numbers a sweep compares: the trial from which each
        task's error is 0 (-1 if never), the gap green - red (NaN unless both reach 0),
        and whether red came first."""
        rows = []
        for red, green in self.zero_trial.tolist():
            gap = float(green - red) if red >= 1 and green >= 1 else float("nan")
            rows.append({"red_zero_trial": red, "green_zero_trial": green, "zero_gap": gap,
                         "red_first": bool(comes_first(red, green))})
        return rows

    def green_below_red(self):
        """[seed, trial] True where the green error is below the red one: the learner
        is, for the moment, more familiar with the hard task than with the easy one."""
        return self.prediction_error[:, :, 1] < self.prediction_error[:, :, 0]

    def green_below_red_only_before_red_press(self):
        """Whether, in every seed, the green error is below the red one only in trials
        before the red button was first pressed (before a press opened the red box;
        none at all if it never was)."""
        below = self.green_below_red()
        pressed = self.practice[:, :, 0] > 0  # a red press opens the red box
        trials = np.arange(1, self.n_trials + 1)
        first_press = np.where(pressed.any(axis=1), np.argmax(pressed, axis=1) + 1,
                               self.n_trials + 1)
        last_below = np.where(below, trials, 0).max(axis=1)
        return bool(np.all(last_below <= first_press))

    def green_below_red_fraction(self):
        """Share of seeds in which the green error is below the red one at some trial
        (the paper's "familiarity with the more complex task would temporarily
        increase above the simple task")."""
        return float(self.green_below_red().any(axis=1).mean())

    def summary(self):
        """The numbers the book quotes, as a dict.

        For each task (keys starting ``red_`` or ``green_``): the share of seeds whose
        error reaches 0 for good (``_zero_share``), the mean and median of that trial
        over those seeds, the mean final error, the share of presses opening the box in
        the last `LATE_TRIALS` trials (``_late_practice_share``) and the final
        probability of pressing its button. Also `red_first`, `green_below_red` (with
        how many trials and until when), the reward per press at the end, and the
        largest absolute critic value at the end (max and median over seeds)."""
        out = {"red_first": self.red_first_fraction(),
               "green_below_red": self.green_below_red_fraction()}
        below = self.green_below_red()
        seeds_below = below.any(axis=1)
        if seeds_below.any():
            trials = np.arange(1, self.n_trials + 1)
            last = np.where(below, trials, 0).max(axis=1)[seeds_below]
            out["green_below_red_trials"] = float(below[seeds_below].sum(axis=1).mean())
            out["green_below_red_last_mean"] = float(last.mean())
            out["green_below_red_last_max"] = int(last.max())
        else:
            out["green_below_red_trials"] = 0.0
            out["green_below_red_last_mean"] = math.nan
            out["green_below_red_last_max"] = -1
        late = slice(max(0, self.n_trials - LATE_TRIALS), None)
        presses = self.settings["presses_per_trial"]
        for i, task in enumerate(TASKS):
            zero = self.zero_trial[:, i]
            done = zero >= 1
            out[f"{task}_zero_share"] = float(done.mean())
            out[f"{task}_zero_mean"] = float(zero[done].mean()) if done.any() else math.nan
            out[f"{task}_zero_median"] = float(np.median(zero[done])) if done.any() else math.nan
            out[f"{task}_final_error"] = float(self.prediction_error[:, -1, i].mean())
            out[f"{task}_late_practice_share"] = float(
                self.practice[:, late, i].mean() / presses)
            out[f"{task}_final_press_probability"] = float(
                self.press_probability[:, -1, i].mean())
        out["late_reward_per_press"] = float(self.reward[:, late].mean() / presses)
        out["max_abs_value"] = float(self.max_abs_value[:, -1].max())
        out["median_abs_value"] = float(np.median(self.max_abs_value[:, -1]))
        return out


def panel_curves(result, every=1):
    """What the Figure 6 panel draws, as numbers: section 4.1's prediction error for
    each task per trial, the mean over the seeds with a 95% percentile-bootstrap band
    (which, unlike mean +/- t standard errors, never dips below an error of 0).

    Args:
      result: an `ActorCriticResult`.
      every: keep every `every`-th trial (and the last); each kept point's numbers do
        not depend on it.

    Returns:
      {"x": trials, "xlabel", "groups": [{"title", "ylabel", "series": {task: (mean,
      low, high)}}]}.
    """
    _validate.instance("result", result, ActorCriticResult,
                       "an ActorCriticResult (from icm.experiments.run_actor_critic)")
    keep = every_nth(result.n_trials, every)
    series = {task: bootstrap_band(result.prediction_error[:, keep, i],
                                   resamples=PANEL_RESAMPLES)
              for i, task in enumerate(TASKS)}
    return {"x": keep + 1, "xlabel": "trial",
            "groups": [{"title": f"Prediction error, {result.n_seeds} seeds",
                        "ylabel": "prediction error (mean, 95% band)", "series": series}]}
