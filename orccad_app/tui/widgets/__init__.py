"""Widgets of the terminal UI (each in its own small module)."""
