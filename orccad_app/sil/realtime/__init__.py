"""``orccad sil --realtime``: the controller's threads on the wall clock, this process the plant
server over shared memory (:mod:`.run`), the memory's layout (:mod:`.shared`) and the jobs'
records handed to the trace (:mod:`.job_trace`)."""
