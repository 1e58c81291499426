/* orccad_io_udp.c: the robot's I/O (orccad_io.h) over UDP to a plant process — the template
 * to copy as your orccad_io.c (docs/deploy.md, "The robot's I/O over UDP").
 *
 * `--io HOST:PORT` names the plant process (the robot's driver, or a simulator). Datagrams are
 * arrays of doubles in the machine's byte order:
 *
 *   controller -> plant   [-1]                          once at start: "here I am"
 *   controller -> plant   [k, v_0 .. v_(dim-1)]         actuator port k written (held)
 *   plant -> controller   [k, v_0 .. v_(dim-1)]         sensor port k's latest value
 *
 * where k is the port's index in ORC_ROBOT_PORTS ("arm.q", "arm.tau"; dim doubles in the
 * robot type's units). The plant sends every sensor at its own rate (the arm's: every 1 ms);
 * a read takes the latest datagram of its port, never waits (a sensor not heard from yet is
 * "none yet"). The socket is non-blocking and shared by the processor threads under a mutex;
 * the run's t = 0 is the controller's start. Timing, reactions and job records are not sent
 * (return 1 from orc_io_jobs_wanted and log them in orc_io_job to keep them). C99 + POSIX
 * sockets; no allocation. */
#define _POSIX_C_SOURCE 200809L
#include <arpa/inet.h>
#include <netdb.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/types.h>
#include <unistd.h>

#include "orccad_io.h"

#define MAX_PORTS 64
#define DATAGRAM_DOUBLES (1 + ORC_MAX_DIM)

static int sock = -1;
static pthread_mutex_t io_lock = PTHREAD_MUTEX_INITIALIZER;
static orc_value latest[MAX_PORTS];

int orc_io_open(const char *where)
{
    char host[256];
    const char *colon = strrchr(where, ':');
    struct addrinfo hints, *found = NULL;
    double hello = -1.0;
    size_t length;
    if (colon == NULL || colon == where || (length = (size_t)(colon - where)) >= sizeof host) {
        fprintf(stderr, "orccad_io_udp: --io %s: expected HOST:PORT\n", where);
        return -1;
    }
    memcpy(host, where, length);
    host[length] = '\0';
    memset(&hints, 0, sizeof hints);
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_DGRAM;
    if (getaddrinfo(host, colon + 1, &hints, &found) != 0 || found == NULL) {
        fprintf(stderr, "orccad_io_udp: --io %s: unknown host or port\n", where);
        return -1;
    }
    sock = socket(found->ai_family, SOCK_DGRAM, 0);
    if (sock < 0 || connect(sock, found->ai_addr, found->ai_addrlen) != 0
        || send(sock, &hello, sizeof hello, 0) != (ssize_t)sizeof hello) {
        fprintf(stderr, "orccad_io_udp: --io %s: cannot reach the plant process\n", where);
        freeaddrinfo(found);
        return -1;
    }
    freeaddrinfo(found);
    return 0;
}

/* Every datagram waiting, each the latest value of its sensor port (under io_lock). */
static void drain(void)
{
    double words[DATAGRAM_DOUBLES];
    ssize_t got;
    int ports = ORC_N_ROBOT_PORTS < MAX_PORTS ? ORC_N_ROBOT_PORTS : MAX_PORTS;
    while ((got = recv(sock, words, sizeof words, MSG_DONTWAIT)) > 0) {
        int k = (int)words[0], i, dim;
        if ((size_t)got < sizeof(double) || !(words[0] >= 0 && k < ports)
            || ORC_ROBOT_PORTS[k].actuator) {
            continue; /* not a sensor of ours: ignored */
        }
        dim = ORC_ROBOT_PORTS[k].dim;
        if ((size_t)got != (size_t)(1 + dim) * sizeof(double)) {
            continue;
        }
        for (i = 0; i < dim; i++) {
            latest[k].v[i] = words[1 + i];
        }
        latest[k].dim = dim;
        latest[k].present = 1;
    }
}

void orc_io_read_sensor(int k, orc_value *into)
{
    pthread_mutex_lock(&io_lock);
    drain();
    *into = latest[k];
    into->dim = ORC_ROBOT_PORTS[k].dim;
    pthread_mutex_unlock(&io_lock);
}

void orc_io_write_actuator(int k, const orc_value *value)
{
    double words[DATAGRAM_DOUBLES];
    int i, dim = ORC_ROBOT_PORTS[k].dim;
    words[0] = (double)k;
    for (i = 0; i < dim; i++) {
        words[1 + i] = value->v[i];
    }
    pthread_mutex_lock(&io_lock);
    (void)send(sock, words, (size_t)(1 + dim) * sizeof(double), MSG_DONTWAIT);
    pthread_mutex_unlock(&io_lock);
}

long long orc_io_epoch_ns(long long fallback)
{
    return fallback; /* t = 0: the controller's start */
}

void orc_io_publish(int m, const orc_mt *mt, long long released, long long overruns,
                    long long misses, long long events, double response_max_ns)
{
    (void)m; (void)mt; (void)released; (void)overruns; (void)misses; (void)events;
    (void)response_max_ns;
}

void orc_io_lateness(int m, double lateness_ns)
{
    (void)m;
    (void)lateness_ns;
}

void orc_io_reaction(const double *request, unsigned n_request, const double *reply,
                     unsigned n_reply)
{
    (void)request; (void)n_request; (void)reply; (void)n_reply;
}

int orc_io_jobs_wanted(void)
{
    return 0;
}

void orc_io_job(int m, const orc_job *job)
{
    (void)m;
    (void)job;
}
