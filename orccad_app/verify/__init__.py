"""Verification: temporal properties of missions model-checked on their composed automata.

One concept per module: :mod:`.formula` (core LTL with past), :mod:`.lasso` (reference
semantics on lassos), :mod:`.data` (the data abstraction), :mod:`.model` (the model: steps and fairness),
:mod:`.letters` (the meaning of atoms in an instant), :mod:`.tableau` (LTL with past to a
generalized Büchi tableau), :mod:`.search` (emptiness of the product: fair accepting lassos).
"""
