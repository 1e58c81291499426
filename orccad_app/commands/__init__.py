"""Sub-commands of the ``orccad`` CLI, one module each (see :mod:`orccad_app.cli`)."""
