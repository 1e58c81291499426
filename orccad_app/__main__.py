"""``python -m orccad_app``: the ``orccad`` command, for environments without the script."""

import sys

from orccad_app.cli import main

if __name__ == "__main__":
    sys.exit(main())
