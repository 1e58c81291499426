/* orccad_wire.c: the frames of orccad_wire.h. */
#define _POSIX_C_SOURCE 200809L
#include "orccad_wire.h"

#include <errno.h>
#include <string.h>
#include <unistd.h>

#include "orccad_mt.h"

int orc_wire_read(int fd, void *buf, size_t size)
{
    char *p = buf;
    while (size > 0) {
        ssize_t got = read(fd, p, size);
        if (got == 0 || (got < 0 && errno != EINTR)) {
            return -1;
        }
        if (got > 0) {
            p += got;
            size -= (size_t)got;
        }
    }
    return 0;
}

static int write_full(int fd, const void *buf, size_t size)
{
    const char *p = buf;
    while (size > 0) {
        ssize_t put = write(fd, p, size);
        if (put < 0 && errno != EINTR) {
            return -1;
        }
        if (put > 0) {
            p += put;
            size -= (size_t)put;
        }
    }
    return 0;
}

int orc_wire_reply(int fd, uint32_t status, uint32_t n, const double *values)
{
    orc_reply head;
    head.status = status;
    head.n = n;
    if (write_full(fd, &head, sizeof head) != 0) {
        return -1;
    }
    return n ? write_full(fd, values, n * sizeof(double)) : 0;
}

void orc_wire_put_int(double *word, int64_t value)
{
    memcpy(word, &value, sizeof value);
}

int64_t orc_wire_get_int(const double *word)
{
    int64_t value;
    memcpy(&value, word, sizeof value);
    return value;
}

void orc_wire_hello(double *answer)
{
    size_t len = strlen(ORC_TABLE_DIGEST);
    memset(answer, 0, ORC_HELLO_DOUBLES * sizeof(double));
    orc_wire_put_int(&answer[0], ORC_N_MODULES);
    memcpy(&answer[1], ORC_TABLE_DIGEST, len < 64 ? len : 64);
}
