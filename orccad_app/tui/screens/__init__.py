"""Screens of the terminal UI: the mission browser, the run, the report."""
