/* port_check.c: drives one orc_port with commands on stdin and prints what each end sees,
 * so that tests/sil/test_ports.py can compare it with the executive's channel on the same
 * operations. Test code, not part of the runtime.
 *
 *   p N    a fresh connection with protocol N      x    reset (fresh ports)
 *   w V    the producer writes V                   r    the consumer reads
 *
 * After each command: "W done|blocked", "R V|none|blocked", then "R woke V|none" and
 * "W woke" for a blocked end that the command released. */
#include <stdio.h>
#include <string.h>

#include "orccad_port.h"

static void print_value(const char *prefix, const orc_value *v)
{
    if (v->present) {
        printf("%s%g\n", prefix, v->v[0]);
    } else {
        printf("%snone\n", prefix);
    }
}

int main(void)
{
    orc_port port;
    char op[8];
    double number;
    int reading = 0, writing = 0;
    orc_port_reset(&port, 0);
    while (scanf("%7s", op) == 1) {
        orc_value value;
        memset(&value, 0, sizeof value);
        if (strcmp(op, "p") == 0 && scanf("%lf", &number) == 1) {
            orc_port_reset(&port, (int)number);
            reading = writing = 0;
        } else if (strcmp(op, "x") == 0) {
            orc_port_reset(&port, port.protocol);
            reading = writing = 0;
        } else if (strcmp(op, "w") == 0 && scanf("%lf", &number) == 1) {
            value.present = 1;
            value.dim = 1;
            value.v[0] = number;
            writing = orc_port_write(&port, &value) == ORC_PORT_BLOCKED;
            printf(writing ? "W blocked\n" : "W done\n");
        } else if (strcmp(op, "r") == 0) {
            reading = orc_port_read(&port, &value) == ORC_PORT_BLOCKED;
            if (reading) {
                printf("R blocked\n");
            } else {
                print_value("R ", &value);
            }
        } else {
            return 2;
        }
        if (reading && orc_port_read_done(&port, &value) == ORC_PORT_DONE) {
            reading = 0;
            print_value("R woke ", &value);
        }
        if (writing && orc_port_write_done(&port) == ORC_PORT_DONE) {
            writing = 0;
            printf("W woke\n");
        }
    }
    return 0;
}
