"""``python -m orccad_app``: the ``orccad`` command, for environments without the script."""

import sys

try:
    from orccad_app.cli import entry_point
except KeyboardInterrupt:  # Ctrl-C in the very first instants: no traceback either
    print("orccad: interrupted", file=sys.stderr)
    sys.exit(130)

if __name__ == "__main__":
    entry_point()
