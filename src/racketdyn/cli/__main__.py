"""``python -m racketdyn.cli``."""

import sys

from racketdyn.cli import main

sys.exit(main())
