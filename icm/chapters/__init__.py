"""The chapters of the book, one module per chapter that states claims or quotes
numbers: its claims in words, their checks, its Markdown tables and the numbers its
text glues, computed from the results `icm.experiments` returns."""

from icm.chapters import curiosity, forming_actions, robustness

__all__ = ["curiosity", "forming_actions", "robustness"]
