"""Progress bars for long runs: tqdm in terminals and notebooks, shown only for runs
that last longer than a second."""


def progress_bar(iterable, total, description, enabled=True, unit="seed"):
    """Wraps `iterable` in a tqdm progress bar (tqdm.auto: a widget in notebooks, text in
    terminals) if `enabled`; the bar appears only after one second, so quick runs stay
    quiet.

    Raises:
      ValueError: if `enabled` is not True or False.
    """
    if not isinstance(enabled, bool):
        raise ValueError(f"progress must be True or False, got {enabled!r}")
    if not enabled:
        return iterable
    from tqdm.auto import tqdm

    return tqdm(iterable, total=total, desc=description, unit=unit, delay=1.0)
