"""Compiling the controller: the project's own build step (the C compiler, cached by content)
and the controller executable of a plan (what :mod:`orccad_app.sil.generate` writes, with the
runtime library)."""
