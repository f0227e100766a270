"""The long studies of the chapter "Forming actions", in one package: the arms every one
of them runs, a variant of the goal-babbling learner or a condition (growing up, being
shown), and the run that measures one (`arms`); the study "goal-babbling" of the
learner's variants (`strategies`); and the studies "remedies" and
"remedies-replication" of the two remedies (`remedies`). Each registers its studies
beside its units (`icm.studies.registry`), and reads its own files."""

from icm.studies.forming_actions import arms, remedies, strategies

__all__ = ["arms", "remedies", "strategies"]
