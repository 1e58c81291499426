/* orccad_mt_kinds.h: what the Module-Task kinds of the runtime library share, internal to it
 * (orccad_mt.c dispatches a job to its kind; the kinds are in orccad_mt_trajectory.c,
 * orccad_mt_laws.c; what every kind may call, a plugin's too, is in orccad_mt.h).
 * C99, no allocation, no recursion. */
#ifndef ORCCAD_MT_KINDS_H
#define ORCCAD_MT_KINDS_H

#include "orccad_mt.h"


/* The kinds: one job of Module-Task m at t_s [s since the run's t = 0]. */
void orc_mt_cosine(orc_mt *m, double t_s);             /* orccad_mt_trajectory.c */
void orc_mt_min_jerk(orc_mt *m, double t_s);
void orc_mt_constant(orc_mt *m, double t_s);
void orc_mt_pid(orc_mt *m, double t_s);                /* orccad_mt_laws.c */
void orc_mt_computed_torque(orc_mt *m, double t_s);
void orc_mt_dynamic_model(orc_mt *m);
void orc_mt_ct_feedback(orc_mt *m);

#endif
