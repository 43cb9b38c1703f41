"""``python -m tcarod`` runs the command line (see :mod:`tcarod.cli`)."""

import sys

from .cli import main

sys.exit(main())
