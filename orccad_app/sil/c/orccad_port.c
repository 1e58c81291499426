/* orccad_port.c: the 8 port protocols (see orccad_port.h). */
#include "orccad_port.h"

#include <string.h>

void orc_port_reset(orc_port *p, int protocol)
{
    memset(p, 0, sizeof *p);
    p->protocol = protocol;
    p->demand = 1;
}

static void hand(orc_port *p, const orc_value *value)
{
    p->reader = 0;
    p->reader_free = 1;
    p->handed = *value;
}

static void let_go(orc_port *p)
{
    p->writer = 0;
    p->writer_free = 1;
    p->value = p->pending;
}

static int wait_to_read(orc_port *p)
{
    p->reader = 1;
    p->reader_free = 0;
    return ORC_PORT_BLOCKED;
}

int orc_port_read(orc_port *p, orc_value *into)
{
    switch (p->protocol) {
    case ORC_ASYN_SYN:
        if (!p->fresh) {
            return wait_to_read(p);
        }
        p->fresh = 0;
        break;
    case ORC_ASYN_SYNF:
    case ORC_ASYN_SYNDF:
        return wait_to_read(p);
    case ORC_SYN_SYN:
        if (!p->writer) {
            return wait_to_read(p);
        }
        let_go(p); /* the writer's value crosses now */
        break;
    case ORC_SYN_ASYN:
    case ORC_SYNF_ASYN:
        *into = p->value; /* the value before the waiting writer's */
        if (p->writer) {
            let_go(p);
        } else if (p->protocol == ORC_SYN_ASYN) {
            p->demand = 1;
        }
        return ORC_PORT_DONE;
    default: /* asyn/asyn, asyn/synD */
        break;
    }
    *into = p->value;
    return ORC_PORT_DONE;
}

int orc_port_read_done(orc_port *p, orc_value *into)
{
    if (!p->reader_free) {
        return ORC_PORT_BLOCKED;
    }
    p->reader_free = 0;
    *into = p->handed;
    return ORC_PORT_DONE;
}

int orc_port_write(orc_port *p, const orc_value *value)
{
    switch (p->protocol) {
    case ORC_SYN_SYN:
        if (!p->reader) {
            break; /* wait for the reader */
        }
        p->value = *value;
        hand(p, value);
        return ORC_PORT_DONE;
    case ORC_SYN_ASYN:
        if (!p->demand) {
            break; /* wait for the next read */
        }
        p->demand = 0;
        p->value = *value;
        return ORC_PORT_DONE;
    case ORC_SYNF_ASYN:
        break;
    default: /* the asynchronous writers */
        p->value = *value;
        if (p->reader && p->protocol != ORC_ASYN_ASYN && p->protocol != ORC_ASYN_SYND) {
            hand(p, value);
        } else if (p->protocol == ORC_ASYN_SYN) {
            p->fresh = 1;
        }
        return ORC_PORT_DONE;
    }
    p->writer = 1;
    p->writer_free = 0;
    p->pending = *value;
    return ORC_PORT_BLOCKED;
}

int orc_port_write_done(orc_port *p)
{
    if (!p->writer_free) {
        return ORC_PORT_BLOCKED;
    }
    p->writer_free = 0;
    return ORC_PORT_DONE;
}

void orc_port_cancel(orc_port *p, int reader_end)
{
    if (reader_end) {
        p->reader = 0;
        p->reader_free = 0;
    } else {
        p->writer = 0;
        p->writer_free = 0;
    }
}
