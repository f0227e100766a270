"""Memory guards of the run functions: each run function computes, from the shapes of
its run, an upper bound on the memory the run will add to the process, and refuses
before allocating anything a run that the machine could not hold.

Each bound is the sum of the arrays the run holds at its peak, in bytes, counted from
their shapes, plus a few per-row allowances measured once (a Python object per row, a
trial's temporaries); `tests/test_memory.py` runs each function at mid sizes in a fresh
process and checks that the peak it adds (the resident set above what the process held
once its code was loaded) is below the bound and above two thirds of it. Code loaded
once per process (Numba's compiled loop, about 180 MB on the first tabular rods run;
MuJoCo's first scene) is not counted: it does not grow with the sizes that the guards
refuse.
"""

from icm import _validate

FIXED_BYTES = 1_000_000
"""An allowance, in every bound, for what a run holds whatever its sizes: small tables,
a progress bar, the interpreter's own allocations."""
PHYSICS_SCENE_BYTES = 3_000_000
"""An upper bound on one simulated iCub scene (a button console or a rod table: its
MuJoCo model, data and Python objects), measured at 2.6 to 2.9 MB a row."""


def check_memory(function, sizes, needed):
    """Raises ValueError, before anything is allocated, if a call of `function` of the
    given `sizes` ({argument: value}, named in the message) would need `needed` bytes,
    more than the machine has available (see `icm._validate.fits_in_memory`)."""
    described = ", ".join(f"{name}={value}" for name, value in sizes.items())
    _validate.fits_in_memory(f"{function} with {described}", needed)
