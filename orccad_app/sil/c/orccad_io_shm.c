/* orccad_io_shm.c: the robot's I/O (orccad_io.h) over the shared memory of the plant server
 * of `orccad sil --realtime` (orccad_app/sil/shared.py has the same layout), as 8-byte
 * words: a header of 8 (word 1: t = 0 on CLOCK_MONOTONIC [ns]); per robot port
 * [seq, v0 .. v7] under a sequence lock (odd: being written; 0: never written); per
 * Module-Task a mirror [seq, released, overruns, misses, events, lateness count, response max
 * (double), unused] then its output slots [present, v0 .. v7]; per Module-Task a ring of
 * its last release latenesses [ns]; a ring of the automaton's last reactions (header word 2:
 * how many were published), each the words of its request then of its reply
 * (orccad_automaton.h); a ring of the Module-Tasks' last job records (header word 3: 1 when
 * the plant server wants them, word 4: how many were published), each [module, flags
 * (1 overrun, 2 missed), job, release, start, compute end, finish, unused]. C99 + POSIX. */
#define _POSIX_C_SOURCE 200809L
#include <fcntl.h>
#include <stdint.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "orccad_automaton.h"
#include "orccad_io.h"

#define HEADER_WORDS 8
#define ROBOT_WORDS (1 + ORC_MAX_DIM)
#define MODULE_HEAD 8
#define MODULE_WORDS (MODULE_HEAD + ORC_MAX_PORTS * (1 + ORC_MAX_DIM))
#define LATENESS_RING 16384
#define REACTION_RING 4096
#define REACTION_WORDS (ORC_AUTOMATON_IN_WORDS + ORC_AUTOMATON_OUT_WORDS)
#define JOB_RING 16384
#define JOB_WORDS 8
#define READ_SPIN_TRIES 64
#define READ_PAUSE_NS 20000L
#define READ_GIVE_UP_TRIES (READ_SPIN_TRIES + 5000)

static int64_t *shm_words;

int orc_io_open(const char *where)
{
    int fd = open(where, O_RDWR);
    struct stat st;
    void *p;
    if (fd < 0) {
        return -1;
    }
    if (fstat(fd, &st) != 0) {
        close(fd);
        return -1;
    }
    p = mmap(NULL, (size_t)st.st_size, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
    close(fd);
    if (p == MAP_FAILED) {
        return -1;
    }
    shm_words = (int64_t *)p;
    return 0;
}

long long orc_io_epoch_ns(long long fallback)
{
    return shm_words[1] ? (long long)shm_words[1] : fallback;
}

static double *robot_port(int k)
{
    return (double *)&shm_words[HEADER_WORDS + k * ROBOT_WORDS];
}

static int64_t *module_words(int m)
{
    return &shm_words[HEADER_WORDS + ORC_N_ROBOT_PORTS * ROBOT_WORDS + m * MODULE_WORDS];
}

static double *lateness_ring(int m)
{
    return (double *)&shm_words[HEADER_WORDS + ORC_N_ROBOT_PORTS * ROBOT_WORDS
                                + ORC_N_MODULES * MODULE_WORDS + (int64_t)m * LATENESS_RING];
}

void orc_io_read_sensor(int k, orc_value *into)
{
    volatile int64_t *seq = (volatile int64_t *)robot_port(k);
    int64_t before, after;
    int i, dim = ORC_ROBOT_PORTS[k].dim;
    long tries = 0;
    do {
        /* A torn read: the plant server is writing. Past a few tries, sleep 20 µs so that a
         * writer of lower priority on this core can finish (spinning at SCHED_FIFO would
         * starve it for ever); past READ_GIVE_UP_TRIES (~0.1 s) the writer is gone: no value,
         * so the thread gets back to its loop and sees the runtime stopping. */
        if (++tries > READ_SPIN_TRIES) {
            struct timespec pause = {0, READ_PAUSE_NS};
            if (tries > READ_GIVE_UP_TRIES) {
                into->present = 0;
                return;
            }
            nanosleep(&pause, NULL);
        }
        before = *seq;
        __sync_synchronize();
        for (i = 0; i < dim; i++) {
            into->v[i] = robot_port(k)[1 + i];
        }
        __sync_synchronize();
        after = *seq;
    } while (before != after || (before & 1));
    into->present = before > 0; /* 0: the plant server has not written it yet */
}

void orc_io_write_actuator(int k, const orc_value *value)
{
    volatile int64_t *seq = (volatile int64_t *)robot_port(k);
    int i;
    *seq += 1;
    __sync_synchronize();
    for (i = 0; i < ORC_ROBOT_PORTS[k].dim; i++) {
        robot_port(k)[1 + i] = value->v[i];
    }
    __sync_synchronize();
    *seq += 1;
}

/* The mirror of Module-Task m: [seq, released, overruns, misses, events, lateness count,
 * response max (double), unused] then its output slots [present, v...]. */
void orc_io_publish(int m, const orc_mt *mt, long long released, long long overruns,
                    long long misses, long long events, double response_max_ns)
{
    volatile int64_t *w = module_words(m);
    double *slots = (double *)&module_words(m)[MODULE_HEAD];
    int s, i;
    w[0] += 1;
    __sync_synchronize();
    w[1] = released;
    w[2] = overruns;
    w[3] = misses;
    w[4] = events;
    ((volatile double *)w)[6] = response_max_ns;
    for (s = 0; s < mt->n_out; s++) {
        slots[s * (1 + ORC_MAX_DIM)] = mt->out[s].present ? 1.0 : 0.0;
        for (i = 0; i < mt->out[s].dim; i++) {
            slots[s * (1 + ORC_MAX_DIM) + 1 + i] = mt->out[s].v[i];
        }
    }
    __sync_synchronize();
    w[0] += 1;
}

void orc_io_lateness(int m, double lateness_ns)
{
    volatile int64_t *w = module_words(m);
    lateness_ring(m)[w[5] % LATENESS_RING] = lateness_ns;
    __sync_synchronize();
    w[5] += 1;
}


void orc_io_reaction(const double *request, unsigned n_request, const double *reply,
                     unsigned n_reply)
{
    volatile int64_t *count = &shm_words[2];
    double *entry = (double *)&shm_words[HEADER_WORDS + ORC_N_ROBOT_PORTS * ROBOT_WORDS
                                         + ORC_N_MODULES * (MODULE_WORDS + LATENESS_RING)
                                         + (*count % REACTION_RING) * REACTION_WORDS];
    memcpy(entry, request, n_request * sizeof(double));
    memcpy(entry + ORC_AUTOMATON_IN_WORDS, reply, n_reply * sizeof(double));
    __sync_synchronize();
    *count += 1;
}

int orc_io_jobs_wanted(void)
{
    return ((volatile int64_t *)shm_words)[3] != 0;
}

void orc_io_job(int m, const orc_job *job)
{
    volatile int64_t *count = &shm_words[4];
    int64_t *entry = &shm_words[HEADER_WORDS + ORC_N_ROBOT_PORTS * ROBOT_WORDS
                                + ORC_N_MODULES * (MODULE_WORDS + LATENESS_RING)
                                + REACTION_RING * REACTION_WORDS
                                + (*count % JOB_RING) * JOB_WORDS];
    entry[0] = m;
    entry[1] = (job->overrun ? 1 : 0) | (job->missed ? 2 : 0);
    entry[2] = job->job;
    entry[3] = job->release_ns;
    entry[4] = job->start_ns;
    entry[5] = job->compute_end_ns;
    entry[6] = job->finish_ns;
    entry[7] = 0;
    __sync_synchronize();
    *count += 1;
}
