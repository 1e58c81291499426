"""Shared by every test process (the pytest-xdist workers too)."""

from __future__ import annotations

import signal
import threading

# Tests send Ctrl-C (SIGINT) to the commands they start and expect the command's answer to it.
# A suite launched with SIGINT ignored (a background job of a shell without job control) would
# pass that on to every command it starts, which then rightly keeps ignoring it, as Python does:
# the tests' processes take Ctrl-C's default back, so that their commands start with it.
if threading.current_thread() is threading.main_thread() and \
        signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
    signal.signal(signal.SIGINT, signal.default_int_handler)
