"""The mission layer: between the compiled automaton and the timed executive.

Data flows one way: a command compiles a mission (:mod:`orccad_app.pipeline`, a
:class:`~orccad_app.robottask.composition.Composition`), the mission layer plans it
(:mod:`.plan`: one TCS for every ``run`` site, through :mod:`.tcs_bridge`; the plants), runs
it (:mod:`.run`: the automaton reacts, the executive runs the TCS, :mod:`.injection` raises
inputs and faults at given instants) and reports (:mod:`.result`), observed through
:mod:`.observer`. The executive (:mod:`orccad_app.executive`) knows nothing of missions.

Import the modules themselves (``from orccad_app.mission.run import MissionRun``): the package
imports nothing, so that readers of a run's result (:mod:`orccad_app.trace`) do not load the
compiler front end.
"""
