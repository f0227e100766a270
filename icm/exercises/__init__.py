"""Exercises: checks that run a student's piece of a learner on generated cases (the
paper's edge cases first) against the library's reference, and say which case failed,
with its input, the expected and the given result, and a hint."""
