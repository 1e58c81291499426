/* orccad_rt.h: what the real-time runtime's parts share (orccad_rt.c: the processor threads
 * and the commands; orccad_rt_automaton.c: the mission's automaton task). Part of the ORCCAD
 * runtime library; C99 + POSIX threads. Everything here is read and written under
 * orc_rt_lock. */
#ifndef ORCCAD_RT_H
#define ORCCAD_RT_H

#include <pthread.h>
#include <stdint.h>

#define ORC_RT_MAX_MODULES 64

/* The runtime's one lock, and its condition variable (CLOCK_MONOTONIC): broadcast when a
 * port, an interrupt, an observer's event or a command changed. */
extern pthread_mutex_t orc_rt_lock;
extern pthread_cond_t orc_rt_changed;
extern volatile int orc_rt_stopping;

/* Now [ns, CLOCK_MONOTONIC]; the run's t = 0 on it; the events Module-Task m has fired. */
int64_t orc_rt_now_ns(void);
int64_t orc_rt_epoch_ns(void);
int64_t orc_rt_events(int m);

/* Start `body(arg)` on a thread under SCHED_FIFO at `priority` when permitted, else under
 * the default policy after one warning (*warned set); 0 or the error. */
int orc_rt_start_thread(pthread_t *thread, void *(*body)(void *), void *arg, int priority,
                        int *warned);

/* The automaton task (orccad_rt_automaton.c). Its thread's body: */
void *orc_automaton_task(void *unused);
/* OP_EPOCH: the run's t = 0 is set, the task starts reacting at its ticks. */
void orc_automaton_start(void);
/* OP_INPUT: inputs for the first reaction at or after their instant (`n` words: the instant
 * [ns], then the inputs' words of a reaction, orccad_automaton.h); 0, or the refusal. */
uint32_t orc_automaton_input(const double *words, uint32_t n);

#endif
