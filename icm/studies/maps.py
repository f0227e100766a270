"""What a study of robustness maps measured for one learner (`RobustnessResult`, from
`icm.studies.robustness.run_robustness` or the study "robustness"'s file): every seed's
claims at every point of the maps of its pairs of settings, read as shares with their
95% intervals, verdicts ("holds", "unclear", "fails"), tables of a pair's map, and the
interactions of two settings."""

import dataclasses

import numpy as np

from icm import _validate
from icm.stats import VERDICTS, bootstrap_band, share_interval, verdict

INTERACTION_ALPHA = 0.05
"""How often a whole map may show an interaction that is not there: the bands of
`RobustnessResult.interaction` are at the level 1 - INTERACTION_ALPHA / (points)."""


INTERACTION_RESAMPLES = 2000
"""Bootstrap resamples of the interaction bands (their level is high: see
`RobustnessResult.interaction`)."""


@dataclasses.dataclass(frozen=True)
class RobustnessResult:
    """What `run_robustness` measured for one study.

    Attributes:
      study: the learner's `icm.studies.robustness.Study`.
      settings: the arguments of the run (n_seeds, seed).
      frames: {(setting, setting): DataFrame}, the sweep of each pair (the other
        settings at their defaults): one row per grid point and seed, with the
        settings, `seed_index` and a boolean column per claim.
    """

    study: object
    settings: dict
    frames: dict
    _cache: dict = dataclasses.field(default_factory=dict, init=False, repr=False,
                                     compare=False)

    @property
    def n_seeds(self):
        """Seeds per grid point."""
        return self.settings["n_seeds"]

    def points(self):
        """One row per measured grid point (points shared by two pairs' sweeps, which
        ran the same seeds, once): every setting's value, the seeds, and per claim the
        share of seeds in which it held (`<claim>`), its 95% interval (`<claim>_low`,
        `<claim>_high`) and the verdict (`<claim>_verdict`)."""
        if "points" not in self._cache:
            self._cache["points"] = self._points()
        return self._cache["points"].copy()

    def _points(self):
        import pandas as pd

        names = [s.name for s in self.study.settings]
        rows = self._seed_rows()
        claims = [c.name for c in self.study.claims]
        grouped = rows.groupby(names, sort=False)
        table = grouped[claims].agg(["sum", "count"])
        out = pd.DataFrame(index=table.index)
        for claim in self.study.claims:
            successes = table[(claim.name, "sum")].to_numpy().astype(np.int64)
            n = table[(claim.name, "count")].to_numpy().astype(np.int64)
            low, high = share_interval(successes, n)
            out["n_seeds"] = n
            out[claim.name] = successes / n
            out[claim.name + "_low"] = low
            out[claim.name + "_high"] = high
            out[claim.name + "_verdict"] = [verdict(lo, hi, claim.threshold)
                                            for lo, hi in zip(low, high)]
        return out.reset_index()

    def _point(self, point):
        point = {**self.study.defaults(), **point}
        for name, value in point.items():
            setting = self.study.setting(name)
            _validate.one_of(name, value, setting.values)
        table = self.points()
        match = np.ones(len(table), dtype=bool)
        for name, value in point.items():
            match &= (table[name] == value).to_numpy()
        if not match.any():
            varied = {n: v for n, v in point.items() if v != self.study.setting(n).default}
            raise ValueError(f"the point {varied} was not measured: at most two settings "
                             f"differ from their defaults in a map of pairs")
        return table[match].iloc[0]

    def share(self, claim, **point):
        """(share, low, high): the share of seeds in which `claim` held at `point`
        (settings not given at their defaults), with its 95% interval.

        Raises:
          ValueError: for an unknown claim or setting, a value off the grid, or a point
            that changes more than two settings.
        """
        claim = self.study.claim(claim).name
        row = self._point(point)
        return (float(row[claim]), float(row[claim + "_low"]), float(row[claim + "_high"]))

    def verdict(self, claim, **point):
        """"holds", "unclear" or "fails": what `point` says about `claim` (see
        `share`)."""
        claim = self.study.claim(claim).name
        return str(self._point(point)[claim + "_verdict"])

    def pair_table(self, claim, pair):
        """The map of `claim` over `pair` (the other settings at their defaults), as a
        dict of arrays [second setting's value, first setting's value]: "share",
        "low", "high" (its 95% interval) and "verdict"."""
        claim = self.study.claim(claim)
        held = self.seed_table(claim.name, pair)
        successes = held.sum(axis=0)
        low, high = share_interval(successes, np.full_like(successes, held.shape[0]))
        verdicts = np.array([verdict(lo, hi, claim.threshold)
                             for lo, hi in zip(low.ravel(), high.ravel())], dtype=object)
        return {"share": successes / held.shape[0], "low": low, "high": high,
                "verdict": verdicts.reshape(successes.shape)}

    def holding_values(self, claim, setting):
        """The values of `setting` at which `claim` holds, the other settings at their
        defaults, in grid order."""
        setting = self.study.setting(setting)
        return [v for v in setting.values if self.verdict(claim, **{setting.name: v})
                == "holds"]

    def holds_from(self, claim, setting):
        """The value of `setting` (the others at their defaults) from which `claim`
        holds at every larger value of the grid and at no smaller one; None when the
        values at which it holds are not such a tail of the grid (or are none)."""
        values = list(self.study.setting(setting).values)
        held = self.holding_values(claim, setting)
        for i in range(len(values)):
            if held == values[i:]:
                return values[i]
        return None

    def seed_table(self, claim, pair):
        """[seed, second setting's value, first setting's value], whether `claim`
        held in each seed at each point of the map of `pair` (a boolean array)."""
        claim = self.study.claim(claim).name
        pair = self._check_pair(pair)
        a, b = (self.study.setting(n) for n in pair)
        rows = self._seed_rows()
        for name, value in self.study.defaults().items():
            if name not in pair:
                rows = rows[rows[name] == value]
        out = np.zeros((self.n_seeds, len(b.values), len(a.values)), dtype=bool)
        column = {v: j for j, v in enumerate(a.values)}
        line = {v: i for i, v in enumerate(b.values)}
        out[rows["seed_index"].to_numpy(), rows[b.name].map(line).to_numpy(),
            rows[a.name].map(column).to_numpy()] = rows[claim].to_numpy(bool)
        return out

    def interaction(self, claim, pair):
        """How much the two settings of `pair` interact for `claim`, at every point of
        their map.

        The interaction at (a, b) is the classic contrast of the shares,
        share(a, b) - share(a, b0) - share(a0, b) + share(a0, b0) (a0, b0: the
        defaults): how far changing both moves the share from what changing each
        alone predicts. It is 0 where the two effects add up. Its band is a
        percentile bootstrap over the seeds (`icm.stats.bootstrap_band`, the seeds
        resampled together at all points, since every point ran the same seeds), at
        the level 1 - `INTERACTION_ALPHA` / (number of points), so that the whole map,
        not each point, is wrong less than that share of the time.

        Returns:
          A dict of arrays [second setting's value, first setting's value]:
          "contrast", "low", "high".
        """
        pair = self._check_pair(pair)
        key = ("interaction", self.study.claim(claim).name, pair)
        if key in self._cache:
            return self._cache[key]
        held = self.seed_table(claim, pair).astype(float)
        a, b = (self.study.setting(n) for n in pair)
        ia, ib = a.values.index(a.default), b.values.index(b.default)
        contrast = (held - held[:, :, [ia]] - held[:, [ib], :]
                    + held[:, [ib], :][:, :, [ia]])
        level = 1 - INTERACTION_ALPHA / contrast[0].size
        mean, low, high = bootstrap_band(contrast, level=level, resamples=INTERACTION_RESAMPLES,
                                         seed=self.settings["seed"])
        self._cache[key] = {"contrast": mean, "low": low, "high": high}
        return self._cache[key]

    def interacts(self, claim, pair):
        """Whether the settings of `pair` interact for `claim`: the band of the
        interaction (see `interaction`) excludes 0 at some point of their map."""
        found = self.interaction(claim, pair)
        return bool(np.any((found["low"] > 0) | (found["high"] < 0)))

    def strongest_interaction(self, claim, pair):
        """(contrast, low, high, a, b): the interaction of largest size on the map of
        `pair` for `claim`, its band, and the values of the pair's two settings there
        (see `interaction`)."""
        pair = self._check_pair(pair)
        found = self.interaction(claim, pair)
        i, j = np.unravel_index(np.argmax(np.abs(found["contrast"])), found["contrast"].shape)
        a, b = (self.study.setting(n) for n in pair)
        return (float(found["contrast"][i, j]), float(found["low"][i, j]),
                float(found["high"][i, j]), a.values[j], b.values[i])

    def _check_pair(self, pair):
        if not isinstance(pair, (tuple, list)) or tuple(pair) not in self.frames:
            raise ValueError(f"pair must be one of {list(self.frames)}, got {pair!r}")
        return tuple(pair)

    def _seed_rows(self):
        """Every seed's row at every measured point, the settings all filled in."""
        if "rows" in self._cache:
            return self._cache["rows"]
        import pandas as pd

        names = [s.name for s in self.study.settings]
        defaults = self.study.defaults()
        tables = [frame.assign(**{n: defaults[n] for n in names if n not in frame.columns})
                  for frame in self.frames.values()]
        self._cache["rows"] = pd.concat(tables).drop_duplicates(names + ["seed_index"])
        return self._cache["rows"]

    def summary(self):
        """The numbers the book quotes, as a dict: for each claim, its share of seeds
        at the defaults (`<claim>`), the lowest and highest share on the whole map
        (`<claim>_min`, `<claim>_max`), and how many grid points it holds, fails or
        is unclear at (`<claim>_holds`, `_fails`, `_unclear`); and `n_points`, the
        grid points measured."""
        table = self.points()
        out = {"n_points": len(table), "n_seeds": self.n_seeds}
        for claim in self.study.claims:
            out[claim.name] = self.share(claim.name)[0]
            out[claim.name + "_min"] = float(table[claim.name].min())
            out[claim.name + "_max"] = float(table[claim.name].max())
            for v in VERDICTS:
                out[f"{claim.name}_{v}"] = int((table[claim.name + "_verdict"] == v).sum())
        return out
