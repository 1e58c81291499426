/* orccad_rt_task.h: the real-time runtime's state of each Module-Task and of its current job,
 * internal to the runtime: orccad_rt.c owns it (the processor threads run the jobs through
 * it), orccad_rt_lifecycle.c applies the Robot-Tasks' lifecycle to it, orccad_rt_record.c
 * records its jobs for the trace and orccad_rt_deadlock.c searches it for jobs waiting on
 * each other. Read and written under orc_rt_lock (orccad_rt.h). C99 + POSIX threads. */
#ifndef ORCCAD_RT_TASK_H
#define ORCCAD_RT_TASK_H

#include <stdint.h>

#include "orccad_port.h"

/* The state of one Module-Task in the runtime, and of its current job. */
typedef struct {
    int active;
    int64_t next_release_ns;  /* absolute, CLOCK_MONOTONIC; INT64_MAX: none due (sporadic) */
    int64_t last_release_ns;  /* sporadic: the previous release (INT64_MIN: none yet) */
    int64_t released, overruns, misses, events;
    double response_max_ns;
    int phase;                /* JOB_IDLE, JOB_READING (its inputs), JOB_WRITING */
    int at;                   /* the next input slot to read, or write to do */
    int waiting;              /* blocked on that read or write (a port protocol) */
    int64_t job_release_ns;   /* the current job's release */
    int64_t job_start_ns;     /* its compute's start, end (-1: not yet), for the trace */
    int64_t job_compute_end_ns;
    int job_traced;           /* its life cycle is recorded (orc_io_jobs_wanted at release) */
    int computing;            /* its compute runs, outside the runtime's lock */
    unsigned generation;      /* changed by a kill or an activation: a job computing across
                                 one is aborted */
} rt_task;

enum { JOB_IDLE = 0, JOB_READING = 1, JOB_WRITING = 2 };

/* Module-Task m's state; connection c's port (the table's ORC_CONNECTIONS[c]). */
rt_task *orc_rt_task(int m);
orc_port *orc_rt_port(int c);
/* The connection of the read (phase JOB_READING) or the write (JOB_WRITING) m's job is at. */
int orc_rt_job_connection(int m);
/* The trace's record of m's current job (finish_ns -1: aborted), and of m's release at
 * release_ns skipped (an overrun, its current job unfinished) (orccad_rt_record.c). */
void orc_rt_record_job(int m, int64_t finish_ns, int missed);
void orc_rt_record_overrun(int m, int64_t release_ns);

#endif
