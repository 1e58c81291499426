"""Software in the loop: the mission's Module-Tasks and automaton as C, in a controller process.

Split by job, each package importing only those below it (``pyproject.toml``, contract
``sil-by-job``):

- :mod:`.generate` — writing the controller's C, nothing built or run: each kind's C layout
  (:mod:`.generate.layout`), the mission's Module-Task table (:mod:`.generate.table`), the
  type-1 updates the controller applies itself (:mod:`.generate.adjust`), the mission's
  automaton and its binding header (:mod:`.generate.automaton`), the runtime library's files
  (:mod:`.generate.library`; the library itself is ``orccad_app/sil/c``, C99, no allocation,
  no recursion);
- :mod:`.build` — compiling it: the C compiler, cached by content (:mod:`.build.compiler`), the
  controller executable of a plan (:mod:`.build.executable`);
- :mod:`.controller` — speaking to the running controller: the process over a Unix socket with
  its heartbeat (:mod:`.controller.process`), the Module-Task proxies the executive drives
  (:mod:`.controller.remote`), the mission's automaton stepped in it
  (:mod:`.controller.automaton`);
- :mod:`.lockstep` — ``orccad sil --lockstep``: every job computed by the controller, one
  exchange per job, the executive's timing model;
- :mod:`.realtime` — ``orccad sil --realtime``: the controller's threads on the wall clock, this
  process the plant server over shared memory;
- :mod:`.runs` — how ``orccad sil`` runs through the run façade.

See docs/deploy.md.
"""
