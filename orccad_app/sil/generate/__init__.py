"""Writing the controller's C: each kind's layout, the Module-Task table, the type-1 updates
the controller applies itself, the mission's automaton and the runtime library's files.
Nothing here compiles or runs anything (docs/deploy.md)."""
