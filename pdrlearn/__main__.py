"""``python -m pdrlearn`` runs the command-line interface (same as the ``pdrlearn`` script)."""

import sys

from pdrlearn.cli import main

if __name__ == "__main__":
    sys.exit(main())
