/* orccad_io.h: the robot's I/O as the real-time runtime (orccad_rt*.c) uses it.
 *
 * Write these functions for your hardware to put the generated controller on a robot
 * (docs/deploy.md); `orccad sil --realtime` links orccad_io_shm.c, which implements them over
 * the plant server's shared memory. Called from the processor threads: they must not block
 * for long, and must be safe to call from several threads.
 *
 * Robot port k is ORC_ROBOT_PORTS[k] ("arm.q", "arm.tau"), of ORC_ROBOT_PORTS[k].dim doubles
 * in the robot type's units ([rad], [rad/s], [N·m]). */
#ifndef ORCCAD_IO_H
#define ORCCAD_IO_H

#include "orccad_mt.h"

/* 0 on success; -1 if it cannot start (the controller then exits with status 2). `where`
 * is the argument after --io on the command line (the shared memory's path in SIL). */
int orc_io_open(const char *where);
/* The current value of sensor port k into `into` (present = 0 while none is available). */
void orc_io_read_sensor(int k, orc_value *into);
/* Apply `value` to actuator port k (held until the next write). */
void orc_io_write_actuator(int k, const orc_value *value);
/* The instant of the run's t = 0 [ns, CLOCK_MONOTONIC], when the I/O side decides it
 * (SIL: the plant server's); return `fallback` otherwise. */
long long orc_io_epoch_ns(long long fallback);
/* Publish Module-Task m's measured timing and outputs (SIL: to the plant server). */
void orc_io_publish(int m, const orc_mt *mt, long long released, long long overruns,
                    long long misses, long long events, double response_max_ns);
void orc_io_lateness(int m, double lateness_ns);
/* Publish one reaction of the mission's automaton: its request's `n_request` words and its
 * reply's `n_reply` (orccad_automaton.h; SIL: to the plant server, which applies the
 * Robot-Tasks' lifecycle it decides). Called from the automaton task. */
void orc_io_reaction(const double *request, unsigned n_request, const double *reply,
                     unsigned n_reply);

/* One job of a Module-Task as measured, for a trace: instants [ns] on the run's clock (from
 * its t = 0), -1 where not reached. */
typedef struct {
    long long job;            /* its index, 0-based, counted over the run */
    long long release_ns;     /* its release (of an overrun: the release skipped) */
    long long start_ns;       /* its compute begins (its inputs read) */
    long long compute_end_ns; /* its compute ends: it writes its outputs */
    long long finish_ns;      /* its outputs written (-1: aborted, its Module-Task killed) */
    int missed;               /* finished after its deadline (the period) */
    int overrun;              /* 1: a release skipped while job `job` was unfinished */
} orc_job;
/* Record Module-Task m's job (at its finish or abort) or a skipped release (at once); called
 * under the runtime's lock, in order per Module-Task, only while orc_io_jobs_wanted()
 * (SIL: a ring in the shared memory, which the plant server hands to the trace). */
int orc_io_jobs_wanted(void);
void orc_io_job(int m, const orc_job *job);

#endif
