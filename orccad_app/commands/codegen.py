"""``orccad codegen FILE [--mission M] [-o DIR] [--name PREFIX] [--main] [--module-tasks]
[--controller] [--generator auto|explicit|circuit]``: C99 of the composed mission automaton
(see ``docs/deploy.md``), or of its circuit (``--generator``,
:func:`orccad_app.codegen.mission.generate_chosen`).

Writes ``PREFIX.h`` and ``PREFIX.c`` (and, with ``--main``, ``PREFIX_main.c``, a program
that runs the automaton on an input script and prints what ``orccad react --composed
--jsonl`` prints; with ``--module-tasks``, the Module-Tasks' table ``orccad_modules.c`` and
the C runtime, :mod:`orccad_app.sil.generate.table`) into the folder ``DIR`` (default: ``PREFIX``),
all or nothing. With ``--controller``, the whole controller as a C tree with its ``Makefile``
and ``CMakeLists.txt`` (:mod:`orccad_app.sil.generate.tree`; default folder
``PREFIX_controller``), the user's ``orccad_io.c`` in it left alone.
"""

from __future__ import annotations

import argparse

from orccad_app.commands.arguments import add_file, add_max_states, add_mission

__all__ = ["register"]


def register(sub) -> None:
    parser = sub.add_parser(
        "codegen", help="generate C99 for a mission's composed automaton",
        description="Generate C99 for the composed mission automaton (the one orccad check "
                    "proves): PREFIX.h, PREFIX.c and, with --main, PREFIX_main.c.")
    add_file(parser)
    add_mission(parser)
    parser.add_argument("-o", "--output", metavar="DIR",
                        help="the output folder: new, empty, or holding only the files "
                             "written (default: PREFIX)")
    parser.add_argument("--name", metavar="PREFIX",
                        help="prefix of the files and C identifiers (default: the mission's "
                             "name in snake case, e.g. arm_recovery)")
    parser.add_argument("--main", action="store_true",
                        help="also write PREFIX_main.c: runs the automaton on an input script "
                             "and prints what 'orccad react --composed --jsonl' prints")
    parser.add_argument("--module-tasks", action="store_true",
                        help="also write the Module-Tasks of every Robot-Task the mission runs "
                             "(orccad_modules.c) and the C runtime that runs them on threads "
                             "(see docs/deploy.md, part 2)")
    parser.add_argument("--generator", choices=("auto", "explicit", "circuit"),
                        default="auto",
                        help="explicit: the automaton's reaction trees (the fastest step, "
                             "but its size is the product of parallel branches); circuit: "
                             "registers and BDDs (grows with the mission's text); auto "
                             "(default): the circuit unless the explicit C is no larger. "
                             "The header says which was written, and why")
    parser.add_argument("--controller", action="store_true",
                        help="write the whole controller as a C tree built without ORCCAD: "
                             "the generated tables, the runtime, the plugins' C, a Makefile "
                             "and a CMakeLists.txt (make: ./controller for orccad sil; make "
                             "robot: with your orccad_io.c, which is never written); see "
                             "docs/deploy.md")
    add_max_states(parser)
    parser.set_defaults(func=run)


def _controller(args: argparse.Namespace, source, mission) -> int:
    """``--controller``: the controller tree of the mission (:mod:`orccad_app.sil.generate.tree`)."""
    from orccad_app.codegen.names import default_prefix
    from orccad_app.codegen.output import write_files
    from orccad_app.diagnostics import OrccadError
    from orccad_app.mission.plan import plan_mission
    from orccad_app.sil.generate.automaton import mission_automaton
    from orccad_app.sil.generate.tree import controller_tree, user_file

    if args.main or args.module_tasks or args.name is not None:
        raise OrccadError("--controller writes the whole controller tree: it takes no --main, "
                          "--module-tasks or --name")
    plan = plan_mission(source, mission)
    program = mission_automaton(plan, args.max_states).program
    files = controller_tree(plan, program, args.file)
    folder = default_prefix(mission.name) + "_controller" if args.output is None else args.output
    for path in write_files(folder, files, keep=user_file):
        print(path)
    return 0


def run(args: argparse.Namespace) -> int:
    from orccad_app.codegen.driver import main_source
    from orccad_app.codegen.mission import generate_chosen
    from orccad_app.codegen.names import check_prefix, default_prefix
    from orccad_app.codegen.output import write_files
    from orccad_app.pipeline import compose_mission, load, select_mission

    if args.output is not None and not args.output.strip():
        from orccad_app.diagnostics import OrccadError
        raise OrccadError("-o/--output: an empty name (name a folder, or leave the flag out: "
                          "PREFIX)")
    source = load(args.file)
    source.print_warnings()
    mission = select_mission(source, args.mission)
    if args.controller:
        return _controller(args, source, mission)
    prefix = check_prefix(args.name if args.name is not None else default_prefix(mission.name))
    generator = args.generator
    if args.module_tasks:  # the C runtime reports the automaton's state numbers
        if generator == "circuit":
            from orccad_app.diagnostics import OrccadError
            raise OrccadError("--module-tasks runs the explicit automaton (its runtime reports "
                              "state numbers): leave out --generator circuit")
        generator = "explicit"
    composition = compose_mission(source, mission, max_states=args.max_states, lazy=True)
    program = generate_chosen(composition, prefix,
                              origin=f" from {args.file}, mission {mission.name}",
                              generator=generator, max_states=args.max_states)
    files = dict(program.files)
    if args.main:
        files[f"{prefix}_main.c"] = main_source(program)
    if args.module_tasks:
        from orccad_app.mission.plan import plan_mission
        from orccad_app.sil.generate.automaton import binding_header
        from orccad_app.sil.generate.table import module_table, module_task_files

        plan = plan_mission(source, mission)
        files.update(module_task_files(plan, args.file))
        files["orccad_automaton_binding.h"] = binding_header(program, plan, module_table(plan))
    for path in write_files(prefix if args.output is None else args.output, files):
        print(path)
    return 0
