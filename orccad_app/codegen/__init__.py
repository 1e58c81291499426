"""C99 from a compiled automaton (``orccad codegen``): types, expressions, the step function,
the documented header, the script-driven ``main`` and the all-or-nothing writer."""
