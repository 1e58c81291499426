/* orccad_lockstep.c: the controller process of `orccad sil --lockstep`.
 *
 * The Module-Tasks of the generated table run here, in their own process; the plant server
 * (orccad_app/sil/lockstep.py) keeps the timing model — releases, declared execution times,
 * the port protocols, the automaton — and the MuJoCo plant, and sends one request per job
 * over a Unix socket (a socketpair inherited as file descriptor argv[2]), and one request per
 * reaction of the mission's automaton, which runs here too (orccad_automaton.h: the C of
 * `orccad codegen`, its memory reset at HELLO). Each request is
 * answered before the plant goes on: the two wait for each other, so a run does not depend on
 * the machine's speed.
 *
 * Frames (native byte order): request = u32 op, u32 module, f64 t_s, u32 n, u32 offset, then
 * n doubles; reply = u32 status (enum orc_status, orccad_wire.h), u32 n, then n doubles. A value slot is
 * [present, v_0 .. v_(dim-1)]. C99, no allocation, no recursion. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "orccad_automaton.h"
#include "orccad_mt.h"
#include "orccad_wire.h"

#define MODULE_DOUBLES (ORC_MAX_PORTS * (ORC_MAX_DIM + 1) + ORC_MAX_PARAMS)
#define MAX_DOUBLES (MODULE_DOUBLES > ORC_AUTOMATON_IN_WORDS ? MODULE_DOUBLES \
                                                              : ORC_AUTOMATON_IN_WORDS)
#define MAX_REPLY (MODULE_DOUBLES > ORC_AUTOMATON_OUT_WORDS ? MODULE_DOUBLES \
                                                             : ORC_AUTOMATON_OUT_WORDS)

static double data_in[MAX_DOUBLES], data_out[MAX_REPLY];

static int reply(int fd, uint32_t status, uint32_t n)
{
    return orc_wire_reply(fd, status, n, data_out);
}

static uint32_t compute(orc_mt *m, double t_s)
{
    int slot, i, k = 0, n = 0;
    for (slot = 0; slot < m->n_in; slot++) {
        m->in[slot].present = data_in[k++] != 0.0;
        for (i = 0; i < m->in[slot].dim; i++) {
            m->in[slot].v[i] = data_in[k++];
        }
    }
    if (orc_mt_compute(m, t_s) != 0) {
        return (uint32_t)-1;
    }
    for (slot = 0; slot < m->n_out; slot++) {
        data_out[n++] = m->out[slot].present ? 1.0 : 0.0;
        for (i = 0; i < m->out[slot].dim; i++) {
            data_out[n++] = m->out[slot].present ? m->out[slot].v[i] : 0.0;
        }
    }
    return (uint32_t)n;
}

/* The lockstep loop on socket `fd` (its own main, or the combined controller's `--fd N
 * --lockstep`: orccad_rt_main.c built with ORC_COMBINED_MAIN, `orccad codegen --controller`). */
int orc_lockstep_main(int fd);

#ifndef ORC_COMBINED_MAIN
int main(int argc, char **argv)
{
    if (argc != 3 || strcmp(argv[1], "--fd") != 0) {
        fprintf(stderr, "usage: %s --fd N (started by orccad sil)\n", argv[0]);
        return 2;
    }
    return orc_lockstep_main(atoi(argv[2]));
}
#endif

int orc_lockstep_main(int fd)
{
    orc_request req;
    for (;;) {
        orc_mt *m = NULL;
        uint32_t n;
        if (orc_wire_read(fd, &req, sizeof req) != 0) {
            return 0; /* the plant server is gone: end quietly */
        }
        if (req.n > MAX_DOUBLES || orc_wire_read(fd, data_in, req.n * sizeof(double)) != 0) {
            return 3;
        }
        if (req.op != OP_HELLO && req.op != OP_PING && req.op != OP_QUIT && req.op != OP_REACT) {
            if (req.module >= (uint32_t)ORC_N_MODULES) {
                reply(fd, ORC_NO_SUCH_MODULE, 0);
                continue;
            }
            m = &ORC_INSTANCES[req.module];
        }
        switch (req.op) {
        case OP_HELLO:
            orc_automaton_reset();
            orc_wire_hello(data_out);
            if (reply(fd, ORC_OK, ORC_HELLO_DOUBLES) != 0) {
                return 3;
            }
            break;
        case OP_START:
            orc_mt_load(m, &ORC_MODULES[req.module]);
            orc_mt_init(m);
            reply(fd, ORC_OK, 0);
            break;
        case OP_PARAM:
            reply(fd, orc_mt_set_param(m, (int)req.offset, data_in, (int)req.n) ? ORC_BAD_PARAMS : ORC_OK,
                  0);
            break;
        case OP_INIT:
            orc_mt_init(m);
            reply(fd, ORC_OK, 0);
            break;
        case OP_COMPUTE:
            n = compute(m, req.t_s);
            if (n == (uint32_t)-1) {
                reply(fd, ORC_NO_SUCH_KIND, 0);
            } else if (reply(fd, ORC_OK, n) != 0) {
                return 3;
            }
            break;
        case OP_REACT:
            if (orc_automaton_react(data_in, req.n, data_out, &n) != 0) {
                reply(fd, ORC_BAD_REACTION, 0);
            } else if (reply(fd, ORC_OK, n) != 0) {
                return 3;
            }
            break;
        case OP_PING:
            reply(fd, ORC_OK, 0);
            break;
        case OP_QUIT:
            reply(fd, ORC_OK, 0);
            return 0;
        default:
            reply(fd, ORC_UNKNOWN_OP, 0);
        }
    }
}
