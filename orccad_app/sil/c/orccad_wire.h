/* orccad_wire.h: the frames between the plant server (orccad_app/sil/controller/process.py) and a
 * controller process, over the socket it inherits (file descriptor after --fd). Part of the
 * ORCCAD runtime library; C99 + POSIX read/write, no allocation.
 *
 * A request is an orc_request then `n` 8-byte words; a reply an orc_reply then `n` words; a
 * word is a double, or an integer where the operation says so (orc_wire_put_int); a port
 * value is [present, v0 ... v(dim-1)]. */
#ifndef ORCCAD_WIRE_H
#define ORCCAD_WIRE_H

#include <stddef.h>
#include <stdint.h>

enum orc_op {
    OP_HELLO = 1,    /* answer: the number of Module-Tasks, then the table's digest (8 doubles) */
    OP_START = 2,    /* a fresh Module-Task: nominal parameters */
    OP_PARAM = 3,    /* parameters [offset, offset + n) replaced (a type-1 update) */
    OP_INIT = 4,     /* an activation's reset of the Module-Task's state */
    OP_COMPUTE = 5,  /* lockstep: one job, its inputs in, its outputs out */
    OP_PING = 6,     /* the heartbeat (real time: answered with the jobs deadlocked, if any) */
    OP_QUIT = 7,     /* end */
    OP_ACTIVATE = 8, /* real time: first release at t_s (the Module-Tasks in the data) */
    OP_KILL = 9,     /* real time: deactivated, the unfinished job aborted */
    OP_RESET = 10,   /* real time: the Module-Task's ports back to "before any write" */
    OP_EPOCH = 11,   /* real time: t = 0 is now (the I/O side's epoch) */
    OP_REACT = 12,   /* lockstep: one reaction of the mission's automaton (orccad_automaton.h) */
    OP_INPUT = 13,   /* real time: inputs for the automaton task at an instant (orccad_rt.h) */
    OP_PARAMS = 14   /* real time: answer the Module-Task's current parameter words */
};

/* A reply's status (orccad_app/sil/controller/process.py: Reply). */
enum orc_status {
    ORC_OK = 0,
    ORC_NO_SUCH_MODULE = 1, /* the request's Module-Task (or one in its data) is not in the table */
    ORC_BAD_PARAMS = 2,     /* parameter words outside the Module-Task's */
    ORC_NO_SUCH_KIND = 3,   /* the Module-Task's kind has no C in this controller */
    ORC_UNKNOWN_OP = 4,     /* an operation this controller does not serve */
    ORC_BAD_REACTION = 5,   /* the automaton refused the reaction's words */
    ORC_INPUTS_FULL = 6,    /* more inputs ahead than a reaction period can hold */
    ORC_BAD_WORDS = 7       /* the request's data has not the words its operation takes */
};

typedef struct {
    uint32_t op, module;
    double t_s;
    uint32_t n, offset;
} orc_request;

typedef struct {
    uint32_t status, n;
} orc_reply;

#define ORC_HELLO_DOUBLES 9

/* 0, or -1 when the socket is closed or fails (the plant server is gone). */
int orc_wire_read(int fd, void *buf, size_t size);
/* A reply of `n` doubles; 0, or -1 when the socket fails. */
int orc_wire_reply(int fd, uint32_t status, uint32_t n, const double *values);
/* HELLO's answer into `answer` (ORC_HELLO_DOUBLES words: the number of Module-Tasks, an
 * integer, then the table's digest). */
void orc_wire_hello(double *answer);
/* An integer word of a frame (a Module-Task's index, a count): 8 bytes, two's complement, in
 * a slot of the frame's data (written and read as bytes, never as a double). */
void orc_wire_put_int(double *word, int64_t value);
int64_t orc_wire_get_int(const double *word);

#endif
