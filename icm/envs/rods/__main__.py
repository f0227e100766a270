"""`python -m icm.envs.rods`: measures the topple map in physics (see `measure.main`)."""

from icm.envs.rods.measure import main

main()
