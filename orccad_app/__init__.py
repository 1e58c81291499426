"""ORCCAD: reactive and real-time robot controller design.

Layers (imports go one way): ``lang → reactive → robottask/verify → tcs/executive →
trace → cli/tui``. The core imports without Textual.
"""

__all__ = ["__version__"]

__version__ = "0.1.0"
