/* orccad_rt_main.c: the real-time controller's main, configured from its command line:
 *
 *   controller --fd N --io WHERE   supervised (orccad sil --realtime): the commands thread
 *                                  reads the supervisor's socket (file descriptor N; the
 *                                  frames of orccad_wire.h), the robot's I/O opened at WHERE
 *   controller --io WHERE [--until S]
 *                                  alone, on the robot: the I/O opened at WHERE, the run's
 *                                  t = 0 now, the mission run to its end (or S seconds, or
 *                                  SIGINT/SIGTERM); exit 0 done, 1 failed/aborted/timeout,
 *                                  130 interrupted, 2 it cannot start
 *   controller --fd N --lockstep   (built with ORC_COMBINED_MAIN: orccad codegen --controller)
 *                                  the lockstep loop of orccad_lockstep.c
 *
 * The processor threads and the automaton task are started, every request applied under the
 * runtime's lock (orccad_rt.h), and the threads stopped and joined when the supervisor quits
 * or is gone (or the mission ends, alone). C99 + POSIX threads; no allocation. */
#define _POSIX_C_SOURCE 200809L
#include <pthread.h>
#include <sched.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "orccad_automaton.h"
#include "orccad_io.h"
#include "orccad_mt.h"
#include "orccad_rt.h"
#include "orccad_wire.h"

#define MODULE_DOUBLES (ORC_MAX_PARAMS + ORC_MAX_PORTS * (ORC_MAX_DIM + 1))
#define MAX_DOUBLES (MODULE_DOUBLES > ORC_AUTOMATON_IN_WORDS ? MODULE_DOUBLES \
                                                              : ORC_AUTOMATON_IN_WORDS)
#define MAX_ANSWER (3 * ORC_RT_MAX_MODULES + ORC_HELLO_DOUBLES + ORC_MAX_PARAMS)

static double data_in[MAX_DOUBLES];

static uint32_t command(const orc_request *req, double *answer, uint32_t *n)
{
    uint32_t i;
    *n = 0;
    if (req->op == OP_HELLO) {
        orc_automaton_reset();
        orc_wire_hello(answer);
        *n = ORC_HELLO_DOUBLES;
        return ORC_OK;
    }
    if (req->op == OP_PING) { /* the heartbeat, with the jobs deadlocked if any */
        *n = orc_rt_deadlock(answer);
        return ORC_OK;
    }
    if (req->op == OP_INPUT) { /* inputs for the automaton task, at their instant */
        return orc_automaton_input(data_in, req->n);
    }
    if (req->op == OP_EPOCH) { /* the I/O side's t = 0 (SIL: the plant server's): the
                                * automaton task starts its ticks */
        orc_rt_take_epoch();
        orc_automaton_start();
        return ORC_OK;
    }
    if (req->module >= (uint32_t)ORC_N_MODULES) {
        return ORC_NO_SUCH_MODULE;
    }
    switch (req->op) {
    case OP_START:
        orc_rt_fresh((int)req->module);
        return ORC_OK;
    case OP_PARAM:
        return orc_rt_set_params((int)req->module, (int)req->offset, data_in, (int)req->n);
    case OP_INIT:
        orc_rt_init((int)req->module);
        return ORC_OK;
    case OP_ACTIVATE: { /* every Module-Task in the data (or the request's one), their
                         * first release shared, as in the executive (their jobs read before
                         * any of them computes): at epoch + t_s, or now when that has passed
                         * (the plant server behind the wall clock is not the threads' lateness) */
        int64_t at = orc_rt_epoch_ns() + (int64_t)(req->t_s * 1e9 + 0.5), now = orc_rt_now_ns();
        for (i = 0; i < req->n; i++) { /* their indices: integer words */
            int64_t index = orc_wire_get_int(&data_in[i]);
            if (index < 0 || index >= ORC_N_MODULES) {
                return ORC_NO_SUCH_MODULE;
            }
        }
        if (req->n == 0) {
            orc_rt_activate((int)req->module, at > now ? at : now);
        }
        for (i = 0; i < req->n; i++) {
            orc_rt_activate((int)orc_wire_get_int(&data_in[i]), at > now ? at : now);
        }
        return ORC_OK;
    }
    case OP_KILL:
        orc_rt_kill((int)req->module);
        return ORC_OK;
    case OP_RESET:
        orc_rt_reset_ports((int)req->module);
        return ORC_OK;
    case OP_PARAMS: /* what the Module-Task computes with now (the type-1 updates applied) */
        for (i = 0; i < (uint32_t)ORC_MODULES[req->module].n_params; i++) {
            answer[i] = orc_rt_get_param((int)req->module, (int)i);
        }
        *n = i;
        return ORC_OK;
    default:
        return ORC_UNKNOWN_OP;
    }
}

#ifdef ORC_COMBINED_MAIN
int orc_lockstep_main(int fd);
#endif

static volatile sig_atomic_t interrupted;

static void on_signal(int sig)
{
    (void)sig;
    interrupted = 1;
}

/* Alone on the robot: t = 0 now, the mission run until it ends, `until_s` passes or a
 * signal comes; the exit status (see the top of this file). */
static int run_alone(double until_s)
{
    static const char *const said[] = {"running", "done", "failed", "aborted"};
    struct sigaction action;
    struct timespec pause;
    int64_t start;
    int status = 0;
    memset(&action, 0, sizeof action);
    action.sa_handler = on_signal;
    sigemptyset(&action.sa_mask);
    (void)sigaction(SIGINT, &action, NULL);
    (void)sigaction(SIGTERM, &action, NULL);
    pthread_mutex_lock(&orc_rt_lock);
    orc_rt_take_epoch();
    orc_automaton_start();
    start = orc_rt_now_ns();
    pthread_cond_broadcast(&orc_rt_changed);
    pthread_mutex_unlock(&orc_rt_lock);
    pause.tv_sec = 0;
    pause.tv_nsec = 10000000L;
    while (!interrupted && status == 0
           && (until_s <= 0.0 || (double)(orc_rt_now_ns() - start) < until_s * 1e9)) {
        nanosleep(&pause, NULL);
        pthread_mutex_lock(&orc_rt_lock);
        status = orc_automaton_status();
        pthread_mutex_unlock(&orc_rt_lock);
    }
    if (interrupted) {
        fprintf(stderr, "orccad controller: interrupted\n");
        return 130;
    }
    if (status < 0) {
        fprintf(stderr, "orccad controller: mission failed: a run-time error of the mission\n");
        return 1;
    }
    if (status == 0) {
        fprintf(stderr, "orccad controller: mission timeout after %g s\n", until_s);
        return 1;
    }
    fprintf(stderr, "orccad controller: mission %s after %.3f s\n", said[status & 3],
            (double)(orc_rt_now_ns() - start) / 1e9);
    return status == 1 ? 0 : 1;
}

static int usage(const char *name)
{
    fprintf(stderr, "usage: %s --io WHERE [--until S]    (alone, on the robot)\n"
                    "       %s --fd N --io WHERE        (started by orccad sil --realtime)\n",
            name, name);
    return 2;
}

int main(int argc, char **argv)
{
    pthread_t threads[ORC_RT_MAX_PROCESSORS], automaton;
    int fd = -1, p, i, warned = 0, status = 0;
    const char *io = NULL;
    double until_s = 0.0;
    orc_request req;
    static double answer[MAX_ANSWER];
    for (i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--fd") == 0 && i + 1 < argc) {
            fd = atoi(argv[++i]);
        } else if (strcmp(argv[i], "--io") == 0 && i + 1 < argc) {
            io = argv[++i];
        } else if (strcmp(argv[i], "--until") == 0 && i + 1 < argc) {
            char *end;
            until_s = strtod(argv[++i], &end);
            if (*end != '\0' || !(until_s > 0.0 && until_s <= 31536000.0)) {
                fprintf(stderr, "%s: --until %s: expected seconds in (0, 31536000]\n",
                        argv[0], argv[i]);
                return 2;
            }
#ifdef ORC_COMBINED_MAIN
        } else if (strcmp(argv[i], "--lockstep") == 0 && fd >= 0 && io == NULL) {
            return orc_lockstep_main(fd);
#endif
        } else {
            return usage(argv[0]);
        }
    }
    if (io == NULL || (fd >= 0 && until_s > 0.0)) {
        return usage(argv[0]);
    }
    if (fd < 0 && ORC_AUTOMATON_SUPERVISOR[0] != '\0') {
        fprintf(stderr, "%s: this mission still needs ORCCAD's supervisor (orccad sil "
                        "--realtime): %s (docs/deploy.md, Limits)\n", argv[0],
                ORC_AUTOMATON_SUPERVISOR);
        return 2;
    }
    if (orc_io_open(io) != 0) {
        fprintf(stderr, "orccad_rt: the robot's I/O cannot start (%s)\n", io);
        return 2;
    }
    if (orc_rt_setup() != 0) {
        fprintf(stderr, "orccad_rt: the table exceeds the runtime's sizes\n");
        return 2;
    }
    for (p = 0; p < ORC_N_PROCESSORS; p++) {
        if (orc_rt_start_processor(&threads[p], p, &warned) != 0) {
            fprintf(stderr, "orccad_rt: cannot start the thread of processor %d\n", p);
            return 2;
        }
    }
    /* the mission's automaton task: above every processor thread (its reactions start and
     * stop their Module-Tasks, its observers' events are the most urgent) */
    if (orc_rt_start_thread(&automaton, orc_automaton_task, NULL, 80, &warned) != 0) {
        fprintf(stderr, "orccad_rt: cannot start the automaton task\n");
        return 2;
    }
    if (!warned) { /* the commands' thread: above the plant server, below the processors */
        struct sched_param command_param;
        command_param.sched_priority = 70;
        (void)pthread_setschedparam(pthread_self(), SCHED_FIFO, &command_param);
    }
    if (fd < 0) {
        status = run_alone(until_s);
    }
    for (; fd >= 0;) {
        uint32_t n, code;
        if (orc_wire_read(fd, &req, sizeof req) != 0 || req.n > MAX_DOUBLES
            || orc_wire_read(fd, data_in, req.n * sizeof(double)) != 0) {
            break; /* the plant server is gone */
        }
        if (req.op == OP_QUIT) {
            orc_wire_reply(fd, ORC_OK, 0, NULL);
            break;
        }
        pthread_mutex_lock(&orc_rt_lock);
        code = command(&req, answer, &n);
        pthread_cond_broadcast(&orc_rt_changed);
        pthread_mutex_unlock(&orc_rt_lock);
        if (orc_wire_reply(fd, code, n, answer) != 0) {
            status = 3;
            break;
        }
    }
    orc_rt_stop();
    for (p = 0; p < ORC_N_PROCESSORS; p++) {
        pthread_join(threads[p], NULL);
    }
    pthread_join(automaton, NULL);
    return status;
}
