"""Helpers shared by the experiments' results: checking a dict of labelled results
(what the chapters' tables and the figures take); and, until the chapter "The simulated
iCub" reads it from `icm.chapters`, the check that stops a build whose run contradicts
a claim of its chapter (`require`)."""

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


class ClaimFailed(AssertionError):
    """A claim the book states in words did not hold in the run it is stated about."""


def require(claims, texts):
    """Raises `ClaimFailed`, naming them in words, if any of `claims` ({name: bool},
    from a result's `claims()`) is false: the chapters call it on their own runs, so
    that the book is not built with a sentence its numbers contradict.

    Args:
      claims: {claim name: whether it holds}.
      texts: {claim name: the claim in words}.

    Returns:
      The names of the claims checked.
    """
    if not isinstance(claims, dict) or not claims:
        raise _validate.ArgumentTypeError(f"claims must be a non-empty dict of claim name "
                                          f"to bool, got {_validate.show(claims)}")
    failed = [texts.get(name, name) for name, held in claims.items() if not held]
    if failed:
        raise ClaimFailed("the chapter states what its run contradicts: "
                          + "; ".join(failed))
    return list(claims)

