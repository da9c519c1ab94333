"""``python -m medialaxis`` runs the command line."""

import sys

from medialaxis._entry import run

sys.exit(run())
