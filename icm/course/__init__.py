"""The course around the book: assignments generated from the chapters' exercises and
graded by otter-grader, with hidden tests (`python -m icm.course assign`, `grade`),
the in-page questions exported for a learning platform (`lms`), and one slide deck
per chapter from the built book (`slides`)."""
