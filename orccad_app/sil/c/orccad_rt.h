/* orccad_rt.h: what the real-time runtime's parts share (orccad_rt.c: the processor threads;
 * orccad_rt_lifecycle.c: the Robot-Tasks' lifecycle on the Module-Tasks; orccad_rt_deadlock.c:
 * the deadlock search; orccad_rt_main.c: the commands; orccad_rt_automaton.c: the mission's
 * automaton task). Part of the ORCCAD runtime library; C99 + POSIX threads. Everything here
 * is read and written under orc_rt_lock. */
#ifndef ORCCAD_RT_H
#define ORCCAD_RT_H

#include <pthread.h>
#include <stdint.h>

#define ORC_RT_MAX_MODULES 64
#define ORC_RT_MAX_PROCESSORS 16

/* The runtime's one lock, and its condition variable (CLOCK_MONOTONIC): broadcast when a
 * port, an interrupt, an observer's event or a command changed. */
extern pthread_mutex_t orc_rt_lock;
extern pthread_cond_t orc_rt_changed;
extern volatile int orc_rt_stopping;

/* Now [ns, CLOCK_MONOTONIC]; the run's t = 0 on it; the events Module-Task m has fired. */
int64_t orc_rt_now_ns(void);
int64_t orc_rt_epoch_ns(void);
int64_t orc_rt_events(int m);

/* The Robot-Tasks' lifecycle on Module-Task m (orccad_rt_lifecycle.c): active?; a fresh
 * start (nominal parameters, state reset; waits for its compute); killed (its unfinished job
 * aborted); its ports back to "before any write"; activated, its first release at
 * `release_ns` (absolute). */
int orc_rt_active(int m);
void orc_rt_fresh(int m);
void orc_rt_kill(int m);
void orc_rt_reset_ports(int m);
void orc_rt_activate(int m, int64_t release_ns);
/* Parameter word `offset` of Module-Task m set to `value` (a type-1 update; waits for its
 * compute); its current value. */
void orc_rt_set_param(int m, int offset, double value);
double orc_rt_get_param(int m, int offset);

/* The commands (orccad_rt_main.c): a parameter write (0, or 2 when refused); INIT (both
 * orccad_rt_lifecycle.c); the jobs deadlocked, as [module, connection, reading] triples into
 * `cycle` (the number of doubles, 0: none; orccad_rt_deadlock.c); the I/O side's t = 0 taken;
 * the runtime set up (-1: the table exceeds its sizes); a processor's thread started; every
 * thread told to stop. */
uint32_t orc_rt_set_params(int m, int offset, const double *values, int n);
void orc_rt_init(int m);
uint32_t orc_rt_deadlock(double *cycle);
void orc_rt_take_epoch(void);
int orc_rt_setup(void);
int orc_rt_start_processor(pthread_t *thread, int processor, int *warned);
void orc_rt_stop(void);

/* Start `body(arg)` on a thread under SCHED_FIFO at `priority` when permitted, else under
 * the default policy after one warning (*warned set); 0 or the error. */
int orc_rt_start_thread(pthread_t *thread, void *(*body)(void *), void *arg, int priority,
                        int *warned);

/* The automaton task (orccad_rt_automaton.c). Its thread's body: */
void *orc_automaton_task(void *unused);
/* A job of Module-Task m is released at `release_ns` [ns since t = 0], before it reads: the
 * type-1 ramps on its parameters take their step. */
void orc_automaton_release(int m, int64_t release_ns);
/* OP_EPOCH: the run's t = 0 is set, the task starts reacting at its ticks. */
void orc_automaton_start(void);
/* The mission's status after the task's last reaction (0 running, 1 done, 2 failed,
 * 3 aborted; -1: a run-time error of the mission ended the reactions); under the lock. */
int orc_automaton_status(void);
/* OP_INPUT: inputs for the first reaction at or after their instant (`n` words: the instant
 * [ns], then the inputs' words of a reaction, orccad_automaton.h); 0, or the refusal. */
uint32_t orc_automaton_input(const double *words, uint32_t n);

#endif
