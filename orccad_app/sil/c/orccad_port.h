/* orccad_port.h: the 8 port protocols of RR-1801 §3.2.1 on one connection, as the executive
 * runs them on one processor (orccad_app/executive/channel.py; docs/executive.md, "The 8 port
 * protocols"). Part of the ORCCAD runtime library; C99, no allocation, no recursion, no
 * threads: the runtime calls these under its lock and waits on its condition variable while
 * an end is blocked.
 *
 * A read or a write either completes (ORC_PORT_DONE) or blocks (ORC_PORT_BLOCKED: the end is
 * registered as waiting). A blocked end is released by the other end's operation: a blocked
 * reader is handed its value (orc_port_read_done then gives it), a blocked writer is let go
 * (orc_port_write_done). Each end is one Module-Task, whose job does one operation at a time,
 * so a connection has at most one waiting reader and one waiting writer.
 *
 * What a read gets before the first write: "none yet" (present = 0) for asyn/asyn, syn/asyn,
 * synF/asyn and asyn/synD; asyn/syn, asyn/synF, syn/syn and asyn/synDF block until a write.
 * orc_port_reset brings the connection back to that state (a Robot-Task run again: fresh
 * ports). The real-time runtime has no bus: its Module-Tasks share memory, so every
 * connection behaves as between two Module-Tasks on one processor in the executive. */
#ifndef ORCCAD_PORT_H
#define ORCCAD_PORT_H

#include "orccad_mt.h"

/* The protocols, in the generated table's numbering (orccad_app/sil/emit.py). */
enum orc_protocol {
    ORC_ASYN_ASYN = 0,  /* neither end blocks; the last value */
    ORC_SYN_SYN = 1,    /* rendez-vous */
    ORC_ASYN_SYN = 2,   /* a fresh value at once, else the reader waits for the next write */
    ORC_SYN_ASYN = 3,   /* the writer waits for a read unless one happened since its last write */
    ORC_ASYN_SYNF = 4,  /* the reader always waits for the next write */
    ORC_SYNF_ASYN = 5,  /* the writer always waits for the next read */
    ORC_ASYN_SYND = 6,  /* pull: the producer side's latest value (at once, no bus) */
    ORC_ASYN_SYNDF = 7  /* pull: the first value written after the request */
};
#define ORC_N_PROTOCOLS 8

enum { ORC_PORT_DONE = 0, ORC_PORT_BLOCKED = 1 };

typedef struct {
    int protocol;
    orc_value value;    /* what a read gets (present 0: none yet) */
    orc_value pending;  /* a blocked writer's value, committed when a read lets it go */
    orc_value handed;   /* the value handed to the blocked reader */
    int fresh;          /* asyn/syn: written since the last read */
    int demand;         /* syn/asyn: read since the last write */
    int reader;         /* a reader waits (asyn/synDF: its request) */
    int writer;         /* a writer waits */
    int reader_free;    /* the waiting reader has been handed its value */
    int writer_free;    /* the waiting writer has been let go */
} orc_port;

void orc_port_reset(orc_port *p, int protocol);
int orc_port_read(orc_port *p, orc_value *into);
/* A blocked reader: ORC_PORT_DONE (and *into) once it has been handed its value. */
int orc_port_read_done(orc_port *p, orc_value *into);
int orc_port_write(orc_port *p, const orc_value *value);
/* A blocked writer: ORC_PORT_DONE once a read has let it go. */
int orc_port_write_done(orc_port *p);
/* A killed end forgets its wait (reader_end 1: the reader's, 0: the writer's). */
void orc_port_cancel(orc_port *p, int reader_end);

#endif
