"""``python -m medialaxis`` runs the command line."""

import sys

from medialaxis.cli import main

sys.exit(main())
