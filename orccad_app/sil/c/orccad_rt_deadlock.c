/* orccad_rt_deadlock.c: the real-time runtime's deadlock search, answered with each heartbeat
 * (OP_PING, orccad_rt_main.c): a cycle of jobs each blocked by a port protocol on the next
 * one's operation. Part of the ORCCAD runtime
 * library; called under orc_rt_lock. C99 + POSIX threads; no allocation, no recursion. */
#include <stdint.h>

#include "orccad_mt.h"
#include "orccad_port.h"
#include "orccad_rt.h"
#include "orccad_rt_task.h"
#include "orccad_wire.h"

/* The Module-Task whose operation alone releases m's job (-1: m's job does not wait), and
 * the connection and direction of the wait. */
static int waits_for(int m, int *connection, int *reading)
{
    const rt_task *t = orc_rt_task(m);
    int c;
    if (!t->active || t->phase == JOB_IDLE || !t->waiting) {
        return -1;
    }
    *reading = t->phase == JOB_READING;
    c = orc_rt_job_connection(m);
    *connection = c;
    if (*reading ? orc_rt_port(c)->reader_free : orc_rt_port(c)->writer_free) {
        return -1; /* released already: it goes on at its thread's next look */
    }
    return *reading ? ORC_CONNECTIONS[c].src_module : ORC_CONNECTIONS[c].dst_module;
}

/* A cycle of jobs waiting on each other (the executive's deadlock, docs/executive.md): its
 * entries [module, connection, reading] into `cycle`; the number of doubles (0: none). */
uint32_t orc_rt_deadlock(double *cycle)
{
    int m;
    for (m = 0; m < ORC_N_MODULES; m++) {
        int at = m, steps, c, reading;
        for (steps = 0; steps <= ORC_N_MODULES; steps++) {
            at = waits_for(at, &c, &reading);
            if (at < 0 || at == m) {
                break;
            }
        }
        if (at == m) {
            uint32_t n = 0;
            do {
                int next = waits_for(at, &c, &reading);
                orc_wire_put_int(&cycle[n++], at);
                orc_wire_put_int(&cycle[n++], c);
                orc_wire_put_int(&cycle[n++], reading);
                at = next;
            } while (at != m);
            return n;
        }
    }
    return 0;
}
