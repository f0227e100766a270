"""`python -m icm.chapters.robustness`, the command the chapter "What the result depends
on" names: reruns its maps on their fresh root and writes them into
assets/replications.json under "robustness", the other chapters' entries kept (the same
as `python -m icm.chapters.replicate robustness`)."""

from icm.chapters import replicate

if __name__ == "__main__":
    replicate.main(["robustness"])
