/* orccad_rt_lifecycle.c: the Robot-Tasks' lifecycle on the real-time runtime's Module-Tasks,
 * as the automaton task (orccad_rt_automaton.c) and the supervisor's commands
 * (orccad_rt_main.c) apply it: a fresh start (nominal parameters), INIT, a type-1 parameter
 * update, ACTIVATE (the first release at an instant), KILL (the unfinished job aborted, its
 * wait on a port forgotten) and RESET (its ports back to "before any write"). Called under
 * orc_rt_lock; a change to a Module-Task's memory waits for its compute (which runs outside the
 * lock) to end. Part of the ORCCAD runtime library; C99 + POSIX threads; no allocation, no
 * recursion. */
#include <pthread.h>
#include <stdint.h>

#include "orccad_mt.h"
#include "orccad_port.h"
#include "orccad_rt.h"
#include "orccad_rt_task.h"
#include "orccad_wire.h"

/* Until Module-Task m's compute (outside the lock) has ended: a command touching its memory
 * waits for it. */
static void wait_compute(int m)
{
    while (orc_rt_task(m)->computing) {
        pthread_cond_wait(&orc_rt_changed, &orc_rt_lock);
    }
}

void orc_rt_reset_ports(int m)
{
    int c;
    for (c = 0; c < ORC_N_CONNECTIONS; c++) {
        if (ORC_CONNECTIONS[c].src_module == m || ORC_CONNECTIONS[c].dst_module == m) {
            orc_port_reset(orc_rt_port(c), ORC_CONNECTIONS[c].protocol);
        }
    }
}

/* Module-Task m killed: its unfinished job aborted, its wait on a port forgotten. */
void orc_rt_kill(int m)
{
    rt_task *t = orc_rt_task(m);
    t->generation += 1;
    if (t->phase != JOB_IDLE && t->job_traced) {
        orc_rt_record_job(m, -1, 0); /* aborted */
    }
    if (t->phase != JOB_IDLE && t->waiting) {
        orc_port_cancel(orc_rt_port(orc_rt_job_connection(m)), t->phase == JOB_READING);
    }
    t->active = 0;
    t->phase = JOB_IDLE;
    t->waiting = 0;
}

/* Module-Task m activated: its first release at release_ns. */
void orc_rt_activate(int m, int64_t release_ns)
{
    rt_task *t = orc_rt_task(m);
    wait_compute(m);
    orc_mt_init(&ORC_INSTANCES[m]);
    orc_rt_kill(m);
    t->active = 1;
    t->next_release_ns = release_ns;
    if (ORC_MODULES[m].sporadic) { /* released by its first interrupt */
        t->next_release_ns = INT64_MAX;
        t->last_release_ns = INT64_MIN;
    }
}

int orc_rt_active(int m)
{
    return orc_rt_task(m)->active;
}

void orc_rt_fresh(int m)
{
    wait_compute(m);
    orc_mt_load(&ORC_INSTANCES[m], &ORC_MODULES[m]);
    orc_mt_init(&ORC_INSTANCES[m]);
}

void orc_rt_set_param(int m, int offset, double value)
{
    wait_compute(m);
    (void)orc_mt_set_param(&ORC_INSTANCES[m], offset, &value, 1);
}

double orc_rt_get_param(int m, int offset)
{
    return ORC_INSTANCES[m].p[offset];
}

uint32_t orc_rt_set_params(int m, int offset, const double *values, int n)
{
    wait_compute(m);
    return orc_mt_set_param(&ORC_INSTANCES[m], offset, values, n) ? ORC_BAD_PARAMS : ORC_OK;
}

void orc_rt_init(int m)
{
    wait_compute(m);
    orc_mt_init(&ORC_INSTANCES[m]);
}
