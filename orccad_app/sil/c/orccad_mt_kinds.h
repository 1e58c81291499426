/* orccad_mt_kinds.h: what the Module-Task kinds of the runtime library share, internal to it
 * (orccad_mt.c dispatches a job to its kind; the kinds are in orccad_mt_trajectory.c,
 * orccad_mt_laws.c, orccad_mt_observers.c and orccad_mt_auv.c). C99, no allocation, no
 * recursion. */
#ifndef ORCCAD_MT_KINDS_H
#define ORCCAD_MT_KINDS_H

#include "orccad_mt.h"

/* Output slot `slot` written: present, `dim` components from v (orccad_mt.c). */
void orc_mt_set_out(orc_mt *m, int slot, const double *v, int dim);
void orc_mt_set_out1(orc_mt *m, int slot, double v);
/* ModuleInstance.task_time: seconds since the first job after init; `state` holds
 * [t0 set, t0] (orccad_mt.c). */
double orc_mt_task_time(double *state, double t_s);
/* The torque interval [lo, hi] [N·m] the actuator constraint allows joint j at velocity
 * qdot (control/constraints.py: |tau + beta·qdot| <= alpha within [tau_min, tau_max], never
 * empty); bounds = [tau_min, tau_max, alpha, beta], dof each (orccad_mt.c). The laws clamp
 * to it, torque_saturation measures against it. */
void orc_mt_torque_bounds(const double *bounds, int dof, int j, double qdot, double *lo,
                          double *hi);
/* An observer's job (plugins/orccad_observers/base.py): its value on slot 1; its event on
 * slot 0 when `holds`, only at the rising edge with the edge parameter p[0] (the state's s[0]
 * is "held"; orccad_mt_observers.c). */
void orc_mt_observe(orc_mt *m, int holds, double value);

/* The kinds: one job of Module-Task m at t_s [s since the run's t = 0]. */
void orc_mt_cosine(orc_mt *m, double t_s);             /* orccad_mt_trajectory.c */
void orc_mt_min_jerk(orc_mt *m, double t_s);
void orc_mt_constant(orc_mt *m, double t_s);
void orc_mt_pid(orc_mt *m, double t_s);                /* orccad_mt_laws.c */
void orc_mt_computed_torque(orc_mt *m, double t_s);
void orc_mt_dynamic_model(orc_mt *m);
void orc_mt_ct_feedback(orc_mt *m);
void orc_mt_joint_limits(orc_mt *m);                   /* orccad_mt_observers.c */
void orc_mt_torque_saturation(orc_mt *m);
void orc_mt_tracking_error(orc_mt *m);
void orc_mt_at_rest(orc_mt *m);
void orc_mt_autopilot(orc_mt *m, double t_s);          /* orccad_mt_auv.c */
void orc_mt_guidance(orc_mt *m);
void orc_mt_auv_observer(orc_mt *m, double t_s);

#endif
