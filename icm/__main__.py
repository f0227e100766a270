"""`python -m icm`: see icm.cli."""

import sys

from icm.cli import main

sys.exit(main())
